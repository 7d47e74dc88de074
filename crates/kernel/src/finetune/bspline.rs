//! Scalar B-spline functions: the fine-tuning functions `α(u)` and `α(u, v)`
//! of paper 003 (docs/math.md §6), on clamped uniform knot vectors over `[0, 1]`.
//!
//! A function of degree `p` with `m` control values `c₀ … c_{m−1}` is
//! `α(u) = Σ cᵢ N_{i,p}(u)` on the knots `0 (p+1 times), 1/(m−p), …, 1 (p+1 times)`.
//! The basis sums to one, so all values 1 give `α ≡ 1` (the identity: nothing
//! changes). The antiderivative of a B-spline is a B-spline of degree `p+1`
//! on the same knots with each end knot repeated once more, and control
//! values `e₀ = 0`, `e_{i+1} = eᵢ + cᵢ (k_{i+p+1} − kᵢ)/(p+1)` (de Boor), which
//! makes `∫ α` exact (no quadrature).

use crate::error::KernelError;
use crate::grid::Grid;

/// The largest degree accepted (quintic).
pub const MAX_DEGREE: usize = 5;

/// The most control values accepted in one direction.
pub const MAX_VALUES: usize = 64;

/// The largest magnitude of a control value. `α` scales arc length, so a
/// value of 1000 already stretches a streamline a thousandfold; larger
/// values only overflow the integrated points to infinity (found by fuzzing).
pub const MAX_VALUE_ABS: f64 = 1e3;

/// A scalar B-spline function on `[0, 1]` (arguments outside are clamped).
#[derive(Debug, Clone, PartialEq)]
pub struct BSpline {
    degree: usize,
    knots: Vec<f64>,
    values: Vec<f64>,
}

/// Checks a degree and control values; `what` names them in the message.
fn check(degree: usize, values: &[f64], what: &'static str) -> Result<(), KernelError> {
    if degree > MAX_DEGREE || values.len() > MAX_VALUES {
        return Err(KernelError::BadFunction {
            what,
            problem: format!(
                "degree {degree} with {} control values is outside the limits (degree ≤ {MAX_DEGREE}, at most {MAX_VALUES} values)",
                values.len()
            ),
        });
    }
    if values.len() < degree + 1 {
        return Err(KernelError::BadFunction {
            what,
            problem: format!(
                "degree {degree} needs at least {} control values, got {}; add values or lower the degree",
                degree + 1,
                values.len()
            ),
        });
    }
    if let Some(i) = values
        .iter()
        .position(|v| v.is_finite() && v.abs() > MAX_VALUE_ABS)
    {
        return Err(KernelError::BadFunction {
            what,
            problem: format!(
                "control value {i} is {}, outside -{MAX_VALUE_ABS} ..= {MAX_VALUE_ABS}; give a smaller value (1 everywhere changes nothing)",
                values[i]
            ),
        });
    }
    if let Some(i) = values.iter().position(|v| !v.is_finite()) {
        return Err(KernelError::BadFunction {
            what,
            problem: format!(
                "control value {i} is {}; give finite numbers (1 everywhere changes nothing)",
                values[i]
            ),
        });
    }
    Ok(())
}

/// The clamped uniform knot vector of degree `p` with `m` control values.
fn clamped_knots(p: usize, m: usize) -> Vec<f64> {
    let spans = m - p;
    let mut k = vec![0.0; p + 1];
    k.extend((1..spans).map(|i| i as f64 / spans as f64));
    k.extend(std::iter::repeat_n(1.0, p + 1));
    k
}

impl BSpline {
    /// Degree `degree` with control values `values` on clamped uniform knots.
    pub fn uniform(degree: usize, values: Vec<f64>) -> Result<Self, KernelError> {
        check(degree, &values, "fine-tuning function")?;
        Ok(BSpline {
            degree,
            knots: clamped_knots(degree, values.len()),
            values,
        })
    }

    /// The constant function 1 (`degree + 1` values of 1).
    pub fn identity(degree: usize) -> Self {
        BSpline::uniform(
            degree.min(MAX_DEGREE),
            vec![1.0; degree.min(MAX_DEGREE) + 1],
        )
        .expect("valid by construction")
    }

    /// The degree.
    pub fn degree(&self) -> usize {
        self.degree
    }

    /// The control values.
    pub fn values(&self) -> &[f64] {
        &self.values
    }

    /// The knot vector.
    pub fn knots(&self) -> &[f64] {
        &self.knots
    }

