//! A B-spline curve on a general clamped knot vector (multiple knots
//! allowed), for the seams of a shell (docs/math.md §10): evaluation by de
//! Boor's algorithm, Boehm's knot insertion (Piegl & Tiller, Algorithm A5.1),
//! the piece of a curve between two parameters (each inserted to
//! multiplicity `p`, Piegl & Tiller §5.3) and refinement onto a finer
//! [`KnotVector`]. None of these changes the curve's shape.

use super::knots::KnotVector;
use glam::DVec3;

/// A non-rational B-spline curve: `knots.len() = poles.len() + degree + 1`,
/// clamped (the first and last `degree + 1` knots equal).
#[derive(Debug, Clone, PartialEq)]
pub struct Curve {
    /// The degree `p`.
    pub degree: usize,
    /// All knots, non-decreasing.
    pub knots: Vec<f64>,
    /// The poles.
    pub poles: Vec<DVec3>,
}

impl Curve {
    /// The curve with `knots`' knots and `poles` (one per basis function).
    pub fn new(knots: &KnotVector, poles: Vec<DVec3>) -> Self {
        debug_assert_eq!(knots.count(), poles.len());
        Curve {
            degree: knots.degree(),
            knots: knots.knots().to_vec(),
            poles,
        }
    }

    /// The span index `k` (`knots[k] ≤ u < knots[k + 1]`, the last non-empty
    /// span closed) for `u` clamped into the curve's range.
    fn span(&self, u: f64) -> usize {
        let (p, n) = (self.degree, self.poles.len());
        let mut k = p;
        while k + 1 < n && self.knots[k + 1] <= u {
            k += 1;
        }
        k
    }

    /// The point at `u` (de Boor's algorithm; `u` clamped to the range).
    pub fn eval(&self, u: f64) -> DVec3 {
        let (p, n) = (self.degree, self.poles.len());
        let u = u.clamp(self.knots[p], self.knots[n]);
        let k = self.span(u);
        let t = &self.knots;
        let mut d: Vec<DVec3> = (0..=p).map(|j| self.poles[j + k - p]).collect();
        for r in 1..=p {
            for j in (r..=p).rev() {
                let (lo, hi) = (t[j + k - p], t[j + 1 + k - r]);
                let alpha = if hi > lo { (u - lo) / (hi - lo) } else { 0.0 };
                d[j] = d[j - 1] * (1.0 - alpha) + d[j] * alpha;
            }
        }
        d[p]
    }

    /// How many knots equal `u` exactly.
    fn multiplicity(&self, u: f64) -> usize {
        self.knots.iter().filter(|k| **k == u).count()
    }

    /// Inserts `u` once (Boehm; Piegl & Tiller Algorithm A5.1 with `r = 1`).
    /// `u` must lie strictly inside the range.
    pub fn insert(&mut self, u: f64) {
        let p = self.degree;
        let k = self.span(u);
        let t = &self.knots;
        let mut q = Vec::with_capacity(self.poles.len() + 1);
        for i in 0..=self.poles.len() {
            let pt = if i + p <= k {
                self.poles[i]
            } else if i > k {
                self.poles[i - 1]
            } else {
                let alpha = (u - t[i]) / (t[i + p] - t[i]);
                self.poles[i] * alpha + self.poles[i - 1] * (1.0 - alpha)
            };
            q.push(pt);
        }
        self.poles = q;
        self.knots.insert(k + 1, u);
    }

    /// The part of the curve over `[a, b]` (`0 ≤ a < b ≤ 1`), reparametrised
    /// onto `[0, 1]` (`w = (u − a)/(b − a)`): `a` and `b` are inserted until
    /// their multiplicity is `p`, when the curve's point there is one pole
    /// and the poles between are the piece's (Piegl & Tiller §5.3).
    pub fn piece(&self, a: f64, b: f64) -> Curve {
        let p = self.degree;
        let mut c = self.clone();
        for x in [a, b] {
            if x > 0.0 && x < 1.0 {
                while c.multiplicity(x) < p {
                    c.insert(x);
                }
            }
        }
        // the pole at a knot of multiplicity p whose last copy is at index k is k − p
        let last_index = |x: f64| c.knots.iter().rposition(|k| *k == x);
        let start = if a <= 0.0 {
            0
        } else {
            last_index(a).expect("inserted") - p
        };
        let end = if b >= 1.0 {
            c.poles.len() - 1
        } else {
            last_index(b).expect("inserted") - p
        };
        let poles = c.poles[start..=end].to_vec();
        let mut knots = vec![0.0; p + 1];
        knots.extend(
            c.knots
                .iter()
                .filter(|k| **k > a && **k < b)
                .map(|k| (k - a) / (b - a)),
        );
        knots.extend(std::iter::repeat_n(1.0, p + 1));
        debug_assert_eq!(knots.len(), poles.len() + p + 1);
        Curve {
            degree: p,
            knots,
            poles,
        }
    }

