//! Blending tangents on the Gaussian sphere (paper 000, §3.2–3.4).
//!
//! `blend(a, b, u)` is the paper's `(1-u) a ⊕ u b` (Eq. 33): `a` rotated about
//! `a × b` by `u·θ`, `θ = atan2(|a × b|, a·b)` ∈ [0, π]. Eq. 21 of the paper writes
//! `θ = asin(|a × b|)`, wrong for obtuse angles; we use `atan2` (docs/math.md §1).
//! `u` is any real: outside [0, 1] it extrapolates along the great circle.
//!
//! All functions here take unit vectors (validated at the kernel's boundary by
//! [`crate::Tangent`]) and return unit vectors; degenerate pairs are branches:
//! - `a ≈ b` (`|a × b| ≤` `DEGENERATE_SIN`, `a·b > 0`): normalised linear
//!   interpolation, exact to O(θ²) ≈ 1e-28;
//! - `a ≈ −b` (antipodal, axis undefined): rotation about the fixed axis
//!   `antipodal_axis(a)` by `u·π`; each such event is counted
//!   ([`antipodal_events`]) so that a client can warn.

use glam::DVec3;
use std::sync::atomic::{AtomicUsize, Ordering};

/// Below this `|a × b|` the rotation axis is not trusted: the pair is treated
/// as equal (if `a·b > 0`) or antipodal (if `a·b < 0`).
pub(crate) const DEGENERATE_SIN: f64 = 1e-14;

/// `|a + b|²` below which the midpoint `(a+b)/|a+b|` (Eq. 32, corrected) is
/// undefined and the antipodal branch takes over.
pub(crate) const MID_MIN_NORM2: f64 = 1e-24;

/// `|a + b|²` below which [`quarters`] computes its two midpoints one by one
/// instead of through the shared norm `√(2 + |a + b|)` (see there).
pub(crate) const QUARTER_MIN_NORM2: f64 = 1e-4;

static ANTIPODAL_EVENTS: AtomicUsize = AtomicUsize::new(0);

/// How many antipodal pairs were blended since the program started (all threads).
/// A diagnostic for tests and benchmarks: a build names the pairs it blends
/// about the fixed axis from its own levels ([`super::antipodal`]).
pub fn antipodal_events() -> usize {
    ANTIPODAL_EVENTS.load(Ordering::Relaxed)
}

/// The documented fixed axis used when `b = −a`: `a` crossed with the coordinate
/// axis along which `a` has its smallest absolute component, normalised. It is
/// perpendicular to `a` and depends on `a` alone.
pub(crate) fn antipodal_axis(a: DVec3) -> DVec3 {
    let abs = a.abs();
    let e = if abs.x <= abs.y && abs.x <= abs.z {
        DVec3::X
    } else if abs.y <= abs.z {
        DVec3::Y
    } else {
        DVec3::Z
    };
    a.cross(e).normalize()
}

#[cold]
fn antipodal_blend(a: DVec3, u: f64) -> DVec3 {
    ANTIPODAL_EVENTS.fetch_add(1, Ordering::Relaxed);
    let k = antipodal_axis(a);
    let (s, c) = (u * std::f64::consts::PI).sin_cos();
    (a * c + k.cross(a) * s).normalize()
}

/// `(1-u) a ⊕ u b` (Eq. 33): `a` rotated towards `b` by `u·θ` along the great circle.
///
/// Written as `a cos(uθ) + (b − (a·b) a) sin(uθ)/sin θ`, which is the rotation of `a`
/// about `(a × b)/|a × b|` (Eqs. 29–31) without building a quaternion.
#[inline]
pub fn blend(a: DVec3, b: DVec3, u: f64) -> DVec3 {
    let c = a.dot(b);
    let s = a.cross(b).length();
    if s <= DEGENERATE_SIN {
        if c > 0.0 {
            return (a + (b - a) * u).normalize();
        }
        return antipodal_blend(a, u);
    }
    let theta = s.atan2(c);
    let (sp, cp) = (u * theta).sin_cos();
    (a * cp + (b - a * c) * (sp / s)).normalize()
}

