//! Curve subdivision of tangents on the Gaussian sphere (paper 000, §3.5–3.7).
//!
//! Open polylines of `n ≥ 2` tangents. One step of each scheme (docs/math.md §2):
//!
//! | scheme | rule | count |
//! |---|---|---|
//! | Chaikin (Eqs. 51–53) | each leg gives `blend(tᵢ,tᵢ₊₁,¼)`, `blend(tᵢ,tᵢ₊₁,¾)`, as two midpoints (Eq. 53) | `2(n−1)` |
//! | cubic B-spline (Eqs. 57–58) | `mid(t₀,t₁)`, then per inner vertex `mid(blend(tᵢ₋₁,tᵢ,¾), blend(tᵢ,tᵢ₊₁,¼))` and edge `mid(tᵢ,tᵢ₊₁)` | `2n−3` |
//! | 4-point (Eqs. 59–61) | keep `tᵢ`; insert `mid(blend(tᵢ₋₁,tᵢ,(8+ω)/8), blend(tᵢ₊₁,tᵢ₊₂,−ω/8))` | `2n−1` |
//!
//! The 4-point end legs use the 3-point rule `mid(blend(t₀,t₁,¼), blend(t₁,t₂,−¼))`
//! (planar `⅜p₀ + ¾p₁ − ⅛p₂`), mirrored at the far end; two tangents get their midpoint.

use crate::error::KernelError;
use crate::limits::{MAX_DEPTH, MAX_TANGENTS_PER_LEVEL};
use crate::sphere::blend::{FixedBlend, mid, quarter, quarters, three_quarters};
use crate::sphere::tangent::normalize_all;
use glam::DVec3;

/// The upper bound (exclusive) of ω for the 4-point rule (defined in
/// [`crate::limits`], which the error messages read too).
pub use crate::limits::OMEGA_MAX;

/// The default ω (the classic 4-point weight `w = 1/16`).
pub const OMEGA_DEFAULT: f64 = 1.0;

/// A curve subdivision scheme on the sphere (and on scalars, for parameters).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum CurveScheme {
    /// Chaikin's corner cutting (quadratic B-spline), approximating.
    Chaikin,
    /// Cubic B-spline refinement, approximating.
    CubicBSpline,
    /// The 4-point interpolatory scheme with tension ω.
    FourPoint { omega: f64 },
}

impl CurveScheme {
    /// Checks ω. Call once at the boundary; refinement assumes a valid scheme.
    pub fn validate(self) -> Result<Self, KernelError> {
        if let CurveScheme::FourPoint { omega } = self
            && !(omega.is_finite() && (0.0..OMEGA_MAX).contains(&omega))
        {
            return Err(KernelError::OmegaOutOfRange { omega });
        }
        Ok(self)
    }

