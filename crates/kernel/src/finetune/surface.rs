//! Fine tuning a streamline surface (docs/math.md §6): one tensor function `α(u, v)`
//! over the surface (`u` along each streamline, `v` across the rows), applied
//! to each streamline as its restriction `α(·, v_row)`. A constraint on every
//! streamline (3 or 6 equations each) cannot in general be met by the few
//! tensor values (the paper's 3×3 or 3×4), so each streamline's own values
//! `dᵢ = Σ_j c_{j,i} M_j(v)` change instead, by the correction field of
//! docs/math.md §6, (T4)–(T6): every streamline's constraint met exactly,
//! the correction least-squares and smooth across the streamlines (a
//! streamline whose equations lose rank — the planar middle streamline of a
//! symmetric design — takes its neighbours' correction, not a jump).

use super::constraint::{Constraint, complement, project_out, row_space};
use super::streamline::{constraint_rows, integrate_tuned};
use crate::finetune::bspline::{BSpline, TensorBSpline};
use crate::grid::Grid;
use glam::DVec3;

/// The smoothing length `ℓ` of the correction field across the streamlines,
/// in `v` (the rows span `v ∈ [0, 1]`), docs/math.md §6, (T5): the
/// correction is smooth on this scale where the streamlines' constraints
/// change fast (a rank drop, a near one), and within `ℓ⁴` of the
/// per-streamline least-squares change where they do not.
pub const SMOOTHING_LENGTH: f64 = 0.2;

/// The largest banded system (unknowns × bandwidth²) the smooth correction
/// solves; beyond it (dozens of values along and thousands of streamlines)
/// each streamline keeps its own least-squares change ((T4) with `x = 0`).
pub const MAX_SMOOTHING_WORK: f64 = 4e8;

/// The fine-tuning of a surface: the function and the constraint.
#[derive(Debug, Clone, PartialEq)]
pub struct SurfaceTuning {
    /// `α(u, v)`: rows across the streamlines, columns along them.
    pub function: TensorBSpline,
    /// What every streamline keeps.
    pub constraint: Constraint,
}

impl SurfaceTuning {
    /// The paper's usual start: quadratic × quadratic, 3×3 values of 1 (changes nothing).
    pub fn identity() -> Self {
        SurfaceTuning {
            function: TensorBSpline::new(2, 2, Grid::filled(3, 3, 1.0)).expect("3×3 quadratic"),
            constraint: Constraint::Free,
        }
    }

    /// `v ∈ [0, 1]` of a row with parameter `t`, on rows spanning `[t_min, t_max]`.
    pub fn row_v(t: f64, t_min: f64, t_max: f64) -> f64 {
        if t_max > t_min {
            ((t - t_min) / (t_max - t_min)).clamp(0.0, 1.0)
        } else {
            0.0
        }
    }

    /// The function along the streamline at `v`.
    pub fn row_function(&self, v: f64) -> BSpline {
        self.function.along_at(v)
    }
}

/// One level of a surface as fine tuning reads it: the tangents and their arc
/// lengths `s` (one row per streamline), each row's parameter `t` across the
/// rows and its anchor arc length `σ` (the fields of a level's tangents and
/// `ParamGrid`).
#[derive(Debug, Clone, Copy)]
pub struct SurfaceRows<'a> {
    /// Unit tangents, one row per streamline.
    pub tangents: &'a Grid<DVec3>,
    /// Their arc lengths.
    pub s: &'a Grid<f64>,
    /// Each row's parameter across the rows.
    pub t: &'a [f64],
    /// Each row's anchor arc length.
    pub sigma: &'a [f64],
}

impl SurfaceRows<'_> {
    /// The number of streamlines.
    pub fn len(&self) -> usize {
        self.tangents.rows()
    }

    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Each row's `v ∈ [0, 1]` ([`SurfaceTuning::row_v`] over the rows' `t`).
    pub fn v(&self) -> Vec<f64> {
        let (lo, hi) = self
            .t
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| {
                (a.min(x), b.max(x))
            });
        self.t
            .iter()
            .map(|&t| SurfaceTuning::row_v(t, lo, hi))
            .collect()
    }
}

