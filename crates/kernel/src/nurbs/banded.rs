//! A symmetric positive definite banded matrix and its Cholesky factor
//! `A = L Lᵀ`, the normal equations of a least-squares B-spline fit (half
//! bandwidth `p`: basis functions more than `p` apart never overlap).

/// Lower band of a symmetric `n × n` matrix, `band[i][d] = A[i][i − d]`.
#[derive(Debug, Clone)]
pub(crate) struct Banded {
    n: usize,
    width: usize,
    band: Vec<f64>,
}

/// The factorisation met a pivot that is not positive: the basis does not
/// have enough data under it (Schoenberg–Whitney fails).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Singular {
    /// The row whose pivot vanished.
    pub row: usize,
}

impl Banded {
    /// The zero matrix of size `n` and half bandwidth `b`.
    pub fn zeros(n: usize, b: usize) -> Self {
        Banded {
            n,
            width: b + 1,
            band: vec![0.0; n * (b + 1)],
        }
    }

    /// Adds `v` to `A[i][j]` (and `A[j][i]`), `j ≤ i ≤ j + b`.
    #[inline]
    pub fn add(&mut self, i: usize, j: usize, v: f64) {
        debug_assert!(j <= i && i - j < self.width);
        self.band[i * self.width + (i - j)] += v;
    }

    #[inline]
    fn at(&self, i: usize, j: usize) -> f64 {
        self.band[i * self.width + (i - j)]
    }

    /// Cholesky in place; a pivot below `1e-13` of its diagonal entry (or not
    /// finite) is refused. Returns the spread of the pivots, the largest
    /// over the smallest: each lies between the matrix's least and largest
    /// eigenvalue, so the spread is a lower bound of its condition number.
    pub fn factor(&mut self) -> Result<f64, Singular> {
        let b = self.width - 1;
        let (mut least, mut most) = (f64::INFINITY, 0.0f64);
        for i in 0..self.n {
            let lo = i.saturating_sub(b);
            for j in lo..=i {
                let mut sum = self.at(i, j);
                for k in lo.max(j.saturating_sub(b))..j {
                    sum -= self.at(i, k) * self.at(j, k);
                }
                let idx = i * self.width + (i - j);
                if j == i {
                    let diag = self.band[idx];
                    if sum.partial_cmp(&(1e-13 * diag.abs())) != Some(std::cmp::Ordering::Greater)
                        || !sum.is_finite()
                    {
                        return Err(Singular { row: i });
                    }
                    least = least.min(sum);
                    most = most.max(sum);
                    self.band[idx] = sum.sqrt();
                } else {
                    self.band[idx] = sum / self.at(j, j);
                }
            }
        }
        Ok(if self.n == 0 { 1.0 } else { most / least })
    }

    /// Solves `L Lᵀ x = r` in place for one vector of points.
    pub(crate) fn solve_vec(&self, r: &mut [glam::DVec3]) {
        let b = self.width - 1;
        let n = self.n;
        debug_assert_eq!(r.len(), n);
        for i in 0..n {
            let row = &self.band[i * self.width..(i + 1) * self.width];
            let mut x = r[i];
            for k in i.saturating_sub(b)..i {
                x -= r[k] * row[i - k];
            }
            r[i] = x / row[0];
        }
        for i in (0..n).rev() {
            let mut x = r[i];
            let hi = (i + b + 1).min(n);
            for (k, rk) in r.iter().enumerate().take(hi).skip(i + 1) {
                x -= *rk * self.band[k * self.width + (k - i)];
            }
            r[i] = x / self.band[i * self.width];
        }
    }

    /// Solves `L Lᵀ X = R` in place for `R` with `n` rows of `cols` entries
    /// (row-major), after [`Self::factor`].
    pub(crate) fn solve_rows<T>(&self, r: &mut [T], cols: usize)
    where
        T: Copy + std::ops::SubAssign + std::ops::Mul<f64, Output = T> + std::ops::DivAssign<f64>,
    {
        let b = self.width - 1;
        let n = self.n;
        debug_assert_eq!(r.len(), n * cols);
        for i in 0..n {
            for k in i.saturating_sub(b)..i {
                let l = self.at(i, k);
                let (done, rest) = r.split_at_mut(i * cols);
                for (x, y) in rest[..cols].iter_mut().zip(&done[k * cols..(k + 1) * cols]) {
                    *x -= *y * l;
                }
            }
            let d = self.at(i, i);
            for x in &mut r[i * cols..(i + 1) * cols] {
                *x /= d;
            }
        }
        for i in (0..n).rev() {
            for k in i + 1..(i + b + 1).min(n) {
                let l = self.at(k, i);
                let (head, tail) = r.split_at_mut(k * cols);
                for (x, y) in head[i * cols..(i + 1) * cols].iter_mut().zip(&tail[..cols]) {
                    *x -= *y * l;
                }
            }
            let d = self.at(i, i);
            for x in &mut r[i * cols..(i + 1) * cols] {
                *x /= d;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    #[allow(clippy::needless_range_loop)]
    fn solves_a_banded_system_against_dense_elimination() {
        let (n, b) = (9, 3);
        let mut a = Banded::zeros(n, b);
        let mut dense = vec![vec![0.0; n]; n];
        for i in 0..n {
            for j in i.saturating_sub(b)..=i {
                let v = if i == j {
                    10.0 + i as f64
                } else {
                    1.0 / (1.0 + (i + 2 * j) as f64)
                };
                a.add(i, j, v);
                dense[i][j] = v;
                dense[j][i] = v;
            }
        }
        let x: Vec<f64> = (0..n).map(|i| (i as f64 * 0.7).sin()).collect();
        let mut r: Vec<f64> = (0..n)
            .map(|i| (0..n).map(|j| dense[i][j] * x[j]).sum())
            .collect();
        a.factor().unwrap();
        let mut rv: Vec<glam::DVec3> = r
            .iter()
            .map(|&v| glam::DVec3::new(v, -v, 2.0 * v))
            .collect();
        a.solve_rows(&mut r, 1);
        a.solve_vec(&mut rv);
        for i in 0..n {
            assert!((r[i] - x[i]).abs() < 1e-13, "x{i}: {} vs {}", r[i], x[i]);
            let want = glam::DVec3::new(x[i], -x[i], 2.0 * x[i]);
            assert!(
                (rv[i] - want).length() < 1e-13,
                "x{i}: {} vs {}",
                rv[i],
                want
            );
        }
    }

    #[test]
    fn a_singular_matrix_is_refused() {
        let mut a = Banded::zeros(3, 1);
        a.add(0, 0, 1.0);
        a.add(1, 0, 1.0);
        a.add(1, 1, 1.0);
        a.add(2, 2, 1.0);
        assert_eq!(a.factor(), Err(Singular { row: 1 }));
    }
}