    /// A short lowercase name (`chaikin`, `cubic-bspline`, `four-point`).
    pub fn name(self) -> &'static str {
        match self {
            CurveScheme::Chaikin => "chaikin",
            CurveScheme::CubicBSpline => "cubic-bspline",
            CurveScheme::FourPoint { .. } => "four-point",
        }
    }

    /// The fewest tangents one step accepts.
    pub fn min_len(self) -> usize {
        match self {
            CurveScheme::CubicBSpline => 3,
            _ => 2,
        }
    }

    /// Number of tangents after one step from `n`.
    pub fn refined_len(self, n: usize) -> usize {
        match self {
            CurveScheme::Chaikin => 2 * (n - 1),
            CurveScheme::CubicBSpline => 2 * n - 3,
            CurveScheme::FourPoint { .. } => 2 * n - 1,
        }
    }

    /// Where the limit of the scalars `s` starts and ends (docs/math.md §4,
    /// "The anchor"): the ends themselves for the interpolating 4-point rule;
    /// for the approximating schemes, which shorten a row at every step, the
    /// limit masks at the ends, Chaikin's `(s₀ + s₁)/2` and the cubic
    /// B-spline's `(s₀ + 4s₁ + s₂)/6`, mirrored at the far end. The masks are
    /// exact on scalars, so a row gives the same two values at every level.
    /// Rows shorter than [`Self::min_len`] give their ends.
    pub fn limit_ends(self, s: &[f64]) -> (f64, f64) {
        let n = s.len();
        let (Some(&first), Some(&last)) = (s.first(), s.last()) else {
            return (0.0, 0.0);
        };
        match self {
            CurveScheme::Chaikin if n >= 2 => (0.5 * (s[0] + s[1]), 0.5 * (s[n - 2] + s[n - 1])),
            CurveScheme::CubicBSpline if n >= 3 => (
                (s[0] + 4.0 * s[1] + s[2]) / 6.0,
                (s[n - 3] + 4.0 * s[n - 2] + s[n - 1]) / 6.0,
            ),
            _ => (first, last),
        }
    }

    #[cfg(test)]
    /// Number of tangents after `depth` steps from `n`, or `None` on overflow.
    pub(crate) fn len_at_depth(self, mut n: usize, depth: u32) -> Option<usize> {
        for _ in 0..depth {
            if n < self.min_len() {
                return None;
            }
            n = n.checked_mul(2)?;
            n = self.refined_len(n / 2);
        }
        Some(n)
    }

    /// Checks that `n` tangents can be refined `depth` times within the size cap.
    pub fn check_depth(self, n: usize, depth: u32, rows: usize) -> Result<(), KernelError> {
        if n < self.min_len() {
            return Err(KernelError::TooFewTangents {
                what: self.name(),
                got: n,
                need: self.min_len(),
            });
        }
        let cap = MAX_TANGENTS_PER_LEVEL;
        if depth > MAX_DEPTH {
            return Err(KernelError::DepthPastMax {
                depth,
                max: MAX_DEPTH,
            });
        }
        if n.saturating_mul(rows) > cap {
            return Err(KernelError::TooManyTangents {
                tangents: n.saturating_mul(rows),
                cap,
            });
        }
        let mut m = n;
        for _ in 0..depth {
            if m < self.min_len() {
                return Err(KernelError::TooFewTangents {
                    what: self.name(),
                    got: m,
                    need: self.min_len(),
                });
            }
            m = self.refined_len(m);
            let total = m.saturating_mul(rows);
            if total > cap {
                return Err(KernelError::DepthTooLarge {
                    depth,
                    tangents: total,
                    cap,
                });
            }
        }
        Ok(())
    }

    /// One refinement step of unit tangents into `out` (cleared first).
    /// `input.len() ≥ self.min_len()` and the inputs are unit (not re-checked).
    /// Every output is computed with the operations of [`Prepared::tangent`]
    /// (bit-for-bit equal), sharing each leg's work between its outputs.
    pub(crate) fn refine_tangents(self, input: &[DVec3], out: &mut Vec<DVec3>) {
        out.clear();
        let n = input.len();
        debug_assert!(n >= self.min_len());
        out.reserve(self.refined_len(n));
        match self {
            CurveScheme::Chaikin => {
                for w in input.windows(2) {
                    let (q, t) = quarters(w[0], w[1]); // Eq. 53
                    out.push(q);
                    out.push(t);
                }
            }
            CurveScheme::CubicBSpline => {
                // leg i gives (blend(tᵢ,tᵢ₊₁,¼), blend(tᵢ,tᵢ₊₁,¾)); the vertex
                // point of tᵢ is mid(¾ of leg i−1, ¼ of leg i) (Eq. 58)
                out.push(mid(input[0], input[1]));
                let mut left = three_quarters(input[0], input[1]);
                for i in 1..n - 1 {
                    let (q, t) = quarters(input[i], input[i + 1]);
                    out.push(mid(left, q)); // vertex point, Eq. 58
                    out.push(mid(input[i], input[i + 1])); // edge point, Eq. 57
                    left = t;
                }
            }
            CurveScheme::FourPoint { omega } => FourPointRule::cached(omega).refine(input, out),
        }
    }

    /// Where output `k` of one step on `n` inputs comes from.
    #[inline]
    pub(crate) fn stencil(self, n: usize, k: usize) -> Stencil {
        match self {
            CurveScheme::Chaikin if k.is_multiple_of(2) => Stencil::Quarter(k / 2),
            CurveScheme::Chaikin => Stencil::ThreeQuarters(k / 2),
            CurveScheme::CubicBSpline if k == 0 => Stencil::Mid(0),
            CurveScheme::CubicBSpline if k % 2 == 1 => Stencil::Vertex(k.div_ceil(2)),
            CurveScheme::CubicBSpline => Stencil::Mid(k / 2),
            CurveScheme::FourPoint { .. } if k.is_multiple_of(2) => Stencil::Copy(k / 2),
            CurveScheme::FourPoint { .. } if n == 2 => Stencil::Mid(0),
            CurveScheme::FourPoint { .. } if k == 1 => Stencil::End(0, 1, 2),
            CurveScheme::FourPoint { .. } if k == 2 * n - 3 => Stencil::End(n - 1, n - 2, n - 3),
            CurveScheme::FourPoint { .. } => Stencil::Insert((k - 1) / 2),
        }
    }
}