    /// Replaces the control values (same count; finite, not re-checked).
    pub(crate) fn set_values(&mut self, values: &[f64]) {
        debug_assert_eq!(values.len(), self.values.len());
        self.values.copy_from_slice(values);
    }

    /// The knot span `μ` holding `u` (`k_μ ≤ u < k_{μ+1}`, the last span for `u = 1`)
    /// and the `p+1` basis values `N_{μ−p … μ, p}(u)` (Cox–de Boor, triangular form).
    pub fn basis(&self, u: f64) -> (usize, [f64; MAX_DEGREE + 2]) {
        basis_at(&self.knots, self.degree, self.values.len(), u)
    }

    /// `α(u)`, `u` clamped to `[0, 1]`.
    pub fn eval(&self, u: f64) -> f64 {
        let (mu, n) = self.basis(u);
        let p = self.degree;
        (0..=p).map(|j| n[j] * self.values[mu - p + j]).sum()
    }

    /// The antiderivative `A(u) = ∫₀ᵘ α`, exactly, as a B-spline of degree `p+1`.
    pub(crate) fn antiderivative(&self) -> BSpline {
        let p = self.degree;
        let k = &self.knots;
        let mut knots = Vec::with_capacity(k.len() + 2);
        knots.push(k[0]);
        knots.extend_from_slice(k);
        knots.push(k[k.len() - 1]);
        let mut values = Vec::with_capacity(self.values.len() + 1);
        let mut e = 0.0;
        values.push(e);
        for (i, c) in self.values.iter().enumerate() {
            e += c * (k[i + p + 1] - k[i]) / (p + 1) as f64;
            values.push(e);
        }
        BSpline {
            degree: p + 1,
            knots,
            values,
        }
    }

    /// `∫₀ᵘ Nᵢ` for every basis function `i` at once (the columns of the
    /// fine-tuning constraints): the antiderivative of basis `i` has values
    /// `wᵢ = (k_{i+p+1} − kᵢ)/(p+1)` from index `i+1` on, so
    /// `∫₀ᵘ Nᵢ = wᵢ · Σ_{j>i} N'_j(u)` with `N'` the degree `p+1` basis.
    pub(crate) fn basis_integrals(&self, u: f64, out: &mut [f64]) {
        let p = self.degree;
        let m = self.values.len();
        debug_assert_eq!(out.len(), m);
        let k = &self.knots;
        // the antiderivative's knots are these with each end repeated once
        // more; its span search and basis read them through an offset view
        let (mu, n) = basis_at_extended(k, p + 1, m + 1, u);
        let first = mu - (p + 1);
        for (i, o) in out.iter_mut().enumerate() {
            // Σ_{j > i} N'_j(u) over the nonzero N'_first … N'_mu
            let tail: f64 = n
                .iter()
                .take(p + 2)
                .enumerate()
                .filter(|(jj, _)| first + jj > i)
                .map(|(_, v)| v)
                .sum();
            *o = tail * (k[i + p + 1] - k[i]) / (p + 1) as f64;
        }
    }
}

/// [`basis_at`] on `knots` with its first and last knot repeated once more
/// (the antiderivative's knot vector), without building it.
fn basis_at_extended(knots: &[f64], p: usize, m: usize, u: f64) -> (usize, [f64; MAX_DEGREE + 2]) {
    let last = knots.len() - 1;
    let kn = |i: usize| {
        if i == 0 {
            knots[0]
        } else {
            knots[(i - 1).min(last)]
        }
    };
    basis_with(kn, p, m, u)
}

/// Basis values of degree `p` on `knots` (with `m` control values) at `u`.
fn basis_at(knots: &[f64], p: usize, m: usize, u: f64) -> (usize, [f64; MAX_DEGREE + 2]) {
    basis_with(|i| knots[i], p, m, u)
}

/// Cox–de Boor in triangular form (NURBS Book A2.2) on knots read through `kn`.
fn basis_with(
    kn: impl Fn(usize) -> f64,
    p: usize,
    m: usize,
    u: f64,
) -> (usize, [f64; MAX_DEGREE + 2]) {
    let u = u.clamp(kn(p), kn(m));
    // the span: largest μ in p..m with knots[μ] ≤ u, and μ ≤ m−1
    let mut mu = p;
    while mu + 1 < m && kn(mu + 1) <= u {
        mu += 1;
    }
    let mut n = [0.0; MAX_DEGREE + 2];
    let mut left = [0.0; MAX_DEGREE + 2];
    let mut right = [0.0; MAX_DEGREE + 2];
    n[0] = 1.0;
    for j in 1..=p {
        left[j] = u - kn(mu + 1 - j);
        right[j] = kn(mu + j) - u;
        let mut saved = 0.0;
        for r in 0..j {
            let den = right[r + 1] + left[j - r];
            let tmp = if den > 0.0 { n[r] / den } else { 0.0 };
            n[r] = saved + right[r + 1] * tmp;
            saved = left[j - r] * tmp;
        }
        n[j] = saved;
    }
    (mu, n)
}

