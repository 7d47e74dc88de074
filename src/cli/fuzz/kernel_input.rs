//! The `kernel` fuzz target: the kernel's public entry points fed with
//! "nasty" numbers read from arbitrary bytes ([`Numbers`]); each returns an
//! error or finite (for tangents, unit) output (`docs/reliability.md`).

use super::{check_mesh, finite, unit};
use streamline_kernel::finetune::{Constraint, fine_tune_into};
use streamline_kernel::loop_subdiv::trimesh::TriMesh;
use streamline_kernel::{
    BlendOrder, CurveScheme, DVec3, Design, Grid, SurfaceScheme, Tangent, curve::scheme as curve,
    levels::surface, levels::tangent_interpolation as sphere_pi, sphere::blend as sphere,
};

/// Reads "nasty" numbers from bytes: each value is one control byte, and raw
/// bits when it says so; NaN, infinities, signed zeros, subnormals, huge and
/// tiny values, repeats of the previous value.
struct Numbers<'a> {
    data: &'a [u8],
    last: f64,
}

impl<'a> Numbers<'a> {
    fn new(data: &'a [u8]) -> Self {
        Numbers { data, last: 0.0 }
    }

    fn byte(&mut self) -> u8 {
        match self.data.split_first() {
            Some((&b, rest)) => {
                self.data = rest;
                b
            }
            None => 0,
        }
    }

    fn f64(&mut self) -> f64 {
        let c = self.byte();
        let x = match c % 16 {
            0 => {
                let mut b = [0u8; 8];
                for x in &mut b {
                    *x = self.byte();
                }
                f64::from_le_bytes(b)
            }
            1 => f64::NAN,
            2 => f64::INFINITY,
            3 => f64::NEG_INFINITY,
            4 => 0.0,
            5 => -0.0,
            6 => f64::MIN_POSITIVE / f64::from(1 + (c >> 4)).exp2(),
            7 => 1e300 * if c & 0x10 == 0 { 1.0 } else { -1.0 },
            8 => 1e-300 * if c & 0x10 == 0 { 1.0 } else { -1.0 },
            9 => self.last,
            10 => self.last + 1e-15,
            11 => f64::MAX,
            _ => f64::from(c >> 4) - 8.0 + f64::from(c % 16 - 12) * 0.25,
        };
        self.last = x;
        x
    }

    /// A vector: fresh, or the previous one repeated, negated (antipodal) or nudged.
    fn vec(&mut self, prev: DVec3) -> DVec3 {
        match self.byte() % 8 {
            0 => prev,
            1 => -prev,
            2 => prev + DVec3::new(1e-12, -1e-13, 1e-14),
            _ => DVec3::new(self.f64(), self.f64(), self.f64()),
        }
    }

    fn vecs(&mut self, n: usize) -> Vec<DVec3> {
        let mut out = Vec::with_capacity(n);
        let mut prev = DVec3::X;
        for _ in 0..n {
            prev = self.vec(prev);
            out.push(prev);
        }
        out
    }

    fn small(&mut self, lo: usize, hi: usize) -> usize {
        lo + usize::from(self.byte()) % (hi - lo + 1)
    }
}

fn curve_scheme(k: usize, omega: f64) -> CurveScheme {
    match k % 3 {
        0 => CurveScheme::Chaikin,
        1 => CurveScheme::CubicBSpline,
        _ => CurveScheme::FourPoint { omega },
    }
}

fn surface_scheme(k: usize, omega: f64) -> SurfaceScheme {
    match k % 3 {
        0 => SurfaceScheme::DooSabin,
        1 => SurfaceScheme::CatmullClark,
        _ => SurfaceScheme::Kobbelt { omega },
    }
}

