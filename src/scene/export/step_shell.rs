//! The STEP file of a design (docs/math.md §10, §11): one `ADVANCED_FACE` per
//! patch (a design of one patch is a shell of one face) in one `OPEN_SHELL`
//! of a `SHELL_BASED_SURFACE_MODEL`, around it what [`super::step`] writes,
//! each face named for its patch, and each seam **one** `EDGE_CURVE` used by
//! both faces in opposite directions, its vertices shared (the faces come
//! from [`streamline_kernel::nurbs::fit_shell`], whose seams are one curve).
//!
//! A face's loop is `v = 0`, `u = 1`, `v = 1`, `u = 0` (counter-clockwise in
//! the parameter plane, so the face's normal is the surface's `∂F/∂u ×
//! ∂F/∂v`), each edge a B-spline curve whose poles are the surface's
//! boundary poles: the edges lie on the surface exactly.
//! A chain's seam is `A`'s `u = 1` edge and `B`'s `u = 0` edge. A side seam
//! covers the part `[u₀, u₁]` of `A`'s `v = 0` (`First`) or `v = 1` (`Last`)
//! edge: that edge is split at `u₀` and `u₁` into up to three edges (each
//! the piece of the boundary curve, cut by knot insertion), the middle one
//! being `B`'s `u = 0` edge. Where `B`'s own orientation (`∂u × ∂v`) turns
//! against `A`'s across the seam (both faces would use the seam edge the
//! same way) `B`'s face is written with `same_sense` false, so the shell is
//! consistently oriented.

use super::cad_text::step_string as string;
use super::format::{file_name, fit_refused, utc_now};
use super::step::{StepInfo, Writer, curve, finish, frame, point, refs, surface_entity, verify};
use crate::scene::files::error::SceneError;
use crate::scene::files::io::write_atomic;
use std::path::Path;
use streamline_kernel::DVec3;
use streamline_kernel::joins::Edge;
use streamline_kernel::nurbs::curve::Curve;
use streamline_kernel::nurbs::{
    FitOptions, PatchGrid, SeamSpec, ShellFace, ShellFit, ShellSeam, fit_shell,
};

/// An edge written: its `EDGE_CURVE` and its start and end vertices.
#[derive(Clone, Copy)]
struct EdgeRec {
    id: usize,
    start: usize,
    end: usize,
}

fn vertex(w: &mut Writer, p: DVec3) -> usize {
    let c = point(w, p);
    w.add(format!("VERTEX_POINT('',#{c})"))
}

fn edge(w: &mut Writer, c: &Curve, start: usize, end: usize) -> EdgeRec {
    let g = curve(w, c);
    let id = w.add(format!("EDGE_CURVE('',#{start},#{end},#{g},.T.)"));
    EdgeRec { id, start, end }
}

/// The edges of one side run along `u` (`v = 0` or `v = 1`), split at
/// `splits` (increasing, inside `(0, 1)`): the curve `c`'s pieces between
/// the vertices `first`, the splits' and `last`.
fn split_side(
    w: &mut Writer,
    c: &Curve,
    splits: &[f64],
    first: usize,
    last: usize,
) -> Vec<(f64, f64, EdgeRec)> {
    let mut cuts = vec![0.0];
    cuts.extend_from_slice(splits);
    cuts.push(1.0);
    let pieces: Vec<Curve> = cuts.windows(2).map(|x| c.piece(x[0], x[1])).collect();
    let mut verts = vec![first];
    for p in &pieces[1..] {
        verts.push(vertex(w, p.poles[0]));
    }
    verts.push(last);
    pieces
        .iter()
        .enumerate()
        .map(|(k, p)| (cuts[k], cuts[k + 1], edge(w, p, verts[k], verts[k + 1])))
        .collect()
}

/// The reflected half of a mirrored shell (docs/math.md §9, §11;
/// [`crate::scene::design::document_mirror`]): faces `originals..` are the reflections of
/// faces `0..originals`, in order, and each pair `(i, j)` of `shared` shares
/// its `v = 0` edge (the first streamline, in the mirror plane).
#[derive(Debug, Clone, Copy)]
pub struct MirrorFaces<'a> {
    /// How many faces are not reflections.
    pub originals: usize,
    /// `(original, reflection)` whose first streamlines are one edge.
    pub shared: &'a [(usize, usize)],
}

