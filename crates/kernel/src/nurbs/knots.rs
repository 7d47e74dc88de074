//! Clamped knot vectors and the B-spline basis (Piegl & Tiller, *The NURBS
//! Book*, §2.2–2.5 and Eq. 9.69; `docs/math.md §10`).
//!
//! A knot vector of degree `p` with `n` basis functions holds `n + p + 1`
//! non-decreasing knots, the first `p + 1` equal to 0 and the last `p + 1`
//! equal to 1 (clamped: the curve starts and ends at its end poles). The
//! interior knots here are simple (multiplicity 1), so every one of the
//! `n − p` spans `[k_{p+j}, k_{p+j+1})` is non-empty and the basis is `C^{p−1}`.

/// The largest degree the fit accepts.
pub const MAX_DEGREE: usize = 5;
/// The smallest degree the fit accepts (degree 1 has no interior unknowns).
pub const MIN_DEGREE: usize = 2;

/// Basis values at one parameter: the first nonzero function's index and
/// the `p + 1` values `N_{first}, …, N_{first+p}` (padded with zeros).
pub(crate) type Basis = (usize, [f64; MAX_DEGREE + 1]);

/// A clamped knot vector on `[0, 1]` with simple interior knots.
#[derive(Debug, Clone, PartialEq)]
pub struct KnotVector {
    degree: usize,
    knots: Vec<f64>,
}

impl KnotVector {
    /// No interior knots: the Bernstein (Bézier) basis, `p + 1` functions.
    pub fn bezier(degree: usize) -> Self {
        let mut knots = vec![0.0; degree + 1];
        knots.extend(std::iter::repeat_n(1.0, degree + 1));
        KnotVector { degree, knots }
    }

    /// A clamped vector with the given interior knots (strictly increasing,
    /// inside `(0, 1)`); `None` if they are not.
    pub fn with_interior(degree: usize, interior: &[f64]) -> Option<Self> {
        let inside = interior.iter().all(|k| *k > 0.0 && *k < 1.0);
        let rising = interior.windows(2).all(|w| w[1] > w[0]);
        if !(inside && rising && (MIN_DEGREE..=MAX_DEGREE).contains(&degree)) {
            return None;
        }
        let mut v = Self::bezier(degree);
        v.knots
            .splice(degree + 1..degree + 1, interior.iter().copied());
        Some(v)
    }

    /// Averaged knots for `count` functions over the data parameters
    /// `params` (increasing, from 0 to 1), Piegl & Tiller Eq. 9.69:
    /// with `m + 1` parameters and `d = (m + 1)/(count − p)`, the interior
    /// knot `j` (1 ≤ j < count − p) is `(1 − α) ū_{i−1} + α ū_i`, `i = ⌊j d⌋`,
    /// `α = j d − i`, so every span holds about `d` parameters.
    /// `count` is clamped to `p + 1 ..= params.len()`.
    #[cfg(test)]
    pub(crate) fn averaged(degree: usize, params: &[f64], count: usize) -> Self {
        let count = count.clamp(degree + 1, params.len().max(degree + 1));
        let spans = count - degree;
        let d = params.len() as f64 / spans as f64;
        let mut v = Self::bezier(degree);
        let interior: Vec<f64> = (1..spans)
            .map(|j| {
                let jd = j as f64 * d;
                let i = (jd.floor() as usize).clamp(1, params.len() - 1);
                let a = jd - i as f64;
                (1.0 - a) * params[i - 1] + a * params[i]
            })
            .collect();
        v.knots.splice(degree + 1..degree + 1, interior);
        v
    }

    /// The degree `p`.
    pub fn degree(&self) -> usize {
        self.degree
    }

    /// All knots, `count + p + 1` of them.
    pub fn knots(&self) -> &[f64] {
        &self.knots
    }

    /// The interior knots (strictly inside `(0, 1)`).
    pub fn interior(&self) -> &[f64] {
        &self.knots[self.degree + 1..self.knots.len() - self.degree - 1]
    }

    /// Number of basis functions (poles in this direction).
    pub fn count(&self) -> usize {
        self.knots.len() - self.degree - 1
    }

    /// Number of (non-empty) spans, `count − p`.
    pub fn spans(&self) -> usize {
        self.count() - self.degree
    }

    /// The span `j` (0-based, `0 ≤ j < spans`) holding `u`: `k_{p+j} ≤ u <
    /// k_{p+j+1}`, the last span closed at 1; `u` outside `[0, 1]` is clamped.
    #[inline]
    pub fn span(&self, u: f64) -> usize {
        let inner = self.interior();
        // number of interior knots ≤ u
        inner.partition_point(|k| *k <= u)
    }

