//! Progressive interpolation with Loop surfaces (paper 002; SPEC §7): find the
//! control mesh whose Loop limit surface passes through every vertex of a
//! given mesh.
//!
//! - [`Method::Plain`] is 002's iteration `V^{k+1} = V^k + (V^0 − V^k_∞)`; on
//!   open meshes the boundary vertices first (their limit points depend on the
//!   boundary alone), then the interior ones with the boundary fixed (002 §4).
//! - [`Method::Fast`] solves the same linear system `L V = V^0` by Krylov
//!   iterations. 002 §3 shows `L = D S` with `D` diagonal positive and `S`
//!   symmetric positive definite, so `S V = D⁻¹ V^0` is solved by conjugate
//!   gradients (Jacobi-preconditioned); the boundary system (the six boundary
//!   masks, not symmetric where types mix) by BiCGSTAB. Each costs one or two
//!   applications of the limit operator per iteration, like a plain step; the
//!   iteration counts reported are those applications.
//!
//! Errors are measured as in 002 Table 1: `|V^0 − V_∞|` on the mesh scaled so
//! that its bounding box's largest side is 1.

use crate::loop_subdiv::subdivide::{limit_beta, limit_point};
use crate::loop_subdiv::trimesh::{Topology, TriMesh};
use glam::DVec3;

/// Which iteration.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Method {
    /// 002's progressive iteration.
    #[default]
    Plain,
    /// Conjugate gradients (interior) and BiCGSTAB (boundary) on the same system.
    Fast,
}

impl Method {
    /// `plain` or `fast`.
    pub fn name(self) -> &'static str {
        match self {
            Method::Plain => "plain",
            Method::Fast => "fast",
        }
    }
}

/// Stopping rules.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Options {
    /// Stop when the largest scaled error is below this (002 uses 1e-3).
    pub tolerance: f64,
    /// Give up after this many limit-operator applications per phase.
    pub max_iterations: usize,
    /// Which iteration.
    pub method: Method,
}

impl Options {
    /// Tolerance 1e-3, at most 10,000 iterations, plain.
    pub const DEFAULT: Options = Options {
        tolerance: 1e-3,
        max_iterations: 10_000,
        method: Method::Plain,
    };
}

impl Default for Options {
    fn default() -> Self {
        Options::DEFAULT
    }
}

/// What an interpolation did.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Report {
    /// Iterations on the boundary (0 for a closed mesh).
    pub boundary_iterations: usize,
    /// Iterations on the interior (all vertices of a closed mesh).
    pub interior_iterations: usize,
    /// Largest scaled distance from a given vertex to its limit point.
    pub max_error: f64,
    /// Mean of those distances.
    pub avg_error: f64,
    /// Whether the tolerance was reached.
    pub converged: bool,
    /// The observer stopped it ([`interpolate_observed`]) before it converged.
    pub stopped: bool,
}

impl Report {
    /// Boundary and interior iterations together.
    pub fn iterations(&self) -> usize {
        self.boundary_iterations + self.interior_iterations
    }
}

/// The control mesh positions whose Loop limit points are `mesh`'s vertices
/// (to `opts.tolerance`), and what it took.
pub fn interpolate(mesh: &TriMesh, topo: &Topology, opts: &Options) -> (Vec<DVec3>, Report) {
    interpolate_observed(mesh, topo, opts, &|_| true)
}

/// [`interpolate`], calling `go(iterations so far)` before every iteration
/// and stopping (`Report::stopped`) when it returns `false`: an editor shows
/// progress and cancels through it, off the frame.
pub fn interpolate_observed(
    mesh: &TriMesh,
    topo: &Topology,
    opts: &Options,
    go: &dyn Fn(usize) -> bool,
) -> (Vec<DVec3>, Report) {
    let v0 = &mesh.positions;
    let scale = mesh.scale().max(f64::MIN_POSITIVE);
    let tol = opts.tolerance * scale;
    let bnd: Vec<usize> = (0..v0.len()).filter(|&v| topo.boundary[v]).collect();
    let int: Vec<usize> = (0..v0.len()).filter(|&v| !topo.boundary[v]).collect();
    let mut x = v0.clone();
    let mut report = Report::default();
    let stopped = std::cell::Cell::new(false);
    let observe = |k: usize| {
        let on = go(k);
        if !on {
            stopped.set(true);
        }
        on
    };
    let (bi, bc) = solve(&mut x, v0, topo, &bnd, tol, opts, false, &observe);
    let (ii, ic) = if stopped.get() {
        (0, false)
    } else {
        let go_int = |k: usize| observe(bi + k);
        solve(&mut x, v0, topo, &int, tol, opts, true, &go_int)
    };
    report.boundary_iterations = bi;
    report.interior_iterations = ii;
    report.converged = bc && ic;
    report.stopped = stopped.get() && !report.converged;
    let all: Vec<usize> = (0..v0.len()).collect();
    let mut r = vec![DVec3::ZERO; v0.len()];
    residuals(&x, v0, topo, &all, &mut r);
    let errs: Vec<f64> = r.iter().map(|d| d.length() / scale).collect();
    report.max_error = errs.iter().copied().fold(0.0, f64::max);
    report.avg_error = errs.iter().sum::<f64>() / errs.len().max(1) as f64;
    (x, report)
}