/// A tensor-product function `α(u, v) = Σ c_{j,i} M_j(v) N_i(u)`: `u` along
/// the streamlines (`s`), `v` across them (`t`); `values` has one row per `v`
/// control value (the paper's surfaces use 3×3 and 3×4). Two functions are
/// equal when their degrees, knots and control values are (`along` and
/// `across` carry the bases; their own values are not the function's).
#[derive(Debug, Clone)]
pub struct TensorBSpline {
    along: BSpline,
    across: BSpline,
    values: Grid<f64>,
}

impl PartialEq for TensorBSpline {
    fn eq(&self, o: &Self) -> bool {
        self.along.degree == o.along.degree
            && self.across.degree == o.across.degree
            && self.along.knots == o.along.knots
            && self.across.knots == o.across.knots
            && self.values == o.values
    }
}

impl TensorBSpline {
    /// Degrees along `s` and across (`t`), and the control values (rows across).
    pub fn new(degree_s: usize, degree_t: usize, values: Grid<f64>) -> Result<Self, KernelError> {
        let row0 = values.row(0).to_vec();
        let col0 = values.column(0);
        check(degree_s, &row0, "fine-tuning function along s")?;
        check(
            degree_t,
            &col0,
            "fine-tuning function across streamlines (t)",
        )?;
        if let Some(i) = values.data().iter().position(|v| !v.is_finite()) {
            let (row, col) = (i / values.cols(), i % values.cols());
            return Err(KernelError::BadFunction {
                what: "fine-tuning function",
                problem: format!(
                    "control value ({row}, {col}) is {}; give finite numbers (1 everywhere changes nothing)",
                    values.data()[i]
                ),
            });
        }
        Ok(TensorBSpline {
            along: BSpline::uniform(degree_s, row0)?,
            across: BSpline::uniform(degree_t, col0)?,
            values,
        })
    }

    /// Degree along `s`.
    pub fn degree_s(&self) -> usize {
        self.along.degree
    }

    /// Degree across (`t`).
    pub fn degree_t(&self) -> usize {
        self.across.degree
    }

    /// The control values (rows across, columns along).
    pub fn values(&self) -> &Grid<f64> {
        &self.values
    }

    /// Sets control value `(row, col)` (must be finite).
    pub fn set(&mut self, row: usize, col: usize, v: f64) -> Result<(), KernelError> {
        let (rows, cols) = (self.values.rows(), self.values.cols());
        if row >= rows || col >= cols {
            return Err(KernelError::BadFunction {
                what: "fine-tuning function",
                problem: format!(
                    "control value ({row}, {col}) is out of range: there are {rows} rows (across the streamlines) of {cols} values (along them); use row 0..{} and column 0..{}",
                    rows - 1,
                    cols - 1
                ),
            });
        }
        if !v.is_finite() {
            return Err(KernelError::BadFunction {
                what: "fine-tuning function",
                problem: format!("control value ({row}, {col}) is {v}; give a finite number"),
            });
        }
        if v.abs() > MAX_VALUE_ABS {
            return Err(KernelError::BadFunction {
                what: "fine-tuning function",
                problem: format!(
                    "control value ({row}, {col}) is {v}, outside -{MAX_VALUE_ABS} ..= {MAX_VALUE_ABS}; give a smaller value"
                ),
            });
        }
        self.values.set(row, col, v);
        Ok(())
    }

    /// The function along one streamline at `v` ∈ [0, 1]: control values
    /// `dᵢ = Σ_j c_{j,i} M_j(v)`.
    pub(crate) fn along_at(&self, v: f64) -> BSpline {
        let (mu, m) = self.across.basis(v);
        let q = self.across.degree;
        let cols = self.values.cols();
        let mut d = vec![0.0; cols];
        for (jj, w) in m.iter().enumerate().take(q + 1) {
            let row = self.values.row(mu - q + jj);
            for (di, ci) in d.iter_mut().zip(row) {
                *di += w * ci;
            }
        }
        let mut f = self.along.clone();
        f.values = d;
        f
    }

