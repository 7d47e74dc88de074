//! Error values of the kernel. Each names what is wrong, where, and the fix.

use std::fmt;

/// Where in the input a tangent or parameter sits.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Place {
    /// Index in a curve (a single row of tangents).
    Curve(usize),
    /// Row (streamline, parameter `t`) and column (parameter `s`) of a grid.
    Grid { row: usize, col: usize },
}

impl fmt::Display for Place {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Place::Curve(i) => write!(f, "tangent {i}"),
            Place::Grid { row, col } => write!(f, "row {row}, column {col}"),
        }
    }
}

/// Everything that can be wrong with input to the kernel. New kinds may be
/// added; match with a `_` arm.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum KernelError {
    /// A tangent of length zero has no direction.
    ZeroTangent { at: Place },
    /// A tangent with a NaN or infinite component.
    NonFiniteTangent { at: Place },
    /// ω of the 4-point rule outside `0 ≤ ω < 2(√5 − 1)`.
    OmegaOutOfRange { omega: f64 },
    /// Too few tangents for the scheme.
    TooFewTangents {
        what: &'static str,
        got: usize,
        need: usize,
    },
    /// QI curve order outside `2 ..= number of tangents`.
    OrderOutOfRange { order: usize, tangents: usize },
    /// A net (before any refinement) already has more than
    /// [`crate::limits::MAX_TANGENTS_PER_LEVEL`] tangents.
    TooManyTangents { tangents: usize, cap: usize },
    /// A depth past [`crate::limits::MAX_DEPTH`].
    DepthPastMax { depth: u32, max: u32 },
    /// Refining to `depth` would make a level of more than
    /// [`crate::limits::MAX_TANGENTS_PER_LEVEL`] tangents.
    DepthTooLarge {
        depth: u32,
        tangents: usize,
        cap: usize,
    },
    /// Rows of a grid differ in length.
    RaggedGrid {
        row: usize,
        len: usize,
        expected: usize,
    },
    /// Two inputs that must have matching lengths do not.
    LengthMismatch {
        what: &'static str,
        got: usize,
        expected: usize,
    },
    /// A parameter (s, t, σ, length, origin…) is NaN or infinite.
    NonFiniteParameter { what: &'static str, at: Place },
    /// Arc-length parameters must increase strictly along each row.
    ParamsNotIncreasing { level: u32, at: Place },
    /// An index (anchor column…) points outside its range.
    IndexOutOfRange {
        what: &'static str,
        index: usize,
        len: usize,
    },
    /// A positive quantity (length, sample count) is not positive.
    NotPositive { what: &'static str, value: f64 },
    /// A fine-tuning (scalar B-spline) function is not usable; `problem` says why and what to do.
    BadFunction { what: &'static str, problem: String },
    /// A coordinate or parameter is beyond [`crate::limits::MAX_COORDINATE`].
    TooLargeValue { what: &'static str, value: f64 },
    /// An authored net would be larger than [`crate::authoring::MAX_NET_SIDE`] a side.
    NetTooLarge {
        rows: usize,
        cols: usize,
        max: usize,
    },
    /// A delete would leave fewer than 2 rows or columns.
    NetTooSmall { what: &'static str, count: usize },
    /// An angle outside its open range `(lo, hi)` degrees.
    AngleOutOfRange {
        what: &'static str,
        degrees: f64,
        lo: f64,
        hi: f64,
    },
    /// A seam (row 0) tangent along the mirror plane's normal has no projection into the plane.
    SeamTangentAlongNormal { col: usize },
}

impl fmt::Display for KernelError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        use KernelError::*;
        match self {
            ZeroTangent { at } => write!(
                f,
                "{at} is the zero vector, which has no direction; give it a non-zero direction"
            ),
            NonFiniteTangent { at } => write!(
                f,
                "{at} has a NaN or infinite component; give it three finite numbers"
            ),
            OmegaOutOfRange { omega } => write!(
                f,
                "omega {omega} is outside the 4-point rule's range 0 <= omega < {:.6} (2(sqrt 5 - 1)); the default is 1",
                crate::limits::OMEGA_MAX
            ),
            TooFewTangents { what, got, need } => {
                write!(
                    f,
                    "{what} needs at least {need} tangents, got {got}; add tangents"
                )
            }
            OrderOutOfRange { order, tangents } => write!(
                f,
                "QI curve order {order} is not allowed with {tangents} tangents; use an order from 2 to {} (3, 4 or 5 are usual)",
                (*tangents).min(crate::limits::MAX_QI_ORDER)
            ),
            TooManyTangents { tangents, cap } => write!(
                f,
                "{tangents} tangents are asked for, over the cap of {cap} (what the {} MB memory cap affords); use fewer",
                crate::limits::MEMORY_CAP_BYTES >> 20
            ),
            DepthPastMax { depth, max } => write!(
                f,
                "depth {depth} is past the deepest level allowed ({max}); choose a smaller depth"
            ),
            DepthTooLarge {
                depth,
                tangents,
                cap,
            } => write!(
                f,
                "depth {depth} would produce {tangents} tangents per level, over the cap of {cap} (what the {} MB memory cap affords); choose a smaller depth",
                crate::limits::MEMORY_CAP_BYTES >> 20
            ),
            RaggedGrid { row, len, expected } => write!(
                f,
                "row {row} has {len} tangents but row 0 has {expected}; every row must have the same number"
            ),
            LengthMismatch {
                what,
                got,
                expected,
            } => {
                write!(
                    f,
                    "{what} has {got} entries but {expected} are needed; make the counts match"
                )
            }
            NonFiniteParameter { what, at } => {
                write!(f, "{what} at {at} is NaN or infinite; give a finite number")
            }
            ParamsNotIncreasing { level, at } => write!(
                f,
                "arc-length parameter s does not increase strictly at {at} (subdivision level {level}); make the intervals positive and neighbouring intervals more even"
            ),
            IndexOutOfRange { what, index, len } => {
                write!(
                    f,
                    "{what} {index} is out of range (there are {len}); use 0 to {}",
                    len.saturating_sub(1)
                )
            }
            NotPositive { what, value } => {
                write!(f, "{what} is {value}; it must be a positive finite number")
            }
            BadFunction { what, problem } => write!(f, "{what}: {problem}"),
            TooLargeValue { what, value } => write!(
                f,
                "{what} is {value:e}, beyond ±{:e}, the largest coordinate the kernel works with; scale the model down",
                crate::limits::MAX_COORDINATE
            ),
            NetTooLarge { rows, cols, max } => write!(
                f,
                "a {rows} x {cols} control net is past the {max} x {max} an authored net may have; use at most {max} rows and {max} columns"
            ),
            NetTooSmall { what, count } => write!(
                f,
                "the net has {count} {what}s and must keep at least 2; insert one before deleting this {what}"
            ),
            AngleOutOfRange {
                what,
                degrees,
                lo,
                hi,
            } => write!(
                f,
                "{what} is {degrees} degrees; it must lie strictly between {lo} and {hi} degrees"
            ),
            SeamTangentAlongNormal { col } => write!(
                f,
                "the seam tangent at row 0, column {col} points along the mirror plane's normal, so it has no direction in the plane; turn it away from the initial curve's first tangent before mirroring"
            ),
        }
    }
}

impl std::error::Error for KernelError {}
