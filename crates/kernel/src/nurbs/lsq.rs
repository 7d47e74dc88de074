//! Least-squares B-spline curves with both ends interpolated (Piegl &
//! Tiller §9.4.1), for many data rows that share their parameters: the
//! normal matrix `Nᵀ N` (banded, half bandwidth `p`) is factored once and
//! every row is one right-hand side (`docs/math.md §10`).
//!
//! Data `Q₀ … Q_m` at parameters `ū₀ = 0 < … < ū_m = 1`, poles
//! `P₀ … P_{n−1}` with `P₀ = Q₀`, `P_{n−1} = Q_m`; the interior poles solve
//! `(Nᵀ N) P = Nᵀ R` with `R_k = Q_k − N₀(ū_k) Q₀ − N_{n−1}(ū_k) Q_m`, over
//! the interior data `k = 1 … m−1` and interior functions `1 … n−2`.
//!
//! The normal equations square the condition number of `N`: a pole whose
//! function is small at every parameter it could be read from (Schoenberg–
//! Whitney barely met) would come out to `ε κ(N)²` only. Where the factor's
//! pivots spread over more than [`CORRECT_SPREAD`] (then `κ(Nᵀ N)` does
//! too), one correction step follows (Björck's corrected semi-normal
//! equations: the residual `r = R − N P` of the first solution, then
//! `(Nᵀ N) δ = Nᵀ r` with the same factor, `P + δ`), which brings the error
//! toward `ε κ(N)` (docs/math.md §10). Well-posed fits, the adaptive fit's
//! among them, skip it: it costs as much again as the solution.

use super::banded::{Banded, Singular};
use super::knots::{Basis, KnotVector};
use super::surface::curve_point;
use glam::DVec3;

/// The pivot spread of `Nᵀ N` (a lower bound of its condition number) past
/// which a fit takes the correction step: the plain solution may then be
/// off by more than about `2e-12` of the data's size.
pub(crate) const CORRECT_SPREAD: f64 = 20.0;

/// A factored end-interpolating fit for one knot vector and one parameter list.
#[derive(Debug, Clone)]
pub(crate) struct EndFixedFit {
    degree: usize,
    count: usize,
    basis: Vec<Basis>,
    normal: Banded,
    /// The pivot spread of the factor of `Nᵀ N` (a lower bound of its
    /// condition number): past [`CORRECT_SPREAD`], the solutions take the
    /// correction step.
    spread: f64,
}

impl EndFixedFit {
    /// Builds and factors `Nᵀ N`. Needs `count ≥ 3` and `params.len() ≥ count`.
    pub fn new(knots: &KnotVector, params: &[f64]) -> Result<Self, Singular> {
        let p = knots.degree();
        let count = knots.count();
        let basis: Vec<Basis> = params.iter().map(|&u| knots.basis(u)).collect();
        let unknowns = count - 2;
        let mut normal = Banded::zeros(unknowns, p);
        for (first, n) in &basis[1..basis.len() - 1] {
            for a in 0..=p {
                let i = first + a;
                if i == 0 || i + 1 >= count {
                    continue;
                }
                for b in 0..=a {
                    let j = first + b;
                    if j == 0 {
                        continue;
                    }
                    normal.add(i - 1, j - 1, n[a] * n[b]);
                }
            }
        }
        let spread = normal.factor()?;
        Ok(EndFixedFit {
            degree: p,
            count,
            basis,
            normal,
            spread,
        })
    }

    /// Whether the solutions take the correction step.
    fn corrects(&self) -> bool {
        self.spread > CORRECT_SPREAD
    }

    /// Number of poles per fitted row.
    pub fn count(&self) -> usize {
        self.count
    }

