//! The QI curve: the B-spline unit quaternion curve of Kim–Kim–Shin as used by
//! paper 000 (Eqs. 22–26), the smooth reference the subdivision curves are
//! compared with in Table 1.
//!
//! `t(u) = R_n(u) ··· R_1(u) t₀`, where `R_i(u)` rotates about
//! `(t_{i−1} × t_i)/|t_{i−1} × t_i|` by `θ_i · B̃_{i,k}(u)`, with `θ_i` the angle
//! from `t_{i−1}` to `t_i` (by `atan2`, not the paper's `asin` in Eq. 26) and
//! `B̃_{i,k}(u) = Σ_{j≥i} B_{j,k}(u)` the cumulative basis of order `k` (degree
//! `k−1`) on the clamped uniform knot vector over `u ∈ [0, 1]` (Eqs. 23–24), so
//! `t(0) = t₀` and `t(1) = t_n`.
//!
//! Since `B̃_i = 1` for `i` before the active span and `0` after it, and a full
//! rotation `R_i(1)` maps `t_{i−1}` exactly onto `t_i`, only the `k−1` partial
//! rotations of the active span are applied, starting from the first active tangent.

use crate::error::KernelError;
use crate::sphere::blend::{DEGENERATE_SIN, antipodal_axis};
use crate::sphere::tangent::normalize_all;
use glam::DVec3;

/// A QI curve of order `k` through unit tangents `t₀ … t_n`.
#[derive(Debug, Clone)]
pub struct QiCurve {
    tangents: Vec<DVec3>,
    order: usize,
    knots: Vec<f64>,
    /// Unit axis and angle of the rotation from `t_{i−1}` to `t_i`, index `i−1`.
    axes: Vec<DVec3>,
    angles: Vec<f64>,
}

impl QiCurve {
    /// Builds the curve; `order` must lie in `2 ..= tangents.len()` (order 2 is the
    /// piecewise great-arc curve; 3, 4, 5 are the paper's). Tangents are normalised.
    pub fn new(tangents: &[DVec3], order: usize) -> Result<Self, KernelError> {
        let t = normalize_all(tangents)?;
        if t.len() < 2 {
            return Err(KernelError::TooFewTangents {
                what: "a QI curve",
                got: t.len(),
                need: 2,
            });
        }
        if order < 2 || order > t.len() || order > MAX_ORDER {
            return Err(KernelError::OrderOutOfRange {
                order,
                tangents: t.len(),
            });
        }
        let n = t.len() - 1;
        let k = order;
        let spans = (n + 2 - k) as f64;
        let knots = (0..n + 1 + k)
            .map(|i| {
                if i < k {
                    0.0
                } else if i > n {
                    1.0
                } else {
                    (i + 1 - k) as f64 / spans
                }
            })
            .collect();
        let (mut axes, mut angles) = (Vec::with_capacity(n), Vec::with_capacity(n));
        for w in t.windows(2) {
            let c = w[0].cross(w[1]);
            let s = c.length();
            let d = w[0].dot(w[1]);
            if s > DEGENERATE_SIN {
                axes.push(c / s);
                angles.push(s.atan2(d));
            } else if d > 0.0 {
                axes.push(antipodal_axis(w[0]));
                angles.push(0.0);
            } else {
                // Antipodal neighbours: rotate by π about the documented fixed axis.
                axes.push(antipodal_axis(w[0]));
                angles.push(std::f64::consts::PI);
            }
        }
        Ok(QiCurve {
            tangents: t,
            order,
            knots,
            axes,
            angles,
        })
    }

    /// The order `k`.
    pub fn order(&self) -> usize {
        self.order
    }

    /// The control tangents (unit).
    pub fn tangents(&self) -> &[DVec3] {
        &self.tangents
    }

    /// The knot vector (clamped, uniform).
    pub fn knots(&self) -> &[f64] {
        &self.knots
    }

    /// Index of the knot span holding `u` (clamped to `[0, 1]`): `l` with
    /// `knots[l] ≤ u < knots[l+1]`, `k−1 ≤ l ≤ n`.
    fn span(&self, u: f64) -> usize {
        let n = self.tangents.len() - 1;
        let k = self.order;
        if u >= 1.0 {
            return n;
        }
        let mut l = k - 1;
        while l < n && self.knots[l + 1] <= u {
            l += 1;
        }
        l
    }

