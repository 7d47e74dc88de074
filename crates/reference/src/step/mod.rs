//! STEP (ISO 10303, the Part 21 clear text): the faces of a file as
//! references.
//!
//! The text is parsed by the `ruststep` crate's Part 21 parser
//! (`ruststep::parser::parse`, [`part21`]) into its syntax tree: entity
//! instances, simple `#N = NAME(…)` or complex `#N = (A(…) B(…))`, with
//! untyped parameters. This module maps by hand the handful of entities a
//! reference needs, whatever the schema. `ruststep`'s schema-derived types
//! (its `ap201`/`ap203` features, generated from the EXPRESS schemas) are
//! not used:
//!
//! - a reference comes in AP203, AP214 or AP242 and `ruststep` 0.4
//!   generates only AP201 and AP203; each schema compiles thousands of
//!   types to read a dozen;
//! - their tables stop with `unimplemented!` (a panic) at the first complex
//!   instance, and every CAD system's file has some: its length unit
//!   `(LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT(.MILLI.,.METRE.))`, every
//!   rational surface (a set of records, one per supertype).
//!
//! The entities read are the same in all three schemas:
//!
//! - every `ADVANCED_FACE` or `FACE_SURFACE` is a face, in file order; its
//!   surface is a `B_SPLINE_SURFACE_WITH_KNOTS` (simple instance), the
//!   complex instance `(BOUNDED_SURFACE() B_SPLINE_SURFACE(…)
//!   B_SPLINE_SURFACE_WITH_KNOTS(…) GEOMETRIC_REPRESENTATION_ITEM()
//!   RATIONAL_B_SPLINE_SURFACE(…) REPRESENTATION_ITEM('') SURFACE())` (its
//!   records in any order), a `PLANE`, or anything else (kind `Other`,
//!   named by its entity type);
//! - `control_points_list` is indexed `[u][v]`; the kernel's grid has one
//!   row per `v` index, so it is transposed, and the knots are expanded
//!   from their multiplicities;
//! - the length unit is the one of the geometric representation contexts
//!   (`GLOBAL_UNIT_ASSIGNED_CONTEXT`): an `SI_UNIT` of `.METRE.` with or
//!   without a prefix, or a `CONVERSION_BASED_UNIT` (`'INCH'`, `'FOOT'`)
//!   over a `LENGTH_MEASURE_WITH_UNIT`; every pole is scaled to metres.
//!   A file whose contexts disagree on the length unit is refused, and so
//!   is one that names none;
//! - a face is untrimmed when it has one bound, its loop has at most four
//!   edges and every vertex lies on one of the surface's four corners
//!   (within 1e-6 of the diagonal of the surface's box); otherwise it is
//!   trimmed. A plane or another surface has no corners to compare with:
//!   such a face is reported trimmed;
//! - closed: the surface's `u_closed`/`v_closed` flags (`.T.`); periodic:
//!   the knot vector in that direction is not clamped (its first `p + 1`
//!   or last `p + 1` knots differ), whatever the flags say.
//!
//! Weights that are all equal make a rational instance the same surface as
//! its poles alone; it is then read as a non-rational B-spline, as
//! OpenCascade does.

mod args;
pub(crate) mod part21;
mod scan;
mod syntax_error;
mod units;

use args::{as_list, as_real, as_ref, describe};

use crate::error::{MAX_FILE_POLES, MAX_POLES, ReferenceError};
use crate::geom::{self, Bbox};
use crate::{FaceData, SurfaceKind};
use part21::{Data, Instance, params};
use ruststep::ast::Parameter;
use std::cell::Cell;
use std::path::Path;
use streamline_kernel::DVec3;
use streamline_kernel::grid::Grid;
use streamline_kernel::nurbs::rational::NurbsSurface;

/// What a STEP file gives: its length unit and its faces.
pub(crate) struct StepFile {
    pub unit: String,
    pub metres_per_unit: f64,
    pub faces: Vec<FaceData>,
}

const FIX: &str = "the file does not follow the STEP schema here: re-export it from the CAD system";