/// The midpoint `(a + b)/|a + b|` (Eq. 32 corrected: the paper prints
/// `/|t0 × t1|`). Equal to `blend(a, b, 1/2)`, and exactly symmetric in `a, b`.
#[inline]
pub fn mid(a: DVec3, b: DVec3) -> DVec3 {
    let m = a + b;
    let n2 = m.length_squared();
    if n2 > MID_MIN_NORM2 {
        // one division, then three multiplications (a vector divided by a
        // scalar would cost three divisions)
        m * (1.0 / n2.sqrt())
    } else {
        antipodal_blend(a, 0.5)
    }
}

/// Chaikin's two points on the leg `a, b`: `(blend(a, b, ¼), blend(a, b, ¾))`
/// (Eqs. 51–53), with one square root and one division per point.
///
/// Eq. 53 computes them as midpoints of the midpoint `m = mid(a, b)`:
/// `mid(a, m)` and `mid(m, b)`. With `l = |a + b|`, `|a + m|² = 2 + 2 a·m =
/// 2 + l` (since `1 + a·b = l²/2`), so both share the norm `√(2 + l)` and
/// `blend(a, b, ¼) = (a + m)/√(2 + l)`. Equal to [`quarter`] and
/// [`three_quarters`] bit for bit.
///
/// The identity `|a + m|² = 2 + l` carries the inputs' rounding (`|a|² = 1 ±
/// 2⁻⁵²`) divided by `l`; below `QUARTER_MIN_NORM2` (θ > 179.4°) the two
/// midpoints are computed as they stand, and antipodal pairs take [`mid`]'s branch.
#[inline]
pub fn quarters(a: DVec3, b: DVec3) -> (DVec3, DVec3) {
    let sum = a + b;
    let l2 = sum.length_squared();
    if l2 > QUARTER_MIN_NORM2 {
        let l = l2.sqrt();
        let m = sum * (1.0 / l);
        let r = 1.0 / (2.0 + l).sqrt();
        ((a + m) * r, (m + b) * r)
    } else {
        let m = mid(a, b);
        (mid(a, m), mid(m, b))
    }
}

/// `blend(a, b, ¼)`: the first of [`quarters`], with the same operations.
#[inline]
pub fn quarter(a: DVec3, b: DVec3) -> DVec3 {
    let sum = a + b;
    let l2 = sum.length_squared();
    if l2 > QUARTER_MIN_NORM2 {
        let l = l2.sqrt();
        let m = sum * (1.0 / l);
        (a + m) * (1.0 / (2.0 + l).sqrt())
    } else {
        quarters(a, b).0
    }
}

/// `blend(a, b, ¾)`: the second of [`quarters`], with the same operations.
#[inline]
pub fn three_quarters(a: DVec3, b: DVec3) -> DVec3 {
    let sum = a + b;
    let l2 = sum.length_squared();
    if l2 > QUARTER_MIN_NORM2 {
        let l = l2.sqrt();
        let m = sum * (1.0 / l);
        (m + b) * (1.0 / (2.0 + l).sqrt())
    } else {
        quarters(a, b).1
    }
}

/// `blend(a, b, u)` for one fixed `u`, without trigonometry.
///
/// With `c = a·b = cos θ` and `h = sin²(θ/2) = |a − b|²/4`,
/// `cos(uθ) = ₂F₁(−u, u; ½; h)` and `sin(uθ)/sin θ = u·₂F₁(1−u, 1+u; 3/2; h)`
/// (the Chebyshev functions `T_u`, `U_{u−1}` of `cos θ`). Their Taylor
/// coefficients depend on `u` only, so they are computed once here; a blend is
/// then a dot product and two short polynomials in `h`. Used for `h ≤`
/// [`FixedBlend::H_MAX`] (θ ≤ 53°), where at most [`FixedBlend::TERMS`] terms
/// give full double precision; wider angles fall back to [`blend`].
#[derive(Debug, Clone, Copy)]
pub(crate) struct FixedBlend {
    u: f64,
    cos_coef: [f64; FixedBlend::TERMS],
    sin_coef: [f64; FixedBlend::TERMS],
}

