//! A design from row and column positions (`docs/math.md §12`, "The
//! tangents").
//!
//! Positions are fractions: a column node `x ∈ [0, 1]` is the fraction of
//! every row's arc length, a row node `y ∈ [0, 1]` the fraction of the
//! initial curve's. Control row `j` at `y_j` is the reference's row at arc
//! length `t_j = y_j L_t` along the anchor curve, of length `λ_j = ℓ(v_j)`;
//! the arc length of control `(i, j)` is `s_ij = x_i λ_j` (eq. 12.3), so
//! `σ_j = x_a λ_j` is the anchor's, and every parameter is a fixed multiple
//! of what it measures: whatever the scheme's scalar rules make of them,
//! `s`, `t` and the tangents are combined with the same weights and stay
//! consistent to second order.
//!
//! * **Kobbelt** (interpolating): the control positions are the nodes, the
//!   control tangents the samples `T(x_i λ_j, v_j)`.
//! * **Catmull–Clark, Doo–Sabin** (approximating): one phantom control on
//!   each side, in both directions, placed so that the net refined to the fit
//!   depth starts at 0 and ends at 1 (the level's first and last scalars are
//!   linear in the controls: a 2 × 2 solve, eq. 12.5). The interior controls
//!   are turned by the sphere iteration of §7 until the limit tangent at
//!   every node is the sample at the node's limit position; the phantoms are
//!   the samples continued along great circles.

use super::error::ReferenceFitError;
use super::options::AnchorAt;
use super::reference::{AnchorCurve, Frame, RowTable};
use crate::grid::Grid;
use crate::levels::design::Design;
use crate::levels::surface::{BlendOrder, SurfaceScheme};
use crate::levels::tangent_interpolation::{RELAXATION, limit_tangent};
use crate::sphere::blend::blend;
use crate::streamline::initial_curve::InitialCurve;
use glam::DVec3;
use std::collections::HashMap;

/// Interior node positions in both directions, increasing, in `[0, 1]`.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Nodes {
    pub cols: Vec<f64>,
    pub rows: Vec<f64>,
}

/// The smallest net of a scheme and anchor: 4 × 4 control tangents (5
/// columns with the anchor in the middle, so that a column sits there).
pub(crate) fn initial_nodes(scheme: SurfaceScheme, anchor: AnchorAt) -> Nodes {
    let thirds = vec![0.0, 1.0 / 3.0, 2.0 / 3.0, 1.0];
    match (scheme, anchor) {
        (SurfaceScheme::Kobbelt { .. }, AnchorAt::First) => Nodes {
            cols: thirds.clone(),
            rows: thirds,
        },
        (SurfaceScheme::Kobbelt { .. }, AnchorAt::Middle) => Nodes {
            cols: vec![0.0, 0.25, 0.5, 0.75, 1.0],
            rows: thirds,
        },
        (SurfaceScheme::CatmullClark, AnchorAt::First) => Nodes {
            cols: vec![0.0, 1.0],
            rows: vec![0.0, 1.0],
        },
        (SurfaceScheme::CatmullClark, AnchorAt::Middle) => Nodes {
            cols: vec![0.0, 0.5, 1.0],
            rows: vec![0.0, 1.0],
        },
        (SurfaceScheme::DooSabin, AnchorAt::First) => Nodes {
            cols: vec![0.25, 0.75],
            rows: vec![0.25, 0.75],
        },
        (SurfaceScheme::DooSabin, AnchorAt::Middle) => Nodes {
            cols: vec![1.0 / 6.0, 0.5, 5.0 / 6.0],
            rows: vec![0.25, 0.75],
        },
    }
}

/// The fraction of each row where the streamlines are anchored: the first
/// node for the first column (0, or the first interior node of Doo–Sabin,
/// whose limit never reaches its border), one half for the middle.
pub(crate) fn anchor_fraction(scheme: SurfaceScheme, anchor: AnchorAt) -> f64 {
    match anchor {
        AnchorAt::First => initial_nodes(scheme, anchor).cols[0],
        AnchorAt::Middle => 0.5,
    }
}

/// Phantoms per side of a scheme (1 for the approximating ones).
pub(crate) fn phantoms(scheme: SurfaceScheme) -> usize {
    usize::from(!scheme.is_interpolatory())
}

/// Refines scalars `depth` times.
fn refine_to(scheme: SurfaceScheme, c: &[f64], depth: u32) -> Vec<f64> {
    let curve = scheme.curve();
    let mut cur = c.to_vec();
    let mut next = Vec::new();
    for _ in 0..depth {
        curve.refine_scalars(&cur, &mut next);
        std::mem::swap(&mut cur, &mut next);
    }
    cur
}