/// Reads the faces of a STEP file (`text`: the whole file).
pub(crate) fn read(path: &Path, text: String) -> Result<StepFile, ReferenceError> {
    let data = part21::read(path, text)?;
    let poles_read = Cell::new(0);
    let m = Mapper {
        path,
        data: &data,
        scale: 1.0,
        poles_read: &poles_read,
    };
    let face_ids: Vec<&Instance> = data
        .instances
        .iter()
        .filter(|i| i.has("ADVANCED_FACE") || i.has("FACE_SURFACE"))
        .collect();
    if face_ids.is_empty() {
        return Err(ReferenceError::whole(
            path,
            "the file has no face: no ADVANCED_FACE or FACE_SURFACE entity; export the reference as surfaces or a solid (faces), not as curves, points or a mesh",
        ));
    }
    let (unit, metres_per_unit) = m.length_unit()?;
    let m = Mapper {
        scale: metres_per_unit,
        ..m
    };
    let mut faces = Vec::with_capacity(face_ids.len());
    for f in face_ids {
        faces.push(m.face(f)?);
    }
    Ok(StepFile {
        unit,
        metres_per_unit,
        faces,
    })
}

/// Maps instances to faces, errors located at the instance at fault.
#[derive(Clone, Copy)]
struct Mapper<'a> {
    path: &'a Path,
    data: &'a Data,
    /// Metres per file unit.
    scale: f64,
    /// The poles of the faces read so far (at most [`MAX_FILE_POLES`]).
    poles_read: &'a Cell<usize>,
}

/// The parameters of one record of one instance, read with located errors.
#[derive(Clone, Copy)]
struct Args<'a> {
    m: Mapper<'a>,
    inst: &'a Instance,
    params: &'a [Parameter],
}

impl<'a> Mapper<'a> {
    /// An error at `inst`, prefixed with `#N TYPE: `.
    fn err(&self, inst: &Instance, msg: impl AsRef<str>) -> ReferenceError {
        ReferenceError::at(
            self.path,
            inst.line,
            inst.col,
            format!("{}: {}", inst.describe(), msg.as_ref()),
        )
    }

