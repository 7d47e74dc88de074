//! Why an edit failed: the errors of the edit stage ([`super::edit`],
//! [`super::authoring`]) and of the stages after it that report into
//! [`super::EditLog`] (tracking, blending, saving, exporting). Each variant
//! carries the values its message is made from; `Display` is the message
//! the user reads (the bad-input catalogue, `tests/bad_inputs.rs`).

use crate::scene::SceneError;
use std::fmt;
use streamline_kernel::{DVec3, KernelError};

/// An edit that was refused, or a stage that could not follow it.
#[derive(Debug, Clone, PartialEq)]
pub enum EditError {
    /// A handle outside the level being edited (`rows` × `cols` tangents).
    OutsideLevel {
        row: usize,
        col: usize,
        level: u32,
        rows: usize,
        cols: usize,
    },
    /// The level being edited is not built yet.
    LevelNotBuilt { level: u32 },
    /// A direction that is zero or not finite.
    BadDirection { dir: DVec3 },
    /// A rotation axis that is zero or not finite.
    BadAxis,
    /// An initial-curve rotation axis that is zero or not finite.
    BadInitialAxis { axis: DVec3 },
    /// A rotation angle that is not finite.
    BadAngle,
    /// A rotation of no handles.
    NoHandles,
    /// No detail to clear at this handle and level.
    NoDetail { row: usize, col: usize, level: u32 },
    /// With the mirror on, only the control tangents (edit depth 0) are handles.
    MirrorDepth,
    /// A length coefficient that is not a positive finite number.
    BadLength { k: f64 },
    /// A length coefficient that makes `s` overflow.
    LengthOverflow { k: f64 },
    /// A length coefficient the design refused.
    LengthRefused {
        k: f64,
        row: usize,
        col: usize,
        reason: Box<EditError>,
    },
    /// An initial-curve tangent index out of range (`len` tangents).
    InitialIndex { index: usize, len: usize },
    /// Nothing to undo.
    NothingToUndo,
    /// Nothing to redo.
    NothingToRedo,
    /// A drag to cancel that is not the last edit.
    NotLastDrag { group: u64 },
    /// A fine-tuning value the function refused.
    TuningValue(KernelError),
    /// The kernel refused, its message passed on.
    Kernel(KernelError),
    /// The kernel refused the mirrored (doubled) surface.
    MirroredSurface(KernelError),
    /// An authoring edit (`what`, its label) was refused.
    Refused {
        what: String,
        reason: Box<EditError>,
    },
    /// A scene file could not be loaded (the current scene is kept).
    Load(SceneError),
    /// A scene could not be saved.
    Save(SceneError),
    /// A mesh or CAD file could not be exported.
    Export(SceneError),
    /// The patch's scene could not be assembled from its entities.
    Assemble(String),
    /// The handles' values make no kernel design (the tracking stage).
    NoDesign(String),
    /// The levels could not be built afresh (the blend stage).
    RebuildFailed(KernelError),
    /// The kernel refused to update the dirty windows; everything is built afresh.
    IncrementalRefused(KernelError),
    /// An edit of the design's patches, or of a joined patch's handles,
    /// was refused: the message names the patch and the fix (docs/math.md §11).
    Patch(String),
}

impl From<KernelError> for EditError {
    fn from(e: KernelError) -> Self {
        EditError::Kernel(e)
    }
}