    /// The start and end of span `j`.
    pub(crate) fn span_range(&self, j: usize) -> (f64, f64) {
        (self.knots[self.degree + j], self.knots[self.degree + j + 1])
    }

    /// Inserts the knot `u` (strictly inside span `j`'s interior); returns
    /// false if it is not strictly inside a span.
    pub fn insert(&mut self, u: f64) -> bool {
        let j = self.span(u);
        let (a, b) = self.span_range(j);
        if !(u > a && u < b) {
            return false;
        }
        self.knots.insert(self.degree + 1 + j, u);
        true
    }

    /// The nonzero basis functions at `u` (Piegl & Tiller, Algorithm A2.2,
    /// the triangular Cox–de Boor scheme without divisions by zero).
    #[inline]
    pub fn basis(&self, u: f64) -> Basis {
        let p = self.degree;
        let u = u.clamp(0.0, 1.0);
        let span = self.span(u) + p; // index into the knots
        let k = &self.knots;
        let mut n = [0.0; MAX_DEGREE + 1];
        let mut left = [0.0; MAX_DEGREE + 1];
        let mut right = [0.0; MAX_DEGREE + 1];
        n[0] = 1.0;
        for j in 1..=p {
            left[j] = u - k[span + 1 - j];
            right[j] = k[span + j] - u;
            let mut saved = 0.0;
            for r in 0..j {
                let temp = n[r] / (right[r + 1] + left[j - r]);
                n[r] = saved + right[r + 1] * temp;
                saved = left[j - r] * temp;
            }
            n[j] = saved;
        }
        (span - p, n)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Cox–de Boor recursion, straight from the definition (an independent check).
    fn cox_de_boor(k: &[f64], i: usize, p: usize, u: f64, last: bool) -> f64 {
        if p == 0 {
            let inside = k[i] <= u && u < k[i + 1];
            let closed_end = last && u == k[i + 1] && k[i] < k[i + 1];
            return f64::from(u8::from(inside || closed_end));
        }
        let mut v = 0.0;
        if k[i + p] > k[i] {
            v += (u - k[i]) / (k[i + p] - k[i]) * cox_de_boor(k, i, p - 1, u, last);
        }
        if k[i + p + 1] > k[i + 1] {
            v += (k[i + p + 1] - u) / (k[i + p + 1] - k[i + 1])
                * cox_de_boor(k, i + 1, p - 1, u, last);
        }
        v
    }

    #[test]
    fn basis_matches_the_recursive_definition_and_sums_to_one() {
        for p in MIN_DEGREE..=MAX_DEGREE {
            let kv = KnotVector::with_interior(p, &[0.1, 0.35, 0.4, 0.8]).unwrap();
            for i in 0..=200 {
                let u = i as f64 / 200.0;
                let (first, n) = kv.basis(u);
                let sum: f64 = n[..=p].iter().sum();
                assert!((sum - 1.0).abs() < 1e-14, "p{p} u{u}: sum {sum}");
                for f in 0..kv.count() {
                    // the last span is closed at u = 1
                    let want = cox_de_boor(kv.knots(), f, p, u, u == 1.0);
                    let got = if f >= first && f <= first + p {
                        n[f - first]
                    } else {
                        0.0
                    };
                    assert!(
                        (want - got).abs() < 1e-13,
                        "p{p} u{u} N{f}: {got} vs {want}"
                    );
                }
            }
        }
    }

    #[test]
    fn averaged_knots_follow_eq_9_69() {
        let params: Vec<f64> = (0..11).map(|i| i as f64 / 10.0).collect();
        // m + 1 = 11 parameters, 6 functions of degree 3: d = 11/3
        let kv = KnotVector::averaged(3, &params, 6);
        assert_eq!(kv.count(), 6);
        let d = 11.0 / 3.0;
        for (j, k) in kv.interior().iter().enumerate() {
            let jd = (j + 1) as f64 * d;
            let i = jd.floor() as usize;
            let a = jd - i as f64;
            let want = (1.0 - a) * params[i - 1] + a * params[i];
            assert!((k - want).abs() < 1e-15, "knot {j}: {k} vs {want}");
        }
    }

    #[test]
    fn spans_and_insertion() {
        let mut kv = KnotVector::bezier(3);
        assert_eq!((kv.count(), kv.spans(), kv.span(1.0)), (4, 1, 0));
        assert!(kv.insert(0.5));
        assert!(!kv.insert(0.5), "a double knot is refused");
        assert!(!kv.insert(1.0));
        assert_eq!(
            (kv.count(), kv.span(0.49), kv.span(0.5), kv.span(1.0)),
            (5, 0, 1, 1)
        );
    }
}
