//! Triangle meshes for Loop subdivision (paper 002; docs/math.md §7): positions and
//! faces, their topology built once (each vertex's ring of neighbours in fan
//! order, boundary loops), and validation that names the offending element.

mod refine;

use glam::DVec3;
use std::fmt;

/// A triangle mesh: positions and counter-clockwise faces (0-based indices).
#[derive(Debug, Clone, PartialEq)]
pub struct TriMesh {
    /// Vertex positions.
    pub positions: Vec<DVec3>,
    /// Triangles.
    pub faces: Vec<[u32; 3]>,
}

/// What is wrong with a mesh, with the ids of the elements involved (0-based
/// here; the messages count from 1, as OBJ files do).
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum MeshError {
    /// The mesh has no faces.
    Empty,
    /// A face refers to a vertex that does not exist.
    IndexOutOfRange {
        face: usize,
        index: u32,
        vertices: usize,
    },
    /// A vertex position is NaN or infinite.
    NonFiniteVertex { vertex: usize },
    /// A vertex coordinate is beyond [`crate::limits::MAX_COORDINATE`].
    VertexTooFar { vertex: usize },
    /// A face repeats a vertex (or its corners coincide).
    DegenerateFace { face: usize },
    /// More than two faces share an edge.
    NonManifoldEdge { a: u32, b: u32, faces: usize },
    /// Two faces use the same directed edge: their windings disagree.
    InconsistentWinding {
        a: u32,
        b: u32,
        face1: usize,
        face2: usize,
    },
    /// A vertex's faces form more than one fan.
    NonManifoldVertex { vertex: usize },
    /// A vertex no face uses.
    UnreferencedVertex { vertex: usize },
    /// Too large for the documented cap.
    TooLarge {
        what: &'static str,
        count: usize,
        cap: usize,
    },
}

impl fmt::Display for MeshError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        use MeshError::*;
        match self {
            Empty => write!(f, "the mesh has no triangles; give a mesh with `f` lines"),
            IndexOutOfRange {
                face,
                index,
                vertices,
            } => write!(
                f,
                "face {} uses vertex {} but there are {vertices} vertices; fix the face's indices (1-based, as in OBJ)",
                face + 1,
                index + 1
            ),
            NonFiniteVertex { vertex } => write!(
                f,
                "vertex {} has a NaN or infinite coordinate; give finite coordinates",
                vertex + 1
            ),
            VertexTooFar { vertex } => write!(
                f,
                "vertex {} has a coordinate beyond ±{:e}, the largest the kernel works with; scale the mesh down",
                vertex + 1,
                crate::limits::MAX_COORDINATE
            ),
            DegenerateFace { face } => write!(
                f,
                "face {} is degenerate (a repeated vertex or zero area); remove it",
                face + 1
            ),
            NonManifoldEdge { a, b, faces } => write!(
                f,
                "edge {}–{} is shared by {faces} faces (a manifold edge has 1 or 2); split the mesh there",
                a + 1,
                b + 1
            ),
            InconsistentWinding { a, b, face1, face2 } => write!(
                f,
                "faces {} and {} both run edge {}→{}: their orientations disagree (or one repeats the other); flip or remove one",
                face1 + 1,
                face2 + 1,
                a + 1,
                b + 1
            ),
            NonManifoldVertex { vertex } => write!(
                f,
                "vertex {} joins separate fans of faces (non-manifold); duplicate it for each fan",
                vertex + 1
            ),
            UnreferencedVertex { vertex } => {
                write!(f, "vertex {} is used by no face; remove it", vertex + 1)
            }
            TooLarge { what, count, cap } => write!(
                f,
                "{count} {what} is over the limit of {cap}; use a smaller mesh"
            ),
        }
    }
}

impl std::error::Error for MeshError {}

