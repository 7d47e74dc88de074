//! Loop subdivision with boundary rules, and limit points (paper 002, §2 and §4;
//! `docs/math.md §7`).
//!
//! Inside, every rule is Loop's:
//! - Interior vertex of valence `n`: `(1 − nβ) V + β Σ neighbours`, Loop's
//!   `β = (5/8 − (3/8 + ¼ cos(2π/n))²)/n` (not Warren's `3/(8n)`).
//! - Interior edge `(a, b)` with opposite vertices `c, d`: `⅜(a + b) + ⅛(c + d)`.
//!
//! On the boundary, one of three [`BoundaryRule`]s:
//! - [`BoundaryRule::Paper`] (002 §4, its refs [18, 19]): boundary vertex
//!   `¾ V + ⅛ (L + R)`, `L, R` its boundary neighbours; a boundary vertex is
//!   *regular* when its valence is 4, else *extraordinary*; boundary edge: the
//!   midpoint when both ends have the same type, else `⅝ regular + ⅜
//!   extraordinary`. New boundary vertices have valence 4 (regular); old
//!   vertices keep their valence, so their type, at every level.
//! - [`BoundaryRule::EdgeOnly`] (OpenSubdiv's `VTX_BOUNDARY_EDGE_ONLY`, the
//!   crease rules): boundary vertex `¾ V + ⅛ (L + R)`, boundary edge the
//!   midpoint — each boundary loop is a uniform cubic B-spline.
//! - [`BoundaryRule::EdgeAndCorner`] (`VTX_BOUNDARY_EDGE_AND_CORNER`, USD's
//!   default): as edge-only, but a *corner* — a boundary vertex with a single
//!   face (valence 2) — stays where it is at every level.
//!
//! Limit points. Interior (002 Eq. 3): `V∞ = β_n V + (1 − β_n) Q̄`, `Q̄` the
//! neighbours' mean, `β_n = 3/(11 − 8(3/8 + (3/8 + ¼ cos(2π/n))²))` (½ for n = 6).
//! Boundary: after one step a boundary vertex's boundary neighbours are new
//! vertices, and the triple (L, C, R) subdivides by itself; the limit mask is
//! the left eigenvector for eigenvalue 1 of that 3×3 matrix (`docs/math.md §7`):
//! - paper (the six masks of 002 Fig. 1 e–j, lost in the text, derived here):
//!   `C' = ⅛L + ¾C + ⅛R`, `R' = ½(C + R)` (C regular) or `⅜C + ⅝R` (C
//!   extraordinary); the eigenvector is `(1/6, 2/3, 1/6)` (regular C) and
//!   `(1/5, 3/5, 1/5)` (extraordinary C). Composing with one step of the
//!   level-0 rules, whose edge points depend on the neighbours' types, gives
//!   the mask for each of the 6 configurations (`boundary_mask`).
//! - edge-only: the matrix rows `(½, ½, 0)`, `(⅛, ¾, ⅛)`, `(0, ½, ½)` at every
//!   level, eigenvector `(1/6, 2/3, 1/6)`, already at level 0.
//! - edge-and-corner: a corner's row is `(0, 1, 0)`, so its mask is `(0, 1, 0)`;
//!   every other boundary vertex's triple is edge-only's (a corner neighbour's
//!   edge point is still the midpoint), so its mask is `(1/6, 2/3, 1/6)`.

use crate::loop_subdiv::trimesh::{MeshError, Topology, TriMesh};
use glam::DVec3;

/// Which rules act on the boundary of an open mesh (module docs; `docs/math.md §7`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum BoundaryRule {
    /// 002 §4's rules (regular boundary vertices of valence 4, `⅝–⅜` edge points
    /// between types). Exact for 002's surface; no renderer implements it.
    Paper,
    /// OpenSubdiv's `VTX_BOUNDARY_EDGE_ONLY`: boundary curves are cubic B-splines.
    EdgeOnly,
    /// OpenSubdiv's `VTX_BOUNDARY_EDGE_AND_CORNER` (USD's `edgeAndCorner`, its
    /// default): edge-only, and a boundary vertex with a single face stays put.
    #[default]
    EdgeAndCorner,
}

impl BoundaryRule {
    /// The three, in the order the command line and the editor list them.
    pub const ALL: [BoundaryRule; 3] = [
        BoundaryRule::Paper,
        BoundaryRule::EdgeOnly,
        BoundaryRule::EdgeAndCorner,
    ];

