//! Whether a face's boundary is its surface's own: parameter-space curves
//! along the domain's sides (141, 142, and the 102, 110 and 126 curves
//! they hold), or a loop (508) through the surface's corners.

use super::records::REEXPORT;
use super::{File, MAX_CHAIN};
use crate::error::{MAX_POLES, ReferenceError};
use crate::geom::{self, Bbox};
use streamline_kernel::DVec3;
use streamline_kernel::nurbs::rational::{MAX_DEGREE, NurbsSurface};

impl File<'_> {
    /// Whether a 142's parameter-space curve runs along the domain's sides.
    pub(super) fn outer_on_sides(
        &self,
        k: usize,
        dom: [[f64; 2]; 2],
    ) -> Result<bool, ReferenceError> {
        if self.des[k].etype != 142 {
            return Ok(false);
        }
        let p = self.params(k)?;
        match self.ptr(&p, 3, "parameter-space curve")? {
            Some(c) => self.curve_on_sides(c, dom, 0),
            None => Ok(false),
        }
    }

    /// Whether a 141's parameter-space curves all run along the domain's
    /// sides.
    pub(super) fn boundary_on_sides(
        &self,
        k: usize,
        dom: [[f64; 2]; 2],
    ) -> Result<bool, ReferenceError> {
        if self.des[k].etype != 141 {
            return Ok(false);
        }
        let p = self.params(k)?;
        let n = p.count(4, "number of curves", 0, p.len())?;
        let mut i = 5;
        for _ in 0..n {
            let kk = p.count(i + 2, "number of parameter-space curves", 0, p.len())?;
            if kk == 0 {
                return Ok(false);
            }
            for j in 0..kk {
                let c = self.need_ptr(&p, i + 3 + j, "parameter-space curve")?;
                if !self.curve_on_sides(c, dom, 0)? {
                    return Ok(false);
                }
            }
            i += 3 + kk;
        }
        Ok(n > 0)
    }

    /// Whether a parameter-space curve (110, 126, or a 102 of them) lies
    /// along the domain's sides, each piece along one side.
    fn curve_on_sides(
        &self,
        k: usize,
        dom: [[f64; 2]; 2],
        depth: usize,
    ) -> Result<bool, ReferenceError> {
        let tol = 1e-6 * ((dom[1][0] - dom[0][0]).hypot(dom[1][1] - dom[0][1]));
        let on_one_side = |pts: &[[f64; 2]]| {
            (0..2).any(|axis| {
                [dom[0][axis], dom[1][axis]]
                    .iter()
                    .any(|side| pts.iter().all(|q| (q[axis] - side).abs() <= tol))
            })
        };
        match self.des[k].etype {
            110 => {
                let p = self.params(k)?;
                let a = [p.real(1, "X1")?, p.real(2, "Y1")?];
                let b = [p.real(4, "X2")?, p.real(5, "Y2")?];
                Ok(on_one_side(&[a, b]))
            }
            126 => {
                let p = self.params(k)?;
                let kk = p.count(1, "K (poles − 1)", 0, MAX_POLES - 1)?;
                let m = p.count(2, "M (degree)", 1, MAX_DEGREE)?;
                let p0 = 7 + (kk + m + 2) + (kk + 1);
                p.need(p0, 3 * (kk + 1), "control points")?;
                let mut pts = Vec::with_capacity(kk + 1);
                for i in 0..=kk {
                    pts.push([p.real(p0 + 3 * i, "X")?, p.real(p0 + 3 * i + 1, "Y")?]);
                }
                Ok(on_one_side(&pts))
            }
            102 => {
                if depth >= MAX_CHAIN {
                    return Err(self.de_err(&self.des[k], 1, format!("composite curves nest more than {MAX_CHAIN} deep (a cycle?); {REEXPORT}")));
                }
                let p = self.params(k)?;
                let n = p.count(1, "number of curves", 0, p.len())?;
                for i in 0..n {
                    let c = self.need_ptr(&p, 2 + i, "curve")?;
                    if !self.curve_on_sides(c, dom, depth + 1)? {
                        return Ok(false);
                    }
                }
                Ok(n > 0)
            }
            _ => Ok(false),
        }
    }

    /// Whether a 508 loop has at most four edges, every vertex on one of
    /// the surface's corners.
    pub(super) fn loop_on_corners(
        &self,
        k: usize,
        s: &NurbsSurface,
        bbox: Bbox,
    ) -> Result<bool, ReferenceError> {
        if self.des[k].etype != 508 {
            return Ok(false);
        }
        let p = self.params(k)?;
        let n = p.count(1, "number of edges", 0, p.len())?;
        if n == 0 || n > 4 {
            return Ok(false);
        }
        let corners = geom::corners(s);
        let tol = geom::corner_tolerance(bbox);
        let on_corner = |x: DVec3| corners.iter().any(|c| c.distance(x) <= tol);
        let mut i = 2;
        for _ in 0..n {
            let ty = p.int(i, "edge type")?;
            let list = self.need_ptr(&p, i + 1, "edge or vertex list")?;
            let ndx = p.count(i + 2, "list index", 1, p.len())?;
            let kk = p.count(i + 4, "number of parameter-space curves", 0, p.len())?;
            let verts = if ty == 1 {
                vec![(list, ndx)]
            } else {
                if self.des[list].etype != 504 {
                    return Ok(false);
                }
                let e = self.params(list)?;
                let at = 2 + 5 * (ndx - 1);
                e.need(at, 5, "edge")?;
                let sv = self.need_ptr(&e, at + 1, "start vertex list")?;
                let si = e.count(at + 2, "start vertex index", 1, MAX_POLES)?;
                let tv = self.need_ptr(&e, at + 3, "end vertex list")?;
                let ti = e.count(at + 4, "end vertex index", 1, MAX_POLES)?;
                vec![(sv, si), (tv, ti)]
            };
            for (vl, vi) in verts {
                if self.des[vl].etype != 502 {
                    return Ok(false);
                }
                let v = self.params(vl)?;
                let at = 2 + 3 * (vi - 1);
                let x = DVec3::new(
                    v.real(at, "vertex X")?,
                    v.real(at + 1, "vertex Y")?,
                    v.real(at + 2, "vertex Z")?,
                ) * self.global.metres_per_unit;
                if !on_corner(x) {
                    return Ok(false);
                }
            }
            i += 5 + 2 * kk;
        }
        Ok(true)
    }
}