/// One streamline's share of (T4): an orthonormal basis `U` of its
/// equations' row space, the per-row least-squares correction
/// `p = −U Uᵀ (d − 1)` and an orthonormal basis `B` of the directions its
/// constraint leaves free.
struct RowSystem {
    own: Vec<Vec<f64>>,
    p: Vec<f64>,
    free: Vec<Vec<f64>>,
}

impl SurfaceTuning {
    /// The function every streamline of `rows` uses (docs/math.md §6,
    /// (T3)–(T6)): its restriction of the tensor function, changed by the
    /// smooth correction field that meets every streamline's constraint
    /// exactly. With [`Constraint::Free`] the restrictions themselves.
    pub fn row_functions(&self, rows: SurfaceRows<'_>) -> Vec<BSpline> {
        let v = rows.v();
        let mut fs: Vec<BSpline> = v.iter().map(|&v| self.row_function(v)).collect();
        if self.constraint == Constraint::Free || fs.is_empty() {
            return fs;
        }
        let m = fs[0].values().len();
        // (T3)–(T4), streamline by streamline
        let systems: Vec<RowSystem> = fs
            .iter()
            .enumerate()
            .map(|(r, f)| {
                let raw = constraint_rows(
                    rows.tangents.row(r),
                    rows.s.row(r),
                    rows.sigma[r],
                    f,
                    self.constraint,
                );
                let own = row_space(&raw);
                let d: Vec<f64> = f.values().iter().map(|x| x - 1.0).collect();
                let p = project_out(&d, &own)
                    .iter()
                    .zip(&d)
                    .map(|(a, b)| a - b)
                    .collect();
                let free = complement(&own, m);
                RowSystem { own, p, free }
            })
            .collect();
        // (T5): the free coordinates x of every row
        let x = smooth_coordinates(&systems, &v, m).unwrap_or_else(|| {
            systems
                .iter()
                .map(|sys| vec![0.0; sys.free.len()])
                .collect()
        });
        // (T6): c = d + p + B x, and once more c − 1 projected off the
        // row space (the rounding of p and B)
        for ((f, sys), xr) in fs.iter_mut().zip(&systems).zip(&x) {
            let mut e = sys.p.clone();
            for (b, xi) in sys.free.iter().zip(xr) {
                e.iter_mut().zip(b).for_each(|(ei, bi)| *ei += xi * bi);
            }
            let delta: Vec<f64> = f
                .values()
                .iter()
                .zip(&e)
                .map(|(a, b)| a - 1.0 + b)
                .collect();
            let c: Vec<f64> = project_out(&delta, &sys.own)
                .iter()
                .map(|x| x + 1.0)
                .collect();
            if c.iter().all(|x| x.is_finite()) {
                f.set_values(&c);
            }
        }
        fs
    }
}

/// Integrates every streamline of `rows` fine-tuned by `tuning` (the
/// functions of [`SurfaceTuning::row_functions`]), row `r` placed so that
/// its point at `σ_r` is `origins[r]`; `out` gets the rows one after another,
/// `n + 2` points each.
pub fn fine_tune_rows_into(
    rows: SurfaceRows<'_>,
    origins: &[DVec3],
    tuning: &SurfaceTuning,
    out: &mut Vec<DVec3>,
) {
    out.clear();
    let mut line = Vec::new();
    for (r, f) in tuning.row_functions(rows).iter().enumerate() {
        integrate_tuned(
            rows.tangents.row(r),
            rows.s.row(r),
            rows.sigma[r],
            origins[r],
            f,
            &mut line,
        );
        out.extend_from_slice(&line);
    }
}