/// An edge seen from its lower vertex while the topology is built.
struct EdgeAt {
    other: u32,
    /// Faces running lower → other, and other → lower.
    out: u8,
    inn: u8,
    /// The vertex opposite the edge in each of those faces.
    opp_out: u32,
    opp_in: u32,
    /// (face, edge index in the face) of the first two faces.
    slots: [(u32, u8); 2],
}

/// The most vertices a mesh may have (and so a subdivision may produce).
pub(crate) const MAX_VERTICES: usize = 20_000_000;

/// The topology of a valid mesh, built once (flat arrays: a million-vertex
/// mesh builds in a fraction of a second).
#[derive(Debug, Clone, PartialEq)]
pub struct Topology {
    /// `ring_data[ring_start[v] .. ring_start[v + 1]]` is vertex `v`'s ring.
    ring_start: Vec<u32>,
    ring_data: Vec<u32>,
    /// `ring_edges[i]`: the edge (index into `edges`) from the ring's vertex to `ring_data[i]`.
    ring_edges: Vec<u32>,
    /// Whether each vertex lies on the boundary.
    pub boundary: Vec<bool>,
    /// Undirected edges `(a, b)`, `a < b`, each once, with its one or two
    /// opposite vertices (`u32::MAX` for the missing one of a boundary edge).
    pub edges: Vec<([u32; 2], [u32; 2])>,
    /// Each face's edges, as indices into `edges`: edge `(v0,v1)`, `(v1,v2)`, `(v2,v0)`.
    pub face_edges: Vec<[u32; 3]>,
    /// Boundary loops, as vertex sequences.
    pub loops: Vec<Vec<u32>>,
}

impl Topology {
    /// Vertex `v`'s neighbours in fan order; for a boundary vertex the first
    /// and the last are its boundary neighbours.
    #[inline]
    pub fn ring(&self, v: usize) -> &[u32] {
        &self.ring_data[self.ring_start[v] as usize..self.ring_start[v + 1] as usize]
    }

    /// The edges from vertex `v` to its ring's vertices (indices into `edges`), in ring order.
    #[inline]
    pub fn ring_edges(&self, v: usize) -> &[u32] {
        &self.ring_edges[self.ring_start[v] as usize..self.ring_start[v + 1] as usize]
    }

    /// The valence of vertex `v` (number of neighbours).
    #[inline]
    pub fn valence(&self, v: usize) -> usize {
        (self.ring_start[v + 1] - self.ring_start[v]) as usize
    }

    /// Number of vertices.
    pub fn vertices(&self) -> usize {
        self.boundary.len()
    }
}

impl TriMesh {
    /// Validates `positions` and `faces` and builds the topology.
    pub fn new(positions: Vec<DVec3>, faces: Vec<[u32; 3]>) -> Result<(Self, Topology), MeshError> {
        let m = TriMesh { positions, faces };
        let t = m.topology()?;
        Ok((m, t))
    }

    /// Unit vertex normals: the area-weighted sum of the adjacent faces'
    /// normals (a vertex whose sum vanishes gets `+z`, never NaN).
    pub fn vertex_normals(&self) -> Vec<DVec3> {
        let mut n = vec![DVec3::ZERO; self.positions.len()];
        for f in &self.faces {
            let [a, b, c] = f.map(|i| self.positions[i as usize]);
            let w = (b - a).cross(c - a); // twice the area, along the normal
            for &i in f {
                n[i as usize] += w;
            }
        }
        for v in n.iter_mut() {
            *v = v.try_normalize().unwrap_or(DVec3::Z);
        }
        n
    }

    /// The mean length of the edges of `topo` (this mesh's topology).
    pub fn mean_edge_length(&self, topo: &Topology) -> f64 {
        let p = &self.positions;
        topo.edges
            .iter()
            .map(|&([a, b], _)| (p[a as usize] - p[b as usize]).length())
            .sum::<f64>()
            / topo.edges.len().max(1) as f64
    }

