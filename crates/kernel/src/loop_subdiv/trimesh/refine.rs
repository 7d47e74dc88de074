//! One step of Loop subdivision's topology derived from the step before
//! ([`Topology::refine`]), without a search or a check: only level 0 is built
//! from its face list (docs/math.md §7; docs/loop.md, speed).

use super::Topology;

/// Edge `e`'s child half at its end `x` in [`Topology::refine`]: `2e` at the lower end, `2e + 1` at the upper.
#[inline]
fn half(edges: &[([u32; 2], [u32; 2])], e: u32, x: u32) -> u32 {
    2 * e + u32::from(edges[e as usize].0[1] == x)
}

/// An edge `(lo, hi)` with the opposite vertex of the face running `from → to`
/// and of the face running back.
#[inline]
fn directed(from: u32, to: u32, opp_fwd: u32, opp_back: u32) -> ([u32; 2], [u32; 2]) {
    if from < to {
        ([from, to], [opp_fwd, opp_back])
    } else {
        ([to, from], [opp_back, opp_fwd])
    }
}

impl Topology {
    /// The faces and the topology of one step of Loop subdivision (1-to-4 split)
    /// of a mesh with this topology and `faces`, derived from this one without
    /// a search or a check (the split of a valid mesh is valid): old vertices
    /// keep their indices, edge `e` becomes vertex `n + e` (as in
    /// [`crate::loop_subdiv::subdivide::subdivide`]); each edge `e` becomes edges `2e`
    /// (at its lower end) and `2e + 1`, face `f`'s inner edges are
    /// `2E + 3f + j`, `j` joining the new vertices of its edges `j` and `j + 1`.
    pub fn refine(&self, faces: &[[u32; 3]]) -> (Vec<[u32; 3]>, Topology) {
        self.refine_with(faces, true)
    }

