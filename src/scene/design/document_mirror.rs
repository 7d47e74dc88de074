//! The mirror of a design of several patches (docs/math.md §9, §11: the
//! mirror plane `P` is the first patch's, and every patch is reflected).
//!
//! Each patch's reflection is a patch of its own, named `<name>-mirror`,
//! after the originals: its points and tangents at every level are the
//! reflections `R(x) = x − 2((x − p)·n) n` of the original's (same grid
//! order, same `s` and `t`), and every join is reflected with its patches
//! (a seam `A → B` gives `R(A) → R(B)`, with the same report: the gap, angle
//! and curvature deviation are invariant under a reflection). A reflection
//! turns orientation over (`R(a) × R(b) = −R(a × b)`), so the exports turn
//! each reflected patch back: its triangles are wound the other way and its
//! normals are `R(n)`, its STEP face is written with `same_sense` false, so
//! the two halves of the symmetric product face the same way.
//!
//! In a STEP shell a patch whose first streamline lies in `P` (the first
//! patch's does when the mirror is on: its row 0 is projected into `P`) and
//! that has no side join on that streamline shares it with its reflection:
//! one `EDGE_CURVE` for both faces ([`mirror_shell`]). The one-patch design
//! keeps its own export (one face over both halves, docs/math.md §10).

use super::document::Document;
use super::document_build::{BuiltDocument, Seam};
use streamline_kernel::DVec3;
use streamline_kernel::grid::Grid;
use streamline_kernel::joins::{Edge, Stack};
use streamline_kernel::levels::design::Level;
use streamline_kernel::nurbs::{PatchGrid, Samples, ShellFit, ShellSeam, deviation_within};
use streamline_kernel::plane::MirrorPlane;

/// How far (in the face's diagonal) a first streamline's poles may be from
/// `P` for the face to share it with its reflection.
pub const IN_PLANE: f64 = 1e-9;

/// The mirror plane of a mirrored document (its first patch's, docs/math.md §9).
pub fn mirror_plane(doc: &Document) -> Option<MirrorPlane> {
    (doc.mirror && !doc.patches.is_empty()).then(|| doc.patches[0].design.mirror_plane())
}

/// The reflection of a direction in `plane`.
pub fn reflect_dir(plane: &MirrorPlane, v: DVec3) -> DVec3 {
    v - plane.normal * (2.0 * v.dot(plane.normal))
}

fn reflect_grid(g: &Grid<DVec3>, f: impl Fn(DVec3) -> DVec3) -> Grid<DVec3> {
    let data = g.data().iter().map(|&p| f(p)).collect();
    Grid::new(g.rows(), g.cols(), data).expect("the same shape")
}

/// A patch's levels and points reflected in `plane` (the grid order kept).
pub fn reflect_stack(stack: &Stack, plane: &MirrorPlane) -> Stack {
    Stack {
        levels: stack
            .levels
            .iter()
            .map(|l| Level {
                tangents: reflect_grid(&l.tangents, |v| reflect_dir(plane, v)),
                params: l.params.clone(),
            })
            .collect(),
        points: stack
            .points
            .iter()
            .map(|g| reflect_grid(g, |p| plane.reflect_point(p)))
            .collect(),
    }
}

/// The names of the patches a mirrored export writes: the document's, then
/// each one's reflection `<name>-mirror` (made unique).
pub fn mirrored_names(doc: &Document) -> Vec<String> {
    let mut names: Vec<String> = doc.patches.iter().map(|p| p.name.clone()).collect();
    if doc.mirror {
        for i in 0..doc.patches.len() {
            let mut n = format!("{}-mirror", doc.patches[i].name);
            while names.contains(&n) {
                n.push_str("-mirror");
            }
            names.push(n);
        }
    }
    names
}

/// The document as exported: `built` itself without the mirror; with it, the
/// `N` patches and then their `N` reflections, the seams and then theirs
/// (patch `i`'s reflection is patch `N + i`).
pub fn mirrored(doc: &Document, built: &BuiltDocument) -> BuiltDocument {
    let Some(plane) = mirror_plane(doc) else {
        return built.clone();
    };
    let n = built.patches.len();
    let mut out = built.clone();
    out.patches
        .extend(built.patches.iter().map(|s| reflect_stack(s, &plane)));
    out.seams.extend(built.seams.iter().map(|s| Seam {
        a: s.a + n,
        b: s.b + n,
        join: s.join,
        report: s.report.clone(),
    }));
    out
}

/// A shell with the reflected faces: faces `0..N` as fitted, `N + i` the
/// reflection of face `i`; seams, then their reflections; and the pairs of
/// faces (original, reflection) whose first streamlines are one edge.
#[derive(Debug, Clone)]
pub struct MirroredShell {
    /// The faces and seams.
    pub shell: ShellFit,
    /// `(i, N + i)` for each face whose `v = 0` edge lies in `P`.
    pub shared: Vec<(usize, usize)>,
}

/// Reflects a fitted shell in `plane` (`patches` are what it was fitted to):
/// each face's poles reflected (the fit commutes with isometries, and a
/// reflection keeps every distance, so the reflected face is within the
/// same tolerance of the reflected points, measured again here). A face
/// whose `v = 0` row of poles lies within [`IN_PLANE`] of `P` and which has
/// no side join on that edge gets, in its reflection, those very poles (so
/// both faces' first streamline is one curve, bit for bit) and is listed in
/// [`MirroredShell::shared`].
pub fn mirror_shell(shell: &ShellFit, patches: &[PatchGrid], plane: &MirrorPlane) -> MirroredShell {
    let n = shell.faces.len();
    let mut faces = shell.faces.clone();
    let mut shared = Vec::new();
    for (i, f) in shell.faces.iter().enumerate() {
        let mut r = f.clone();
        r.name = format!("{}-mirror", f.name);
        r.surface.poles = reflect_grid(&f.surface.poles, |p| plane.reflect_point(p));
        let diag = patches[i].data.diagonal().max(f64::MIN_POSITIVE);
        let side_on_first = shell
            .seams
            .iter()
            .any(|s| s.spec.a == i && s.spec.join.edge == Edge::First);
        let in_plane = f
            .surface
            .poles
            .row(0)
            .iter()
            .all(|&p| plane.distance(p).abs() <= IN_PLANE * diag);
        if in_plane && !side_on_first {
            for (k, &p) in f.surface.poles.row(0).iter().enumerate() {
                r.surface.poles.set(0, k, p);
            }
            shared.push((i, n + i));
        }
        let check = &patches[i].check;
        let reflected = Samples {
            points: reflect_grid(&check.points, |p| plane.reflect_point(p)),
            u: check.u.clone(),
            v: f.v.1.clone(),
        };
        r.deviation = deviation_within(&r.surface, &reflected, r.tolerance);
        faces.push(r);
    }
    let mut seams = shell.seams.clone();
    seams.extend(shell.seams.iter().map(|s| {
        let mut spec = s.spec;
        (spec.a, spec.b) = (spec.a + n, spec.b + n);
        ShellSeam {
            spec,
            range: s.range,
            slope_held: s.slope_held,
        }
    }));
    MirroredShell {
        shell: ShellFit { faces, seams },
        shared,
    }
}