    /// Fits `cols` data series laid out as the rows of a `params.len() ×
    /// cols` row-major block `data` (series `c` is column `c`), writing a
    /// `count × cols` block of poles into `out`.
    pub(crate) fn fit_columns(&self, data: &[DVec3], cols: usize, out: &mut Vec<DVec3>) {
        let m = self.basis.len();
        debug_assert_eq!(data.len(), m * cols);
        let n = self.count;
        let unknowns = n - 2;
        out.clear();
        out.resize(n * cols, DVec3::ZERO);
        let (first_row, last_row) = (&data[..cols], &data[(m - 1) * cols..]);
        {
            let x = &mut out[cols..(n - 1) * cols];
            let mut r = vec![DVec3::ZERO; cols];
            // the first solution: Nᵀ R, solved
            for k in 1..m - 1 {
                self.end_free_row(data, cols, k, &mut r);
                self.add_transposed(k, &r, cols, x);
            }
            debug_assert_eq!(x.len(), unknowns * cols);
            self.normal.solve_rows(x, cols);
            if self.corrects() {
                self.correct_columns(data, cols, x);
            }
        }
        out[..cols].copy_from_slice(first_row);
        out[(n - 1) * cols..].copy_from_slice(last_row);
    }

    /// The correction step of [`Self::fit_columns`]: `Nᵀ (R − N x)`,
    /// solved, added to the interior poles `x` (`count − 2` rows of `cols`).
    fn correct_columns(&self, data: &[DVec3], cols: usize, x: &mut [DVec3]) {
        let m = self.basis.len();
        let mut r = vec![DVec3::ZERO; cols];
        let mut dx = vec![DVec3::ZERO; x.len()];
        for k in 1..m - 1 {
            self.end_free_row(data, cols, k, &mut r);
            for (row, w) in self.interior_at(k) {
                for (o, xi) in r.iter_mut().zip(&x[row * cols..(row + 1) * cols]) {
                    *o -= *xi * w;
                }
            }
            self.add_transposed(k, &r, cols, &mut dx);
        }
        self.normal.solve_rows(&mut dx, cols);
        for (xi, d) in x.iter_mut().zip(&dx) {
            *xi += *d;
        }
    }

    /// `R_k` of every series: data row `k` of the `cols`-wide block less
    /// the end poles' share (`Q₀ N₀(ū_k)`, `Q_m N_{n−1}(ū_k)`).
    fn end_free_row(&self, data: &[DVec3], cols: usize, k: usize, r: &mut [DVec3]) {
        let (p, n, m) = (self.degree, self.count, self.basis.len());
        let (f, b) = &self.basis[k];
        let n0 = if *f == 0 { b[0] } else { 0.0 };
        let nl = if f + p == n - 1 { b[p] } else { 0.0 };
        let row = &data[k * cols..(k + 1) * cols];
        let (first_row, last_row) = (&data[..cols], &data[(m - 1) * cols..]);
        for (c, x) in r.iter_mut().enumerate() {
            *x = row[c] - first_row[c] * n0 - last_row[c] * nl;
        }
    }

    /// Adds `N_i(ū_k) r` to row `i − 1` of `rhs` (`cols` wide) for every
    /// interior function `i` that is non-zero at `ū_k`.
    fn add_transposed(&self, k: usize, r: &[DVec3], cols: usize, rhs: &mut [DVec3]) {
        for (row, w) in self.interior_at(k) {
            for (o, x) in rhs[row * cols..(row + 1) * cols].iter_mut().zip(r) {
                *o += *x * w;
            }
        }
    }

