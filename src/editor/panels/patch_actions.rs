//! What the Patches section offers and refuses (docs/editor.md, "Several
//! patches"; docs/math.md §11): each patch as listed ([`PatchRow`]), the
//! new-patch form's settings ([`NewPatchForm`]), the refusals the section
//! shows before sending anything (deleting a patch others start on, a bad
//! new patch), and each action as the [`Edit::Patch`] that carries it out
//! ([`PatchAction::edit`]). Pure: no ECS query, no egui.

use crate::ecs::Edit;
use crate::scene::edits::patch_edit::PatchEdit;
use crate::scene::files::format::Finite;
use crate::scene::files::format_v3::{ContinuitySpec, EdgeSpec};
use bevy::prelude::Entity;
use streamline_kernel::joins::{Continuity, Edge};

/// One patch as the section lists it.
#[derive(Debug, Clone, PartialEq)]
pub struct PatchRow {
    /// Its entity.
    pub entity: Entity,
    /// Its name.
    pub name: String,
    /// Its place in the document.
    pub index: usize,
    /// Where it starts: `None` on its own curve, else `(A's name, edge, continuity)`.
    pub start: Option<(String, Edge, Continuity)>,
    /// Hidden by the designer.
    pub hidden: bool,
    /// Its net's rows (a chain on it must have as many).
    pub rows: usize,
}

impl PatchRow {
    /// "curve", or "on hood End, G2".
    pub fn start_text(&self) -> String {
        match &self.start {
            None => "own curve".into(),
            Some((a, e, c)) => format!("on {a} {}, {}", e.name(), c.name()),
        }
    }
}

/// Why patch `p` cannot be deleted (`None`: it can): the first patch holds
/// the design's own curve, and a patch others start on would leave them
/// on nothing.
pub fn delete_refusal(rows: &[PatchRow], p: &PatchRow) -> Option<String> {
    if p.index == 0 {
        return Some(format!(
            "`{}` is the first patch: every other patch starts on it or after it",
            p.name
        ));
    }
    let on: Vec<&str> = rows
        .iter()
        .filter(|r| r.start.as_ref().is_some_and(|(a, ..)| *a == p.name))
        .map(|r| r.name.as_str())
        .collect();
    (!on.is_empty()).then(|| {
        format!(
            "{} start{} on `{}`: delete {} first",
            on.iter()
                .map(|n| format!("`{n}`"))
                .collect::<Vec<_>>()
                .join(", "),
            if on.len() == 1 { "s" } else { "" },
            p.name,
            if on.len() == 1 { "it" } else { "them" }
        )
    })
}

/// Why a new patch with these settings would be refused before it is sent
/// (`None`: send it); the edit stage checks the rest (docs/math.md §11).
pub fn new_patch_refusal(rows: &[PatchRow], form: &NewPatchForm, a: &PatchRow) -> Option<String> {
    let name = form.name.trim();
    if name.is_empty()
        || name.len() > 32
        || !name
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-')
    {
        return Some("a name of 1–32 letters, digits, `_` or `-`".into());
    }
    if rows.iter().any(|r| r.name == name) {
        return Some(format!(
            "there is a patch `{name}` already: choose another name"
        ));
    }
    if form.edge != Edge::End && form.continuity == Continuity::G2 {
        return Some("G2 on a side edge is future work: choose G0 or G1, or the End edge".into());
    }
    if form.edge == Edge::End && form.rows != a.rows {
        return Some(format!(
            "a chain has the rows of `{}` ({}): set rows to {}",
            a.name, a.rows, a.rows
        ));
    }
    if form.rows < 2 || form.cols < 2 {
        return Some("a net has at least 2 rows and 2 columns".into());
    }
    if !(form.length.is_finite() && form.length > 0.0) {
        return Some("the length is a positive number".into());
    }
    None
}

/// The "New patch on edge…" form.
#[derive(Debug, Clone, PartialEq)]
pub struct NewPatchForm {
    /// The new patch's name.
    pub name: String,
    /// The edge of the chosen patch it starts on.
    pub edge: Edge,
    /// The continuity across it.
    pub continuity: Continuity,
    /// Its net's rows.
    pub rows: usize,
    /// Its net's columns.
    pub cols: usize,
    /// Its streamlines' length.
    pub length: f64,
}

impl Default for NewPatchForm {
    fn default() -> Self {
        NewPatchForm {
            name: String::new(),
            edge: Edge::End,
            continuity: Continuity::G1,
            rows: 5,
            cols: 4,
            length: 1.0,
        }
    }
}

/// What the designer asked for.
#[derive(Debug, Clone, PartialEq)]
pub enum PatchAction {
    /// Make this patch the one handle edits act on.
    Select(String),
    /// Rename `(from, to)`.
    Rename(String, String),
    /// Hide (`true`) or show.
    Hide(String, bool),
    /// Delete.
    Remove(String),
    /// Start a new patch on `from`'s edge.
    Add { from: String, form: NewPatchForm },
}