    /// [`Topology::refine`]; with `full == false` without the ring edges and
    /// the boundary loops, which only a further refinement reads: enough for
    /// one more subdivision step (a quarter less memory to fault in).
    pub(crate) fn refine_with(&self, faces: &[[u32; 3]], full: bool) -> (Vec<[u32; 3]>, Topology) {
        let nv = self.vertices() as u32;
        let ne = self.edges.len() as u32;
        let nf = faces.len();
        const NONE: u32 = u32::MAX;
        // each edge's face running lower → upper, and upper → lower, as 3f + k
        let mut edge_face = vec![[NONE; 2]; ne as usize];
        for (fi, (f, fe)) in faces.iter().zip(&self.face_edges).enumerate() {
            for k in 0..3 {
                let fwd = f[k] < f[(k + 1) % 3];
                edge_face[fe[k] as usize][usize::from(!fwd)] = (3 * fi + k) as u32;
            }
        }
        let inner = |f: usize, j: usize| 2 * ne + 3 * f as u32 + j as u32;
        // written in order (halves of edge e at 2e, 2e + 1, then the faces' inner edges)
        let mut edges = Vec::with_capacity(2 * ne as usize + 3 * nf);
        for (e, &([a, b], _)) in self.edges.iter().enumerate() {
            let m = nv + e as u32;
            let [fw, bk] = edge_face[e];
            // the face a → b → c gives c's edges b–c and c–a; b → a → d gives a–d, d–b
            let side = |slot: u32| {
                let (f, k) = ((slot / 3) as usize, (slot % 3) as usize);
                let fe = self.face_edges[f];
                (nv + fe[(k + 1) % 3], nv + fe[(k + 2) % 3])
            };
            let (ca, bc) = if fw != NONE {
                let (bc, ca) = side(fw);
                (ca, bc)
            } else {
                (NONE, NONE)
            };
            let (ad, db) = if bk != NONE { side(bk) } else { (NONE, NONE) };
            // (a, m): out in a's child of a → b (opposite ca), in in a's child of b → a (ad)
            // (b, m): out in b's child of b → a (opposite db), in in b's child of a → b (bc)
            let pack = |x: u32, y: u32| if x == NONE { [y, NONE] } else { [x, y] };
            edges.push(([a, m], pack(ca, ad)));
            edges.push(([b, m], pack(db, bc)));
        }
        let mut child = Vec::with_capacity(4 * nf);
        let mut face_edges = Vec::with_capacity(4 * nf);
        for (fi, (f, fe)) in faces.iter().zip(&self.face_edges).enumerate() {
            let m = fe.map(|e| nv + e);
            for j in 0..3 {
                // m_j → m_{j+1} in the middle face (opposite m_{j+2}), back in v_{j+1}'s corner face
                debug_assert_eq!(edges.len(), inner(fi, j) as usize);
                edges.push(directed(
                    m[j],
                    m[(j + 1) % 3],
                    m[(j + 2) % 3],
                    f[(j + 1) % 3],
                ));
            }
            for i in 0..3 {
                let i2 = (i + 2) % 3;
                child.push([f[i], m[i], m[i2]]);
                face_edges.push([
                    half(&self.edges, fe[i], f[i]),
                    inner(fi, i2),
                    half(&self.edges, fe[i2], f[i]),
                ]);
            }
            child.push(m);
            face_edges.push([inner(fi, 0), inner(fi, 1), inner(fi, 2)]);
        }
        let total = nv as usize + ne as usize;
        let mut ring_start = Vec::with_capacity(total + 1);
        let mut ring_data = Vec::with_capacity(self.ring_data.len() + 6 * ne as usize);
        let mut ring_edges = Vec::with_capacity(if full { ring_data.capacity() } else { 0 });
        ring_start.push(0u32);
        for v in 0..nv as usize {
            let re = self.ring_edges(v);
            ring_data.extend(re.iter().map(|&e| nv + e));
            if full {
                ring_edges.extend(re.iter().map(|&e| half(&self.edges, e, v as u32)));
            }
            ring_start.push(ring_data.len() as u32);
        }
        let mut boundary = self.boundary.clone();
        boundary.reserve(ne as usize);
        for (e, &([a, b], [_, d])) in self.edges.iter().enumerate() {
            let [fw, bk] = edge_face[e];
            let seg = |slot: u32, from: u32, to: u32| {
                // around the new vertex of edge k of face f (from → to): to, m_{k+1}, m_{k+2}, from
                let (f, k) = ((slot / 3) as usize, (slot % 3) as usize);
                let fe = self.face_edges[f];
                [
                    (to, half(&self.edges, e as u32, to)),
                    (nv + fe[(k + 1) % 3], inner(f, k)),
                    (nv + fe[(k + 2) % 3], inner(f, (k + 2) % 3)),
                    (from, half(&self.edges, e as u32, from)),
                ]
            };
            let ring: &[(u32, u32)] = &match (fw != NONE, bk != NONE) {
                (true, true) => {
                    let (s, t) = (seg(fw, a, b), seg(bk, b, a));
                    [s[0], s[1], s[2], s[3], t[1], t[2]]
                }
                (true, false) => {
                    let s = seg(fw, a, b);
                    [s[0], s[1], s[2], s[3], s[0], s[0]]
                }
                _ => {
                    let s = seg(bk, b, a);
                    [s[0], s[1], s[2], s[3], s[0], s[0]]
                }
            }[..if d == NONE { 4 } else { 6 }];
            ring_data.extend(ring.iter().map(|&(u, _)| u));
            if full {
                ring_edges.extend(ring.iter().map(|&(_, ue)| ue));
            }
            ring_start.push(ring_data.len() as u32);
            boundary.push(d == NONE);
        }
        let loops = if !full {
            Vec::new()
        } else {
            self.loops
                .iter()
                .map(|lp| {
                    lp.iter()
                        .flat_map(|&v| {
                            let next = *self.ring_edges(v as usize).last().expect("non-empty ring");
                            [v, nv + next]
                        })
                        .collect()
                })
                .collect()
        };
        (
            child,
            Topology {
                ring_start,
                ring_data,
                ring_edges,
                boundary,
                edges,
                face_edges,
                loops,
            },
        )
    }
}
