//! Scripts: a RON list of steps, each an edit message (what a user can do in
//! the editor) or an expectation checked by `streamline-studio play`.
//!
//! ```ron
//! (steps: [
//!     Load("../../scenes/car1.ron"),          // paths are relative to the script
//!     SetDirection(row: 2, col: 4, dir: (1.0, 0.0, 0.4)),
//!     ExpectStats(max_reintegrated: Some(40)),
//!     Undo,
//!     ExpectSame(mark: "start", tolerance: 0.0),
//! ])
//! ```

use super::error::SceneError;
use super::format::{ConstraintSpec, Dir, Finite, OrderSpec, Point, SchemeSpec, TuningSpec};
use serde::{Deserialize, Serialize};
use std::path::Path;

/// The most steps a script may hold (larger scripts are refused before running).
pub const MAX_STEPS: usize = 100_000;

/// A script file.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Script {
    /// The steps, run in order.
    pub steps: Vec<Step>,
}

/// One step.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub enum Step {
    /// Opens a scene file (relative to the script) or `builtin:NAME`.
    Load(String),
    /// Saves the scene (relative to the script).
    Save(String),
    /// Exports the surface mesh as `.obj` or `.stl` (relative to the script).
    Export(String),
    /// Points the handle `(row, col)` of the edit depth in `dir` (unit length kept).
    SetDirection { row: usize, col: usize, dir: Dir },
    /// Rotates the handle about `axis` by `degrees`.
    Rotate {
        row: usize,
        col: usize,
        axis: Dir,
        degrees: Finite,
    },
    /// Scales the `s` intervals on both sides of control tangent `(row, col)`.
    SetLength {
        row: usize,
        col: usize,
        coefficient: Finite,
    },
    /// Removes the detail of handle `(row, col)` at the edit depth.
    ClearDetail { row: usize, col: usize },
    /// Changes the scheme (and ω).
    SetScheme(SchemeSpec),
    /// Changes the blend order.
    SetBlendOrder(OrderSpec),
    /// Changes the display depth.
    SetDisplayDepth(u32),
    /// Changes the edit depth.
    SetEditDepth(u32),
    /// Turns fine tuning on with this function (see the scene's `tuning`), or off with `None`.
    SetTuning(Option<TuningSpec>),
    /// Sets fine-tuning control value `(row, col)` (row across, column along the streamlines).
    SetTuningValue {
        row: usize,
        col: usize,
        value: Finite,
    },
    /// What fine-tuned streamlines keep: `Free`, `KeepEnds` or `KeepClosed`.
    SetTuningConstraint(ConstraintSpec),
    /// Makes Catmull–Clark and Doo–Sabin pass through the interior control tangents, or not.
    SetInterpolateTangents(bool),
    /// Undoes the last edit.
    Undo,
    /// Redoes the last undone edit.
    Redo,
    /// Point `index` of streamline `row` (display depth) is within `tolerance` of `near`.
    ExpectPoint {
        row: usize,
        index: usize,
        near: Point,
        tolerance: Finite,
    },
    /// Bounds on what the last edit recomputed.
    ExpectStats {
        #[serde(default)]
        max_reblended: Option<usize>,
        #[serde(default)]
        max_reintegrated: Option<usize>,
        #[serde(default)]
        min_reintegrated: Option<usize>,
        #[serde(default)]
        full_rebuild: Option<bool>,
    },
    /// Properties of the scene.
    ExpectScene {
        #[serde(default)]
        display_depth: Option<u32>,
        #[serde(default)]
        edit_depth: Option<u32>,
        #[serde(default)]
        scheme: Option<SchemeSpec>,
        #[serde(default)]
        blend_order: Option<OrderSpec>,
        #[serde(default)]
        streamlines: Option<usize>,
        #[serde(default)]
        details: Option<usize>,
        #[serde(default)]
        can_undo: Option<bool>,
        #[serde(default)]
        can_redo: Option<bool>,
        #[serde(default)]
        tuning: Option<bool>,
        #[serde(default)]
        interpolate_tangents: Option<bool>,
    },
    /// The previous step failed with a message containing this text.
    ExpectError(String),
    /// Remembers every streamline point under a name.
    Mark(String),
    /// Every streamline point is within `tolerance` of those remembered under `mark`.
    ExpectSame { mark: String, tolerance: Finite },
    /// Every streamline point differs from `mark` by more than `tolerance` somewhere.
    ExpectChanged { mark: String, tolerance: Finite },
    /// The first and last points of every streamline are within `tolerance` of those under `mark`.
    ExpectEndsSame { mark: String, tolerance: Finite },
}

impl Step {
    /// Whether the step is an expectation (checked, not sent to the model).
    pub fn is_expectation(&self) -> bool {
        matches!(
            self,
            Step::ExpectPoint { .. }
                | Step::ExpectStats { .. }
                | Step::ExpectScene { .. }
                | Step::ExpectError(_)
                | Step::Mark(_)
                | Step::ExpectSame { .. }
                | Step::ExpectChanged { .. }
                | Step::ExpectEndsSame { .. }
        )
    }
}

impl Script {
    /// Parses script text.
    pub fn parse(text: &str, file: &Path) -> Result<Self, SceneError> {
        let s: Script = ron::Options::default()
            .from_str(text)
            .map_err(|e| SceneError::ron(file, text, &e))?;
        if s.steps.len() > MAX_STEPS {
            return Err(SceneError::locate(
                file,
                text,
                "steps",
                format!(
                    "{} steps is over the limit of {MAX_STEPS}; split the script",
                    s.steps.len()
                ),
            ));
        }
        Ok(s)
    }

    /// Reads a script file.
    pub fn load(path: &Path) -> Result<Self, SceneError> {
        let text = super::io::read_text(path, super::io::MAX_SCENE_BYTES)?;
        Script::parse(&text, path)
    }
}