/// The controls of one direction: the nodes, with a phantom on each side
/// for an approximating scheme such that the level `depth` runs from 0 to 1
/// (eq. 12.5). `None` when they would not increase strictly.
pub(crate) fn controls(scheme: SurfaceScheme, nodes: &[f64], depth: u32) -> Option<Vec<f64>> {
    if scheme.is_interpolatory() {
        return Some(nodes.to_vec());
    }
    let n = nodes.len() + 2;
    let mut c = vec![0.0; n];
    c[1..n - 1].copy_from_slice(nodes);
    let ends = |v: &[f64]| -> Option<(f64, f64)> {
        let r = refine_to(scheme, v, depth.max(1));
        Some((*r.first()?, *r.last()?))
    };
    let (f0, l0) = ends(&c)?;
    let mut unit = vec![0.0; n];
    unit[0] = 1.0;
    let (a0, b0) = ends(&unit)?;
    unit[0] = 0.0;
    unit[n - 1] = 1.0;
    let (a1, b1) = ends(&unit)?;
    // f0 + a0 p0 + a1 p1 = 0, l0 + b0 p0 + b1 p1 = 1
    let det = a0 * b1 - a1 * b0;
    if det.is_nan() || det.abs() <= 1e-300 {
        return None;
    }
    let (r0, r1) = (-f0, 1.0 - l0);
    c[0] = (r0 * b1 - a1 * r1) / det;
    c[n - 1] = (a0 * r1 - r0 * b0) / det;
    let rising = c.windows(2).all(|w| w[1] > w[0]) && c.iter().all(|x| x.is_finite());
    rising.then_some(c)
}

/// The limit weight of a neighbour at a node: 1/6 for the cubic B-spline,
/// 1/8 for Chaikin, 0 for the interpolating 4-point rule.
pub(crate) fn limit_weight(scheme: SurfaceScheme) -> f64 {
    match scheme {
        SurfaceScheme::CatmullClark => 1.0 / 6.0,
        SurfaceScheme::DooSabin => 1.0 / 8.0,
        SurfaceScheme::Kobbelt { .. } => 0.0,
    }
}

/// The limit of scalars `c` at interior index `i` (the controls themselves
/// at the borders).
pub(crate) fn limit_at(scheme: SurfaceScheme, c: &[f64], i: usize) -> f64 {
    let w = limit_weight(scheme);
    if w == 0.0 || i == 0 || i + 1 >= c.len() {
        return c[i];
    }
    w * c[i - 1] + (1.0 - 2.0 * w) * c[i] + w * c[i + 1]
}

/// Reference samples with their rows kept: rows by their arc length `t`
/// along the anchor curve, tangents by `(t, fraction)`.
pub(crate) struct Sampler<'f, 'a> {
    pub f: &'f Frame<'a>,
    pub anchor: &'f AnchorCurve,
    rows: HashMap<u64, RowTable>,
    tangents: HashMap<(u64, u64), DVec3>,
}

impl<'f, 'a> Sampler<'f, 'a> {
    pub fn new(f: &'f Frame<'a>, anchor: &'f AnchorCurve) -> Self {
        Sampler {
            f,
            anchor,
            rows: HashMap::new(),
            tangents: HashMap::new(),
        }
    }

    /// The row at arc length `t` of the anchor curve (clamped to it).
    pub fn row(&mut self, t: f64) -> Result<&RowTable, ReferenceFitError> {
        let key = t.to_bits();
        if !self.rows.contains_key(&key) {
            let v = self.anchor.v_exact(self.f, t)?;
            let row = RowTable::new(self.f, v)?;
            self.rows.insert(key, row);
        }
        self.rows
            .get(&key)
            .ok_or(ReferenceFitError::NonFinite { what: "row" })
    }

    /// The unit tangent at the fraction `x` of the row at `t`.
    pub fn tangent(&mut self, t: f64, x: f64) -> Result<DVec3, ReferenceFitError> {
        let key = (t.to_bits(), x.to_bits());
        if let Some(&d) = self.tangents.get(&key) {
            return Ok(d);
        }
        let f = self.f;
        let row = self.row(t)?;
        let v = row.v;
        let u = row.u_exact(f, x);
        let d = f.tangent(u, v)?;
        self.tangents.insert(key, d);
        Ok(d)
    }
}

/// Sweeps at most of [`limit_lengths`].
const LENGTH_SWEEPS: usize = 200;

