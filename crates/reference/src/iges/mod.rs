//! IGES (5.3, fixed-format ASCII): the rational B-spline surfaces (entity
//! 128) of a file as references.
//!
//! No maintained Rust crate reads IGES, and the part needed is small, so the
//! reader is written here:
//!
//! - lines of 80 columns, the section letter in column 73 (`S`tart,
//!   `G`lobal, `D`irectory, `P`arameter, `T`erminate, in that order) and
//!   the sequence number in 74–80; a file without line breaks is read as
//!   80-byte records. Compressed and binary IGES are refused;
//! - the global section (columns 1–72 of its lines, run together): its
//!   parameter and record delimiters (fields 1 and 2, `,` and `;` when
//!   empty), Hollerith strings `nH…`, the model space scale (field 13, 1
//!   when empty), the unit flag (field 14: 1 inch, 2 millimetre, 4 foot,
//!   5 mile, 6 metre, 7 kilometre, 8 mil, 9 micrometre, 10 centimetre,
//!   11 microinch, 3 the unit named in field 15). Model space coordinates
//!   are divided by the scale ("ratio of model space to real world"), so
//!   `metres_per_unit` is the unit's metres over the scale;
//! - directory entries, two lines of nine 8-column fields each: entity
//!   type, parameter data pointer, transformation matrix (entity 124,
//!   applied to the poles, through its own matrix in turn), parameter line
//!   count;
//! - parameter data (columns 1–64 of its lines, run together) of entity
//!   128: `K1 K2 M1 M2 PROP1..PROP5`, the `u` knots, the `v` knots, the
//!   weights and the control points (`u` index fastest, as the kernel's
//!   grid holds them: one row per `v` index), `U0 U1 V0 V1`. Weights all
//!   equal, or `PROP3 = 1` (polynomial), give a non-rational surface;
//!   closed is `PROP1`/`PROP2`; periodic, as for STEP, is a knot vector
//!   that is not clamped (`PROP4`/`PROP5` are not used).
//!
//! The faces, in directory order: every trimmed surface (144), bounded
//! surface (143) and face (510), and every 128 that none of them has as
//! its surface. A face is untrimmed when:
//!
//! - a 144 has no inner boundary and either no outer one (`N1 = 0`: the
//!   surface's own boundary) or an outer curve on a parametric surface
//!   (142) whose parameter-space curve is made of lines (110), B-spline
//!   curves (126) or composites (102) of them that each lie along one side
//!   of the surface's domain (all their points within 1e-6 of the domain's
//!   diagonal from it);
//! - a 143 has one boundary (141) whose parameter-space curves (each
//!   model-space curve having at least one) all lie along the domain's
//!   sides, as for a 144;
//! - a 510 has one loop (508) of at most four edges whose vertices (502)
//!   all lie on the surface's corners (the STEP rule);
//! - a lone 128 is untrimmed;
//!
//! and in every case `U0 U1 V0 V1` of the 128 cover its whole knot domain.
//! Anything else is trimmed. A face on another surface is a plane (108, 190:
//! no area or box is computed) or `Other`, and reported trimmed.
//!
//! Errors name the file line and column of the value at fault in the
//! parameter section, or of the field of its directory entry.

use crate::error::{MAX_FILE_POLES, MAX_POLES, ReferenceError};
use crate::geom::{self, Bbox};
use crate::{FaceData, SurfaceKind};
use std::cell::Cell;
use std::path::Path;
use streamline_kernel::DVec3;
use streamline_kernel::grid::Grid;
use streamline_kernel::nurbs::rational::{MAX_DEGREE, NurbsError, NurbsSurface};

/// What an IGES file gives: its length unit and its faces.
pub(crate) struct IgesFile {
    pub unit: String,
    pub metres_per_unit: f64,
    pub faces: Vec<FaceData>,
}

mod records;

use records::*;

/// The deepest chain of composite curves or transformation matrices
/// followed (a cycle would otherwise never end).
const MAX_CHAIN: usize = 16;

