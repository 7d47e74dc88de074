//! What a join is: the edge of the earlier patch `A` that the later patch `B`
//! starts on, and the continuity the join holds at every depth
//! (docs/math.md §11).

/// An edge of patch `A` that patch `B` may start on.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Edge {
    /// The curve of `A`'s streamlines' last points `S_A(s_last(t), t)`: a
    /// chain, `B`'s rows are `A`'s rows (docs/math.md §11.1).
    End,
    /// `A`'s first streamline (control row 0) as a curve in `A`'s `s`: a side
    /// join, `B`'s streamlines leave it across (docs/math.md §11.2).
    First,
    /// `A`'s last streamline (control row `R − 1`), as [`Edge::First`].
    Last,
}

impl Edge {
    /// `End`, `First` or `Last`, as a scene writes it.
    pub fn name(self) -> &'static str {
        match self {
            Edge::End => "End",
            Edge::First => "First",
            Edge::Last => "Last",
        }
    }
}

/// The continuity a join holds by construction.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Continuity {
    /// Position: the seam's points are shared (chain) or lie on `A`'s
    /// streamline (side); `B`'s tangents are free.
    G0,
    /// Tangency: the seam's normals agree (exactly on a chain, in the limit on
    /// a side edge).
    G1,
    /// Curvature: on a chain, the two patches are one subdivided net cut at
    /// the seam. Refused on a side edge (future work).
    G2,
}

impl Continuity {
    /// `G0`, `G1` or `G2`.
    pub fn name(self) -> &'static str {
        match self {
            Continuity::G0 => "G0",
            Continuity::G1 => "G1",
            Continuity::G2 => "G2",
        }
    }
}

/// Where patch `B` starts and how it joins: `Edge(patch: "A", edge, continuity)`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Join {
    /// The edge of `A`.
    pub edge: Edge,
    /// The continuity across it.
    pub continuity: Continuity,
}