    /// The instance `#id` that `from` refers to as `what`.
    fn get(&self, id: u64, from: &Instance, what: &str) -> Result<&'a Instance, ReferenceError> {
        self.data.get(id).ok_or_else(|| {
            self.err(
                from,
                format!(
                    "its {what} is #{id}, which the file does not define; the file is incomplete or damaged: re-export it from the CAD system"
                ),
            )
        })
    }

    /// The record `name` of `inst`, with `min` parameters at least.
    fn args(&self, inst: &'a Instance, name: &str, min: usize) -> Result<Args<'a>, ReferenceError> {
        let rec = inst
            .record(name)
            .ok_or_else(|| self.err(inst, format!("it is not a {name}; {FIX}")))?;
        let p = params(rec);
        if p.len() < min {
            return Err(self.err(
                inst,
                format!("{name} has {} parameters, {min} are needed; {FIX}", p.len()),
            ));
        }
        Ok(Args {
            m: *self,
            inst,
            params: p,
        })
    }

    fn face(&self, face: &'a Instance) -> Result<FaceData, ReferenceError> {
        let rec = if face.has("ADVANCED_FACE") {
            "ADVANCED_FACE"
        } else {
            "FACE_SURFACE"
        };
        let a = self.args(face, rec, 3)?;
        let bounds = a.refs(1, "bounds")?;
        let sid = a.reference(2, "face_geometry")?;
        let surf = self.get(sid, face, "face_geometry")?;
        let entity = surf.describe();
        if surf.has("B_SPLINE_SURFACE_WITH_KNOTS") {
            let (surface, closed) = self.bspline(surf)?;
            let (area, bbox) = geom::area_and_bbox(&surface);
            let trimmed = !self.on_corners(face, &bounds, &surface, bbox)?;
            let kind = if surface.is_rational() {
                SurfaceKind::Rational
            } else {
                SurfaceKind::BSpline
            };
            return Ok(FaceData {
                kind,
                entity,
                line: surf.line,
                surface: Some(surface),
                mesh: None,
                not_grid: None,
                closed,
                trimmed,
                area,
                bbox: Some(bbox),
            });
        }
        if surf.has("PLANE") {
            let (area, bbox) = self.plane_bounds(face, &bounds)?;
            return Ok(FaceData {
                kind: SurfaceKind::Plane,
                entity,
                line: surf.line,
                surface: None,
                mesh: None,
                not_grid: None,
                closed: [false; 2],
                trimmed: true,
                area,
                bbox,
            });
        }
        Ok(FaceData {
            kind: SurfaceKind::Other,
            entity,
            line: surf.line,
            surface: None,
            mesh: None,
            not_grid: None,
            closed: [false; 2],
            trimmed: true,
            area: 0.0,
            bbox: None,
        })
    }

    /// The surface of a `B_SPLINE_SURFACE_WITH_KNOTS`, simple or in a
    /// complex instance (rational or not), in metres, and its closed flags.
    fn bspline(&self, s: &'a Instance) -> Result<(NurbsSurface, [bool; 2]), ReferenceError> {
        // (degrees, control points, closed flags) then (multiplicities, knots)
        let (base, base_at, knots, knots_at) = if s.complex {
            let b = self.args(s, "B_SPLINE_SURFACE", 6)?;
            // a name first is not in the schema, but some writers put one
            let off = usize::from(matches!(b.params.first(), Some(Parameter::String(_))));
            (b, off, self.args(s, "B_SPLINE_SURFACE_WITH_KNOTS", 4)?, 0)
        } else {
            let a = self.args(s, "B_SPLINE_SURFACE_WITH_KNOTS", 12)?;
            (a, 1, a, 8)
        };
        let deg_u = base.degree(base_at, "u_degree")?;
        let deg_v = base.degree(base_at + 1, "v_degree")?;
        let cp = base.list(base_at + 2, "control_points_list")?;
        let closed = [
            base.logical(base_at + 4) == Some(true),
            base.logical(base_at + 5) == Some(true),
        ];
        let ku = knots.knots(knots_at, knots_at + 2, 'u')?;
        let kv = knots.knots(knots_at + 1, knots_at + 3, 'v')?;
        // control_points_list[i][j]: i along u, j along v
        let nu = cp.len();
        let nv = match cp.first() {
            Some(row) => as_list(row).map_or(0, <[Parameter]>::len),
            None => 0,
        };
        if nu == 0 || nv == 0 {
            return Err(self.err(s, format!("its control_points_list is empty; {FIX}")));
        }
        if nu.saturating_mul(nv) > MAX_POLES {
            return Err(self.err(
                s,
                format!(
                    "it has {nu} × {nv} poles, more than the {MAX_POLES} read; simplify the face (fewer poles) or export a smaller one"
                ),
            ));
        }
        let total = self.poles_read.get() + nu * nv;
        if total > MAX_FILE_POLES {
            return Err(self.err(
                s,
                format!(
                    "the faces up to this one have {total} poles, more than the {MAX_FILE_POLES} read from one file; export only the faces you need"
                ),
            ));
        }
        self.poles_read.set(total);
        let mut poles = vec![DVec3::ZERO; nu * nv];
        for (i, row) in cp.iter().enumerate() {
            let row = as_list(row).filter(|r| r.len() == nv).ok_or_else(|| {
                self.err(
                    s,
                    format!(
                        "row {i} of its control_points_list is {}, the first row has {nv} points; the rows must all be lists of the same length: {FIX}",
                        describe(row)
                    ),
                )
            })?;
            for (j, p) in row.iter().enumerate() {
                let id = as_ref(p).ok_or_else(|| {
                    self.err(
                        s,
                        format!(
                            "control point [{i}][{j}] is {}, not a reference to a CARTESIAN_POINT; {FIX}",
                            describe(p)
                        ),
                    )
                })?;
                poles[j * nu + i] = self.point(self.get(id, s, "control point")?)?;
            }
        }
        let weights = if s.has("RATIONAL_B_SPLINE_SURFACE") {
            let w = self.args(s, "RATIONAL_B_SPLINE_SURFACE", 1)?;
            let rows = w.list(0, "weights_data")?;
            let mut out = vec![0.0; nu * nv];
            if rows.len() != nu {
                return Err(self.err(
                    s,
                    format!(
                        "its weights_data has {} rows, its poles {nu}; {FIX}",
                        rows.len()
                    ),
                ));
            }
            for (i, row) in rows.iter().enumerate() {
                let row = as_list(row).filter(|r| r.len() == nv).ok_or_else(|| {
                    self.err(
                        s,
                        format!(
                            "row {i} of its weights_data is {}, not a list of {nv} weights; {FIX}",
                            describe(row)
                        ),
                    )
                })?;
                for (j, x) in row.iter().enumerate() {
                    out[j * nu + i] = as_real(x).ok_or_else(|| {
                        self.err(
                            s,
                            format!("weight [{i}][{j}] is {}, not a number; {FIX}", describe(x)),
                        )
                    })?;
                }
            }
            // all equal: the same surface as the poles alone
            let w0 = out[0];
            if out.iter().all(|&w| w == w0) && w0.is_finite() && w0 > 0.0 {
                None
            } else {
                Some(Grid::new(nv, nu, out).map_err(|e| self.err(s, e.to_string()))?)
            }
        } else {
            None
        };
        let poles = Grid::new(nv, nu, poles).map_err(|e| self.err(s, e.to_string()))?;
        let surface = NurbsSurface::new(deg_u, deg_v, ku, kv, poles, weights)
            .map_err(|e| self.err(s, e.to_string()))?;
        Ok((surface, closed))
    }

    /// A `CARTESIAN_POINT` with three coordinates, in metres.
    fn point(&self, p: &Instance) -> Result<DVec3, ReferenceError> {
        let a = self.args(p, "CARTESIAN_POINT", 2)?;
        let c = a.list(1, "coordinates")?;
        if c.len() != 3 {
            return Err(self.err(
                p,
                format!(
                    "it has {} coordinates, a point of a surface or face needs 3; {FIX}",
                    c.len()
                ),
            ));
        }
        let mut x = [0.0; 3];
        for (k, v) in c.iter().enumerate() {
            let r = as_real(v).ok_or_else(|| {
                self.err(
                    p,
                    format!(
                        "coordinate {} is {}, not a number; {FIX}",
                        k + 1,
                        describe(v)
                    ),
                )
            })?;
            let r = r * self.scale;
            if !r.is_finite() {
                return Err(self.err(
                    p,
                    format!(
                        "coordinate {} is not a finite number ({r}); the file is damaged: re-export it",
                        k + 1
                    ),
                ));
            }
            x[k] = r;
        }
        Ok(DVec3::from_array(x))
    }

    /// The vertices of one bound (`FACE_BOUND`/`FACE_OUTER_BOUND`) in loop
    /// order, in metres, its edge count, and whether it is an outer bound;
    /// `None` for a loop that is not an edge or poly loop.
    #[allow(clippy::type_complexity)]
    fn bound(
        &self,
        face: &Instance,
        id: u64,
    ) -> Result<(Option<(Vec<DVec3>, usize)>, bool), ReferenceError> {
        let b = self.get(id, face, "bound")?;
        let outer = b.has("FACE_OUTER_BOUND");
        let rec = if outer {
            "FACE_OUTER_BOUND"
        } else {
            "FACE_BOUND"
        };
        let a = self.args(b, rec, 2)?;
        let lid = a.reference(1, "bound")?;
        let lp = self.get(lid, b, "loop")?;
        if lp.has("EDGE_LOOP") {
            let la = self.args(lp, "EDGE_LOOP", 2)?;
            let edges = la.refs(1, "edge_list")?;
            let mut verts = Vec::with_capacity(edges.len());
            for e in &edges {
                let oe = self.get(*e, lp, "edge")?;
                let (start, _) = self.oriented_edge(oe)?;
                verts.push(start);
            }
            Ok((Some((verts, edges.len())), outer))
        } else if lp.has("POLY_LOOP") {
            let la = self.args(lp, "POLY_LOOP", 2)?;
            let pts = la.refs(1, "polygon")?;
            let mut verts = Vec::with_capacity(pts.len());
            for p in &pts {
                verts.push(self.point(self.get(*p, lp, "polygon point")?)?);
            }
            let n = verts.len();
            Ok((Some((verts, n)), outer))
        } else {
            Ok((None, outer))
        }
    }

    /// The start and end vertices (metres) of an `ORIENTED_EDGE` (or of an
    /// `EDGE_CURVE` used directly), in the loop's direction.
    fn oriented_edge(&self, oe: &Instance) -> Result<(DVec3, DVec3), ReferenceError> {
        let (edge, forward) = if oe.has("ORIENTED_EDGE") {
            let a = self.args(oe, "ORIENTED_EDGE", 5)?;
            let id = a.reference(3, "edge_element")?;
            (
                self.get(id, oe, "edge_element")?,
                a.logical(4) != Some(false),
            )
        } else {
            (oe, true)
        };
        let rec = if edge.has("EDGE_CURVE") {
            "EDGE_CURVE"
        } else {
            "EDGE"
        };
        let a = self.args(edge, rec, 3)?;
        let v1 = self.vertex(edge, a.reference(1, "edge_start")?)?;
        let v2 = self.vertex(edge, a.reference(2, "edge_end")?)?;
        Ok(if forward { (v1, v2) } else { (v2, v1) })
    }

    /// A `VERTEX_POINT`'s point, in metres.
    fn vertex(&self, from: &Instance, id: u64) -> Result<DVec3, ReferenceError> {
        let v = self.get(id, from, "vertex")?;
        let a = self.args(v, "VERTEX_POINT", 2)?;
        let pid = a.reference(1, "vertex_geometry")?;
        self.point(self.get(pid, v, "vertex_geometry")?)
    }

    /// Whether the face's one bound runs along the surface's boundary: at
    /// most four edges, every vertex on a corner.
    fn on_corners(
        &self,
        face: &Instance,
        bounds: &[u64],
        s: &NurbsSurface,
        bbox: Bbox,
    ) -> Result<bool, ReferenceError> {
        let [id] = bounds else {
            return Ok(false);
        };
        let (Some((verts, edges)), _) = self.bound(face, *id)? else {
            return Ok(false);
        };
        if edges > 4 || verts.is_empty() {
            return Ok(false);
        }
        let corners = geom::corners(s);
        let tol = geom::corner_tolerance(bbox);
        Ok(verts
            .iter()
            .all(|v| corners.iter().any(|c| c.distance(*v) <= tol)))
    }

    /// A plane face's area (its outer polygon less its holes' polygons)
    /// and the box of its vertices.
    fn plane_bounds(
        &self,
        face: &Instance,
        bounds: &[u64],
    ) -> Result<(f64, Option<Bbox>), ReferenceError> {
        let mut loops = Vec::new();
        for id in bounds {
            if let (Some((verts, _)), outer) = self.bound(face, *id)? {
                loops.push((geom::polygon_area(&verts), outer, verts));
            }
        }
        let bbox = geom::points_bbox(loops.iter().flat_map(|l| l.2.iter().copied()));
        if loops.is_empty() {
            return Ok((0.0, bbox));
        }
        // the outer bound: the one marked so, else the largest
        let outer = loops.iter().position(|l| l.1).unwrap_or_else(|| {
            let mut best = 0;
            for (i, l) in loops.iter().enumerate() {
                if l.0 > loops[best].0 {
                    best = i;
                }
            }
            best
        });
        let holes: f64 = loops
            .iter()
            .enumerate()
            .filter(|(i, _)| *i != outer)
            .map(|(_, l)| l.0)
            .sum();
        Ok(((loops[outer].0 - holes).max(0.0), bbox))
    }
}
