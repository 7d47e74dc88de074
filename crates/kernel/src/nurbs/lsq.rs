//! Least-squares B-spline curves with both ends interpolated (Piegl &
//! Tiller §9.4.1), for many data rows that share their parameters: the
//! normal matrix `Nᵀ N` (banded, half bandwidth `p`) is factored once and
//! every row is one right-hand side (`docs/math.md §10`).
//!
//! Data `Q₀ … Q_m` at parameters `ū₀ = 0 < … < ū_m = 1`, poles
//! `P₀ … P_{n−1}` with `P₀ = Q₀`, `P_{n−1} = Q_m`; the interior poles solve
//! `(Nᵀ N) P = Nᵀ R` with `R_k = Q_k − N₀(ū_k) Q₀ − N_{n−1}(ū_k) Q_m`, over
//! the interior data `k = 1 … m−1` and interior functions `1 … n−2`.

use super::banded::{Banded, Singular};
use super::knots::{Basis, KnotVector};
use super::surface::curve_point;
use glam::DVec3;

/// A factored end-interpolating fit for one knot vector and one parameter list.
#[derive(Debug, Clone)]
pub(crate) struct EndFixedFit {
    degree: usize,
    count: usize,
    basis: Vec<Basis>,
    normal: Banded,
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
        normal.factor()?;
        Ok(EndFixedFit {
            degree: p,
            count,
            basis,
            normal,
        })
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
        let (p, n) = (self.degree, self.count);
        let unknowns = n - 2;
        out.clear();
        out.resize(n * cols, DVec3::ZERO);
        let (first_row, last_row) = (&data[..cols], &data[(m - 1) * cols..]);
        {
            let rhs = &mut out[cols..(n - 1) * cols];
            let mut r = vec![DVec3::ZERO; cols];
            for (k, (f, b)) in self.basis.iter().enumerate().take(m - 1).skip(1) {
                let row = &data[k * cols..(k + 1) * cols];
                let n0 = if *f == 0 { b[0] } else { 0.0 };
                let nl = if f + p == n - 1 { b[p] } else { 0.0 };
                for (c, x) in r.iter_mut().enumerate() {
                    *x = row[c] - first_row[c] * n0 - last_row[c] * nl;
                }
                for (a, &w) in b[..=p].iter().enumerate() {
                    let i = f + a;
                    if i == 0 || i + 1 >= n {
                        continue;
                    }
                    for (o, x) in rhs[(i - 1) * cols..i * cols].iter_mut().zip(&r) {
                        *o += *x * w;
                    }
                }
            }
            debug_assert_eq!(rhs.len(), unknowns * cols);
            self.normal.solve_rows(rhs, cols);
        }
        out[..cols].copy_from_slice(first_row);
        out[(n - 1) * cols..].copy_from_slice(last_row);
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
    /// the two end slots are then overwritten with the fixed end points.
    fn fit_row_p<const P: usize>(&self, q: &[DVec3], poles: &mut [DVec3]) {
        let n = self.count;
        debug_assert_eq!(self.degree, P);
        let (q0, qm) = (q[0], q[q.len() - 1]);
        poles.fill(DVec3::ZERO);
        for ((f, b), qk) in self.basis[1..q.len() - 1].iter().zip(&q[1..q.len() - 1]) {
            let n0 = if *f == 0 { b[0] } else { 0.0 };
            let nl = if f + P == n - 1 { b[P] } else { 0.0 };
            let r = *qk - q0 * n0 - qm * nl;
            let dst = &mut poles[*f..*f + P + 1];
            for a in 0..=P {
                dst[a] += r * b[a];
            }
        }
        self.normal.solve_vec(&mut poles[1..n - 1]);
        poles[0] = q0;
        poles[n - 1] = qm;
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