impl PatchAction {
    /// The edit that carries it out.
    pub fn edit(&self) -> Edit {
        Edit::Patch(match self.clone() {
            PatchAction::Select(n) => PatchEdit::SetPatch(n),
            PatchAction::Rename(a, b) => PatchEdit::RenamePatch(a, b),
            PatchAction::Hide(n, h) => PatchEdit::HidePatch(n, h),
            PatchAction::Remove(n) => PatchEdit::RemovePatch(n),
            PatchAction::Add { from, form } => PatchEdit::AddPatch {
                name: form.name.trim().to_string(),
                from: (from, EdgeSpec::from_kernel(form.edge)),
                continuity: ContinuitySpec::from_kernel(form.continuity),
                rows: form.rows,
                cols: form.cols,
                length: Finite(form.length),
            },
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rows() -> Vec<PatchRow> {
        let row = |name: &str, index, start: Option<(&str, Edge, Continuity)>| PatchRow {
            entity: Entity::PLACEHOLDER,
            name: name.into(),
            index,
            start: start.map(|(a, e, c)| (a.to_string(), e, c)),
            hidden: false,
            rows: 5,
        };
        vec![
            row("hood", 0, None),
            row("screen", 1, Some(("hood", Edge::End, Continuity::G2))),
            row("wing", 2, Some(("hood", Edge::Last, Continuity::G1))),
            row("tail", 3, Some(("screen", Edge::End, Continuity::G1))),
        ]
    }

    /// A patch others start on, and the first patch, cannot be deleted;
    /// the message names the patches in the way.
    #[test]
    fn deleting_is_refused_while_others_start_on_it() {
        let r = rows();
        let hood = delete_refusal(&r, &r[0]).unwrap();
        assert!(hood.contains("first patch"), "{hood}");
        let screen = delete_refusal(&r, &r[1]).unwrap();
        assert_eq!(screen, "`tail` starts on `screen`: delete it first");
        assert_eq!(delete_refusal(&r, &r[2]), None);
        assert_eq!(delete_refusal(&r, &r[3]), None);
    }

    /// The form refuses what §11 refuses, naming the fix, and lets a good
    /// patch through.
    /// The `PatchEdit` an action sends.
    fn patch_edit(a: PatchAction) -> Option<PatchEdit> {
        match a.edit() {
            Edit::Patch(p) => Some(p),
            other => panic!("not a patch edit: {other:?}"),
        }
    }

    /// Each action is the `PatchEdit` the edit stage applies; a choice is none.
    #[test]
    fn actions_are_patch_edits() {
        assert_eq!(
            patch_edit(PatchAction::Select("wing".into())),
            Some(PatchEdit::SetPatch("wing".into()))
        );
        assert_eq!(
            patch_edit(PatchAction::Hide("wing".into(), true)),
            Some(PatchEdit::HidePatch("wing".into(), true))
        );
        let add = PatchAction::Add {
            from: "hood".into(),
            form: NewPatchForm {
                name: " fin ".into(),
                edge: Edge::Last,
                continuity: Continuity::G1,
                rows: 4,
                cols: 3,
                length: 0.5,
            },
        };
        assert_eq!(
            patch_edit(add),
            Some(PatchEdit::AddPatch {
                name: "fin".into(),
                from: ("hood".into(), EdgeSpec::Last),
                continuity: ContinuitySpec::G1,
                rows: 4,
                cols: 3,
                length: Finite(0.5),
            })
        );
    }

    #[test]
    fn the_new_patch_form_refuses_bad_settings() {
        let r = rows();
        let ok = NewPatchForm {
            name: "fin".into(),
            ..Default::default()
        };
        assert_eq!(new_patch_refusal(&r, &ok, &r[0]), None);
        let bad = |f: NewPatchForm| new_patch_refusal(&r, &f, &r[0]).unwrap();
        assert!(
            bad(NewPatchForm {
                name: "wing".into(),
                ..ok.clone()
            })
            .contains("already")
        );
        assert!(
            bad(NewPatchForm {
                name: "a b".into(),
                ..ok.clone()
            })
            .contains("letters")
        );
        assert!(
            bad(NewPatchForm {
                name: "".into(),
                ..ok.clone()
            })
            .contains("letters")
        );
        let side_g2 = NewPatchForm {
            edge: Edge::First,
            continuity: Continuity::G2,
            ..ok.clone()
        };
        assert!(bad(side_g2).contains("future work"));
        let rows6 = NewPatchForm {
            rows: 6,
            ..ok.clone()
        };
        assert!(bad(rows6.clone()).contains("set rows to 5"));
        // a side join may have other rows
        let side = NewPatchForm {
            edge: Edge::Last,
            ..rows6
        };
        assert_eq!(new_patch_refusal(&r, &side, &r[0]), None);
        assert!(
            bad(NewPatchForm {
                length: f64::NAN,
                ..ok
            })
            .contains("positive")
        );
    }
}
