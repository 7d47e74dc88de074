//! What a fit of a reference may be told (`docs/math.md §12`).

use crate::levels::surface::{BlendOrder, SurfaceScheme};

pub use crate::nurbs::fit::Tolerance;

/// The default relative tolerance: this fraction of the reference's
/// bounding-box diagonal (as for the B-spline export of §10).
pub const DEFAULT_RELATIVE_TOLERANCE: f64 = 1e-4;

/// The default fit depth: the depth at which the design is measured, shown
/// and exported.
pub const DEFAULT_DEPTH: u32 = 5;

/// The deepest fit depth accepted.
pub const MAX_FIT_DEPTH: u32 = 7;

/// The largest net side a fit may grow to (the authoring cap).
pub const MAX_NET_SIDE: usize = crate::authoring::MAX_NET_SIDE;

/// Which parameter of the reference the streamlines follow.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Along {
    /// Rows are the iso-curves `v = const` (the default).
    #[default]
    U,
    /// Rows are the iso-curves `u = const`.
    V,
}

/// Where each streamline is anchored on the initial curve.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum AnchorAt {
    /// At the rows' start, `u = u_min`: the initial curve is the boundary
    /// iso-curve (the default).
    #[default]
    First,
    /// At the middle of each row (half its arc length): the initial curve
    /// runs through the rows' midpoints and streamlines are integrated both
    /// ways from it (`docs/math.md §12`).
    Middle,
}

/// Everything a fit of a reference may be told.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ReferenceFitOptions {
    /// The streamlines' direction on the reference.
    pub along: Along,
    /// The anchor column.
    pub anchor: AnchorAt,
    /// How close the design must come, both ways.
    pub tolerance: Tolerance,
    /// The depth at which the design is measured (1 to [`MAX_FIT_DEPTH`]).
    pub depth: u32,
    /// The design's scheme.
    pub scheme: SurfaceScheme,
    /// The design's blend order.
    pub order: BlendOrder,
    /// The largest net, `(rows, columns)` of control tangents, each at
    /// most [`MAX_NET_SIDE`].
    pub max_net: (usize, usize),
}

impl Default for ReferenceFitOptions {
    fn default() -> Self {
        ReferenceFitOptions {
            along: Along::U,
            anchor: AnchorAt::First,
            tolerance: Tolerance::Relative(DEFAULT_RELATIVE_TOLERANCE),
            depth: DEFAULT_DEPTH,
            scheme: SurfaceScheme::default(),
            order: BlendOrder::SFirst,
            max_net: (MAX_NET_SIDE, MAX_NET_SIDE),
        }
    }
}
