//! Tensor-product subdivision surfaces on the Gaussian sphere (paper 000, §4).
//!
//! An open regular control net of `nt` rows × `ns` columns of tangents; each row
//! is one streamline (parameter `s` along it, `t` across rows).
//! Kobbelt = 4-point ⊗ 4-point, Catmull–Clark = cubic B-spline ⊗ cubic B-spline,
//! Doo–Sabin = Chaikin ⊗ Chaikin. On the sphere the two directions do not
//! commute, so the [`BlendOrder`] is chosen by the scene (000 §4, last paragraph
//! before §5): [`BlendOrder::SFirst`] refines every row, then every column of the result.

use crate::error::{KernelError, Place};
use crate::grid::Grid;
use crate::levels::dirty_window::{DirtyWindow, half_shape, refine_grid_window};
use crate::sphere::tangent::normalize_at;
use glam::DVec3;

// The scheme types and the one-direction steps, defined in `scheme.rs`
// (below `dirty_window.rs`, which this file's whole-grid step runs); their
// public paths stay `levels::surface::…`.
pub use crate::levels::scheme::{BlendOrder, Refine, SurfaceScheme, refine_cols, refine_rows};

/// One tensor-product step in the given blend order: the whole grid as one
/// window (`crate::levels::dirty_window::refine_grid_window`: rows and columns both
/// passed row by row, large grids on two threads).
pub fn refine_grid<T: Refine + Send + Sync>(
    scheme: SurfaceScheme,
    order: BlendOrder,
    g: &Grid<T>,
) -> Grid<T> {
    let (mut half, mut next) = (
        Grid::filled(0, 0, T::default()),
        Grid::filled(0, 0, T::default()),
    );
    refine_grid_into(scheme, order, g, &mut half, &mut next);
    next
}

/// [`refine_grid`] into buffers kept by the caller: `half` (the grid of the
/// first direction; left empty where the step needs none,
/// [`crate::levels::dirty_window::in_place`]) and `next` are reshaped and overwritten.
pub(crate) fn refine_grid_into<T: Refine + Send + Sync>(
    scheme: SurfaceScheme,
    order: BlendOrder,
    g: &Grid<T>,
    half: &mut Grid<T>,
    next: &mut Grid<T>,
) {
    let c = scheme.curve();
    let (hr, hc) = half_shape(scheme, order, g.rows(), g.cols());
    half.reshape(hr, hc, T::default());
    next.reshape(
        c.refined_len(g.rows()),
        c.refined_len(g.cols()),
        T::default(),
    );
    refine_grid_window(
        scheme,
        order,
        g,
        half,
        next,
        DirtyWindow::all(g.rows(), g.cols()),
    );
}

/// Normalises every tangent of a net, reporting the first bad one by row and column.
pub fn normalize_grid(g: &Grid<DVec3>) -> Result<Grid<DVec3>, KernelError> {
    let mut out = g.clone();
    for r in 0..g.rows() {
        for c in 0..g.cols() {
            out.set(
                r,
                c,
                normalize_at(g.get(r, c), Place::Grid { row: r, col: c })?,
            );
        }
    }
    Ok(out)
}

/// Refines a net of tangents `depth` times: the kernel's boundary for surfaces.
pub fn subdivide(
    scheme: SurfaceScheme,
    order: BlendOrder,
    net: &Grid<DVec3>,
    depth: u32,
) -> Result<Grid<DVec3>, KernelError> {
    let scheme = scheme.validate()?;
    scheme.check_depth(net.rows(), net.cols(), depth)?;
    let mut g = normalize_grid(net)?;
    for _ in 0..depth {
        g = refine_grid(scheme, order, &g);
    }
    Ok(g)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `refine_grid_into` reshapes `half` as `half_shape` says (empty where
    /// the step runs in place) and gives `refine_grid`'s numbers.
    #[test]
    fn refine_grid_into_shapes_half_and_matches_refine_grid() {
        let data = (0..70 * 9)
            .map(|i| {
                let a = i as f64 * 0.37;
                DVec3::new(a.cos(), a.sin(), 0.3).normalize()
            })
            .collect();
        let g = Grid::new(70, 9, data).unwrap();
        for scheme in [SurfaceScheme::default(), SurfaceScheme::CatmullClark] {
            for order in [BlendOrder::SFirst, BlendOrder::TFirst] {
                let (mut half, mut next) = (
                    Grid::filled(3, 3, DVec3::ZERO),
                    Grid::filled(0, 0, DVec3::ZERO),
                );
                refine_grid_into(scheme, order, &g, &mut half, &mut next);
                let shape = half_shape(scheme, order, g.rows(), g.cols());
                assert_eq!((half.rows(), half.cols()), shape, "{scheme:?} {order:?}");
                assert_eq!(next, refine_grid(scheme, order, &g), "{scheme:?} {order:?}");
            }
        }
    }

    #[test]
    fn surface_counts_car_net() {
        let net = Grid::filled(6, 9, DVec3::X);
        let g = subdivide(SurfaceScheme::default(), BlendOrder::SFirst, &net, 5).unwrap();
        assert_eq!(
            (g.rows(), g.cols()),
            (161, 257),
            "9x6 Kobbelt depth 5 is 257x161"
        );
        let cc = SurfaceScheme::CatmullClark.check_depth(6, 9, 2).unwrap();
        assert_eq!(cc, (15, 27));
        assert!(matches!(
            SurfaceScheme::default().check_depth(6, 9, 12),
            Err(KernelError::DepthTooLarge { depth: 12, .. })
        ));
        assert!(matches!(
            SurfaceScheme::default().check_depth(6, 9, 17),
            Err(KernelError::DepthPastMax { depth: 17, max: 16 })
        ));
        assert!(matches!(
            SurfaceScheme::default().check_depth(4000, 1001, 0),
            Err(KernelError::TooManyTangents {
                tangents: 4_004_000,
                ..
            })
        ));
    }
}