impl FixedBlend {
    /// Number of series terms kept.
    pub(crate) const TERMS: usize = 24;
    /// Largest `h = sin²(θ/2)` handled by the series (θ ≈ 53°).
    pub(crate) const H_MAX: f64 = 0.2;

    /// Precomputes the series of `cos(uθ)` and `sin(uθ)/sin θ` in `h`.
    pub fn new(u: f64) -> Self {
        let mut cos_coef = [0.0; Self::TERMS];
        let mut sin_coef = [0.0; Self::TERMS];
        let (mut cc, mut sc) = (1.0, u);
        for k in 0..Self::TERMS {
            cos_coef[k] = cc;
            sin_coef[k] = sc;
            let kf = k as f64;
            cc *= (-u + kf) * (u + kf) / ((0.5 + kf) * (kf + 1.0));
            sc *= (1.0 - u + kf) * (1.0 + u + kf) / ((1.5 + kf) * (kf + 1.0));
        }
        FixedBlend {
            u,
            cos_coef,
            sin_coef,
        }
    }

    /// The series coefficients of `cos(uθ)` and `sin(uθ)/sin θ` in `h`.
    pub(crate) fn coefficients(&self) -> (&[f64; Self::TERMS], &[f64; Self::TERMS]) {
        (&self.cos_coef, &self.sin_coef)
    }

    /// `blend(a, b, u)`, to within a few ulps. The result is not renormalised:
    /// its length is 1 to about 1e-15 (callers such as [`mid`] normalise anyway).
    #[inline]
    pub fn apply(&self, a: DVec3, b: DVec3) -> DVec3 {
        let d = a - b;
        let h = 0.25 * d.length_squared();
        if h > Self::H_MAX {
            return blend(a, b, self.u);
        }
        // Number of terms so that h^k·|coef| is below 1e-17: ~ log(1e-17)/log(h).
        let n = terms_for(h);
        let (mut cu, mut su) = (self.cos_coef[n - 1], self.sin_coef[n - 1]);
        for k in (0..n - 1).rev() {
            // plain multiply-add: `mul_add` is a slow library call on CPUs
            // built without the FMA target feature (the default x86-64 target)
            cu = cu * h + self.cos_coef[k];
            su = su * h + self.sin_coef[k];
        }
        // r = a (cos uθ − c · sin uθ / sin θ) + b · sin uθ / sin θ, c = 1 − 2h.
        let c = 1.0 - 2.0 * h;
        a * (cu - c * su) + b * su
    }
}

/// Every blend sums at least this many series terms: enough for `h < 1e-3`
/// (θ < 3.6°, where the neighbours of the finer levels sit), so the vector
/// path's lanes share their first terms and only wider angles add more.
pub(crate) const MIN_TERMS: usize = 6;

/// `TERM_THRESHOLDS[k]`: the smallest `h` whose series uses term `k`
/// (`terms_for(h) > k` ⇔ `h ≥ TERM_THRESHOLDS[k]`), for the vector path
/// ([`crate::simd`]), where each lane starts its sum at its own term.
pub(crate) const TERM_THRESHOLDS: [f64; FixedBlend::TERMS] = [
    0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1e-3, 1e-3, 1e-3, 1e-2, 1e-2, 1e-2, 1e-2, 1e-2, 0.05, 0.05, 0.05,
    0.05, 0.05, 0.05, 0.05, 0.05, 0.05, 0.05,
];

/// How many series terms [`FixedBlend::apply`] sums for `h`: the last term
/// `h^(n−1)·|coef|` is below 1e-17 (`h^6 ≤ 1e-18` for `h < 1e-3`, …).
#[inline]
pub(crate) fn terms_for(h: f64) -> usize {
    if h < 1e-3 {
        MIN_TERMS
    } else if h < 1e-2 {
        9
    } else if h < 0.05 {
        14
    } else {
        FixedBlend::TERMS
    }
}