    /// `α(u, v)`.
    pub fn eval(&self, u: f64, v: f64) -> f64 {
        self.along_at(v).eval(u)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Cox–de Boor written from the recursive definition (independent of `basis_at`).
    fn n_rec(k: &[f64], i: usize, p: usize, u: f64) -> f64 {
        if p == 0 {
            let last = k[k.len() - 1];
            return if (k[i] <= u && u < k[i + 1]) || (u == last && k[i] < u && k[i + 1] == last) {
                1.0
            } else {
                0.0
            };
        }
        let a = if k[i + p] > k[i] {
            (u - k[i]) / (k[i + p] - k[i]) * n_rec(k, i, p - 1, u)
        } else {
            0.0
        };
        let b = if k[i + p + 1] > k[i + 1] {
            (k[i + p + 1] - u) / (k[i + p + 1] - k[i + 1]) * n_rec(k, i + 1, p - 1, u)
        } else {
            0.0
        };
        a + b
    }

    #[test]
    fn bspline_matches_recursive_definition() {
        for p in 0..=4 {
            for m in p + 1..p + 6 {
                let vals: Vec<f64> = (0..m).map(|i| 1.0 + 0.3 * (i as f64 * 1.7).sin()).collect();
                let f = BSpline::uniform(p, vals.clone()).unwrap();
                for s in 0..=50 {
                    let u = s as f64 / 50.0;
                    let want: f64 = (0..m).map(|i| vals[i] * n_rec(f.knots(), i, p, u)).sum();
                    assert!(
                        (f.eval(u) - want).abs() < 1e-13,
                        "p={p} m={m} u={u}: {} vs {want}",
                        f.eval(u)
                    );
                }
            }
        }
    }

    #[test]
    fn bspline_antiderivative_is_exact_integral() {
        for p in 0..=3 {
            let vals: Vec<f64> = (0..p + 4).map(|i| 0.5 + (i as f64 * 0.9).cos()).collect();
            let f = BSpline::uniform(p, vals).unwrap();
            let a = f.antiderivative();
            // Simpson's rule span by span (exact for degree ≤ 3 inside a knot span)
            let simpson = |u: f64| {
                let mut cuts: Vec<f64> = f.knots().iter().copied().filter(|&k| k < u).collect();
                cuts.push(u);
                cuts.dedup();
                let mut total = 0.0;
                for w in cuts.windows(2) {
                    let (x0, x1) = (w[0], w[1]);
                    let xm = 0.5 * (x0 + x1);
                    // evaluate just inside the span (degree 0 jumps at knots)
                    let e = 1e-15;
                    total += (f.eval(x0 + e) + 4.0 * f.eval(xm) + f.eval(x1 - e)) * (x1 - x0) / 6.0;
                }
                total
            };
            for u in [0.0, 0.13, 0.5, 0.77, 1.0] {
                assert!(
                    (a.eval(u) - simpson(u)).abs() < 1e-9,
                    "p={p} u={u}: {} vs {}",
                    a.eval(u),
                    simpson(u)
                );
                let mut cols = vec![0.0; f.values().len()];
                f.basis_integrals(u, &mut cols);
                let via: f64 = cols.iter().zip(f.values()).map(|(g, c)| g * c).sum();
                assert!(
                    (via - a.eval(u)).abs() < 1e-14,
                    "basis integrals p={p} u={u}"
                );
            }
        }
    }

    #[test]
    fn bspline_bad_input_is_error() {
        assert!(BSpline::uniform(3, vec![1.0; 3]).is_err());
        assert!(BSpline::uniform(1, vec![1.0, f64::NAN]).is_err());
        assert!(BSpline::uniform(9, vec![1.0; 12]).is_err());
        let e = BSpline::uniform(2, vec![1.0, 2.0]).unwrap_err().to_string();
        assert!(e.contains("at least 3"), "{e}");
    }

    #[test]
    fn tensor_restricts_to_rows() {
        let vals = Grid::from_rows(&[
            vec![1.0, 1.2, 0.9],
            vec![0.8, 1.0, 1.1],
            vec![1.3, 0.7, 1.0],
        ])
        .unwrap();
        let f = TensorBSpline::new(2, 2, vals.clone()).unwrap();
        let ks = clamped_knots(2, 3);
        for (u, v) in [(0.0, 0.0), (0.3, 0.6), (1.0, 0.25), (0.5, 1.0)] {
            let mut want = 0.0;
            for j in 0..3 {
                for i in 0..3 {
                    want += vals.get(j, i) * n_rec(&ks, j, 2, v) * n_rec(&ks, i, 2, u);
                }
            }
            assert!((f.eval(u, v) - want).abs() < 1e-14, "({u}, {v})");
        }
    }
}