    /// The bounding box `(min, max)`.
    pub fn bounds(&self) -> (DVec3, DVec3) {
        let [lo, hi] = crate::streamline::surface_mesh::bounds(self.positions.iter().copied());
        (lo, hi)
    }

    /// The axis-aligned bounding box's largest side (the error scale of 002 Table 1).
    pub fn scale(&self) -> f64 {
        let (lo, hi) = self.bounds();
        let d = hi - lo;
        d.x.max(d.y).max(d.z)
    }

    /// Checks the mesh and builds its topology; the first problem found is the error.
    pub fn topology(&self) -> Result<Topology, MeshError> {
        let nv = self.positions.len();
        if self.faces.is_empty() {
            return Err(MeshError::Empty);
        }
        if nv > MAX_VERTICES {
            return Err(MeshError::TooLarge {
                what: "vertices",
                count: nv,
                cap: MAX_VERTICES,
            });
        }
        if let Some(v) = self.positions.iter().position(|p| !p.is_finite()) {
            return Err(MeshError::NonFiniteVertex { vertex: v });
        }
        let far = |p: &DVec3| p.to_array().iter().any(|&x| !crate::limits::in_range(x));
        if let Some(v) = self.positions.iter().position(far) {
            return Err(MeshError::VertexTooFar { vertex: v });
        }
        let mut used = vec![false; nv];
        for (fi, f) in self.faces.iter().enumerate() {
            for &i in f {
                if i as usize >= nv {
                    return Err(MeshError::IndexOutOfRange {
                        face: fi,
                        index: i,
                        vertices: nv,
                    });
                }
                used[i as usize] = true;
            }
            let [a, b, c] = f.map(|i| self.positions[i as usize]);
            if f[0] == f[1]
                || f[1] == f[2]
                || f[0] == f[2]
                || (b - a).cross(c - a).length_squared() == 0.0
            {
                return Err(MeshError::DegenerateFace { face: fi });
            }
        }
        if let Some(v) = used.iter().position(|u| !u) {
            return Err(MeshError::UnreferencedVertex { vertex: v });
        }
        // per vertex v, its corners: faces (v, a, b) counter-clockwise, with
        // the face and the corner's index in it (a flat list, offsets per vertex)
        let nf = self.faces.len();
        let mut count = vec![0u32; nv + 1];
        for f in &self.faces {
            for &v in f {
                count[v as usize + 1] += 1;
            }
        }
        for v in 0..nv {
            count[v + 1] += count[v];
        }
        let corner_start = count.clone();
        let mut fill = count;
        let mut corners = vec![(0u32, 0u32, 0u32); nf * 3];
        let mut corner_face = vec![(0u32, 0u8); nf * 3];
        for (fi, f) in self.faces.iter().enumerate() {
            for k in 0..3 {
                let v = f[k] as usize;
                let slot = fill[v] as usize;
                corners[slot] = (f[(k + 1) % 3], f[(k + 2) % 3], 0);
                corner_face[slot] = (fi as u32, k as u8);
                fill[v] += 1;
            }
        }
        // edges, found at their lower vertex: v → a in face (v, a, b) is the
        // face's edge k (opposite b); b → v is its edge k+2 (opposite a)
        let mut edges: Vec<([u32; 2], [u32; 2])> = Vec::with_capacity(nf * 3 / 2 + 8);
        let mut face_edges = vec![[u32::MAX; 3]; nf];
        let mut local: Vec<EdgeAt> = Vec::new();
        for v in 0..nv {
            local.clear();
            let range = corner_start[v] as usize..corner_start[v + 1] as usize;
            for i in range {
                let (a, b, _) = corners[i];
                let (fi, k) = corner_face[i];
                for (u, out, opp, slot) in [(a, true, b, (fi, k)), (b, false, a, (fi, (k + 2) % 3))]
                {
                    if (u as usize) < v {
                        continue;
                    }
                    let e = match local.iter_mut().position(|x| x.other == u) {
                        Some(j) => &mut local[j],
                        None => {
                            local.push(EdgeAt {
                                other: u,
                                out: 0,
                                inn: 0,
                                opp_out: u32::MAX,
                                opp_in: u32::MAX,
                                slots: [(u32::MAX, 0); 2],
                            });
                            local.last_mut().expect("just pushed")
                        }
                    };
                    let n = (e.out + e.inn) as usize;
                    if n < 2 {
                        e.slots[n] = slot;
                    }
                    if out {
                        e.out += 1;
                        e.opp_out = opp;
                    } else {
                        e.inn += 1;
                        e.opp_in = opp;
                    }
                }
            }
            for e in &local {
                let u = e.other;
                let faces = (e.out + e.inn) as usize;
                if faces > 2 {
                    return Err(MeshError::NonManifoldEdge {
                        a: v as u32,
                        b: u,
                        faces,
                    });
                }
                if e.out > 1 || e.inn > 1 {
                    let (a, b) = if e.out > 1 {
                        (v as u32, u)
                    } else {
                        (u, v as u32)
                    };
                    return Err(MeshError::InconsistentWinding {
                        a,
                        b,
                        face1: e.slots[0].0 as usize,
                        face2: e.slots[1].0 as usize,
                    });
                }
                let id = edges.len() as u32;
                let opp = match (e.out, e.inn) {
                    (1, 1) => [e.opp_out, e.opp_in],
                    (1, 0) => [e.opp_out, u32::MAX],
                    _ => [e.opp_in, u32::MAX],
                };
                edges.push(([v as u32, u], opp));
                for &(fi, k) in &e.slots[..faces] {
                    face_edges[fi as usize][k as usize] = id;
                }
            }
        }
        let corners: Vec<(u32, u32)> = corners.iter().map(|&(a, b, _)| (a, b)).collect();
        let mut ring_start = Vec::with_capacity(nv + 1);
        let mut ring_data = Vec::with_capacity(nf * 3 + nv);
        let mut ring_edges = Vec::with_capacity(nf * 3 + nv);
        let mut boundary = vec![false; nv];
        ring_start.push(0u32);
        for v in 0..nv {
            let fan = &corners[corner_start[v] as usize..corner_start[v + 1] as usize];
            // the fan's start: a neighbour that is no corner's `b` (a boundary edge), if any
            let start = fan
                .iter()
                .find(|(a, _)| !fan.iter().any(|(_, b)| b == a))
                .map(|&(a, _)| a);
            boundary[v] = start.is_some();
            let slots = &corner_face[corner_start[v] as usize..corner_start[v + 1] as usize];
            let first = ring_data.len();
            let mut cur = start.unwrap_or(fan[0].0);
            ring_data.push(cur);
            ring_edges.push(u32::MAX);
            while let Some(i) = fan.iter().position(|(a, _)| *a == cur) {
                // corner (v, cur, b) of face fi at its vertex k: edge k is v–cur, edge k+2 is b–v
                let (fi, k) = slots[i];
                let fe = face_edges[fi as usize];
                if ring_edges.len() == first + 1 {
                    ring_edges[first] = fe[k as usize];
                }
                let b = fan[i].1;
                if ring_data.len() - first > fan.len() || b == ring_data[first] {
                    break;
                }
                ring_data.push(b);
                ring_edges.push(fe[(k as usize + 2) % 3]);
                cur = b;
            }
            let expect = fan.len() + usize::from(boundary[v]);
            if ring_data.len() - first != expect {
                return Err(MeshError::NonManifoldVertex { vertex: v });
            }
            ring_start.push(ring_data.len() as u32);
        }
        let mut topo = Topology {
            ring_start,
            ring_data,
            ring_edges,
            boundary,
            edges,
            face_edges,
            loops: Vec::new(),
        };
        // boundary loops: from each unvisited boundary vertex, follow the
        // boundary edge to its ring's last neighbour
        let mut seen = vec![false; nv];
        for v in 0..nv {
            if !topo.boundary[v] || seen[v] {
                continue;
            }
            let mut lp = vec![v as u32];
            seen[v] = true;
            let mut cur = v;
            loop {
                let next = *topo.ring(cur).last().expect("non-empty ring") as usize;
                if next == v || seen[next] {
                    break;
                }
                seen[next] = true;
                lp.push(next as u32);
                cur = next;
            }
            topo.loops.push(lp);
        }
        Ok(topo)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tetra() -> (Vec<DVec3>, Vec<[u32; 3]>) {
        (
            vec![
                DVec3::new(1.0, 1.0, 1.0),
                DVec3::new(1.0, -1.0, -1.0),
                DVec3::new(-1.0, 1.0, -1.0),
                DVec3::new(-1.0, -1.0, 1.0),
            ],
            vec![[0, 1, 2], [0, 3, 1], [0, 2, 3], [1, 3, 2]],
        )
    }

    #[test]
    fn trimesh_topology_of_a_tetrahedron_and_a_disk() {
        let (p, f) = tetra();
        let (_, t) = TriMesh::new(p.clone(), f.clone()).unwrap();
        assert!(t.boundary.iter().all(|b| !b) && t.loops.is_empty());
        assert!((0..4).all(|v| t.ring(v).len() == 3));
        assert_eq!(t.edges.len(), 6);
        // drop one face: a disk with one boundary loop of 3
        let (_, t) = TriMesh::new(p, f[..3].to_vec()).unwrap();
        assert_eq!(t.loops.len(), 1);
        assert_eq!(t.loops[0].len(), 3);
        assert_eq!(t.valence(0), 3);
        assert!(t.boundary[1] && !t.boundary[0]);
    }

    #[test]
    fn trimesh_errors_name_the_element() {
        let (p, f) = tetra();
        let mut bad = f.clone();
        bad[3] = [1, 2, 3]; // flipped
        let e = TriMesh::new(p.clone(), bad).unwrap_err();
        assert!(matches!(e, MeshError::InconsistentWinding { .. }), "{e}");
        let mut bad = f.clone();
        bad[0] = [0, 0, 2];
        assert_eq!(
            TriMesh::new(p.clone(), bad).unwrap_err(),
            MeshError::DegenerateFace { face: 0 }
        );
        let mut bad = f.clone();
        bad[1] = [0, 9, 1];
        assert!(matches!(
            TriMesh::new(p.clone(), bad).unwrap_err(),
            MeshError::IndexOutOfRange {
                face: 1,
                index: 9,
                ..
            }
        ));
        let mut pp = p.clone();
        pp.push(DVec3::ZERO);
        assert_eq!(
            TriMesh::new(pp, f.clone()).unwrap_err().to_string(),
            "vertex 5 is used by no face; remove it"
        );
        // two tetrahedra sharing only vertex 0: a non-manifold vertex
        let mut pp = p.clone();
        pp.extend([
            DVec3::new(3.0, 1.0, 1.0),
            DVec3::new(3.0, 3.0, 1.0),
            DVec3::new(3.0, 1.0, 3.0),
        ]);
        let mut ff = f.clone();
        ff.extend([[0, 4, 5], [0, 6, 4], [0, 5, 6], [4, 6, 5]]);
        assert!(matches!(
            TriMesh::new(pp, ff).unwrap_err(),
            MeshError::NonManifoldVertex { vertex: 0 }
        ));
        // three faces on one edge
        let mut pp = p.clone();
        pp.push(DVec3::new(0.0, 0.0, 5.0));
        let mut ff = f[..3].to_vec();
        ff.push([1, 0, 4]);
        ff.push([0, 1, 4]);
        assert!(TriMesh::new(pp, ff).is_err());
    }
}
