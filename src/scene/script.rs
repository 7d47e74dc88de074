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
use super::format::{
    ConstraintSpec, Dir, Finite, OrderSpec, Point, SchemeSpec, TemplateSpec, TuningSpec,
};
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// The most steps a script may hold (larger scripts are refused before running).
pub const MAX_STEPS: usize = 1_000_000;

/// A script file.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Script {
    /// The steps, run in order.
    pub steps: Vec<Step>,
}

/// One step.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum Step {
    /// Opens a scene file (relative to the script) or `builtin:NAME`.
    Load(String),
    /// Saves the scene (relative to the script).
    Save(String),
    /// Exports the surface (relative to the script) by the extension: the
    /// mesh as `.obj`, `.stl` or `.glb`, the fitted B-spline surface as
    /// `.step`/`.stp` or `.igs`/`.iges` (default degree and tolerance).
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
    /// Replaces the scene with a new, unsaved design from a template
    /// (`docs/math.md §9`); the scheme defaults to Kobbelt.
    NewDesign {
        rows: usize,
        cols: usize,
        length: Finite,
        template: TemplateSpec,
        #[serde(default)]
        scheme: Option<SchemeSpec>,
    },
    /// Inserts a control row (a streamline) so that it gets index `at` (0 ..= rows).
    InsertRow { at: usize },
    /// Inserts a control column so that it gets index `at` (0 ..= columns).
    InsertColumn { at: usize },
    /// Deletes control row `i` (the net keeps at least 2).
    DeleteRow(usize),
    /// Deletes control column `j` (the net keeps at least 2).
    DeleteColumn(usize),
    /// Points the initial curve's control tangent `index` in `dir`.
    SetInitialDirection { index: usize, dir: Dir },
    /// Rotates the initial curve's control tangent `index` about `axis` by `degrees`.
    RotateInitial {
        index: usize,
        axis: Dir,
        degrees: Finite,
    },
    /// The initial curve's arc length.
    SetInitialLength(Finite),
    /// The initial curve's start point.
    SetInitialOrigin(Point),
    /// The initial curve's QI order.
    SetInitialOrder(usize),
    /// The anchor column (where every streamline meets the initial curve).
    SetAnchor(usize),
    /// Makes control row `row`'s streamline exactly `length` long (Eq. 65).
    SetStreamlineLength { row: usize, length: Finite },
    /// Turns several handles `(row, col)` of the edit depth by one rotation.
    RotateMany {
        handles: Vec<(usize, usize)>,
        axis: Dir,
        degrees: Finite,
    },
    /// Mirror symmetry on or off (`docs/math.md §9`).
    SetMirror(bool),
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
        /// Control rows of the net.
        #[serde(default)]
        rows: Option<usize>,
        /// Control columns of the net.
        #[serde(default)]
        cols: Option<usize>,
        /// Mirror symmetry on.
        #[serde(default)]
        mirror: Option<bool>,
        /// The anchor column.
        #[serde(default)]
        anchor: Option<usize>,
        /// The initial curve's QI order.
        #[serde(default)]
        initial_order: Option<usize>,
    },
    /// Control row `row`'s streamline is `length` long, within `tolerance`.
    ExpectStreamlineLength {
        row: usize,
        length: Finite,
        tolerance: Finite,
    },
    /// The surface shown (both halves when mirrored) equals its reflection in
    /// the mirror plane within `tolerance`, and the mirror is on.
    ExpectMirrorSymmetric { tolerance: Finite },
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
    /// Every streamline point is the one under `mark` moved by `by`, within `tolerance`.
    ExpectShifted {
        mark: String,
        by: Point,
        tolerance: Finite,
    },
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
                | Step::ExpectStreamlineLength { .. }
                | Step::ExpectShifted { .. }
                | Step::ExpectMirrorSymmetric { .. }
        )
    }
}

impl Script {
    /// Parses script text.
    pub fn parse(text: &str, file: &Path) -> Result<Self, SceneError> {
        if text.trim().is_empty() {
            return Err(SceneError::at(
                file,
                1,
                1,
                "the file is empty; a script is `(steps: [ … ])` — see tests/scripts/01-set-direction.ron",
            ));
        }
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

/// Where a script's `Save` or `Export` of `p` writes, for a script in `dir`.
/// Scripts are data: they write only inside their own folder, so `p` must be
/// a relative path that never climbs above it (checked on the words of the
/// path; [`confine`] checks the folder on disk, links resolved).
pub fn output_path(dir: &Path, p: &str) -> Result<PathBuf, String> {
    use std::path::Component;
    let refuse = || {
        format!(
            "`{p}` would write outside the script's folder ({}); scripts write only there: give a relative path such as \"out/scene.ron\"",
            dir.display()
        )
    };
    let mut depth = 0i32;
    for c in Path::new(p).components() {
        match c {
            Component::Normal(_) => depth += 1,
            Component::CurDir => {}
            Component::ParentDir => depth -= 1,
            Component::RootDir | Component::Prefix(_) => depth = -1,
        }
        if depth < 0 {
            return Err(refuse());
        }
    }
    if depth == 0 {
        return Err(format!(
            "`{p}` names the script's folder itself, not a file; give a file name such as \"out/scene.ron\""
        ));
    }
    Ok(dir.join(p))
}

/// Creates the folder of `path` (from [`output_path`]) and checks that, with
/// symbolic links resolved, it still lies inside `dir`: a link inside the
/// script's folder cannot lead a write elsewhere.
pub fn confine(dir: &Path, path: &Path) -> Result<(), String> {
    let parent = path.parent().unwrap_or(dir);
    std::fs::create_dir_all(parent)
        .map_err(|e| format!("cannot create {}: {e}", parent.display()))?;
    let real_dir = dir
        .canonicalize()
        .map_err(|e| format!("cannot resolve {}: {e}", dir.display()))?;
    let real_parent = parent
        .canonicalize()
        .map_err(|e| format!("cannot resolve {}: {e}", parent.display()))?;
    let link_out = |p: &Path| {
        format!(
            "`{}` leads outside the script's folder ({}) through a symbolic link; scripts write only there",
            p.display(),
            real_dir.display()
        )
    };
    if !real_parent.starts_with(&real_dir) {
        return Err(link_out(path));
    }
    // the file itself may be a link to elsewhere
    if let Ok(meta) = std::fs::symlink_metadata(path)
        && meta.file_type().is_symlink()
    {
        return Err(link_out(path));
    }
    Ok(())
}