/// Reads the faces of an IGES file.
pub(crate) fn read(path: &Path, bytes: &[u8]) -> Result<IgesFile, ReferenceError> {
    let lines = split_lines(bytes);
    let (g, d, p) = sections(path, &lines)?;
    let global = global(path, &g)?;
    let file = File {
        path,
        global: &global,
        des: directory(path, &d)?,
        p: &p,
        poles_read: Cell::new(0),
    };
    let faces = file.faces()?;
    Ok(IgesFile {
        unit: global.unit.clone(),
        metres_per_unit: global.metres_per_unit,
        faces,
    })
}

/// The file's lines: split at line feeds (a carriage return before one
/// dropped), or 80-byte records when there is no line feed; blank lines
/// are skipped.
/// How a face's base surface reads.
enum Base {
    /// A 128, in metres, with its closed flags and whether `U0 U1 V0 V1`
    /// leave part of its knot domain out.
    BSpline(NurbsSurface, [bool; 2], bool),
    Plane,
    Other,
}

/// What makes a directory entry a face.
enum Source {
    /// A 144: base surface, N1, N2, outer boundary (142) when N1 ≠ 0.
    Trimmed {
        surf: usize,
        n1: i64,
        n2: i64,
        outer: Option<usize>,
    },
    /// A 143: base surface and its boundaries (141).
    Bounded { surf: usize, bounds: Vec<usize> },
    /// A 510: base surface and its loops (508).
    Face { surf: usize, loops: Vec<usize> },
    /// A 128 that no face has as its surface.
    Lone,
}

struct File<'a> {
    path: &'a Path,
    global: &'a Global,
    des: Vec<De>,
    p: &'a [Line<'a>],
    /// The poles of the faces read so far (at most [`MAX_FILE_POLES`]).
    poles_read: Cell<usize>,
}

impl<'a> File<'a> {
    fn who(de: &De) -> String {
        format!("DE {} ({})", de.number, de.etype)
    }

    /// An error at a field of directory entry `de`.
    fn de_err(&self, de: &De, col: usize, msg: impl AsRef<str>) -> ReferenceError {
        ReferenceError::at(
            self.path,
            de.line,
            col,
            format!("{}: {}", Self::who(de), msg.as_ref()),
        )
    }

