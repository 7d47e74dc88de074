//! A streamline's curvature as designers read it: `κ` over arc length `s`,
//! and the logarithmic curvature graph of Miura's aesthetic curves
//! (`docs/math.md §9`; K. T. Miura, "A general equation of aesthetic curves
//! and its self-affinity", CAD&A 3, 2006).
//!
//! * **Curvature profile.** A streamline is integrated from unit tangents
//!   `t_k` at arc lengths `s_k` (Eq. 65); between `t_k` and `t_{k+1}` its
//!   tangent turns by `θ_k` over `s_{k+1} − s_k`, so `κ_k = θ_k / (s_{k+1} − s_k)`
//!   is the mean curvature over that interval, put at its midpoint
//!   `(s_k + s_{k+1}) / 2` ([`crate::analysis::streamline_curvature`]). For a
//!   clothoid (`κ = c·s`) that is exact; for a circle it is `1/R` exactly.
//! * **Logarithmic curvature graph.** With `ρ = 1/κ`, a log-aesthetic curve
//!   has `ρ · ds/dρ = C ρ^α`, so `y = log(ρ |ds/dρ|)` against `x = log ρ` is a
//!   straight line of slope `α` (clothoid `α = −1`, logarithmic spiral
//!   `α = 1`, circle involute `α = 2`). Between neighbouring samples,
//!   `|ds/dρ| ≈ |Δs / Δρ|` at `ρ = √(ρ_k ρ_{k+1})`, the geometric mean: with
//!   it the graph of a clothoid and of a logarithmic spiral sampled at any
//!   spacing is exactly their line. The slope is the least-squares line
//!   through the graph's points; the residual is the RMS distance in `y`.
//! * A curve whose `κ` is constant (a circle, or a straight line with `κ = 0`)
//!   has no graph (`ds/dρ` is unbounded): it is reported as such
//!   ([`LogCurvatureGraph::Circle`], [`LogCurvatureGraph::Straight`]).

use crate::analysis::streamline_curvature;
use glam::DVec3;

/// Relative spread of `κ` (`(max − min) / max`) below which a curve counts as a circle.
pub const CIRCLE_TOLERANCE: f64 = 1e-9;

/// Curvature below which a curve counts as straight (in 1 / length units).
pub const STRAIGHT_KAPPA: f64 = 1e-12;

/// `κ` at arc lengths `s` along one streamline.
#[derive(Debug, Clone, PartialEq)]
pub struct CurvatureProfile {
    /// Arc length of each sample (the midpoints of the tangent intervals).
    pub s: Vec<f64>,
    /// The curvature there (≥ 0).
    pub kappa: Vec<f64>,
}

/// The curvature profile of a streamline integrated from `tangents` at arc
/// lengths `s` (module doc); `n − 1` samples for `n` tangents.
pub fn curvature_profile(tangents: &[DVec3], s: &[f64]) -> CurvatureProfile {
    let kappa = streamline_curvature(tangents, s);
    let s = s.windows(2).map(|w| 0.5 * (w[0] + w[1])).collect();
    CurvatureProfile { s, kappa }
}

/// The logarithmic curvature graph of a profile.
#[derive(Debug, Clone, PartialEq)]
pub enum LogCurvatureGraph {
    /// `κ ≈ 0` everywhere: a straight line, `ρ = ∞`.
    Straight,
    /// `κ` constant within [`CIRCLE_TOLERANCE`]: a circle of this curvature;
    /// its graph would be the single abscissa `log(1/κ)`, `ds/dρ` unbounded.
    Circle {
        /// The mean curvature.
        kappa: f64,
    },
    /// Too few usable samples (fewer than 2 intervals where `ρ` changes).
    TooFew,
    /// A graph with its fitted line `y = α x + intercept`.
    Graph {
        /// `(log ρ, log(ρ |ds/dρ|))` per pair of neighbouring samples.
        points: Vec<(f64, f64)>,
        /// The slope α.
        alpha: f64,
        /// The line's value at `log ρ = 0`.
        intercept: f64,
        /// RMS of `y − (α x + intercept)` over the points.
        residual: f64,
    },
}

/// The logarithmic curvature graph of `profile` (module doc). Intervals
/// where `κ` is 0 or does not change are left out (no finite point).
pub fn log_curvature_graph(profile: &CurvatureProfile) -> LogCurvatureGraph {
    let k = &profile.kappa;
    if k.is_empty() {
        return LogCurvatureGraph::TooFew;
    }
    let (lo, hi) = k
        .iter()
        .fold((f64::INFINITY, 0.0_f64), |(a, b), &v| (a.min(v), b.max(v)));
    if hi <= STRAIGHT_KAPPA {
        return LogCurvatureGraph::Straight;
    }
    if hi - lo <= CIRCLE_TOLERANCE * hi {
        let kappa = k.iter().sum::<f64>() / k.len() as f64;
        return LogCurvatureGraph::Circle { kappa };
    }
    let mut points = Vec::with_capacity(k.len());
    for i in 0..k.len().saturating_sub(1) {
        let (k0, k1) = (k[i], k[i + 1]);
        if !(k0 > STRAIGHT_KAPPA && k1 > STRAIGHT_KAPPA) {
            continue;
        }
        let (r0, r1) = (1.0 / k0, 1.0 / k1);
        let (dr, ds) = (r1 - r0, profile.s[i + 1] - profile.s[i]);
        if dr == 0.0 || ds.is_nan() || ds <= 0.0 {
            continue;
        }
        let rho = (r0 * r1).sqrt();
        let (x, y) = (rho.ln(), (rho * (ds / dr).abs()).ln());
        if x.is_finite() && y.is_finite() {
            points.push((x, y));
        }
    }
    if points.len() < 2 {
        return LogCurvatureGraph::TooFew;
    }
    let n = points.len() as f64;
    let (mx, my) = points
        .iter()
        .fold((0.0, 0.0), |(a, b), &(x, y)| (a + x / n, b + y / n));
    let (sxx, sxy) = points.iter().fold((0.0, 0.0), |(a, b), &(x, y)| {
        (a + (x - mx) * (x - mx), b + (x - mx) * (y - my))
    });
    if sxx.is_nan() || sxx <= 0.0 {
        // every point at one ρ: κ takes two values only; no slope to give
        return LogCurvatureGraph::TooFew;
    }
    let alpha = sxy / sxx;
    let intercept = my - alpha * mx;
    let residual = (points
        .iter()
        .map(|&(x, y)| (y - alpha * x - intercept).powi(2))
        .sum::<f64>()
        / n)
        .sqrt();
    LogCurvatureGraph::Graph {
        points,
        alpha,
        intercept,
        residual,
    }
}