    /// `paper`, `edge-only` or `edge-and-corner` (the command line's names).
    pub fn name(self) -> &'static str {
        match self {
            BoundaryRule::Paper => "paper",
            BoundaryRule::EdgeOnly => "edge-only",
            BoundaryRule::EdgeAndCorner => "edge-and-corner",
        }
    }

    /// The rule of [`BoundaryRule::name`] `s`.
    #[cfg(test)]
    pub(crate) fn from_name(s: &str) -> Option<BoundaryRule> {
        BoundaryRule::ALL.into_iter().find(|r| r.name() == s)
    }

    /// USD's `interpolateBoundary` token (`edgeOnly`, `edgeAndCorner`); `None`
    /// for 002's rule, which USD cannot say.
    pub fn usd_token(self) -> Option<&'static str> {
        match self {
            BoundaryRule::Paper => None,
            BoundaryRule::EdgeOnly => Some("edgeOnly"),
            BoundaryRule::EdgeAndCorner => Some("edgeAndCorner"),
        }
    }

    /// Whether a boundary vertex of valence `n` is a corner that stays put.
    #[inline]
    pub fn is_corner(self, n: usize) -> bool {
        self == BoundaryRule::EdgeAndCorner && n == 2
    }
}

/// Loop's vertex weight `β` for an interior vertex of valence `n`.
#[inline]
pub fn loop_beta(n: usize) -> f64 {
    static TABLE: std::sync::OnceLock<[f64; 64]> = std::sync::OnceLock::new();
    let table = TABLE.get_or_init(|| std::array::from_fn(loop_beta_formula));
    match table.get(n) {
        Some(&b) if n > 0 => b,
        _ => loop_beta_formula(n),
    }
}

fn loop_beta_formula(n: usize) -> f64 {
    let n = n as f64;
    let c = 0.375 + 0.25 * (std::f64::consts::TAU / n).cos();
    (0.625 - c * c) / n
}

/// The limit weight `β_n` of Eq. 3 (the vertex's own weight in its limit point).
#[inline]
pub fn limit_beta(n: usize) -> f64 {
    static TABLE: std::sync::OnceLock<[f64; 64]> = std::sync::OnceLock::new();
    let table = TABLE.get_or_init(|| std::array::from_fn(limit_beta_formula));
    match table.get(n) {
        Some(&b) if n > 0 => b,
        _ => limit_beta_formula(n),
    }
}

fn limit_beta_formula(n: usize) -> f64 {
    let c = 0.375 + 0.25 * (std::f64::consts::TAU / n as f64).cos();
    3.0 / (11.0 - 8.0 * (0.375 + c * c))
}

/// Whether a boundary vertex of valence `n` is regular (valence 4).
pub fn is_regular_boundary(n: usize) -> bool {
    n == 4
}

/// Weights `(w_other, w_self)` of the boundary edge point between a vertex of
/// type `me_regular` and its neighbour of type `other_regular`.
fn edge_weights(me_regular: bool, other_regular: bool) -> (f64, f64) {
    match (me_regular, other_regular) {
        (a, b) if a == b => (0.5, 0.5),
        (true, false) => (0.375, 0.625),
        _ => (0.625, 0.375),
    }
}

/// The limit mask `(l, c, r)` of a boundary vertex on `(L, C, R)`: its type and
/// its boundary neighbours' types (the six configurations of 002 Fig. 1 e–j).
pub fn boundary_mask(center_regular: bool, left_regular: bool, right_regular: bool) -> [f64; 3] {
    // level-1 mask of C over (L', C', R'), whose neighbours are regular
    let (side, mid) = if center_regular {
        (1.0 / 6.0, 4.0 / 6.0)
    } else {
        (0.2, 0.6)
    };
    let (wl, wcl) = edge_weights(center_regular, left_regular);
    let (wr, wcr) = edge_weights(center_regular, right_regular);
    // L' = wl L + wcl C, C' = ⅛L + ¾C + ⅛R, R' = wr R + wcr C
    [
        side * wl + mid * 0.125,
        side * (wcl + wcr) + mid * 0.75,
        side * wr + mid * 0.125,
    ]
}

/// The limit mask `(l, c, r)` of a boundary vertex of valence `nc` on
/// `(L, C, R)`, its boundary neighbours of valences `nl` and `nr`, under `rule`.
pub fn boundary_limit_mask(rule: BoundaryRule, nc: usize, nl: usize, nr: usize) -> [f64; 3] {
    match rule {
        BoundaryRule::Paper => boundary_mask(
            is_regular_boundary(nc),
            is_regular_boundary(nl),
            is_regular_boundary(nr),
        ),
        _ if rule.is_corner(nc) => [0.0, 1.0, 0.0],
        _ => [1.0 / 6.0, 4.0 / 6.0, 1.0 / 6.0],
    }
}