/// The general combination `Σ cᵢ tᵢ` on the sphere, `Σ cᵢ = 1` (Eqs. 35–48):
/// reversal-symmetric recursive halving.
///
/// - one tangent: itself;
/// - an even count: left = indices `0..=(n−1)/2`, right = the rest;
/// - an odd count: the middle index belongs to both halves with half its weight;
/// - with `d0` the left weight sum and `d1 = 1 − d0`, the result is
///   `blend(combine(left, c/d0), combine(right, c/d1), d1)`; a half of zero weight
///   is dropped.
///
/// The weights need not be positive (only their sum matters). Returns `None` for
/// empty input or weights that do not sum to 1 within 1e-9.
pub fn combine(ts: &[DVec3], cs: &[f64]) -> Option<DVec3> {
    if ts.is_empty() || ts.len() != cs.len() {
        return None;
    }
    let sum: f64 = cs.iter().sum();
    if !sum.is_finite() || (sum - 1.0).abs() > 1e-9 {
        return None;
    }
    Some(combine_rec(ts, cs))
}

fn combine_rec(ts: &[DVec3], cs: &[f64]) -> DVec3 {
    let len = ts.len();
    if len == 1 {
        return ts[0];
    }
    let total: f64 = cs.iter().sum();
    let (left_t, left_c, right_t, right_c): (&[DVec3], Vec<f64>, &[DVec3], Vec<f64>);
    if len.is_multiple_of(2) {
        let h = len / 2;
        left_t = &ts[..h];
        right_t = &ts[h..];
        left_c = cs[..h].to_vec();
        right_c = cs[h..].to_vec();
    } else {
        let m = len / 2;
        left_t = &ts[..=m];
        right_t = &ts[m..];
        left_c = cs[..=m]
            .iter()
            .enumerate()
            .map(|(i, &c)| if i == m { c / 2.0 } else { c })
            .collect();
        right_c = cs[m..]
            .iter()
            .enumerate()
            .map(|(i, &c)| if i == 0 { c / 2.0 } else { c })
            .collect();
    }
    let d0: f64 = left_c.iter().sum::<f64>() / total;
    let d1 = 1.0 - d0;
    if d0.abs() < 1e-300 {
        return combine_rec(right_t, &right_c);
    }
    if d1.abs() < 1e-300 {
        return combine_rec(left_t, &left_c);
    }
    let l = combine_rec(left_t, &left_c);
    let r = combine_rec(right_t, &right_c);
    blend(l, r, d1)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn unit(x: f64, y: f64, z: f64) -> DVec3 {
        DVec3::new(x, y, z).normalize()
    }

    #[test]
    fn blend_obtuse_angle_uses_atan2() {
        // 120° apart: asin(|a×b|) would say 60°.
        let a = DVec3::X;
        let b = unit(-0.5, 3f64.sqrt() / 2.0, 0.0);
        let m = blend(a, b, 0.5);
        let expect = unit(0.5, 3f64.sqrt() / 2.0, 0.0);
        assert!(
            (m - expect).length() < 1e-15,
            "blend(a,b,1/2) = {m:?}, expected {expect:?}"
        );
    }

    #[test]
    fn blend_midpoint_matches_mid() {
        let a = unit(1.0, 2.0, 3.0);
        let b = unit(-2.0, 0.5, 1.0);
        assert!((blend(a, b, 0.5) - mid(a, b)).length() < 1e-15);
    }

    #[test]
    fn blend_degenerate_pairs_are_unit() {
        let a = unit(0.3, -0.2, 0.9);
        for u in [-0.125, 0.0, 0.25, 0.5, 1.125, 3.0] {
            let e = blend(a, a, u);
            assert!((e - a).length() < 1e-15, "equal pair at u={u}: {e:?}");
            let before = antipodal_events();
            let r = blend(a, -a, u);
            assert!(
                (r.length() - 1.0).abs() < 1e-14 && r.is_finite(),
                "antipodal u={u}: {r:?}"
            );
            assert!(antipodal_events() > before, "antipodal event counted");
            let expect_angle = (u * std::f64::consts::PI).rem_euclid(std::f64::consts::TAU);
            let got = a.dot(r).clamp(-1.0, 1.0).acos();
            let want = if expect_angle > std::f64::consts::PI {
                std::f64::consts::TAU - expect_angle
            } else {
                expect_angle
            };
            assert!(
                (got - want).abs() < 1e-7,
                "antipodal angle u={u}: {got} vs {want}"
            );
        }
        let m = mid(a, -a);
        assert!((m.length() - 1.0).abs() < 1e-14 && m.dot(a).abs() < 1e-12);
    }

    #[test]
    fn quarters_match_blend_and_singles() {
        for k in 0..400 {
            let ang = 1e-9 + (k as f64 / 400.0) * (std::f64::consts::PI - 1e-3);
            let a = unit(0.2, 0.7, -0.3);
            let axis = a.any_orthonormal_vector();
            let b = glam::DQuat::from_axis_angle(axis, ang) * a;
            let (q, t) = quarters(a, b);
            assert_eq!((q, t), (quarter(a, b), three_quarters(a, b)), "θ={ang}");
            // |a + b| = 2 cos(θ/2) is the conditioning of the midpoint
            let tol = 2e-15 + 1e-15 / (ang / 2.0).cos();
            assert!((q - blend(a, b, 0.25)).length() < tol, "¼ at θ={ang}");
            assert!((t - blend(a, b, 0.75)).length() < tol, "¾ at θ={ang}");
            assert!((q - mid(a, mid(a, b))).length() < tol, "Eq. 53 at θ={ang}");
        }
        let a = unit(0.3, -0.2, 0.9);
        let (q, t) = quarters(a, -a);
        assert!((q.length() - 1.0).abs() < 1e-14 && (t.length() - 1.0).abs() < 1e-14);
    }

    #[test]
    fn fixed_blend_matches_trig_blend() {
        for &u in &[-0.125, 0.25, 0.75, 1.125, 9.0 / 8.0, -1.0 / 16.0] {
            let fb = FixedBlend::new(u);
            for k in 0..200 {
                let ang = 1e-12 + (k as f64 / 200.0).powi(3) * 1.5;
                let a = unit(0.2, 0.7, -0.3);
                let axis = a.any_orthonormal_vector();
                let b = glam::DQuat::from_axis_angle(axis, ang) * a;
                let x = fb.apply(a, b);
                let y = blend(a, b, u);
                assert!((x - y).length() < 4e-15, "u={u} θ={ang}: {x:?} vs {y:?}");
            }
        }
    }

    #[test]
    fn every_blend_takes_the_minimum_terms() {
        // simd::kernels sums terms below MIN_TERMS in every lane unmasked
        assert!(TERM_THRESHOLDS[..MIN_TERMS].iter().all(|&t| t == 0.0));
        const { assert!(TERM_THRESHOLDS[MIN_TERMS] > 0.0) };
        assert_eq!(terms_for(0.0), MIN_TERMS);
    }

    #[test]
    fn term_thresholds_agree_with_terms_for() {
        let mut h = 1e-12;
        while h < 1.0 {
            for x in [h, h * 0.999_999, h * 1.000_001] {
                let n = terms_for(x);
                for (k, &t) in TERM_THRESHOLDS.iter().enumerate() {
                    assert_eq!(k < n, x >= t, "h = {x}, k = {k}");
                }
            }
            h *= 1.01;
        }
        for t in [1e-3f64, 1e-2, 0.05] {
            for x in [t, f64::from_bits(t.to_bits() - 1)] {
                let n = terms_for(x);
                for (k, &th) in TERM_THRESHOLDS.iter().enumerate() {
                    assert_eq!(k < n, x >= th, "h = {x}, k = {k}");
                }
            }
        }
    }

    #[test]
    fn combine_two_is_blend() {
        let a = unit(1.0, 0.0, 0.2);
        let b = unit(0.0, 1.0, 0.5);
        let c = combine(&[a, b], &[0.3, 0.7]).unwrap();
        assert!((c - blend(a, b, 0.7)).length() < 1e-15);
        assert_eq!(combine(&[a], &[1.0]), Some(a));
        assert_eq!(combine(&[a, b], &[0.3, 0.3]), None);
    }
}
