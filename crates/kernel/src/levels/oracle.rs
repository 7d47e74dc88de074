//! Test oracles of the levels: independent reference computations that the
//! kernel's unit tests compare the fast paths against; built only for them,
//! not part of the API (the integration tests write their own).

use crate::grid::Grid;
use crate::levels::scheme::{BlendOrder, Refine, SurfaceScheme, refine_cols, refine_rows};

/// One tensor-product step ([`crate::levels::surface::refine_grid`]) computed
/// the plain way, curve by curve (columns gathered into buffers): the
/// independent reference the windowed path is tested against.
pub fn refine_grid_gathered<T: Refine>(
    scheme: SurfaceScheme,
    order: BlendOrder,
    g: &Grid<T>,
) -> Grid<T> {
    let c = scheme.curve();
    match order {
        BlendOrder::SFirst => refine_cols(c, &refine_rows(c, g)),
        BlendOrder::TFirst => refine_rows(c, &refine_cols(c, g)),
    }
}