/// (T5): the coordinates `x_r` (in each row's free basis `B_r`) of the
/// correction `e_r = p_r + B_r x_r` that minimises
/// `Σ w_r |e_r|² + ℓ⁴ Σ w_r |D²e_r|²` (the trapezoid rule for
/// `∫ |e|² + ℓ⁴ |∂²e/∂v²|² dv`, `D²` the three-point second difference on
/// the rows' `v`), by a banded Cholesky factorisation of the normal
/// equations. `None` when there is nothing to smooth, the system is too big
/// ([`MAX_SMOOTHING_WORK`]) or not positive definite in floating point.
fn smooth_coordinates(systems: &[RowSystem], v: &[f64], m: usize) -> Option<Vec<Vec<f64>>> {
    let n = systems.len();
    if n < 3 {
        return None;
    }
    let q: Vec<usize> = systems.iter().map(|s| s.free.len()).collect();
    let mut offset = vec![0usize; n + 1];
    for r in 0..n {
        offset[r + 1] = offset[r] + q[r];
    }
    let unknowns = offset[n];
    if unknowns == 0 {
        return None;
    }
    // each stencil couples rows r−1 … r+1
    let bw = (1..n - 1)
        .map(|r| offset[r + 2] - offset[r - 1])
        .max()
        .unwrap_or(1)
        .max(1)
        - 1;
    if unknowns as f64 * ((bw + 1) as f64).powi(2) > MAX_SMOOTHING_WORK {
        return None;
    }
    let lambda = SMOOTHING_LENGTH.powi(4);
    let gap = |r: usize| v[r + 1] - v[r];
    if (0..n - 1).any(|r| !(gap(r) > 0.0 && gap(r).is_finite())) {
        return None;
    }
    let mut h = Band::zeros(unknowns, bw);
    let mut g = vec![0.0; unknowns];
    // data term: w_r |p_r + B_r x_r|² = w_r (|p_r|² + |x_r|²), p_r ⟂ B_r
    for r in 0..n {
        let w = 0.5 * (if r > 0 { gap(r - 1) } else { 0.0 } + if r + 1 < n { gap(r) } else { 0.0 });
        for i in 0..q[r] {
            h.add(offset[r] + i, offset[r] + i, w);
        }
    }
    // smoothing term: λ w_r |Σ_j γ_j e_j|², j = r−1, r, r+1
    for r in 1..n - 1 {
        let (hm, hp) = (gap(r - 1), gap(r));
        let w = 0.5 * (hm + hp);
        let gamma = [
            2.0 / (hm * (hm + hp)),
            -2.0 / (hm * hp),
            2.0 / (hp * (hm + hp)),
        ];
        let rows3 = [r - 1, r, r + 1];
        // Σ_j γ_j p_j (an m-vector)
        let mut pp = vec![0.0; m];
        for (j, &rr) in rows3.iter().enumerate() {
            pp.iter_mut()
                .zip(&systems[rr].p)
                .for_each(|(a, b)| *a += gamma[j] * b);
        }
        // the columns γ_j B_j of the stencil, with their unknowns
        let mut cols: Vec<(usize, Vec<f64>)> = Vec::new();
        for (j, &rr) in rows3.iter().enumerate() {
            for (i, b) in systems[rr].free.iter().enumerate() {
                cols.push((offset[rr] + i, b.iter().map(|x| gamma[j] * x).collect()));
            }
        }
        let scale = lambda * w;
        for (a, (ia, ca)) in cols.iter().enumerate() {
            g[*ia] += scale * dot(ca, &pp);
            for (ib, cb) in cols.iter().take(a + 1) {
                let (hi, lo) = if ia >= ib { (*ia, *ib) } else { (*ib, *ia) };
                h.add(hi, lo, scale * dot(ca, cb));
            }
        }
    }
    if !g.iter().all(|x| x.is_finite()) {
        return None;
    }
    h.factor()?;
    let rhs: Vec<f64> = g.iter().map(|x| -x).collect();
    let x = h.solve(&rhs);
    if !x.iter().all(|v| v.is_finite()) {
        return None;
    }
    Some(
        (0..n)
            .map(|r| x[offset[r]..offset[r + 1]].to_vec())
            .collect(),
    )
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// A symmetric positive definite band matrix (lower half, half-bandwidth
/// `bw`) and its Cholesky factor in place.
struct Band {
    n: usize,
    bw: usize,
    a: Vec<f64>,
}

impl Band {
    fn zeros(n: usize, bw: usize) -> Self {
        Band {
            n,
            bw,
            a: vec![0.0; n * (bw + 1)],
        }
    }

    /// Entry `(i, j)`, `j ≤ i ≤ j + bw`.
    fn at(&mut self, i: usize, j: usize) -> &mut f64 {
        debug_assert!(j <= i && i - j <= self.bw);
        &mut self.a[i * (self.bw + 1) + (i - j)]
    }

    fn get(&self, i: usize, j: usize) -> f64 {
        self.a[i * (self.bw + 1) + (i - j)]
    }

    fn add(&mut self, i: usize, j: usize, v: f64) {
        *self.at(i, j) += v;
    }

    /// `A = L Lᵀ` in place; `None` when a pivot is not positive.
    fn factor(&mut self) -> Option<()> {
        for i in 0..self.n {
            let lo = i.saturating_sub(self.bw);
            for j in lo..=i {
                let mut sum = self.get(i, j);
                for k in lo.max(j.saturating_sub(self.bw))..j {
                    sum -= self.get(i, k) * self.get(j, k);
                }
                if i == j {
                    if !(sum > 0.0 && sum.is_finite()) {
                        return None;
                    }
                    *self.at(i, i) = sum.sqrt();
                } else {
                    *self.at(i, j) = sum / self.get(j, j);
                }
            }
        }
        Some(())
    }

    /// Solves `L Lᵀ x = b` with the factor.
    fn solve(&self, b: &[f64]) -> Vec<f64> {
        let mut y = b.to_vec();
        for i in 0..self.n {
            let lo = i.saturating_sub(self.bw);
            let sum: f64 = y[i]
                - (lo..i)
                    .zip(&y[lo..i])
                    .map(|(k, yk)| self.get(i, k) * yk)
                    .sum::<f64>();
            y[i] = sum / self.get(i, i);
        }
        for i in (0..self.n).rev() {
            let hi = (i + self.bw + 1).min(self.n);
            let sum: f64 = y[i]
                - (i + 1..hi)
                    .zip(&y[i + 1..hi])
                    .map(|(k, yk)| self.get(k, i) * yk)
                    .sum::<f64>();
            y[i] = sum / self.get(i, i);
        }
        y
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn band_cholesky_solves_like_dense_elimination() {
        // a symmetric positive definite pentadiagonal matrix
        let n = 9;
        let entry = |i: usize, j: usize| -> f64 {
            match i.abs_diff(j) {
                0 => 6.0 + i as f64 * 0.1,
                1 => -1.5 + 0.05 * (i + j) as f64,
                2 => 0.3,
                _ => 0.0,
            }
        };
        let mut band = Band::zeros(n, 2);
        for i in 0..n {
            for j in i.saturating_sub(2)..=i {
                band.add(i, j, entry(i, j));
            }
        }
        band.factor().expect("positive definite");
        let b: Vec<f64> = (0..n).map(|i| (i as f64 * 0.7).sin() + 1.0).collect();
        let x = band.solve(&b);
        for (i, bi) in b.iter().enumerate() {
            let ax: f64 = (0..n).map(|j| entry(i, j) * x[j]).sum();
            assert!((ax - bi).abs() < 1e-13, "row {i}: {ax} vs {bi}");
        }
        // not positive definite: refused
        let mut bad = Band::zeros(2, 1);
        bad.add(0, 0, 1.0);
        bad.add(1, 0, 2.0);
        bad.add(1, 1, 1.0);
        assert!(bad.factor().is_none());
    }

    #[test]
    fn row_space_keeps_small_rows_and_drops_rounding() {
        let rows = vec![
            vec![1.0, 2.0, 0.5, -1.0],
            vec![0.0, 1.0, 1.0, 1.0],
            // a small but real equation, and a combination of the first two
            vec![1e-9, -2e-9, 3e-9, 1e-9],
            vec![2.0, 5.0, 2.0, -1.0],
        ];
        let basis = row_space(&rows);
        assert_eq!(basis.len(), 3, "the small row is an equation");
        for (i, u) in basis.iter().enumerate() {
            for (j, w) in basis.iter().enumerate() {
                let d: f64 = u.iter().zip(w).map(|(a, b)| a * b).sum();
                let want = if i == j { 1.0 } else { 0.0 };
                assert!((d - want).abs() < 1e-14, "basis {i}·{j} = {d}");
            }
        }
        // every row lies in the span
        for row in &rows {
            let rest = project_out(row, &basis);
            let n: f64 = rest.iter().map(|x| x * x).sum::<f64>().sqrt();
            assert!(n < 1e-14, "a row outside the span by {n:e}");
        }
        // the complement completes it to an orthonormal basis of R⁴
        let free = complement(&basis, 4);
        assert_eq!(free.len(), 1);
        assert!(
            project_out(&free[0], &basis)
                .iter()
                .zip(&free[0])
                .all(|(a, b)| (a - b).abs() < 1e-14)
        );
        // a row of rounding (1e-18 of the others) is not an equation
        let noisy = vec![vec![1.0, 2.0, 0.5, -1.0], vec![1e-18, 3e-18, -1e-18, 2e-18]];
        assert_eq!(row_space(&noisy).len(), 1);
    }

    #[test]
    fn correction_meets_every_row_and_free_is_untouched() {
        // three rows of a wavy net, keep ends from the first point
        let rows = 5;
        let cols = 7;
        let mut t = Vec::new();
        let mut s = Vec::new();
        for r in 0..rows {
            for c in 0..cols {
                let (a, b) = (
                    0.4 * c as f64 - 1.0,
                    0.2 * (r as f64 - 2.0) * (c as f64 * 0.9).sin(),
                );
                t.push(DVec3::new(a.cos() * b.cos(), b.sin(), a.sin() * b.cos()));
                s.push(0.5 * c as f64);
            }
        }
        let tangents = Grid::new(rows, cols, t).unwrap();
        let s = Grid::new(rows, cols, s).unwrap();
        let tt: Vec<f64> = (0..rows).map(|r| 0.3 * r as f64).collect();
        let sigma = vec![0.0; rows];
        let view = SurfaceRows {
            tangents: &tangents,
            s: &s,
            t: &tt,
            sigma: &sigma,
        };
        let values = Grid::from_rows(&[
            vec![1.0, 0.7, 1.3, 1.1, 0.9],
            vec![1.2, 1.0, 0.8, 1.4, 1.0],
            vec![0.9, 1.1, 1.2, 0.8, 1.0],
        ])
        .unwrap();
        for constraint in [
            Constraint::Free,
            Constraint::KeepEnds,
            Constraint::KeepClosed,
        ] {
            let tuning = SurfaceTuning {
                function: TensorBSpline::new(2, 2, values.clone()).unwrap(),
                constraint,
            };
            let fs = tuning.row_functions(view);
            for (r, f) in fs.iter().enumerate() {
                if constraint == Constraint::Free {
                    assert_eq!(f, &tuning.row_function(view.v()[r]));
                    continue;
                }
                let a = constraint_rows(tangents.row(r), s.row(r), 0.0, f, constraint);
                for row in &a {
                    let moved: f64 = row.iter().zip(f.values()).map(|(x, c)| x * (c - 1.0)).sum();
                    assert!(moved.abs() < 1e-13, "row {r} ({constraint:?}): {moved:e}");
                }
                assert!(f.values() != tuning.row_function(view.v()[r]).values());
            }
        }
    }
}