/// The 4-point rule with its blends precomputed for one ω.
#[derive(Debug, Clone, Copy)]
pub struct FourPointRule {
    /// `blend(·,·,(8+ω)/8)`.
    outer: FixedBlend,
    /// `blend(·,·,−ω/8)`.
    inner: FixedBlend,
    /// `blend(·,·,¼)` and `blend(·,·,−¼)` for the end legs.
    quarter: FixedBlend,
    minus_quarter: FixedBlend,
}

impl FourPointRule {
    /// Precomputes the blends for `omega` (assumed validated).
    pub fn new(omega: f64) -> Self {
        FourPointRule {
            outer: FixedBlend::new((8.0 + omega) / 8.0),
            inner: FixedBlend::new(-omega / 8.0),
            quarter: FixedBlend::new(0.25),
            minus_quarter: FixedBlend::new(-0.25),
        }
    }

    /// The rule for `omega`, from a per-thread cache of the last ω used (building
    /// one costs four 24-term series; a surface step refines hundreds of rows).
    #[inline]
    pub(crate) fn cached(omega: f64) -> Self {
        Self::with_cached(omega, |rule| *rule)
    }

    /// Runs `f` on the cached rule for `omega` without copying it (the rule is
    /// 1.5 kB: the per-entry window path calls this for every output).
    #[inline]
    pub(crate) fn with_cached<R>(omega: f64, f: impl FnOnce(&FourPointRule) -> R) -> R {
        thread_local! {
            static LAST: std::cell::RefCell<Option<(u64, FourPointRule)>> = const { std::cell::RefCell::new(None) };
        }
        LAST.with(|c| {
            let bits = omega.to_bits();
            if !matches!(&*c.borrow(), Some((b, _)) if *b == bits) {
                *c.borrow_mut() = Some((bits, FourPointRule::new(omega)));
            }
            let guard = c.borrow();
            let (_, rule) = guard.as_ref().expect("set above");
            f(rule)
        })
    }

    /// `blend(·,·,(8+ω)/8)`, the outer blend of an insert.
    pub(crate) fn outer(&self) -> &FixedBlend {
        &self.outer
    }

    /// `blend(·,·,−ω/8)`, the inner blend of an insert.
    pub(crate) fn inner(&self) -> &FixedBlend {
        &self.inner
    }

    /// `blend(·,·,¼)`, the first blend of the end rule.
    pub(crate) fn quarter(&self) -> &FixedBlend {
        &self.quarter
    }

    /// `blend(·,·,−¼)`, the second blend of the end rule.
    pub(crate) fn minus_quarter(&self) -> &FixedBlend {
        &self.minus_quarter
    }