/// Solves for the vertices `set` (others fixed), returning iterations and
/// convergence; stops early when `go(k)` is false.
#[allow(clippy::too_many_arguments)]
fn solve(
    x: &mut [DVec3],
    v0: &[DVec3],
    topo: &Topology,
    set: &[usize],
    tol: f64,
    opts: &Options,
    symmetric: bool,
    go: &dyn Fn(usize) -> bool,
) -> (usize, bool) {
    if set.is_empty() {
        return (0, true);
    }
    let cap = opts.max_iterations;
    match opts.method {
        Method::Plain => plain(x, v0, topo, set, tol, cap, go),
        Method::Fast if symmetric => cg(x, v0, topo, set, tol, cap, go),
        Method::Fast => bicgstab(x, v0, topo, set, tol, cap, go),
    }
}

/// Sets at least this large compute their residuals on two threads.
const PARALLEL_MIN_VERTICES: usize = 65_536;

/// `r_i = v0[set_i] − L(x)[set_i]`, in two halves on two threads when large.
fn residuals(x: &[DVec3], v0: &[DVec3], topo: &Topology, set: &[usize], r: &mut [DVec3]) {
    let run = |r: &mut [DVec3], set: &[usize]| {
        for (ri, &v) in r.iter_mut().zip(set) {
            *ri = v0[v] - limit_point(x, topo, v);
        }
    };
    if set.len() < PARALLEL_MIN_VERTICES {
        return run(r, set);
    }
    let h = set.len() / 2;
    let (r0, r1) = r.split_at_mut(h);
    let (s0, s1) = set.split_at(h);
    crate::parallel::join(|| run(r0, s0), || run(r1, s1));
}

fn max_len(r: &[DVec3]) -> f64 {
    r.iter().map(|v| v.length()).fold(0.0, f64::max)
}

/// 002's iteration on `set`.
fn plain(
    x: &mut [DVec3],
    v0: &[DVec3],
    topo: &Topology,
    set: &[usize],
    tol: f64,
    cap: usize,
    go: &dyn Fn(usize) -> bool,
) -> (usize, bool) {
    let mut r = vec![DVec3::ZERO; set.len()];
    for k in 0..=cap {
        residuals(x, v0, topo, set, &mut r);
        if max_len(&r) < tol {
            return (k, true);
        }
        if k == cap || !go(k) {
            return (k, false);
        }
        for (ri, &v) in r.iter().zip(set) {
            x[v] += *ri;
        }
    }
    (cap, false)
}

/// `L` on `set`, reading `y` for the vertices of `set` and zero elsewhere
/// (the fixed vertices' part goes into the right-hand side).
fn apply_on(y: &[DVec3], topo: &Topology, set: &[usize], scratch: &mut [DVec3], out: &mut [DVec3]) {
    for (&v, &yi) in set.iter().zip(y) {
        scratch[v] = yi;
    }
    for (o, &v) in out.iter_mut().zip(set) {
        *o = limit_point(scratch, topo, v);
    }
}

/// Componentwise dot product: three systems (x, y, z) solved side by side.
fn dot3(a: &[DVec3], b: &[DVec3]) -> DVec3 {
    a.iter().zip(b).fold(DVec3::ZERO, |s, (x, y)| s + *x * *y)
}

/// `a / b` per component, 0 where `b` is 0.
fn safe_div(a: DVec3, b: DVec3) -> DVec3 {
    DVec3::new(
        if b.x != 0.0 { a.x / b.x } else { 0.0 },
        if b.y != 0.0 { a.y / b.y } else { 0.0 },
        if b.z != 0.0 { a.z / b.z } else { 0.0 },
    )
}

/// Right-hand side of `L_set y = v0_set − L(fixed part)`, and the start `y = x_set`.
fn system(
    x: &[DVec3],
    v0: &[DVec3],
    topo: &Topology,
    set: &[usize],
) -> (Vec<DVec3>, Vec<DVec3>, Vec<DVec3>) {
    let mut fixed = x.to_vec();
    for &v in set {
        fixed[v] = DVec3::ZERO;
    }
    let rhs: Vec<DVec3> = set
        .iter()
        .map(|&v| v0[v] - limit_point(&fixed, topo, v))
        .collect();
    let y: Vec<DVec3> = set.iter().map(|&v| x[v]).collect();
    // scratch: zero on `set`'s complement, so `apply_on` sees only `set`
    let scratch = vec![DVec3::ZERO; x.len()];
    (rhs, y, scratch)
}