    /// The interior functions non-zero at `ū_k`: each as its unknown's
    /// index (`i − 1`) and its value `N_i(ū_k)`.
    fn interior_at(&self, k: usize) -> impl Iterator<Item = (usize, f64)> + '_ {
        let (f, b) = &self.basis[k];
        b[..=self.degree]
            .iter()
            .enumerate()
            .map(move |(a, &w)| (f + a, w))
            .filter(|&(i, _)| i != 0 && i + 1 < self.count)
            .map(|(i, w)| (i - 1, w))
    }

    /// Fits one data row `q` (`params.len()` points) into `poles` (`count`).
    pub(crate) fn fit_row(&self, q: &[DVec3], poles: &mut [DVec3]) {
        match self.degree {
            2 => self.fit_row_p::<2>(q, poles),
            3 => self.fit_row_p::<3>(q, poles),
            4 => self.fit_row_p::<4>(q, poles),
            _ => self.fit_row_p::<5>(q, poles),
        }
    }

    /// [`Self::fit_row`] for degree `P` (unrolled). The right-hand side is
    /// summed into all `count` slots (no branch for the end functions) and
    /// the two end slots are then overwritten with the fixed end points;
    /// then the correction step of the module's header, the same way.
    fn fit_row_p<const P: usize>(&self, q: &[DVec3], poles: &mut [DVec3]) {
        let n = self.count;
        debug_assert_eq!(self.degree, P);
        let (q0, qm) = (q[0], q[q.len() - 1]);
        poles.fill(DVec3::ZERO);
        for (fb, qk) in self.basis[1..q.len() - 1].iter().zip(&q[1..q.len() - 1]) {
            let (f, b) = fb;
            let r = self.end_free::<P>(fb, *qk, q0, qm);
            let dst = &mut poles[*f..*f + P + 1];
            for a in 0..=P {
                dst[a] += r * b[a];
            }
        }
        self.normal.solve_vec(&mut poles[1..n - 1]);
        if self.corrects() {
            self.correct_row::<P>(q, poles);
        }
        poles[0] = q0;
        poles[n - 1] = qm;
    }

    /// The correction step of [`Self::fit_row_p`] on its first solution
    /// `poles` (interior slots; the end slots are overwritten after).
    fn correct_row<const P: usize>(&self, q: &[DVec3], poles: &mut [DVec3]) {
        let n = self.count;
        let (q0, qm) = (q[0], q[q.len() - 1]);
        // the residual of that solution (the end slots hold the end
        // functions' sums, not poles: zero there, as the end points' share
        // is taken out of the data already), its Nᵀ, solved, added
        poles[0] = DVec3::ZERO;
        poles[n - 1] = DVec3::ZERO;
        let mut dx = vec![DVec3::ZERO; n];
        for (fb, qk) in self.basis[1..q.len() - 1].iter().zip(&q[1..q.len() - 1]) {
            let (f, b) = fb;
            let x = &poles[*f..*f + P + 1];
            let mut r = self.end_free::<P>(fb, *qk, q0, qm);
            for a in 0..=P {
                r -= x[a] * b[a];
            }
            let dst = &mut dx[*f..*f + P + 1];
            for a in 0..=P {
                dst[a] += r * b[a];
            }
        }
        self.normal.solve_vec(&mut dx[1..n - 1]);
        for (x, d) in poles[1..n - 1].iter_mut().zip(&dx[1..n - 1]) {
            *x += *d;
        }
    }

    /// `R_k = Q_k − N₀(ū_k) Q₀ − N_{n−1}(ū_k) Q_m` for degree `P`, from
    /// the basis at `ū_k` (`f`: its first function).
    #[inline(always)]
    fn end_free<const P: usize>(&self, (f, b): &Basis, qk: DVec3, q0: DVec3, qm: DVec3) -> DVec3 {
        let n0 = if *f == 0 { b[0] } else { 0.0 };
        let nl = if f + P == self.count - 1 { b[P] } else { 0.0 };
        qk - q0 * n0 - qm * nl
    }

    /// The fitted curve with poles `poles` at data parameter `k`.
    #[inline]
    pub fn point(&self, poles: &[DVec3], k: usize) -> DVec3 {
        curve_point(poles, &self.basis[k], self.degree)
    }

    /// The span of data parameter `k`.
    #[inline]
    pub(crate) fn span_of(&self, k: usize) -> usize {
        self.basis[k].0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The poles of a degree-`p` curve with interior knots `interior`,
    /// sampled exactly at `params` and fitted back, with and without the
    /// correction step: the largest pole error of each, and the fit's pivot
    /// spread.
    fn round_trip(p: usize, interior: &[f64], params: &[f64]) -> (f64, f64, f64) {
        let knots = KnotVector::with_interior(p, interior).unwrap();
        let n = knots.count();
        let poles: Vec<DVec3> = (0..n)
            .map(|i| DVec3::new(i as f64, (i * i) as f64 * 0.3, (i as f64).sin()))
            .collect();
        let data: Vec<DVec3> = params
            .iter()
            .map(|&u| curve_point(&poles, &knots.basis(u), p))
            .collect();
        let worst = |got: &[DVec3]| {
            got.iter()
                .zip(&poles)
                .map(|(a, b)| (*a - *b).length())
                .fold(0.0, f64::max)
        };
        let mut fit = EndFixedFit::new(&knots, params).unwrap();
        let spread = fit.spread;
        let mut got = vec![DVec3::ZERO; n];
        fit.spread = f64::INFINITY;
        fit.fit_row(&data, &mut got);
        let corrected = worst(&got);
        // by columns too: two series side by side, the second moved
        let cols: Vec<DVec3> = data.iter().flat_map(|&d| [d, d + DVec3::X]).collect();
        let mut out = Vec::new();
        fit.fit_columns(&cols, 2, &mut out);
        let first: Vec<DVec3> = out.iter().step_by(2).copied().collect();
        let second: Vec<DVec3> = out
            .iter()
            .skip(1)
            .step_by(2)
            .map(|q| *q - DVec3::X)
            .collect();
        let corrected = corrected.max(worst(&first)).max(worst(&second));
        fit.spread = 0.0;
        fit.fit_row(&data, &mut got);
        (worst(&got), corrected, spread)
    }

    /// Schoenberg–Whitney barely met: the second cubic function is seen only
    /// at `ū = 0.211`, near the end of its support `[0, 0.2137]`, where it
    /// is `2.6e-6`, so `κ(N) ≳ 4e5` and the data's own rounding (`ε |Q|`)
    /// moves that pole by some `1e-10`. The normal equations alone give the
    /// poles back `1.7e-8` off (and `8e-8` in the property test's case this
    /// comes from); with the correction step, `1.5e-9` (by rows `7.5e-10`).
    /// The pivots spread `2.9e10`, far past [`CORRECT_SPREAD`].
    #[test]
    fn a_barely_seen_pole_comes_back_with_the_correction() {
        let params = [
            0.0, 0.211, 0.4387, 0.4542, 0.5444, 0.6144, 0.63, 0.7761, 0.8257, 0.8413, 0.8771,
            0.9674, 1.0,
        ];
        corrected_within(round_trip(3, &[0.05, 0.2137], &params), 3e-9, 5.0);
    }

    /// The fit takes the correction, which brings the poles within `bound`,
    /// `gain` times closer than the plain solution.
    fn corrected_within((plain, corrected, spread): (f64, f64, f64), bound: f64, gain: f64) {
        assert!(corrected < bound, "corrected {corrected:e}");
        assert!(
            plain > gain * corrected,
            "plain {plain:e}, corrected {corrected:e}"
        );
        assert!(spread > CORRECT_SPREAD, "spread {spread:e}");
    }

    /// A quintic with three interior knots at a property test's random
    /// parameters (every function seen at 1 % or more, pivot spread `7.2e2`):
    /// the normal equations alone missed a pole by `1.8e-9` in that test, by
    /// `5.3e-10` here; with the correction, `5.9e-12`.
    #[test]
    fn a_loosely_seen_quintic_comes_back_with_the_correction() {
        let params = [
            0.0,
            0.12303415426844726,
            0.24406088808977625,
            0.3378192658050536,
            0.46121220758509035,
            0.5115623012411799,
            0.59270341446727,
            0.7072358650480552,
            0.7269251657241814,
            0.7839633296221216,
            0.8599921258245574,
            0.8710553229817177,
            1.0,
        ];
        let interior = [0.0709731938499065, 0.19673598494687294, 0.4829403265922129];
        corrected_within(round_trip(5, &interior, &params), 1e-10, 10.0);
    }

    /// Well spread parameters under uniform knots: the pivots stay close
    /// (`2.4`; the adaptive fits on the car spread 1.9–2.8), so the
    /// correction is skipped, and the poles come back to `1.3e-14` without it.
    #[test]
    fn a_well_posed_fit_skips_the_correction() {
        let params: Vec<f64> = (0..=40).map(|k| k as f64 / 40.0).collect();
        let (plain, _, spread) = round_trip(3, &[0.25, 0.5, 0.75], &params);
        assert!(spread < CORRECT_SPREAD, "spread {spread:e}");
        assert!(plain < 1e-12, "plain {plain:e}");
    }
}
