//! A script's expectations ([`Expect`]), checked by `streamline-studio play`.

use crate::scene::files::format::{Finite, OrderSpec, Point, SchemeSpec};
use crate::scene::files::format_v3::ContinuitySpec;
use serde::{Deserialize, Serialize};

/// One expectation: checked by `streamline-studio play`, not sent to the model.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum Expect {
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
    /// Every streamline point of the first patch at the display depth (the
    /// design's own half when mirrored) is within `max` of the face the
    /// design's `reference` names, and, with `min: Some(m)`, some point is
    /// further than `m` (a design edited away from its reference); the
    /// distance is to the closest point of the face (docs/math.md §12,
    /// eq. 12.6). A design without a reference, or a reference file that
    /// cannot be read, is the step's error (which `ExpectError` can expect).
    ExpectReferenceDeviation {
        max: Finite,
        #[serde(default)]
        min: Option<Finite>,
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
    /// Every streamline point is the one under `mark` moved by `by`, within `tolerance`.
    ExpectShifted {
        mark: String,
        by: Point,
        tolerance: Finite,
    },
    /// The seam between patches `a` and `b` (which starts on `a`) has
    /// `continuity`, a gap of at most `max_gap` and a normal angle of at
    /// most `max_angle_deg` (docs/math.md §11). Naming a patch that is not
    /// there, or two patches without a seam, is the step's error (which
    /// `ExpectError` can expect).
    ExpectSeam {
        a: String,
        b: String,
        continuity: ContinuitySpec,
        max_gap: Finite,
        max_angle_deg: Finite,
    },
}