    /// The same curve run backwards (`u → 1 − u`).
    pub fn reversed(&self) -> Curve {
        let mut knots: Vec<f64> = self.knots.iter().rev().map(|k| 1.0 - k).collect();
        // 1 − 1 and 1 − 0 are exact; keep the ends exactly 0 and 1
        let n = knots.len();
        for k in &mut knots[..=self.degree] {
            *k = 0.0;
        }
        for k in &mut knots[n - self.degree - 1..] {
            *k = 1.0;
        }
        Curve {
            degree: self.degree,
            knots,
            poles: self.poles.iter().rev().copied().collect(),
        }
    }

    /// The same curve on `target`'s knots, when `target` holds every knot of
    /// this curve (same degree, simple interior knots): each knot of
    /// `target` missing here is inserted. `None` when `target` cannot hold it.
    pub fn refined_to(&self, target: &KnotVector) -> Option<Curve> {
        if target.degree() != self.degree {
            return None;
        }
        let mut c = self.clone();
        for &k in target.interior() {
            if c.multiplicity(k) == 0 {
                c.insert(k);
            }
        }
        (c.knots == target.knots()).then_some(c)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn wavy() -> Curve {
        let kv = KnotVector::with_interior(3, &[0.2, 0.45, 0.5, 0.8]).unwrap();
        let poles = (0..kv.count())
            .map(|i| {
                let x = i as f64;
                DVec3::new(x, (x * 1.3).sin(), (x * 0.7).cos() * x)
            })
            .collect();
        Curve::new(&kv, poles)
    }

    /// The same curve by the basis of [`KnotVector`] (an independent evaluation).
    fn by_basis(c: &Curve, kv: &KnotVector, u: f64) -> DVec3 {
        let (first, n) = kv.basis(u);
        (0..=c.degree).map(|a| c.poles[first + a] * n[a]).sum()
    }

    #[test]
    fn de_boor_matches_the_basis() {
        let c = wavy();
        let kv = KnotVector::with_interior(3, &[0.2, 0.45, 0.5, 0.8]).unwrap();
        for i in 0..=100 {
            let u = i as f64 / 100.0;
            assert!((c.eval(u) - by_basis(&c, &kv, u)).length() < 1e-13, "u {u}");
        }
    }

    #[test]
    fn insertion_pieces_and_reversal_keep_the_curve() {
        let c = wavy();
        let mut d = c.clone();
        d.insert(0.3);
        d.insert(0.3);
        for (a, b) in [(0.0, 1.0), (0.1, 0.6), (0.2, 0.9), (0.0, 0.45), (0.55, 1.0)] {
            let piece = c.piece(a, b);
            let back = piece.reversed();
            for i in 0..=50 {
                let w = i as f64 / 50.0;
                let want = c.eval(a + w * (b - a));
                assert!((piece.eval(w) - want).length() < 1e-12, "[{a},{b}] w {w}");
                assert!((back.eval(1.0 - w) - want).length() < 1e-12);
                assert!((d.eval(w) - c.eval(w)).length() < 1e-12);
            }
            assert_eq!(piece.poles[0], piece.eval(0.0));
        }
        let target = KnotVector::with_interior(3, &[0.1, 0.2, 0.45, 0.5, 0.6, 0.8]).unwrap();
        let r = c.refined_to(&target).unwrap();
        for i in 0..=50 {
            let u = i as f64 / 50.0;
            assert!((r.eval(u) - c.eval(u)).length() < 1e-12);
        }
        // a target without one of the curve's knots cannot hold it
        let short = KnotVector::with_interior(3, &[0.2, 0.5, 0.8]).unwrap();
        assert!(c.refined_to(&short).is_none());
    }
}