/// The whole file: `faces` in one shell, sharing the edges of `seams`
/// (none: every face on its own edges, as separate exports would be). With
/// `mirror`, the reflected faces are each written with the opposite
/// `same_sense` of its original (a reflection turns the orientation over),
/// and the pairs of `mirror.shared` on one `v = 0` edge, used by both faces
/// in opposite directions.
pub fn faces_text(
    faces: &[ShellFace],
    seams: &[ShellSeam],
    mirror: Option<MirrorFaces>,
    info: &StepInfo,
) -> String {
    let mut w = Writer {
        text: String::new(),
        next: 1,
    };
    let frame = frame(&mut w, info);
    // per seam: the edge written for it on `a`'s side, whether `b`'s v runs
    // along the edge's curve, and whether `a`'s loop runs along it
    let mut seam_edge: Vec<Option<(EdgeRec, bool, bool)>> = vec![None; seams.len()];
    let mut flipped = vec![false; faces.len()];
    // each face's `v = 0` edge, when it is one piece
    let mut bottoms: Vec<Option<EdgeRec>> = vec![None; faces.len()];
    let reflection_of = |f: usize| mirror.filter(|m| f >= m.originals).map(|m| f - m.originals);
    let mirror_bottom =
        |f: usize| mirror.and_then(|m| m.shared.iter().find(|(_, j)| *j == f).map(|(i, _)| *i));
    let mut face_ids = Vec::with_capacity(faces.len());
    for (f, face) in faces.iter().enumerate() {
        let s = &face.surface;
        let (nu, nv) = s.pole_counts();
        let srf = surface_entity(&mut w, s);
        let bottom_c = Curve::new(&s.knots_u, s.poles.row(0).to_vec());
        let top_c = Curve::new(&s.knots_u, s.poles.row(nv - 1).to_vec());
        let right_c = Curve::new(&s.knots_v, s.poles.column(nu - 1));
        let left_c = Curve::new(&s.knots_v, s.poles.column(0));
        // the incoming seam: b's u = 0 edge is a's edge
        let incoming = seams.iter().position(|x| x.spec.b == f);
        let (left, left_along) = match incoming.and_then(|k| seam_edge[k].map(|e| (k, e))) {
            Some((k, (e, along, a_along))) => {
                // b's loop runs its left edge against v
                let b_along = !along;
                flipped[f] = flipped[seams[k].spec.a] ^ (a_along == b_along);
                (Some(e), along)
            }
            None => {
                // a reflected face with no incoming seam faces the other way
                if let Some(o) = reflection_of(f) {
                    flipped[f] = !flipped[o];
                }
                (None, true)
            }
        };
        let left_ends = left.map(|e| {
            if left_along {
                (e.start, e.end)
            } else {
                (e.end, e.start)
            }
        });
        // the original's first streamline, when this reflection shares it
        let shared_bottom = mirror_bottom(f)
            .and_then(|o| bottoms[o])
            .filter(|e| left_ends.is_none_or(|(c00, _)| c00 == e.start));
        let (c00, c01) = match (left_ends, shared_bottom) {
            (Some(ends), _) => ends,
            (None, Some(e)) => (e.start, vertex(&mut w, s.poles.get(nv - 1, 0))),
            (None, None) => (
                vertex(&mut w, s.poles.get(0, 0)),
                vertex(&mut w, s.poles.get(nv - 1, 0)),
            ),
        };
        let c10 = match shared_bottom {
            Some(e) => e.end,
            None => vertex(&mut w, s.poles.get(0, nu - 1)),
        };
        let c11 = vertex(&mut w, s.poles.get(nv - 1, nu - 1));
        // side seams that start on this face's first or last streamline
        let splits = |edge: Edge| -> Vec<f64> {
            let mut x: Vec<f64> = seams
                .iter()
                .filter(|k| k.spec.a == f && k.spec.join.edge == edge)
                .flat_map(|k| [k.range.0, k.range.1])
                .filter(|u| *u > 0.0 && *u < 1.0)
                .collect();
            x.sort_by(f64::total_cmp);
            x.dedup();
            x
        };
        let bottom = match shared_bottom {
            Some(e) => vec![(0.0, 1.0, e)],
            None => split_side(&mut w, &bottom_c, &splits(Edge::First), c00, c10),
        };
        if let [(_, _, e)] = bottom.as_slice() {
            bottoms[f] = Some(*e);
        }
        let right = edge(&mut w, &right_c, c10, c11);
        let top = split_side(&mut w, &top_c, &splits(Edge::Last), c01, c11);
        let left = left.unwrap_or_else(|| edge(&mut w, &left_c, c00, c01));
        for (k, x) in seams.iter().enumerate().filter(|(_, x)| x.spec.a == f) {
            let (lo, hi) = (x.range.0.min(x.range.1), x.range.0.max(x.range.1));
            let along = x.range.0 <= x.range.1;
            let find = |side: &[(f64, f64, EdgeRec)]| {
                side.iter()
                    .find(|(a, b, _)| *a == lo && *b == hi)
                    .map(|(_, _, e)| *e)
            };
            seam_edge[k] = match x.spec.join.edge {
                Edge::End => Some((right, true, true)),
                Edge::First => find(&bottom).map(|e| (e, along, true)),
                Edge::Last => find(&top).map(|e| (e, along, false)),
            };
        }
        let mut oriented = Vec::new();
        let mut use_edge = |w: &mut Writer, e: EdgeRec, sense: bool| {
            let s = if sense { ".T." } else { ".F." };
            oriented.push(w.add(format!("ORIENTED_EDGE('',*,*,#{},{s})", e.id)));
        };
        for (_, _, e) in &bottom {
            use_edge(&mut w, *e, true);
        }
        use_edge(&mut w, right, true);
        for (_, _, e) in top.iter().rev() {
            use_edge(&mut w, *e, false);
        }
        use_edge(&mut w, left, !left_along);
        let lp = w.add(format!("EDGE_LOOP('',{})", refs(&oriented)));
        let bound = w.add(format!("FACE_OUTER_BOUND('',#{lp},.T.)"));
        let sense = if flipped[f] { ".F." } else { ".T." };
        face_ids.push(w.add(format!(
            "ADVANCED_FACE({},(#{bound}),#{srf},{sense})",
            string(&face.name)
        )));
    }
    let shell = w.add(format!("OPEN_SHELL('',{})", refs(&face_ids)));
    let model = w.add(format!("SHELL_BASED_SURFACE_MODEL('',(#{shell}))"));
    finish(w, model, frame, info, "B-spline faces in one shell")
}