/// The phantom row lengths continued linearly from the two rows next to
/// them (at least half the next one's).
fn continue_lengths(r: &[f64], lam: &mut [f64]) {
    let m = lam.len();
    let line = |lam: &[f64], j0: usize, j1: usize, j: usize| {
        let k = (r[j] - r[j0]) / (r[j1] - r[j0]);
        let l = lam[j0] + k * (lam[j1] - lam[j0]);
        l.max(0.5 * lam[j0])
    };
    lam[0] = line(lam, 1, 2, 0);
    lam[m - 1] = line(lam, m - 2, m - 3, m - 1);
}

/// Control row lengths of an approximating scheme whose limit at every
/// interior row is `want` (the reference's length at the limit row), the
/// phantoms continued linearly: progressive interpolation on the scalars,
/// `λ ← λ + (want − limit(λ))`, which contracts by at least `4w` (the
/// limit weight's) a sweep. Without it the limit's rows are the blend
/// `(λ_{j−1} + 4λ_j + λ_{j+1})/6` of lengths sampled elsewhere, off by
/// `λ''h²/6` wherever the rows' length is not linear across them (a torus:
/// the fit could not come within its tolerance with any net).
pub(crate) fn limit_lengths(scheme: SurfaceScheme, r: &[f64], want: &[f64]) -> Vec<f64> {
    let m = want.len();
    let mut lam = want.to_vec();
    continue_lengths(r, &mut lam);
    let scale = want.iter().fold(0.0f64, |a, x| a.max(x.abs()));
    let mut next = lam.clone();
    for _ in 0..LENGTH_SWEEPS {
        let mut worst = 0.0f64;
        for j in 1..m - 1 {
            let e = want[j] - limit_at(scheme, &lam, j);
            worst = worst.max(e.abs());
            next[j] = lam[j] + e;
        }
        if !next.iter().all(|x| x.is_finite() && *x > 0.0) {
            // (a row of no length: keep the samples)
            let mut lam = want.to_vec();
            continue_lengths(r, &mut lam);
            return lam;
        }
        if worst <= 1e-14 * scale {
            break;
        }
        lam.copy_from_slice(&next);
        continue_lengths(r, &mut lam);
    }
    lam
}

/// What [`build_design`] needs beyond the nodes.
pub(crate) struct Setup<'c> {
    pub scheme: SurfaceScheme,
    pub order: BlendOrder,
    pub depth: u32,
    pub anchor_fraction: f64,
    pub initial: &'c InitialCurve,
    /// The initial curve's length `L_t`.
    pub length: f64,
    /// The sphere iteration stops when every node's limit tangent is
    /// within this angle (radians) of its sample.
    pub angle_tolerance: f64,
}

/// Sphere iterations at most for the approximating schemes.
const MAX_SPHERE_ITERATIONS: usize = 300;

/// The phantom rows and columns continued along great circles through the
/// two controls next to them, at the controls' positions, so that a net
/// sampled from a tangent field linear in the positions stays linear and the
/// fit depth's border tangents are the field's at the border (eq. 12.5).
fn set_phantoms(net: &mut Grid<DVec3>, c: &[f64], r: &[f64]) {
    let (m, n) = (net.rows(), net.cols());
    for j in 1..m - 1 {
        net.set(j, 0, extend(net.get(j, 1), c[1], net.get(j, 2), c[2], c[0]));
        let e = extend(
            net.get(j, n - 2),
            c[n - 2],
            net.get(j, n - 3),
            c[n - 3],
            c[n - 1],
        );
        net.set(j, n - 1, e);
    }
    for i in 0..n {
        net.set(0, i, extend(net.get(1, i), r[1], net.get(2, i), r[2], r[0]));
        let e = extend(
            net.get(m - 2, i),
            r[m - 2],
            net.get(m - 3, i),
            r[m - 3],
            r[m - 1],
        );
        net.set(m - 1, i, e);
    }
}

/// The sphere iteration of §7 with phantom borders: every interior control
/// is turned by `RELAXATION` times the rotation from its limit tangent to
/// its node's sample, the phantoms following the interior after every sweep.
fn interpolate_interior(
    scheme: SurfaceScheme,
    order: BlendOrder,
    targets: &Grid<DVec3>,
    c: &[f64],
    r: &[f64],
    tolerance: f64,
) -> Grid<DVec3> {
    let (m, n) = (targets.rows(), targets.cols());
    let mut cur = targets.clone();
    for _ in 0..MAX_SPHERE_ITERATIONS {
        set_phantoms(&mut cur, c, r);
        let mut worst = 0.0f64;
        let mut next = cur.clone();
        for j in 1..m - 1 {
            for i in 1..n - 1 {
                let Some(l) = limit_tangent(scheme, order, &cur, j, i) else {
                    continue;
                };
                let d = targets.get(j, i);
                let x = l.cross(d);
                let a = x.length().atan2(l.dot(d));
                worst = worst.max(a);
                if let Some(axis) = x.try_normalize() {
                    let q = glam::DQuat::from_axis_angle(axis, RELAXATION * a);
                    next.set(j, i, (q * cur.get(j, i)).normalize());
                }
            }
        }
        if worst <= tolerance {
            break;
        }
        cur = next;
    }
    set_phantoms(&mut cur, c, r);
    cur
}