    /// The tangent inserted between `b` and `c` with outer neighbours `a`, `d` (Eq. 61).
    #[inline]
    pub fn interior(&self, a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> DVec3 {
        mid(self.outer.apply(a, b), self.inner.apply(c, d))
    }

    /// The tangent inserted between `a` and `b` with `c` beyond `b` (3-point end rule).
    #[inline]
    pub fn end(&self, a: DVec3, b: DVec3, c: DVec3) -> DVec3 {
        mid(self.quarter.apply(a, b), self.minus_quarter.apply(b, c))
    }

    /// One step into `out` (appended). `input.len() ≥ 2`.
    pub fn refine(&self, t: &[DVec3], out: &mut Vec<DVec3>) {
        let n = t.len();
        if n == 2 {
            out.extend_from_slice(&[t[0], mid(t[0], t[1]), t[1]]);
            return;
        }
        out.push(t[0]);
        out.push(self.end(t[0], t[1], t[2]));
        for i in 1..n - 2 {
            out.push(t[i]);
            out.push(self.interior(t[i - 1], t[i], t[i + 1], t[i + 2]));
        }
        out.push(t[n - 2]);
        out.push(self.end(t[n - 1], t[n - 2], t[n - 3]));
        out.push(t[n - 1]);
    }
}

/// Which inputs one output of a step reads, and by which rule (docs/math.md §2).
/// The same stencils drive tangents ([`Prepared::tangent`]) and scalars
/// (`crate::curve::scalar::apply`), so the parameter grids follow the tangents.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Stencil {
    /// Input `i` itself (4-point, even outputs).
    Copy(usize),
    /// The midpoint of inputs `i`, `i+1` (cubic edge points, Eq. 57; 4-point on two inputs).
    Mid(usize),
    /// Chaikin's first point on leg `(i, i+1)`: `blend(tᵢ, tᵢ₊₁, ¼)` (Eq. 53).
    Quarter(usize),
    /// Chaikin's second point on leg `(i, i+1)`: `blend(tᵢ, tᵢ₊₁, ¾)`.
    ThreeQuarters(usize),
    /// The cubic B-spline vertex point of input `i` (reads `i−1 … i+1`, Eq. 58).
    Vertex(usize),
    /// The 4-point insert between inputs `i`, `i+1` (reads `i−1 … i+2`, Eq. 61).
    Insert(usize),
    /// The 3-point end insert between inputs `a` and `b`, with `c` beyond `b`.
    End(usize, usize, usize),
}

impl Stencil {
    /// The lowest and highest input index read.
    pub fn reads(self) -> (usize, usize) {
        match self {
            Stencil::Copy(i) => (i, i),
            Stencil::Mid(i) | Stencil::Quarter(i) | Stencil::ThreeQuarters(i) => (i, i + 1),
            Stencil::Vertex(i) => (i - 1, i + 1),
            Stencil::Insert(i) => (i - 1, i + 2),
            Stencil::End(a, b, c) => (a.min(b).min(c), a.max(b).max(c)),
        }
    }
}

/// A scheme ready to apply entry by entry: the 4-point rule's series are
/// computed once (for the other schemes the rule is unused).
#[derive(Debug, Clone, Copy)]
pub struct Prepared {
    scheme: CurveScheme,
    four: FourPointRule,
}

impl Prepared {
    /// Prepares `scheme` (assumed validated).
    #[inline]
    pub fn new(scheme: CurveScheme) -> Self {
        let omega = match scheme {
            CurveScheme::FourPoint { omega } => omega,
            _ => OMEGA_DEFAULT,
        };
        Prepared {
            scheme,
            four: FourPointRule::cached(omega),
        }
    }

    /// The scheme.
    pub fn scheme(&self) -> CurveScheme {
        self.scheme
    }

    /// The 4-point rule, when the scheme is the 4-point scheme.
    pub(crate) fn four_point(&self) -> Option<&FourPointRule> {
        matches!(self.scheme, CurveScheme::FourPoint { .. }).then_some(&self.four)
    }

    /// The output of stencil `st`, reading input `j` as `f(j)`.
    #[inline(always)]
    pub fn tangent(&self, st: Stencil, f: impl Fn(usize) -> DVec3) -> DVec3 {
        match st {
            Stencil::Copy(i) => f(i),
            Stencil::Mid(i) => mid(f(i), f(i + 1)),
            Stencil::Quarter(i) => quarter(f(i), f(i + 1)),
            Stencil::ThreeQuarters(i) => three_quarters(f(i), f(i + 1)),
            Stencil::Vertex(i) => {
                let b = f(i);
                mid(three_quarters(f(i - 1), b), quarter(b, f(i + 1)))
            }
            Stencil::Insert(i) => self.four.interior(f(i - 1), f(i), f(i + 1), f(i + 2)),
            Stencil::End(a, b, c) => self.four.end(f(a), f(b), f(c)),
        }
    }
}