/// Fits `patches` as one shell whose `seams` are shared
/// ([`fit_shell`]) and writes its STEP file to `path` atomically, verified;
/// nothing is written when the fit or the write fails (the old file is kept).
/// `name` is the product's; the faces are named for the patches.
pub fn write_shell(
    path: &Path,
    name: &str,
    patches: &[PatchGrid],
    seams: &[SeamSpec],
    opts: &FitOptions,
) -> Result<ShellFit, SceneError> {
    let shell = fit_shell(patches, seams, opts).map_err(|e| fit_refused(path, e))?;
    write_fitted(path, name, &shell, None)?;
    Ok(shell)
}

/// Writes a fitted shell (with its reflected faces, if `mirror`) to `path`
/// atomically, verified (one face per patch).
pub fn write_fitted(
    path: &Path,
    name: &str,
    shell: &ShellFit,
    mirror: Option<MirrorFaces>,
) -> Result<(), SceneError> {
    let file_name = file_name(path);
    let tol = shell
        .faces
        .iter()
        .map(|f| f.tolerance)
        .fold(f64::INFINITY, f64::min);
    let (y, mo, d, h, mi, se) = utc_now();
    let stamp = format!("{y:04}-{mo:02}-{d:02}T{h:02}:{mi:02}:{se:02}");
    let info = StepInfo {
        name,
        file_name: &file_name,
        uncertainty: (tol / 10.0).min(1e-6),
        timestamp: &stamp,
    };
    let bytes = faces_text(&shell.faces, &shell.seams, mirror, &info).into_bytes();
    let n = shell.faces.len();
    write_atomic(path, &bytes, |b| verify(b, n))
}