/// Why a net could not be made from nodes.
#[derive(Debug)]
pub(crate) enum BuildFailure {
    /// The phantoms would not keep the positions increasing.
    Uneven,
    /// The anchor fraction is not a column node.
    NoAnchor,
    /// A refusal to pass on.
    Error(ReferenceFitError),
}

impl From<ReferenceFitError> for BuildFailure {
    fn from(e: ReferenceFitError) -> Self {
        BuildFailure::Error(e)
    }
}

/// Extrapolates along the great circle through `a` (at position `pa`) and
/// `b` (at `pb`) to position `p`.
fn extend(a: DVec3, pa: f64, b: DVec3, pb: f64, p: f64) -> DVec3 {
    if (pb - pa).abs() > 0.0 {
        blend(a, b, (p - pa) / (pb - pa))
    } else {
        a
    }
}

/// The design of `nodes` (eq. 12.3).
pub(crate) fn build_design(
    sampler: &mut Sampler<'_, '_>,
    nodes: &Nodes,
    setup: &Setup<'_>,
) -> Result<Design, BuildFailure> {
    let scheme = setup.scheme;
    let c = controls(scheme, &nodes.cols, setup.depth).ok_or(BuildFailure::Uneven)?;
    let r = controls(scheme, &nodes.rows, setup.depth).ok_or(BuildFailure::Uneven)?;
    let (n, m) = (c.len(), r.len());
    let ph = phantoms(scheme);
    let anchor = nodes
        .cols
        .iter()
        .position(|&x| x == setup.anchor_fraction)
        .ok_or(BuildFailure::NoAnchor)?
        + ph;
    let lt = setup.length;
    // row lengths: sampled at the node rows (Kobbelt); for an approximating
    // scheme, whose limit row `j` lies at `limit_at(r, j)` and has the
    // length `limit_at(λ, j)`, the lengths are turned until that limit is
    // the reference's row length there, the phantoms continued linearly
    let lam = if ph == 0 {
        let mut lam = Vec::with_capacity(m);
        for &y in &r {
            lam.push(sampler.row(y * lt)?.length());
        }
        lam
    } else {
        let mut want = vec![0.0; m];
        for (j, w) in want.iter_mut().enumerate().take(m - 1).skip(1) {
            let y = limit_at(scheme, &r, j).clamp(0.0, 1.0);
            *w = sampler.row(y * lt)?.length();
        }
        limit_lengths(scheme, &r, &want)
    };
    let mut s = Vec::with_capacity(n * m);
    for &l in &lam {
        s.extend(c.iter().map(|x| x * l));
    }
    let t: Vec<f64> = r.iter().map(|y| y * lt).collect();
    let mut net = Grid::filled(m, n, DVec3::X);
    if ph == 0 {
        for (j, &tj) in t.iter().enumerate() {
            for (i, &ci) in c.iter().enumerate() {
                net.set(j, i, sampler.tangent(tj, ci)?);
            }
        }
    } else {
        let lc: Vec<f64> = (0..n).map(|i| limit_at(scheme, &c, i)).collect();
        let lr: Vec<f64> = (0..m).map(|j| limit_at(scheme, &r, j)).collect();
        for (j, &lj) in lr.iter().enumerate().take(m - 1).skip(1) {
            let t = lj.clamp(0.0, 1.0) * lt;
            for (i, &li) in lc.iter().enumerate().take(n - 1).skip(1) {
                net.set(j, i, sampler.tangent(t, li.clamp(0.0, 1.0))?);
            }
        }
        net = interpolate_interior(scheme, setup.order, &net, &c, &r, setup.angle_tolerance);
    }
    let s = Grid::new(m, n, s).map_err(ReferenceFitError::from)?;
    Design::new(
        &net,
        s,
        t,
        anchor,
        scheme,
        setup.order,
        setup.initial.clone(),
    )
    .map_err(|e| BuildFailure::Error(e.into()))
}