/// Refines a curve of tangents `depth` times: the kernel's boundary for curves.
/// Inputs are normalised (zero or non-finite ones are errors); ω and the size are checked.
pub fn subdivide(
    scheme: CurveScheme,
    tangents: &[DVec3],
    depth: u32,
) -> Result<Vec<DVec3>, KernelError> {
    let scheme = scheme.validate()?;
    // sizes first: nothing is allocated for a request past the cap
    scheme.check_depth(tangents.len(), depth, 1)?;
    let mut cur = normalize_all(tangents)?;
    let mut next = Vec::new();
    for _ in 0..depth {
        scheme.refine_tangents(&cur, &mut next);
        std::mem::swap(&mut cur, &mut next);
    }
    Ok(cur)
}

/// Like [`subdivide`] for inputs already unit and a scheme already validated,
/// reusing two buffers (no allocation once they are large enough). The result
/// is in `a`. For benchmarks and the incremental pipeline.
pub fn subdivide_into(scheme: CurveScheme, depth: u32, a: &mut Vec<DVec3>, b: &mut Vec<DVec3>) {
    for _ in 0..depth {
        scheme.refine_tangents(a, b);
        std::mem::swap(a, b);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn five() -> Vec<DVec3> {
        [
            (1.0, 0.0, 0.0),
            (1.0, 1.0, 0.0),
            (0.0, 1.0, 0.3),
            (-1.0, 1.0, 1.0),
            (-1.0, 0.0, 0.5),
        ]
        .iter()
        .map(|&(x, y, z)| DVec3::new(x, y, z))
        .collect()
    }

    #[test]
    fn curve_counts_of_table1() {
        let t = five();
        let c = subdivide(CurveScheme::Chaikin, &t, 7).unwrap().len();
        let b = subdivide(CurveScheme::CubicBSpline, &t, 7).unwrap().len();
        let f = subdivide(CurveScheme::FourPoint { omega: 1.0 }, &t, 6)
            .unwrap()
            .len();
        assert_eq!(
            (c, b, f),
            (386, 259, 257),
            "Table 1 counts: Chaikin d7, cubic d7, 4-point d6"
        );
        assert_eq!(CurveScheme::Chaikin.len_at_depth(5, 7), Some(386));
    }

    #[test]
    fn curve_bad_input_is_error() {
        let t = five();
        assert!(matches!(
            subdivide(CurveScheme::FourPoint { omega: 2.5 }, &t, 1),
            Err(KernelError::OmegaOutOfRange { .. })
        ));
        assert!(matches!(
            subdivide(CurveScheme::FourPoint { omega: f64::NAN }, &t, 1),
            Err(KernelError::OmegaOutOfRange { .. })
        ));
        assert!(matches!(
            subdivide(CurveScheme::Chaikin, &t[..1], 1),
            Err(KernelError::TooFewTangents { .. })
        ));
        assert!(matches!(
            subdivide(CurveScheme::Chaikin, &t, 40),
            Err(KernelError::DepthPastMax { depth: 40, max: 16 })
        ));
        assert!(matches!(
            CurveScheme::Chaikin.check_depth(t.len(), 16, 1000),
            Err(KernelError::DepthTooLarge {
                depth: 16,
                cap: MAX_TANGENTS_PER_LEVEL,
                ..
            })
        ));
        assert!(matches!(
            CurveScheme::Chaikin.check_depth(t.len(), 0, MAX_TANGENTS_PER_LEVEL),
            Err(KernelError::TooManyTangents {
                cap: MAX_TANGENTS_PER_LEVEL,
                ..
            })
        ));
        let mut z = t.clone();
        z[2] = DVec3::ZERO;
        let e = subdivide(CurveScheme::Chaikin, &z, 1).unwrap_err();
        assert_eq!(
            e.to_string(),
            "tangent 2 is the zero vector, which has no direction; give it a non-zero direction"
        );
    }
}