/// The kernel's public entry points with arbitrary `f64` input: each returns
/// an error or finite (and, for tangents, unit) output.
pub fn kernel(data: &[u8]) {
    let mut n = Numbers::new(data);
    let op = n.byte();
    match op % 9 {
        0 => {
            let k = n.small(0, 2);
            let depth = n.small(0, 4) as u32;
            let omega = n.f64();
            let count = n.small(0, 24);
            let t = n.vecs(count);
            if let Ok(out) = curve::subdivide(curve_scheme(k, omega), &t, depth) {
                unit("curve subdivision", &out);
            }
        }
        1 => {
            let k = n.small(0, 2);
            let depth = n.small(0, 3) as u32;
            let omega = n.f64();
            let (rows, cols) = (n.small(1, 6), n.small(1, 6));
            let order = if n.byte().is_multiple_of(2) {
                BlendOrder::SFirst
            } else {
                BlendOrder::TFirst
            };
            let data = n.vecs(rows * cols);
            if let Ok(g) = Grid::new(rows, cols, data)
                && let Ok(out) = surface::subdivide(surface_scheme(k, omega), order, &g, depth)
            {
                unit("surface subdivision", out.data());
            }
        }
        2 => {
            let order = n.small(0, 7);
            let m = n.small(0, 64);
            let count = n.small(0, 12);
            let t = n.vecs(count);
            if let Ok(q) = streamline_kernel::curve::qi::QiCurve::new(&t, order)
                && let Ok(out) = q.sample(m)
            {
                unit("QI curve", &out);
            }
        }
        3 => {
            let count = n.small(0, 16);
            let t = n.vecs(count);
            let s: Vec<f64> = (0..n.small(0, 17)).map(|_| n.f64()).collect();
            let anchor = n.small(0, 17);
            let origin = DVec3::new(n.f64(), n.f64(), n.f64());
            if let Ok(p) =
                streamline_kernel::streamline::integrate::streamline(&t, &s, anchor, origin)
            {
                finite("streamline", &p);
            }
        }
        4 => design(&mut n),
        5 => {
            let nv = n.small(0, 12);
            let positions = n.vecs(nv);
            let nf = n.small(0, 16);
            let faces: Vec<[u32; 3]> = (0..nf)
                .map(|_| {
                    let b = n.byte();
                    let i = |x: u8| u32::from(x) % (nv as u32 + 2);
                    [i(b), i(n.byte()), i(n.byte())]
                })
                .collect();
            if let Ok((mesh, topo)) = TriMesh::new(positions, faces) {
                check_mesh(&mesh, &topo);
            }
        }
        6 => {
            let a = Tangent::new(n.vec(DVec3::X));
            let b = Tangent::new(n.vec(DVec3::Y));
            // the weight is the scheme's constant, never the user's: any number in [0, 1]
            let u = n.f64().abs() % 1.0;
            let u = if u.is_finite() { u } else { 0.5 };
            if let (Ok(a), Ok(b)) = (a, b) {
                let (a, b) = (a.get(), b.get());
                let (q1, q3) = sphere::quarters(a, b);
                let what = format!("sphere blends of {a:?} and {b:?} at {u}");
                unit(
                    &what,
                    &[
                        sphere::blend(a, b, u),
                        sphere::mid(a, b),
                        q1,
                        q3,
                        sphere::quarter(a, b),
                        sphere::three_quarters(a, b),
                    ],
                );
                let w = n.f64();
                if let Some(c) = sphere::combine(&[a, b, a], &[w, 1.0 - 2.0 * w, w]) {
                    unit("sphere combine", &[c]);
                }
            }
        }
        7 => {
            let k = n.small(0, 2);
            let (rows, cols) = (n.small(1, 6), n.small(1, 6));
            let data = n.vecs(rows * cols);
            let scheme = surface_scheme(k, 1.0);
            if let Ok(g) = Grid::new(rows, cols, data)
                && let Ok(g) = surface::normalize_grid(&g)
                && scheme.check_depth(rows, cols, 1).is_ok()
            {
                let r = sphere_pi::interpolate_net(scheme, BlendOrder::SFirst, &g, 1e-9, 20);
                unit("interpolated net", r.net.data());
            }
        }
        _ => {
            let count = n.small(2, 12);
            let t = n.vecs(count);
            let Ok(t) = streamline_kernel::sphere::tangent::normalize_all(&t) else {
                return;
            };
            let mut s = vec![0.0];
            for _ in 1..count {
                let d = n.f64().abs().min(1e6);
                s.push(s[s.len() - 1] + d.max(1e-3));
            }
            let degree = n.small(0, 5);
            let values: Vec<f64> = (0..n.small(0, 10)).map(|_| n.f64()).collect();
            let constraint = [
                Constraint::Free,
                Constraint::KeepEnds,
                Constraint::KeepClosed,
            ][n.small(0, 2)];
            if let Ok(f) = streamline_kernel::finetune::bspline::BSpline::uniform(degree, values) {
                let mut out = Vec::new();
                fine_tune_into(&t, &s, s[0], DVec3::ZERO, &f, constraint, &mut out);
                finite("fine-tuned streamline", &out);
            }
        }
    }
}

/// A design from numbers: net, parameters, anchor, initial curve; built at a small depth.
fn design(n: &mut Numbers) {
    let k = n.small(0, 2);
    let omega = n.f64();
    let (rows, cols) = (n.small(1, 5), n.small(1, 5));
    let net = n.vecs(rows * cols);
    let s: Vec<f64> = (0..rows * cols).map(|_| n.f64()).collect();
    let t: Vec<f64> = (0..rows).map(|_| n.f64()).collect();
    let anchor = n.small(0, 5);
    let init_count = n.small(0, 5);
    let init = n.vecs(init_count);
    let order = n.small(0, 5);
    let length = n.f64();
    let origin = DVec3::new(n.f64(), n.f64(), n.f64());
    let depth = n.small(0, 3) as u32;
    let Ok(net) = Grid::new(rows, cols, net) else {
        return;
    };
    let Ok(s) = Grid::new(rows, cols, s) else {
        return;
    };
    let Ok(initial) = streamline_kernel::streamline::initial_curve::InitialCurve::new(
        &init, order, length, origin,
    ) else {
        return;
    };
    let Ok(d) = Design::new(
        &net,
        s,
        t,
        anchor,
        surface_scheme(k, omega),
        BlendOrder::SFirst,
        initial,
    ) else {
        return;
    };
    if let Ok(b) = d.build(depth) {
        unit("design tangents", b.level.tangents.data());
        finite("design points", b.points.data());
        finite("design normals", &b.mesh.normals);
    }
}
