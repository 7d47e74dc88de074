//! The rational B-spline surface (entity 128) of an IGES face, in metres.

use super::records::REEXPORT;
use super::transforms::apply;
use super::{Base, File};
use crate::error::{MAX_FILE_POLES, MAX_POLES, ReferenceError};
use streamline_kernel::DVec3;
use streamline_kernel::grid::Grid;
use streamline_kernel::nurbs::rational::{MAX_DEGREE, NurbsError, NurbsSurface};

impl File<'_> {
    /// Entity 128 at index `k`, in metres.
    pub(super) fn surface(&self, k: usize) -> Result<Base, ReferenceError> {
        let p = self.params(k)?;
        let k1 = p.count(1, "K1 (u poles − 1)", 0, MAX_POLES - 1)?;
        let k2 = p.count(2, "K2 (v poles − 1)", 0, MAX_POLES - 1)?;
        let m1 = p.count(3, "M1 (u degree)", 1, MAX_DEGREE)?;
        let m2 = p.count(4, "M2 (v degree)", 1, MAX_DEGREE)?;
        let (nu, nv) = (k1 + 1, k2 + 1);
        if nu * nv > MAX_POLES {
            return Err(p.err(
                1,
                format!("it has {nu} × {nv} poles, more than the {MAX_POLES} read; simplify the surface (fewer poles) or export a smaller one"),
            ));
        }
        let total = self.poles_read.get() + nu * nv;
        if total > MAX_FILE_POLES {
            return Err(p.err(
                1,
                format!("the faces up to this one have {total} poles, more than the {MAX_FILE_POLES} read from one file; export only the faces you need"),
            ));
        }
        self.poles_read.set(total);
        let closed = [
            p.int(5, "PROP1 (closed in u)")? == 1,
            p.int(6, "PROP2 (closed in v)")? == 1,
        ];
        let polynomial = p.int(7, "PROP3 (polynomial)")? == 1;
        let (na, nb) = (nu + m1 + 1, nv + m2 + 1);
        let ku0 = 10;
        let kv0 = ku0 + na;
        let w0 = kv0 + nb;
        let p0 = w0 + nu * nv;
        let d0 = p0 + 3 * nu * nv;
        p.need(0, d0 + 4, "knots, weights, poles and U0 U1 V0 V1")?;
        let reals = |from: usize, n: usize, what: &str| -> Result<Vec<f64>, ReferenceError> {
            (from..from + n).map(|i| p.real(i, what)).collect()
        };
        let ku = reals(ku0, na, "u knot")?;
        let kv = reals(kv0, nb, "v knot")?;
        let w = reals(w0, nu * nv, "weight")?;
        let xyz = reals(p0, 3 * nu * nv, "control point coordinate")?;
        let range = reals(d0, 4, "parameter range U0 U1 V0 V1")?;
        let transform = self.transform(k, 0)?;
        let scale = self.global.metres_per_unit;
        let mut poles = Vec::with_capacity(nu * nv);
        for (i, c) in xyz.chunks(3).enumerate() {
            let mut x = DVec3::new(c[0], c[1], c[2]);
            if let Some(m) = &transform {
                x = apply(m, x);
            }
            let x = x * scale;
            if !x.is_finite() {
                return Err(p.err(
                    p0 + 3 * i,
                    format!(
                        "control point {} is not finite in metres; {REEXPORT}",
                        i + 1
                    ),
                ));
            }
            poles.push(x);
        }
        let rational = !polynomial && w.iter().any(|&x| x != w[0]);
        let weights = if rational {
            Some(Grid::new(nv, nu, w).map_err(|e| p.err(w0, e.to_string()))?)
        } else if !polynomial && w[0] <= 0.0 {
            return Err(p.err(
                w0,
                format!("the weights are all {}, not positive; {REEXPORT}", w[0]),
            ));
        } else {
            None
        };
        let poles = Grid::new(nv, nu, poles).map_err(|e| p.err(p0, e.to_string()))?;
        let surface = NurbsSurface::new(m1, m2, ku, kv, poles, weights).map_err(|e| {
            let at = match &e {
                NurbsError::KnotsDecrease {
                    direction: 'u',
                    index,
                }
                | NurbsError::KnotMultiplicity {
                    direction: 'u',
                    index,
                    ..
                } => ku0 + index,
                NurbsError::KnotsDecrease { index, .. }
                | NurbsError::KnotMultiplicity { index, .. } => kv0 + index,
                NurbsError::EmptyDomain { direction: 'u' } => ku0,
                NurbsError::EmptyDomain { .. } => kv0,
                NurbsError::NonPositiveWeight { row, col, .. } => w0 + row * nu + col,
                _ => 1,
            };
            p.err(at, e.to_string())
        })?;
        let ([u0, u1], [v0, v1]) = surface.domain();
        let sub = |a: f64, b: f64, lo: f64, hi: f64| {
            let tol = 1e-9 * (hi - lo);
            a < b && a >= lo - tol && b <= hi + tol && (a > lo + tol || b < hi - tol)
        };
        let sub = sub(range[0], range[1], u0, u1) || sub(range[2], range[3], v0, v1);
        Ok(Base::BSpline(surface, closed, sub))
    }
}