/// Preconditioned conjugate gradients on `S y = D⁻¹ rhs` (interior vertices).
fn cg(
    x: &mut [DVec3],
    v0: &[DVec3],
    topo: &Topology,
    set: &[usize],
    tol: f64,
    cap: usize,
    go: &dyn Fn(usize) -> bool,
) -> (usize, bool) {
    let (rhs, mut y, mut scratch) = system(x, v0, topo, set);
    let n = set.len();
    // D_v = (1 − β_v)/n_v, S_vv = n_v β_v/(1 − β_v)
    let dinv: Vec<f64> = set
        .iter()
        .map(|&v| {
            let k = topo.valence(v);
            k as f64 / (1.0 - limit_beta(k))
        })
        .collect();
    let sdiag: Vec<f64> = set
        .iter()
        .map(|&v| {
            let k = topo.valence(v);
            let b = limit_beta(k);
            k as f64 * b / (1.0 - b)
        })
        .collect();
    let mut ly = vec![DVec3::ZERO; n];
    apply_on(&y, topo, set, &mut scratch, &mut ly);
    // e = rhs − L y is the interpolation error; r = D⁻¹ e
    let mut e: Vec<DVec3> = rhs.iter().zip(&ly).map(|(a, b)| *a - *b).collect();
    let mut r: Vec<DVec3> = e.iter().zip(&dinv).map(|(a, d)| *a * *d).collect();
    let mut z: Vec<DVec3> = r.iter().zip(&sdiag).map(|(a, d)| *a / *d).collect();
    let mut p = z.clone();
    let mut rz = dot3(&r, &z);
    let mut ap = vec![DVec3::ZERO; n];
    let mut done = false;
    let mut k = 0;
    while k <= cap {
        if max_len(&e) < tol {
            done = true;
            break;
        }
        if k == cap || !go(k) {
            break;
        }
        apply_on(&p, topo, set, &mut scratch, &mut ap);
        for (a, d) in ap.iter_mut().zip(&dinv) {
            *a *= *d; // S p = D⁻¹ L p
        }
        let alpha = safe_div(rz, dot3(&p, &ap));
        for i in 0..n {
            y[i] += alpha * p[i];
            r[i] -= alpha * ap[i];
            e[i] = r[i] / dinv[i];
            z[i] = r[i] / sdiag[i];
        }
        let rz_new = dot3(&r, &z);
        let beta = safe_div(rz_new, rz);
        for i in 0..n {
            p[i] = z[i] + beta * p[i];
        }
        rz = rz_new;
        k += 1;
    }
    for (&v, &yi) in set.iter().zip(&y) {
        x[v] = yi;
    }
    (k, done)
}

/// BiCGSTAB on `L_set y = rhs` (boundary vertices; two applications of `L` a step).
fn bicgstab(
    x: &mut [DVec3],
    v0: &[DVec3],
    topo: &Topology,
    set: &[usize],
    tol: f64,
    cap: usize,
    go: &dyn Fn(usize) -> bool,
) -> (usize, bool) {
    let (rhs, mut y, mut scratch) = system(x, v0, topo, set);
    let n = set.len();
    let mut tmp = vec![DVec3::ZERO; n];
    apply_on(&y, topo, set, &mut scratch, &mut tmp);
    let mut r: Vec<DVec3> = rhs.iter().zip(&tmp).map(|(a, b)| *a - *b).collect();
    let r0 = r.clone();
    let (mut rho, mut alpha, mut omega) = (DVec3::ONE, DVec3::ONE, DVec3::ONE);
    let mut v = vec![DVec3::ZERO; n];
    let mut p = vec![DVec3::ZERO; n];
    let mut s = vec![DVec3::ZERO; n];
    let mut t = vec![DVec3::ZERO; n];
    let mut used = 0;
    let mut done = false;
    while used <= cap {
        if max_len(&r) < tol {
            done = true;
            break;
        }
        if used + 2 > cap || !go(used) {
            break;
        }
        let rho_new = dot3(&r0, &r);
        let beta = safe_div(rho_new, rho) * safe_div(alpha, omega);
        for i in 0..n {
            p[i] = r[i] + beta * (p[i] - omega * v[i]);
        }
        apply_on(&p, topo, set, &mut scratch, &mut v);
        alpha = safe_div(rho_new, dot3(&r0, &v));
        for i in 0..n {
            s[i] = r[i] - alpha * v[i];
        }
        used += 1;
        if max_len(&s) < tol {
            for i in 0..n {
                y[i] += alpha * p[i];
            }
            r.copy_from_slice(&s);
            done = true;
            break;
        }
        apply_on(&s, topo, set, &mut scratch, &mut t);
        omega = safe_div(dot3(&t, &s), dot3(&t, &t));
        for i in 0..n {
            y[i] += alpha * p[i] + omega * s[i];
            r[i] = s[i] - omega * t[i];
        }
        rho = rho_new;
        used += 1;
    }
    for (&vv, &yi) in set.iter().zip(&y) {
        x[vv] = yi;
    }
    (used, done)
}