impl fmt::Display for EditError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        use EditError::*;
        match self {
            OutsideLevel {
                row,
                col,
                level,
                rows,
                cols,
            } => write!(
                f,
                "handle ({row}, {col}) is outside level {level}, which has {rows} rows of {cols} tangents; use row 0..{} and column 0..{}",
                rows.saturating_sub(1),
                cols.saturating_sub(1)
            ),
            LevelNotBuilt { level } => write!(
                f,
                "level {level} is not built yet; try again after the next update"
            ),
            BadDirection { dir } => write!(
                f,
                "direction ({}, {}, {}) is zero or not finite; give a non-zero direction",
                dir.x, dir.y, dir.z
            ),
            BadAxis => f.write_str("the rotation axis is zero or not finite; give a non-zero axis"),
            BadInitialAxis { axis } => write!(
                f,
                "the rotation axis ({}, {}, {}) is zero or not finite; give a non-zero direction",
                axis.x, axis.y, axis.z
            ),
            BadAngle => f.write_str("the rotation angle is not finite; give a number of degrees"),
            NoHandles => f.write_str("no handles to rotate; give at least one (row, col)"),
            NoDetail { row, col, level } => write!(
                f,
                "handle ({row}, {col}) at edit depth {level} has no detail to clear"
            ),
            MirrorDepth => f.write_str(
                "with the mirror on, the handles are the control tangents: set the edit depth to 0 first",
            ),
            BadLength { k } => write!(
                f,
                "length coefficient {k} must be a positive finite number (1 keeps the length)"
            ),
            LengthOverflow { k } => write!(
                f,
                "length coefficient {k} makes s overflow; use a smaller one"
            ),
            LengthRefused {
                k,
                row,
                col,
                reason,
            } => write!(
                f,
                "length coefficient {k} at ({row}, {col}) refused: {reason}"
            ),
            InitialIndex { index, len } => write!(
                f,
                "initial curve tangent {index} is out of range (there are {len}); use 0 to {}",
                len.saturating_sub(1)
            ),
            NothingToUndo => f.write_str("nothing to undo"),
            NothingToRedo => f.write_str("nothing to redo"),
            NotLastDrag { group } => write!(
                f,
                "drag {group} is not the last edit; nothing to cancel"
            ),
            TuningValue(e) => write!(f, "{e}; the fine-tuning values are unchanged"),
            Kernel(e) => write!(f, "{e}"),
            MirroredSurface(e) => write!(f, "the mirrored surface: {e}"),
            Refused { what, reason } => write!(f, "{what} refused: {reason}"),
            Load(e) => write!(f, "{e} (the current scene is kept)"),
            Save(e) | Export(e) => write!(f, "{e}"),
            Assemble(e) => f.write_str(e),
            NoDesign(e) => write!(f, "the handles make no design ({e})"),
            RebuildFailed(e) => write!(f, "rebuild failed: {e}"),
            IncrementalRefused(e) => write!(
                f,
                "incremental update refused ({e}); rebuilding in full"
            ),
            Patch(e) => f.write_str(e),
        }
    }
}

impl std::error::Error for EditError {}

#[cfg(test)]
mod tests {
    use super::EditError::{self, *};
    use std::path::PathBuf;
    use streamline_kernel::{DVec3, KernelError, Place};

    fn kernel() -> KernelError {
        KernelError::ZeroTangent {
            at: Place::Grid { row: 1, col: 2 },
        }
    }

    fn scene_error() -> crate::scene::SceneError {
        crate::scene::SceneError {
            file: PathBuf::from("a.ron"),
            line: 3,
            col: 4,
            message: "expected a number".into(),
        }
    }

    const KINDS: usize = 28;

    /// A number for each variant; exhaustive, so a new variant needs a sample.
    fn kind(e: &EditError) -> usize {
        match e {
            OutsideLevel { .. } => 0,
            LevelNotBuilt { .. } => 1,
            BadDirection { .. } => 2,
            BadAxis => 3,
            BadInitialAxis { .. } => 4,
            BadAngle => 5,
            NoHandles => 6,
            NoDetail { .. } => 7,
            MirrorDepth => 8,
            BadLength { .. } => 9,
            LengthOverflow { .. } => 10,
            LengthRefused { .. } => 11,
            InitialIndex { .. } => 12,
            NothingToUndo => 13,
            NothingToRedo => 14,
            NotLastDrag { .. } => 15,
            TuningValue(_) => 16,
            Kernel(_) => 17,
            MirroredSurface(_) => 18,
            Refused { .. } => 19,
            Load(_) => 20,
            Save(_) => 21,
            Export(_) => 22,
            Assemble(_) => 23,
            NoDesign(_) => 24,
            RebuildFailed(_) => 25,
            IncrementalRefused(_) => 26,
            Patch(_) => 27,
        }
    }

