//! Edit messages: the only way the model changes. The editor, scripts and the
//! command line send the same messages.

use crate::scene::Scene;
use bevy::prelude::*;
use std::path::PathBuf;
use streamline_kernel::finetune::{Constraint, SurfaceTuning};
use streamline_kernel::{BlendOrder, DVec3, SurfaceScheme};

/// One edit.
#[derive(Debug, Clone)]
pub enum Edit {
    /// Points handle `(row, col)` of the edit depth in `dir` (normalised).
    SetDirection { row: usize, col: usize, dir: DVec3 },
    /// Rotates handle `(row, col)` of the edit depth about `axis` by `radians`.
    Rotate {
        row: usize,
        col: usize,
        axis: DVec3,
        radians: f64,
    },
    /// Scales the `s` intervals on both sides of control tangent `(row, col)`.
    SetLength {
        row: usize,
        col: usize,
        coefficient: f64,
    },
    /// Removes the detail of handle `(row, col)` at the edit depth.
    ClearDetail { row: usize, col: usize },
    /// Scheme and ω.
    SetScheme(SurfaceScheme),
    /// Blend order.
    SetBlendOrder(BlendOrder),
    /// Levels shown.
    SetDisplayDepth(u32),
    /// Level of the handles.
    SetEditDepth(u32),
    /// Turns fine tuning on with this function and constraint, or off (docs/math.md §6).
    SetTuning(Option<SurfaceTuning>),
    /// Sets fine-tuning control value `(row, col)` (row across the
    /// streamlines, column along them); turns fine tuning on (3×3 quadratic) if off.
    SetTuningValue { row: usize, col: usize, value: f64 },
    /// What fine-tuned streamlines keep; turns fine tuning on if off.
    SetTuningConstraint(Constraint),
    /// Interpolate the control tangents (Catmull–Clark, Doo–Sabin) or not.
    SetInterpolateTangents(bool),
    /// Cancel a drag: restore the scene from before the first edit of `group`
    /// and forget that undo step (no redo). Esc during a drag sends it.
    CancelGroup(u64),
    /// Undo the last edit.
    Undo,
    /// Redo the last undone edit.
    Redo,
    /// Open a scene file; on failure the current scene stays.
    Load(PathBuf),
    /// Replace the scene (new, built-in, recovered).
    Replace(Box<Scene>),
    /// Reopen autosaved work: replace the scene, remember the file it belongs
    /// to, and keep it marked unsaved.
    Recover {
        /// The autosaved scene.
        scene: Box<Scene>,
        /// The file it was edited from.
        origin: Option<PathBuf>,
    },
    /// Save to a file (atomic, verified).
    Save(PathBuf),
    /// Export the surface: the mesh (`.obj`, `.stl`, `.glb`) or its fitted
    /// B-spline surface (`.step`/`.stp`, `.igs`/`.iges`), by the extension.
    Export(PathBuf),
    /// Turns handles `(row, col)` of the edit depth by one rotation about
    /// `axis` (one undo step; refused whole if one handle is out of range).
    RotateMany {
        handles: Vec<(usize, usize)>,
        axis: DVec3,
        radians: f64,
    },
    /// An authoring edit (`docs/math.md §9`): new design, structure, initial
    /// curve, anchor, streamline length, mirror.
    Author(super::authoring::AuthorEdit),
}

impl Edit {
    /// A short description for logs and stats.
    pub fn label(&self) -> String {
        match self {
            Edit::SetDirection { row, col, .. } => format!("set direction ({row}, {col})"),
            Edit::Rotate {
                row, col, radians, ..
            } => {
                format!("rotate ({row}, {col}) by {:.3}°", radians.to_degrees())
            }
            Edit::SetLength {
                row,
                col,
                coefficient,
            } => {
                format!("length coefficient {coefficient} at ({row}, {col})")
            }
            Edit::ClearDetail { row, col } => format!("clear detail ({row}, {col})"),
            Edit::SetScheme(s) => format!("scheme {}", s.name()),
            Edit::SetBlendOrder(o) => format!("blend order {}", o.name()),
            Edit::SetDisplayDepth(d) => format!("display depth {d}"),
            Edit::SetEditDepth(d) => format!("edit depth {d}"),
            Edit::SetTuning(Some(_)) => "fine tuning on".into(),
            Edit::SetTuning(None) => "fine tuning off".into(),
            Edit::SetTuningValue { row, col, value } => {
                format!("fine-tuning value ({row}, {col}) = {value}")
            }
            Edit::SetTuningConstraint(c) => format!("fine-tuning constraint {}", c.name()),
            Edit::SetInterpolateTangents(on) => format!("interpolate control tangents {on}"),
            Edit::CancelGroup(_) => "cancel drag".into(),
            Edit::Undo => "undo".into(),
            Edit::Redo => "redo".into(),
            Edit::Load(p) => format!("load {}", p.display()),
            Edit::Replace(s) => format!("open {}", s.name),
            Edit::Recover { scene, .. } => format!("recover {}", scene.name),
            Edit::Save(p) => format!("save {}", p.display()),
            Edit::Export(p) => format!("export {}", p.display()),
            Edit::RotateMany {
                handles, radians, ..
            } => format!(
                "rotate {} handles by {:.3}°",
                handles.len(),
                radians.to_degrees()
            ),
            Edit::Author(a) => a.label(),
        }
    }

    /// Whether the edit changes the model (and so gets an undo step).
    pub fn is_undoable(&self) -> bool {
        if let Edit::Author(a) = self {
            return a.is_undoable();
        }
        !matches!(
            self,
            Edit::Undo
                | Edit::CancelGroup(_)
                | Edit::Redo
                | Edit::Load(_)
                | Edit::Replace(_)
                | Edit::Recover { .. }
                | Edit::Save(_)
                | Edit::Export(_)
        )
    }
}

/// An edit, with an optional group: consecutive edits of one group (a drag)
/// make one undo step.
#[derive(Message, Debug, Clone)]
pub struct EditMessage {
    /// The edit.
    pub edit: Edit,
    /// Edits with the same group as the previous one share its undo step.
    pub group: Option<u64>,
}

impl From<Edit> for EditMessage {
    fn from(edit: Edit) -> Self {
        EditMessage { edit, group: None }
    }
}