/// Limit points of every vertex of a mesh with the given topology.
pub fn limit_points(
    positions: &[DVec3],
    topo: &Topology,
    rule: BoundaryRule,
    out: &mut Vec<DVec3>,
) {
    out.clear();
    out.extend((0..positions.len()).map(|v| limit_point(positions, topo, rule, v)));
}

/// The limit point of vertex `v`.
#[inline]
pub fn limit_point(positions: &[DVec3], topo: &Topology, rule: BoundaryRule, v: usize) -> DVec3 {
    let ring = topo.ring(v);
    if topo.boundary[v] {
        let (l, r) = (ring[0] as usize, ring[ring.len() - 1] as usize);
        let m = boundary_limit_mask(rule, ring.len(), topo.valence(l), topo.valence(r));
        return positions[l] * m[0] + positions[v] * m[1] + positions[r] * m[2];
    }
    let n = ring.len();
    let b = limit_beta(n);
    let mut q = DVec3::ZERO;
    for &u in ring {
        q += positions[u as usize];
    }
    positions[v] * b + q * ((1.0 - b) / n as f64)
}

/// One step of Loop subdivision with the boundary rules `rule`. Old vertices
/// keep their indices; edge `e` of the topology becomes vertex `old + e`; each
/// face `(a, b, c)` becomes `(a, ab, ca)`, `(b, bc, ab)`, `(c, ca, bc)`, `(ab, bc, ca)`.
pub fn subdivide(
    mesh: &TriMesh,
    topo: &Topology,
    rule: BoundaryRule,
) -> Result<TriMesh, MeshError> {
    let positions = subdivided_positions(&mesh.positions, topo, rule)?;
    let nv = mesh.positions.len() as u32;
    let mut faces = Vec::with_capacity(mesh.faces.len() * 4);
    for (f, fe) in mesh.faces.iter().zip(&topo.face_edges) {
        let [a, b, c] = *f;
        let [ab, bc, ca] = fe.map(|e| nv + e);
        faces.extend([[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]);
    }
    Ok(TriMesh { positions, faces })
}

/// [`subdivide`] with the subdivided mesh's topology, derived from `topo`
/// ([`Topology::refine`]) instead of rebuilt from the faces.
pub fn subdivide_refined(
    mesh: &TriMesh,
    topo: &Topology,
    rule: BoundaryRule,
) -> Result<(TriMesh, Topology), MeshError> {
    let positions = subdivided_positions(&mesh.positions, topo, rule)?;
    let (faces, t) = topo.refine(&mesh.faces);
    Ok((TriMesh { positions, faces }, t))
}

/// `levels` steps of Loop subdivision: the topology of each level but the last
/// is derived from the one before ([`Topology::refine`]), none is rebuilt.
pub fn subdivide_levels(
    mesh: &TriMesh,
    topo: &Topology,
    rule: BoundaryRule,
    levels: u32,
) -> Result<TriMesh, MeshError> {
    if levels == 0 {
        return Ok(mesh.clone());
    }
    if levels == 1 {
        return subdivide(mesh, topo, rule);
    }
    // the last topology derived feeds only the last step: no ring edges, no loops
    let positions = subdivided_positions(&mesh.positions, topo, rule)?;
    let (faces, mut t) = topo.refine_with(&mesh.faces, levels > 2);
    let mut m = TriMesh { positions, faces };
    for level in 2..levels {
        let positions = subdivided_positions(&m.positions, &t, rule)?;
        let (faces, next) = t.refine_with(&m.faces, level + 1 < levels);
        (m, t) = (TriMesh { positions, faces }, next);
    }
    subdivide(&m, &t, rule)
}

/// The positions of one step: the old vertices' new positions, then one per edge.
fn subdivided_positions(
    p: &[DVec3],
    topo: &Topology,
    rule: BoundaryRule,
) -> Result<Vec<DVec3>, MeshError> {
    let nv = p.len();
    let total = nv + topo.edges.len();
    if total > crate::loop_subdiv::trimesh::MAX_VERTICES {
        return Err(MeshError::TooLarge {
            what: "vertices after subdivision",
            count: total,
            cap: crate::loop_subdiv::trimesh::MAX_VERTICES,
        });
    }
    let mut out = Vec::with_capacity(total);
    for v in 0..nv {
        let ring = topo.ring(v);
        if topo.boundary[v] {
            let (l, r) = (ring[0] as usize, ring[ring.len() - 1] as usize);
            if rule.is_corner(ring.len()) {
                out.push(p[v]);
            } else {
                out.push(p[v] * 0.75 + (p[l] + p[r]) * 0.125);
            }
        } else {
            let n = ring.len();
            let b = loop_beta(n);
            let mut s = DVec3::ZERO;
            for &u in ring {
                s += p[u as usize];
            }
            out.push(p[v] * (1.0 - n as f64 * b) + s * b);
        }
    }
    for &([a, b], [c, d]) in &topo.edges {
        let (pa, pb) = (p[a as usize], p[b as usize]);
        if d != u32::MAX {
            out.push((pa + pb) * 0.375 + (p[c as usize] + p[d as usize]) * 0.125);
        } else if rule != BoundaryRule::Paper {
            out.push((pa + pb) * 0.5);
        } else {
            let ra = is_regular_boundary(topo.valence(a as usize));
            let rb = is_regular_boundary(topo.valence(b as usize));
            let (wb, wa) = edge_weights(ra, rb);
            out.push(pa * wa + pb * wb);
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn limit_weights_regular_valence() {
        assert!((limit_beta(6) - 0.5).abs() < 1e-15, "β₆ = 1/2 (002 Eq. 3)");
        assert!(
            (loop_beta(6) - 1.0 / 16.0).abs() < 1e-15,
            "Loop's β₆ = 1/16"
        );
        for cfg in 0..8 {
            let m = boundary_mask(cfg & 1 == 1, cfg & 2 == 2, cfg & 4 == 4);
            assert!((m.iter().sum::<f64>() - 1.0).abs() < 1e-15, "{cfg}: {m:?}");
            assert!(m[1] > m[0] + m[2], "strictly diagonally dominant (002 §4)");
        }
        // the regular interior mask through limit_point itself: a hexagon fan
        // closed by a second one, centre 1/2 and each neighbour 1/12
        let mut pos = vec![DVec3::ZERO; 8];
        let mut faces = Vec::new();
        for i in 0..6u32 {
            faces.push([0, 1 + i, 1 + (i + 1) % 6]);
            faces.push([7, 1 + (i + 1) % 6, 1 + i]);
        }
        for (i, p) in pos.iter_mut().enumerate().take(7).skip(1) {
            let a = std::f64::consts::TAU * i as f64 / 6.0;
            *p = DVec3::new(a.cos(), a.sin(), 0.0);
        }
        pos[7] = DVec3::new(0.0, 0.0, -1.0);
        let (mesh, topo) = TriMesh::new(pos, faces).unwrap();
        assert_eq!(topo.valence(0), 6);
        for probe in 0..7 {
            let mut p = vec![DVec3::ZERO; 8];
            p[probe] = DVec3::X;
            let w = limit_point(&p, &topo, BoundaryRule::Paper, 0).x;
            let want = if probe == 0 { 0.5 } else { 1.0 / 12.0 };
            assert!((w - want).abs() < 1e-15, "weight of vertex {probe}: {w}");
        }
        let _ = mesh;
        // the crease rules: the cubic B-spline's mask, a corner's identity
        for (nc, nl, nr) in [(2, 3, 4), (3, 2, 2), (4, 4, 4), (7, 5, 2)] {
            let e = boundary_limit_mask(BoundaryRule::EdgeOnly, nc, nl, nr);
            assert_eq!(e, [1.0 / 6.0, 4.0 / 6.0, 1.0 / 6.0]);
            let c = boundary_limit_mask(BoundaryRule::EdgeAndCorner, nc, nl, nr);
            assert_eq!(c, if nc == 2 { [0.0, 1.0, 0.0] } else { e });
        }
        assert_eq!(BoundaryRule::default(), BoundaryRule::EdgeAndCorner);
        for r in BoundaryRule::ALL {
            assert_eq!(BoundaryRule::from_name(r.name()), Some(r));
        }
        assert_eq!(BoundaryRule::Paper.usd_token(), None);
        let m = boundary_mask(true, true, true);
        let want = [1.0 / 6.0, 2.0 / 3.0, 1.0 / 6.0];
        assert!(
            m.iter().zip(want).all(|(a, b)| (a - b).abs() < 1e-15),
            "{m:?}"
        );
    }
}
