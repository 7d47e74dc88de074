//! Why a join is refused (docs/math.md §11, "Bad input"): each value names
//! what is wrong, where, and what to do.

use crate::error::KernelError;
use std::fmt;

/// A join that cannot be built as asked. New kinds may be added; match with
/// a `_` arm.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum JoinError {
    /// A patch's own build was refused (depth, parameters, …).
    Kernel(KernelError),
    /// A chain needs the same scheme (and ω) in both patches: their rows are
    /// the same rows at every depth.
    ChainSchemeDiffers { a: String, b: String },
    /// G2 subdivides both patches as one net: same scheme, ω and blend order.
    G2SchemeDiffers { a: String, b: String },
    /// A chain's patches have different numbers of rows.
    ChainRowCount { a: usize, b: usize },
    /// A chain's row `t` differ by more than [`crate::joins::chain::ROW_TOLERANCE`].
    ChainRowParam { row: usize, a: f64, b: f64 },
    /// A joined patch starts from its first column: its anchor must be 0.
    AnchorNotFirst { anchor: usize },
    /// On a G1/G2 chain, `B`'s first control column is `A`'s last (one handle).
    SeamColumnDiffers { row: usize, angle_deg: f64 },
    /// G2 across a side edge is not built.
    SideG2,
    /// A side patch's row `t` is outside `A`'s streamline `[0, L]`.
    SideParamOutside { row: usize, t: f64, length: f64 },
    /// A side patch's `t` must increase strictly along `A`'s streamline.
    SideParamsNotIncreasing { row: usize },
    /// A side G1 boundary tangent along `A`'s normal has no projection into
    /// `A`'s tangent plane.
    SideTangentAlongNormal { row: usize, level: u32 },
    /// A side join reads `A` at every depth `B` is built to.
    DepthMismatch { a: u32, b: u32 },
    /// A G2 run needs at least one patch.
    EmptyRun,
    /// A side join starts on edge `First` or `Last`, not `End`.
    NotASideEdge,
    /// A G2 chain changes `A` too: it is built as one net, not as `B` alone.
    G2IsOneNet,
    /// A G2 run's member (by its place in the run) has fine tuning.
    G2Tuning { member: usize },
}

impl From<KernelError> for JoinError {
    fn from(e: KernelError) -> Self {
        JoinError::Kernel(e)
    }
}

impl fmt::Display for JoinError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        use JoinError::*;
        match self {
            Kernel(e) => e.fmt(f),
            ChainSchemeDiffers { a, b } => write!(
                f,
                "a chain (edge End) makes B's rows A's rows at every depth, so both must refine their rows alike: A uses {a}, B uses {b}; give B A's scheme"
            ),
            G2SchemeDiffers { a, b } => write!(
                f,
                "a G2 chain subdivides A and B as one net, so they need the same scheme, omega and blend order: A uses {a}, B uses {b}; give B A's, or join with G1"
            ),
            ChainRowCount { a, b } => write!(
                f,
                "a chain (edge End) needs B's rows to be A's rows: A has {a} rows, B has {b}; give B {a} rows with A's t"
            ),
            ChainRowParam { row, a, b } => write!(
                f,
                "a chain (edge End) needs B's rows to be A's rows: row {row} has t = {a} in A but {b} in B; set B's t to A's"
            ),
            AnchorNotFirst { anchor } => write!(
                f,
                "a patch that starts on another patch's edge starts from its first column, but its anchor is column {anchor}; set its anchor to column 0"
            ),
            SeamColumnDiffers { row, angle_deg } => write!(
                f,
                "on a G1/G2 chain B's first control column is A's last (one handle), but at row {row} they are {} degrees apart; copy A's last column into B's first, or join with G0",
                readable_degrees(*angle_deg)
            ),
            SideG2 => write!(
                f,
                "G2 across a side edge (First or Last) is future work: the side construction holds G1 in the limit only; use G1 there, or chain on edge End for G2"
            ),
            SideParamOutside { row, t, length } => write!(
                f,
                "row {row} of a patch on a side edge starts at t = {t}, outside A's streamline, which is {length} long; give it a t from 0 to {length}"
            ),
            SideParamsNotIncreasing { row } => write!(
                f,
                "the rows of a patch on a side edge start at arc lengths t along A's streamline, which must increase strictly, but row {row} does not; order the rows along A's streamline"
            ),
            SideTangentAlongNormal { row, level } => write!(
                f,
                "the first-column tangent of row {row} (level {level}) points along A's surface normal where it starts, so it has no direction in A's tangent plane for G1; turn it towards A's surface, or join with G0"
            ),
            DepthMismatch { a, b } => write!(
                f,
                "B is asked for depth {b} but A was built to depth {a}; build A to depth {b} first"
            ),
            EmptyRun => write!(
                f,
                "a G2 run needs at least one patch; give it the chained patches in order"
            ),
            NotASideEdge => write!(
                f,
                "edge End is a chain, not a side edge; build it as a chain (joins::chain::chain), or start B on edge First or Last"
            ),
            G2IsOneNet => write!(
                f,
                "a G2 chain subdivides A and B as one net, so it changes A too; build both together (joins::merged::g2_run, or joins::join)"
            ),
            G2Tuning { member } => write!(
                f,
                "patch {} of the G2 chain has fine tuning, which scales its streamlines' speed, so the curvature across the seam becomes κ/α on each side and G2 holds only where both functions agree; turn fine tuning off on the chain, or join with G1",
                member + 1
            ),
        }
    }
}

impl std::error::Error for JoinError {}

/// An angle as a designer reads it: three decimals from a hundredth of a
/// degree up (`2.726`), otherwise in scientific notation (`3.1e-9`), so that
/// a rounding-sized difference does not print as `0.000`.
fn readable_degrees(deg: f64) -> String {
    if deg.abs() >= 0.01 {
        format!("{deg:.3}")
    } else {
        format!("{deg:.1e}")
    }
}