    /// Each variant, matched with its fields, says what it said as a string.
    #[test]
    fn messages_are_the_old_ones() {
        let k = kernel().to_string();
        let se = scene_error().to_string();
        let cases: Vec<(EditError, String)> = vec![
            (
                OutsideLevel {
                    row: 9,
                    col: 0,
                    level: 1,
                    rows: 5,
                    cols: 6,
                },
                "handle (9, 0) is outside level 1, which has 5 rows of 6 tangents; use row 0..4 and column 0..5".into(),
            ),
            (
                LevelNotBuilt { level: 2 },
                "level 2 is not built yet; try again after the next update".into(),
            ),
            (
                BadDirection {
                    dir: DVec3::new(0.0, f64::NAN, -0.0),
                },
                "direction (0, NaN, -0) is zero or not finite; give a non-zero direction".into(),
            ),
            (
                BadAxis,
                "the rotation axis is zero or not finite; give a non-zero axis".into(),
            ),
            (
                BadInitialAxis { axis: DVec3::ZERO },
                "the rotation axis (0, 0, 0) is zero or not finite; give a non-zero direction"
                    .into(),
            ),
            (
                BadAngle,
                "the rotation angle is not finite; give a number of degrees".into(),
            ),
            (
                NoHandles,
                "no handles to rotate; give at least one (row, col)".into(),
            ),
            (
                NoDetail {
                    row: 1,
                    col: 2,
                    level: 3,
                },
                "handle (1, 2) at edit depth 3 has no detail to clear".into(),
            ),
            (
                MirrorDepth,
                "with the mirror on, the handles are the control tangents: set the edit depth to 0 first".into(),
            ),
            (
                BadLength { k: -1.5 },
                "length coefficient -1.5 must be a positive finite number (1 keeps the length)"
                    .into(),
            ),
            (
                LengthOverflow { k: 1e308 },
                format!("length coefficient {} makes s overflow; use a smaller one", 1e308),
            ),
            (
                LengthRefused {
                    k: 2.0,
                    row: 0,
                    col: 3,
                    reason: Box::new(MirroredSurface(kernel())),
                },
                format!("length coefficient 2 at (0, 3) refused: the mirrored surface: {k}"),
            ),
            (
                InitialIndex { index: 7, len: 4 },
                "initial curve tangent 7 is out of range (there are 4); use 0 to 3".into(),
            ),
            (NothingToUndo, "nothing to undo".into()),
            (NothingToRedo, "nothing to redo".into()),
            (
                NotLastDrag { group: 12 },
                "drag 12 is not the last edit; nothing to cancel".into(),
            ),
            (
                TuningValue(kernel()),
                format!("{k}; the fine-tuning values are unchanged"),
            ),
            (Kernel(kernel()), k.clone()),
            (
                MirroredSurface(kernel()),
                format!("the mirrored surface: {k}"),
            ),
            (
                Refused {
                    what: "insert row 2".into(),
                    reason: Box::new(Kernel(kernel())),
                },
                format!("insert row 2 refused: {k}"),
            ),
            (
                Load(scene_error()),
                format!("{se} (the current scene is kept)"),
            ),
            (Save(scene_error()), se.clone()),
            (Export(scene_error()), se.clone()),
            (
                Assemble("the world has no patch".into()),
                "the world has no patch".into(),
            ),
            (
                NoDesign("a net handle is missing".into()),
                "the handles make no design (a net handle is missing)".into(),
            ),
            (RebuildFailed(kernel()), format!("rebuild failed: {k}")),
            (
                IncrementalRefused(kernel()),
                format!("incremental update refused ({k}); rebuilding in full"),
            ),
            (
                Patch("no patch `x`; the patches are `main`".into()),
                "no patch `x`; the patches are `main`".into(),
            ),
        ];
        for (e, want) in &cases {
            assert_eq!(&e.to_string(), want, "{e:?}");
        }
        // the samples cover every variant (a new one must be added here)
        let mut kinds: Vec<usize> = cases.iter().map(|(e, _)| kind(e)).collect();
        kinds.sort_unstable();
        kinds.dedup();
        assert_eq!(kinds, (0..KINDS).collect::<Vec<_>>());
    }

    /// The fields are there to match on.
    #[test]
    fn variants_carry_their_fields() {
        let e = OutsideLevel {
            row: 9,
            col: 0,
            level: 1,
            rows: 5,
            cols: 6,
        };
        assert!(matches!(
            e,
            OutsideLevel {
                row: 9,
                col: 0,
                level: 1,
                rows: 5,
                cols: 6
            }
        ));
        let e = LengthRefused {
            k: 2.0,
            row: 0,
            col: 3,
            reason: Box::new(Kernel(kernel())),
        };
        match &e {
            LengthRefused {
                k,
                row,
                col,
                reason,
            } => {
                assert_eq!((*k, *row, *col), (2.0, 0, 3));
                assert_eq!(**reason, Kernel(kernel()));
            }
            _ => panic!("{e:?}"),
        }
        let e = Refused {
            what: "mirror".into(),
            reason: Box::new(Kernel(kernel())),
        };
        assert!(
            matches!(&e, Refused { what, reason } if what == "mirror" && matches!(**reason, Kernel(_)))
        );
        assert!(matches!(NotLastDrag { group: 3 }, NotLastDrag { group: 3 }));
        assert!(matches!(
            InitialIndex { index: 7, len: 4 },
            InitialIndex { index: 7, len: 4 }
        ));
        assert!(matches!(
            NoDetail {
                row: 1,
                col: 2,
                level: 3
            },
            NoDetail {
                row: 1,
                col: 2,
                level: 3
            }
        ));
        assert!(matches!(BadLength { k: -1.5 }, BadLength { k } if k == -1.5));
        assert!(matches!(
            BadDirection { dir: DVec3::ZERO },
            BadDirection { dir } if dir == DVec3::ZERO
        ));
        assert_eq!(EditError::from(kernel()), Kernel(kernel()));
        assert!(matches!(Load(scene_error()), Load(s) if s.line == 3));
        let boxed: Box<dyn std::error::Error> = Box::new(NothingToUndo);
        assert_eq!(boxed.to_string(), "nothing to undo");
    }
}