    /// The parameters of entry `k` (index into `des`).
    fn params(&self, k: usize) -> Result<Params<'a>, ReferenceError> {
        let de = &self.des[k];
        let count = de.pcount.max(1);
        let start = de.pstart;
        if start < 1 || start.saturating_add(count) - 1 > self.p.len() as i64 {
            return Err(self.de_err(
                de,
                9,
                format!(
                    "its parameter data (P line {start}, {count} lines) lies outside the parameter section's {} lines; {REEXPORT}",
                    self.p.len()
                ),
            ));
        }
        let lines = &self.p[(start - 1) as usize..(start - 1 + count) as usize];
        let t = Text::new(lines, 64);
        let who = Self::who(de);
        let (toks, end) = tokenize(
            self.path,
            &t,
            0,
            self.global.pd,
            self.global.rd,
            &format!("the parameters of {who}"),
        )?;
        let p = Params {
            path: self.path,
            t,
            toks,
            end,
            who,
        };
        let ty = p.int(0, "entity type")?;
        if ty != de.etype {
            return Err(p.err(
                0,
                format!(
                    "its parameters start with entity type {ty}, its directory entry says {}; {REEXPORT}",
                    de.etype
                ),
            ));
        }
        Ok(p)
    }

    /// The entry a pointer parameter names (its index into `des`); 0 →
    /// `None`.
    fn ptr(&self, p: &Params, k: usize, what: &str) -> Result<Option<usize>, ReferenceError> {
        let v = p.int(k, what)?;
        if v == 0 {
            return Ok(None);
        }
        let v = v.unsigned_abs() as usize;
        if v.is_multiple_of(2) || v / 2 >= self.des.len() {
            return Err(p.err(
                k,
                format!(
                    "its {what} (parameter {k}) points to DE {v}, which is not a directory entry (the file has {}, odd numbers 1 to {}); {REEXPORT}",
                    self.des.len(),
                    2 * self.des.len() - 1
                ),
            ));
        }
        Ok(Some(v / 2))
    }

    fn need_ptr(&self, p: &Params, k: usize, what: &str) -> Result<usize, ReferenceError> {
        self.ptr(p, k, what)?.ok_or_else(|| {
            p.err(
                k,
                format!("its {what} (parameter {k}) is 0, no entity; {REEXPORT}"),
            )
        })
    }

    fn faces(&self) -> Result<Vec<FaceData>, ReferenceError> {
        let mut sources: Vec<(usize, Source)> = Vec::new();
        let mut is_base = vec![false; self.des.len()];
        for k in 0..self.des.len() {
            let src = match self.des[k].etype {
                144 => {
                    let p = self.params(k)?;
                    let surf = self.need_ptr(&p, 1, "surface")?;
                    let n1 = p.int(2, "outer boundary flag N1")?;
                    let n2 = p.int(3, "number of inner boundaries N2")?;
                    let outer = if n1 != 0 {
                        self.ptr(&p, 4, "outer boundary")?
                    } else {
                        None
                    };
                    Source::Trimmed {
                        surf,
                        n1,
                        n2,
                        outer,
                    }
                }
                143 => {
                    let p = self.params(k)?;
                    let surf = self.need_ptr(&p, 2, "surface")?;
                    let n = p.count(3, "number of boundaries", 0, p.len())?;
                    let mut bounds = Vec::with_capacity(n);
                    for i in 0..n {
                        bounds.push(self.need_ptr(&p, 4 + i, "boundary")?);
                    }
                    Source::Bounded { surf, bounds }
                }
                510 => {
                    let p = self.params(k)?;
                    let surf = self.need_ptr(&p, 1, "surface")?;
                    let n = p.count(2, "number of loops", 0, p.len())?;
                    let mut loops = Vec::with_capacity(n);
                    for i in 0..n {
                        loops.push(self.need_ptr(&p, 4 + i, "loop")?);
                    }
                    Source::Face { surf, loops }
                }
                _ => continue,
            };
            match &src {
                Source::Trimmed { surf, .. }
                | Source::Bounded { surf, .. }
                | Source::Face { surf, .. } => {
                    is_base[*surf] = true;
                }
                Source::Lone => {}
            }
            sources.push((k, src));
        }
        for (k, (de, base)) in self.des.iter().zip(&is_base).enumerate() {
            if de.etype == 128 && !base {
                sources.push((k, Source::Lone));
            }
        }
        sources.sort_by_key(|s| s.0);
        if sources.is_empty() {
            return Err(ReferenceError::whole(
                self.path,
                "the file has no face: no rational B-spline surface (entity 128), trimmed surface (144), bounded surface (143) or face (510); export the reference as surfaces, not as curves, points or a mesh",
            ));
        }
        let mut faces = Vec::with_capacity(sources.len());
        for (k, src) in sources {
            faces.push(self.face(k, src)?);
        }
        Ok(faces)
    }

    fn face(&self, k: usize, src: Source) -> Result<FaceData, ReferenceError> {
        let s = match &src {
            Source::Trimmed { surf, .. }
            | Source::Bounded { surf, .. }
            | Source::Face { surf, .. } => *surf,
            Source::Lone => k,
        };
        let sde = &self.des[s];
        let entity = Self::who(sde);
        let line = self
            .p
            .get((sde.pstart.max(1) - 1) as usize)
            .map_or(sde.line, |l| l.number);
        let base = match sde.etype {
            128 => self.surface(s)?,
            108 | 190 => Base::Plane,
            _ => Base::Other,
        };
        let (surface, closed, sub) = match base {
            Base::BSpline(surface, closed, sub) => (surface, closed, sub),
            other => {
                let kind = if matches!(other, Base::Plane) {
                    SurfaceKind::Plane
                } else {
                    SurfaceKind::Other
                };
                return Ok(FaceData {
                    kind,
                    entity,
                    line,
                    surface: None,
                    mesh: None,
                    not_grid: None,
                    closed: [false; 2],
                    trimmed: true,
                    area: 0.0,
                    bbox: None,
                });
            }
        };
        let (area, bbox) = geom::area_and_bbox(&surface);
        let ([u0, u1], [v0, v1]) = surface.domain();
        let dom = [[u0, v0], [u1, v1]];
        let untrimmed = !sub
            && match &src {
                Source::Lone => true,
                Source::Trimmed { n1, n2, outer, .. } => {
                    *n2 == 0
                        && (*n1 == 0
                            || match outer {
                                Some(o) => self.outer_on_sides(*o, dom)?,
                                None => false,
                            })
                }
                Source::Bounded { bounds, .. } => match bounds.as_slice() {
                    [b] => self.boundary_on_sides(*b, dom)?,
                    _ => false,
                },
                Source::Face { loops, .. } => match loops.as_slice() {
                    [l] => self.loop_on_corners(*l, &surface, bbox)?,
                    _ => false,
                },
            };
        let kind = if surface.is_rational() {
            SurfaceKind::Rational
        } else {
            SurfaceKind::BSpline
        };
        Ok(FaceData {
            kind,
            entity,
            line,
            surface: Some(surface),
            mesh: None,
            not_grid: None,
            closed,
            trimmed: !untrimmed,
            area,
            bbox: Some(bbox),
        })
    }

    /// Entity 128 at index `k`, in metres.
    fn surface(&self, k: usize) -> Result<Base, ReferenceError> {
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

    /// The matrix `[R | T]` of entry `k`'s transformation (entity 124),
    /// composed with the matrix of that entity in turn; `None` for none.
    fn transform(&self, k: usize, depth: usize) -> Result<Option<[[f64; 4]; 3]>, ReferenceError> {
        let de = &self.des[k];
        if de.transform == 0 {
            return Ok(None);
        }
        let t = de.transform.unsigned_abs() as usize;
        if t.is_multiple_of(2) || t / 2 >= self.des.len() || self.des[t / 2].etype != 124 {
            return Err(self.de_err(
                de,
                49,
                format!("its transformation matrix pointer {t} is not the DE of a transformation matrix (124); {REEXPORT}"),
            ));
        }
        if depth >= MAX_CHAIN {
            return Err(self.de_err(
                de,
                49,
                format!("its transformation matrices chain more than {MAX_CHAIN} deep (a cycle?); {REEXPORT}"),
            ));
        }
        let p = self.params(t / 2)?;
        let mut m = [[0.0; 4]; 3];
        for (r, row) in m.iter_mut().enumerate() {
            for (c, x) in row.iter_mut().enumerate() {
                *x = p.real(1 + 4 * r + c, "matrix entry")?;
            }
        }
        Ok(Some(match self.transform(t / 2, depth + 1)? {
            None => m,
            Some(parent) => compose(&parent, &m),
        }))
    }

    /// Whether a 142's parameter-space curve runs along the domain's sides.
    fn outer_on_sides(&self, k: usize, dom: [[f64; 2]; 2]) -> Result<bool, ReferenceError> {
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
    fn boundary_on_sides(&self, k: usize, dom: [[f64; 2]; 2]) -> Result<bool, ReferenceError> {
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
    fn loop_on_corners(
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

/// `m x` for the matrix `[R | T]`.
fn apply(m: &[[f64; 4]; 3], x: DVec3) -> DVec3 {
    let r = |i: usize| m[i][0] * x.x + m[i][1] * x.y + m[i][2] * x.z + m[i][3];
    DVec3::new(r(0), r(1), r(2))
}

/// `a ∘ b` (first `b`, then `a`) for matrices `[R | T]`.
fn compose(a: &[[f64; 4]; 3], b: &[[f64; 4]; 3]) -> [[f64; 4]; 3] {
    let mut out = [[0.0; 4]; 3];
    for i in 0..3 {
        for j in 0..4 {
            let mut s: f64 = (0..3).map(|k| a[i][k] * b[k][j]).sum();
            if j == 3 {
                s += a[i][3];
            }
            out[i][j] = s;
        }
    }
    out
}
