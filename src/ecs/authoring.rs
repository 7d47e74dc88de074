//! Authoring edits (`docs/math.md §9`): a new design, structure edits, the
//! initial curve, the anchor and streamline lengths as handles, mirror
//! symmetry. Each is computed on the scene by a kernel function on `Design`;
//! the edit stage writes the result into the patch's components, and what
//! the pipeline redoes follows from which of them differ
//! ([`super::patch::track`]):
//! * a new net shape (insert, delete, mirror on or off): everything, and the
//!   multiresolution details are dropped in the same undo step (a changed net
//!   cannot keep their meaning), which the message says;
//! * an initial-curve or anchor edit: every streamline is placed again, moved
//!   rigidly (Eq. 1), and no tangent is re-blended (`σ` of every level from
//!   [`sigma_of_levels`]);
//! * a streamline length: that row's `s`, through its handles.

use super::components::{LevelData, SubdivisionLevel};
use super::edit_error::EditError;
use crate::scene::Scene;
pub use crate::scene::edits::edit::AuthorEdit;
use crate::scene::files::format::InitialSpec;
use bevy::prelude::*;
use streamline_kernel::levels::incremental::check_params;
use streamline_kernel::{DQuat, DVec3, Design, KernelError, Tangent};

/// What an authoring edit did to the scene.
#[derive(Debug)]
pub(crate) enum Effect {
    /// A new scene replaces the old one (history cleared).
    NewScene(Box<Scene>),
    /// The scene was changed in place (what to redo follows from the
    /// components that differ, [`super::patch::track`]).
    Changed,
}

/// Checks a scene after an authoring edit: its design (and with the mirror
/// on, the doubled one) can be built to the scene's depth.
pub(crate) fn check_scene(scene: &Scene) -> Result<(), EditError> {
    let depth = scene.max_depth();
    let check = |d: &Design| -> Result<(), KernelError> {
        d.scheme()
            .check_depth(d.net().rows(), d.net().cols(), depth)?;
        check_params(d, depth)
    };
    check(&scene.design)?;
    if let Some(m) = scene.mirrored_design() {
        check(&m?).map_err(EditError::MirroredSurface)?;
    }
    Ok(())
}

/// Drops the details (a structure edit), saying how many.
fn drop_details(scene: &mut Scene) -> String {
    let n = scene.details.len();
    scene.details.clear();
    if n == 0 {
        String::new()
    } else {
        format!(
            " ({n} multiresolution detail{} dropped: a changed net cannot keep their meaning; undo brings them back)",
            if n == 1 { "" } else { "s" }
        )
    }
}

/// Applies `e` to a copy of `scene`; on success the copy replaces it and
/// the effect says what to redo. On failure the scene is unchanged.
pub(crate) fn apply(scene: &mut Scene, e: &AuthorEdit) -> Result<(String, Effect), EditError> {
    let mut s = scene.clone();
    let d = &scene.design;
    let label = e.label();
    let refused = |what: &str, reason: EditError| EditError::Refused {
        what: what.to_string(),
        reason: Box::new(reason),
    };
    let (msg, effect) = match e {
        AuthorEdit::NewDesign {
            rows,
            cols,
            length,
            template,
            scheme,
        } => {
            let new = Scene::new_design(*rows, *cols, *length, *template, *scheme)?;
            let msg = format!(
                "new {rows} × {cols} design, display depth {}",
                new.display_depth
            );
            return Ok((msg, Effect::NewScene(Box::new(new))));
        }
        AuthorEdit::InsertRow { .. }
        | AuthorEdit::InsertColumn { .. }
        | AuthorEdit::DeleteRow(_)
        | AuthorEdit::DeleteColumn(_) => {
            if s.mirror && s.edit_depth > 0 {
                return Err(EditError::MirrorDepth);
            }
            let (axis, at) = e.structure().expect("a structure edit");
            s.design = match e {
                AuthorEdit::InsertRow { .. } | AuthorEdit::InsertColumn { .. } => {
                    d.inserted(axis, at)
                }
                _ => d.deleted(axis, at),
            }
            .map_err(|x| refused(&label, x.into()))?;
            if s.mirror {
                s.design = s.design.with_seam_in_plane()?;
            }
            let dropped = drop_details(&mut s);
            (
                format!(
                    "{label}: the net is {} × {}{dropped}",
                    s.design.net().rows(),
                    s.design.net().cols()
                ),
                Effect::Changed,
            )
        }
        AuthorEdit::SetInitialDirection { .. }
        | AuthorEdit::RotateInitial { .. }
        | AuthorEdit::SetInitialLength(_)
        | AuthorEdit::SetInitialOrigin(_)
        | AuthorEdit::SetInitialOrder(_) => {
            s.design = initial_edit(d, e)?;
            s.initial = InitialSpec::from_kernel(s.design.initial());
            if s.mirror {
                // the mirror plane follows the curve: the seam is projected again
                s.design = s.design.with_seam_in_plane()?;
                (
                    format!("{label} (mirrored: seam re-projected)"),
                    Effect::Changed,
                )
            } else {
                (label.clone(), Effect::Changed)
            }
        }
        AuthorEdit::SetAnchor(col) => {
            s.design = d.with_anchor(*col)?;
            (label.clone(), Effect::Changed)
        }
        AuthorEdit::SetStreamlineLength { row, length } => {
            s.design = d
                .with_streamline_length(*row, *length)
                .map_err(|x| refused(&label, x.into()))?;
            (label.clone(), Effect::Changed)
        }
        AuthorEdit::SetMirror(on) => {
            if *on && s.edit_depth > 0 {
                return Err(EditError::MirrorDepth);
            }
            let mut dropped = String::new();
            if *on {
                s.design = d
                    .with_seam_in_plane()
                    .map_err(|x| refused("mirror", x.into()))?;
                dropped = drop_details(&mut s);
            }
            s.mirror = *on;
            (format!("{label}{dropped}"), Effect::Changed)
        }
    };
    check_scene(&s).map_err(|x| refused(&label, x))?;
    *scene = s;
    Ok((msg, effect))
}

