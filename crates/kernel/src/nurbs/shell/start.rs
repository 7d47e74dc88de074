//! A later patch measured from where it starts (docs/math.md §11.5, "A
//! start that moves"): on an approximating scheme the earlier patch's edge
//! moves between depths by a length that halves per depth, and with it
//! the whole later patch, which its check grid one depth finer would read
//! as the fit's error. Each check row is moved back onto where
//! its row starts at the data's depth: what is measured is the patch's
//! shape from its start.

use super::PatchGrid;
use crate::grid::Grid;
use glam::DVec3;

impl PatchGrid {
    /// The check grid moved, row by row, onto the data's start (module
    /// docs): row `j`'s points `C_{j,i}` become
    ///
    /// ```text
    /// C'_{j,i} = C_{j,i} − (C_{j,0} − D(u₀, v_j))                       (77)
    /// ```
    ///
    /// with `u₀` the check's first column's parameter and `D` the tensor
    /// cubic through the nearest 4 × 4 data points (Lagrange's, on the
    /// data's parameters). Returns the farthest a row moved.
    pub fn hold_start(&mut self) -> f64 {
        let (data, check) = (&self.data, &mut self.check);
        let u0 = check.u[0];
        let mut moved = 0.0f64;
        for j in 0..check.points.rows() {
            let here = at(&data.points, &data.u, &data.v, u0, check.v[j]);
            let shift = check.points.get(j, 0) - here;
            moved = moved.max(shift.length());
            for p in check.points.row_mut(j) {
                *p -= shift;
            }
        }
        moved
    }
}

/// The nearest `n ≤ 4` of `xs` around `x`: the first index and `n`.
fn nearest_four(xs: &[f64], x: f64) -> (usize, usize) {
    let n = xs.len().min(4);
    let k = xs.partition_point(|&p| p <= x).saturating_sub(1);
    (k.saturating_sub(1).min(xs.len() - n), n)
}

/// Lagrange's weights of the nodes `xs` at `x`.
fn lagrange(xs: &[f64], x: f64) -> [f64; 4] {
    let mut w = [0.0; 4];
    for (i, wi) in w.iter_mut().enumerate().take(xs.len()) {
        *wi = (0..xs.len())
            .filter(|&k| k != i)
            .map(|k| (x - xs[k]) / (xs[i] - xs[k]))
            .product();
    }
    w
}

/// The tensor cubic through the nearest 4 × 4 points of a grid (fewer
/// where it has fewer rows or columns) at `(u, v)`.
fn at(points: &Grid<DVec3>, us: &[f64], vs: &[f64], u: f64, v: f64) -> DVec3 {
    let (j0, nj) = nearest_four(vs, v);
    let (i0, ni) = nearest_four(us, u);
    let wv = lagrange(&vs[j0..j0 + nj], v);
    let wu = lagrange(&us[i0..i0 + ni], u);
    let mut p = DVec3::ZERO;
    for (j, a) in wv.iter().enumerate().take(nj) {
        for (i, b) in wu.iter().enumerate().take(ni) {
            p += points.get(j0 + j, i0 + i) * (a * b);
        }
    }
    p
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The cubic is exact on a cubic, on uneven nodes, and a grid of two
    /// rows is a line across them.
    #[test]
    fn the_tensor_cubic_is_exact_on_cubics() {
        let f = |u: f64, v: f64| DVec3::new(u * u * u - v, u * v * v, 2.0 * v * v * v + u);
        let us = [0.0, 0.1, 0.35, 0.5, 0.8, 1.0];
        let vs = [0.0, 0.3, 0.45, 1.0];
        let pts: Vec<DVec3> = vs
            .iter()
            .flat_map(|&v| us.iter().map(move |&u| f(u, v)))
            .collect();
        let grid = Grid::new(vs.len(), us.len(), pts).unwrap();
        for (u, v) in [(0.02, 0.9), (0.4, 0.3), (0.97, 0.01)] {
            let p = at(&grid, &us, &vs, u, v);
            assert!(p.distance(f(u, v)) < 1e-12, "{p} {}", f(u, v));
        }
        let two = Grid::new(2, 2, vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::ONE]).unwrap();
        let p = at(&two, &[0.0, 1.0], &[0.0, 1.0], 0.25, 0.5);
        assert!(p.distance(DVec3::new(0.25, 0.5, 0.125)) < 1e-15, "{p}");
    }

    use crate::nurbs::samples::Samples;
    use proptest::prelude::*;

    /// Rising parameters from 0 to 1 with `n` uneven steps.
    fn rising(steps: &[f64]) -> Vec<f64> {
        let total: f64 = steps.iter().sum();
        let mut acc = 0.0;
        let mut out = vec![0.0];
        for s in steps {
            acc += s / total;
            out.push(acc);
        }
        *out.last_mut().unwrap() = 1.0;
        out
    }

    proptest! {
        /// Eq. 77 on a cubic surface: a check grid whose rows were each
        /// moved by a random vector is moved back onto the surface exactly,
        /// and the largest move is the largest of those vectors; a grid
        /// already on it does not move.
        #[test]
        fn a_check_grid_moved_row_by_row_comes_back_onto_a_cubic(
            c in prop::collection::vec(-1.0f64..1.0, 12),
            du in prop::collection::vec(0.2f64..1.0, 3..9),
            dv in prop::collection::vec(0.2f64..1.0, 3..9),
            shifts in prop::collection::vec(prop::array::uniform3(-1e-2f64..1e-2), 5..12),
            cu in prop::collection::vec(0.2f64..1.0, 4..12),
        ) {
            let f = |u: f64, v: f64| DVec3::new(
                c[0] * u * u * u + c[1] * v * v + c[2] * u * v + c[3],
                c[4] * v * v * v + c[5] * u * u * v + c[6] * u,
                c[7] * u * v * v + c[8] * v + c[9] * u * u + c[10] * u * u * v * v + c[11],
            );
            let grid = |us: &[f64], vs: &[f64], shift: &dyn Fn(usize) -> DVec3| {
                let pts = (0..vs.len())
                    .flat_map(|j| us.iter().map(move |&u| (u, j)))
                    .map(|(u, j)| f(u, vs[j]) + shift(j))
                    .collect();
                Grid::new(vs.len(), us.len(), pts).unwrap()
            };
            let (u, v) = (rising(&du), rising(&dv));
            // the check grid inside the data's: its first column near 0
            let cu = rising(&cu).iter().map(|x| 0.01 + 0.98 * x).collect::<Vec<_>>();
            let cv = rising(&vec![1.0; shifts.len() - 1]);
            let moved = |j: usize| DVec3::from(shifts[j]);
            let mut g = PatchGrid {
                name: "b".into(),
                data: Samples { points: grid(&u, &v, &|_| DVec3::ZERO), u: u.clone(), v: v.clone() },
                check: Samples { points: grid(&cu, &cv, &moved), u: cu.clone(), v: cv.clone() },
            };
            let most = shifts.iter().map(|s| DVec3::from(*s).length()).fold(0.0, f64::max);
            let reported = g.hold_start();
            prop_assert!((reported - most).abs() < 1e-12, "{reported} against {most}");
            let on = grid(&cu, &cv, &|_| DVec3::ZERO);
            for (p, q) in g.check.points.data().iter().zip(on.data()) {
                prop_assert!(p.distance(*q) < 1e-12, "{p} off {q}");
            }
            prop_assert!(g.hold_start() < 1e-12);
        }
    }
}