    /// The non-zero B-spline basis values `B_{l−k+1..=l, k}(u)` (The NURBS Book, A2.2).
    fn basis(&self, l: usize, u: f64, out: &mut [f64; 8]) {
        let k = self.order;
        let mut left = [0.0; 8];
        let mut right = [0.0; 8];
        out[0] = 1.0;
        for j in 1..k {
            left[j] = u - self.knots[l + 1 - j];
            right[j] = self.knots[l + j] - u;
            let mut saved = 0.0;
            for r in 0..j {
                let denom = right[r + 1] + left[j - r];
                let temp = if denom != 0.0 { out[r] / denom } else { 0.0 };
                out[r] = saved + right[r + 1] * temp;
                saved = left[j - r] * temp;
            }
            out[j] = saved;
        }
    }

    #[cfg(test)]
    /// `B̃_{i,k}(u)` for `i = 1..=n` (Eq. 24), written into `out` (length `n`).
    pub(crate) fn cumulative_basis(&self, u: f64, out: &mut [f64]) {
        let u = u.clamp(0.0, 1.0);
        let n = self.tangents.len() - 1;
        let k = self.order;
        let l = self.span(u);
        let mut b = [0.0; 8];
        self.basis(l, u, &mut b);
        // B_j non-zero for j in l+1-k ..= l, stored at b[j - (l+1-k)].
        let first = l + 1 - k;
        for i in 1..=n {
            out[i - 1] = if i <= first {
                1.0
            } else if i > l {
                0.0
            } else {
                b[i - first..k].iter().sum()
            };
        }
    }

    /// The unit tangent `t(u)`, `u` clamped to `[0, 1]`.
    pub fn tangent(&self, u: f64) -> DVec3 {
        let u = u.clamp(0.0, 1.0);
        let k = self.order;
        let l = self.span(u);
        let mut b = [0.0; 8];
        self.basis(l, u, &mut b);
        let first = l + 1 - k;
        let mut v = self.tangents[first];
        // Partial rotations i = first+1 ..= l with B̃_i = Σ_{j ≥ i} B_j.
        let mut cum: f64 = b[1..k].iter().sum();
        for i in first + 1..=l {
            let phi = self.angles[i - 1] * cum;
            if phi != 0.0 {
                let axis = self.axes[i - 1];
                let (s, c) = phi.sin_cos();
                v = v * c + axis.cross(v) * s + axis * (axis.dot(v) * (1.0 - c));
            }
            cum -= b[i - first];
        }
        v.normalize()
    }

    /// `m ≥ 2` tangents at evenly spaced `u = j/(m−1)`, at most
    /// [`crate::limits::MAX_TANGENTS_PER_LEVEL`].
    pub fn sample(&self, m: usize) -> Result<Vec<DVec3>, KernelError> {
        if m < 2 {
            return Err(KernelError::TooFewTangents {
                what: "QI sampling",
                got: m,
                need: 2,
            });
        }
        if m > crate::limits::MAX_TANGENTS_PER_LEVEL {
            return Err(KernelError::TooManyTangents {
                tangents: m,
                cap: crate::limits::MAX_TANGENTS_PER_LEVEL,
            });
        }
        Ok((0..m)
            .map(|j| self.tangent(j as f64 / (m - 1) as f64))
            .collect())
    }
}

/// QI curves of order up to this are supported (defined in [`crate::limits`]).
pub use crate::limits::MAX_QI_ORDER as MAX_ORDER;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn qi_endpoints_and_partition() {
        let t = [
            DVec3::X,
            DVec3::Y,
            DVec3::new(0.0, 1.0, 1.0),
            DVec3::Z,
            DVec3::new(-1.0, 0.0, 1.0),
        ];
        for k in 2..=5 {
            let q = QiCurve::new(&t, k).unwrap();
            assert!((q.tangent(0.0) - DVec3::X).length() < 1e-15, "k={k} t(0)");
            assert!(
                (q.tangent(1.0) - q.tangents()[4]).length() < 1e-14,
                "k={k} t(1)"
            );
            let mut cb = [0.0; 4];
            q.cumulative_basis(0.37, &mut cb);
            assert!(
                cb.windows(2).all(|w| w[0] >= w[1] - 1e-15),
                "B̃ non-increasing: {cb:?}"
            );
        }
        assert!(matches!(
            QiCurve::new(&t, 6),
            Err(KernelError::OrderOutOfRange { .. })
        ));
        assert!(matches!(
            QiCurve::new(&t, 1),
            Err(KernelError::OrderOutOfRange { .. })
        ));
    }
}