/// `v` as a unit vector, or `bad` when it is zero or not finite.
fn unit(v: DVec3, bad: impl FnOnce(DVec3) -> EditError) -> Result<DVec3, EditError> {
    Tangent::new(v).map(Tangent::get).map_err(|_| bad(v))
}

fn initial_edit(d: &Design, e: &AuthorEdit) -> Result<Design, EditError> {
    let dir = |dir| EditError::BadDirection { dir };
    let axis = |axis| EditError::BadInitialAxis { axis };
    Ok(match *e {
        AuthorEdit::SetInitialDirection { index, dir: v } => {
            d.with_initial_direction(index, unit(v, dir)?)?
        }
        AuthorEdit::RotateInitial {
            index,
            axis: a,
            radians,
        } => {
            let a = unit(a, axis)?;
            if !radians.is_finite() {
                return Err(EditError::BadAngle);
            }
            let ts = d.initial().qi().tangents();
            let cur = *ts.get(index).ok_or(EditError::InitialIndex {
                index,
                len: ts.len(),
            })?;
            d.with_initial_direction(index, DQuat::from_axis_angle(a, radians) * cur)?
        }
        AuthorEdit::SetInitialLength(l) => d.with_initial_length(l)?,
        AuthorEdit::SetInitialOrigin(o) => d.with_initial_origin(o)?,
        AuthorEdit::SetInitialOrder(o) => d.with_initial_order(o)?,
        _ => unreachable!("initial_edit is called for initial-curve edits only"),
    })
}

/// `σ` of every level after an initial-curve or anchor edit: level 0's
/// (`s` of the anchor column) refined level by level with the scheme's scalar
/// step, the very step [`streamline_kernel::levels::params::ParamGrid::refine`] takes
/// in a full build (so the same bits), written into the levels where it
/// differs. Returns them by level. No tangent is touched.
pub(crate) fn sigma_of_levels(
    design: &Design,
    levels: &mut Query<(Entity, &SubdivisionLevel, &mut LevelData)>,
) -> Vec<Vec<f64>> {
    let mut ls: Vec<_> = levels.iter_mut().map(|(_, l, d)| (l.0, d)).collect();
    ls.sort_by_key(|(l, _)| *l);
    let c = design.scheme().curve();
    let mut out: Vec<Vec<f64>> = Vec::with_capacity(ls.len());
    for (l, data) in &mut ls {
        let sigma = match out.last() {
            Some(prev) if *l > 0 => {
                let mut next = Vec::new();
                c.refine_scalars(prev, &mut next);
                next
            }
            _ => design.params().sigma.clone(),
        };
        if data.0.params.sigma != sigma {
            data.0.params.sigma.clone_from(&sigma);
        }
        out.push(sigma);
    }
    out
}
