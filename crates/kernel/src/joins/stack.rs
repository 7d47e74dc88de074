//! A patch built at every depth `0 ..= d`: its levels and the point grid of
//! each, which is what a patch joined to it reads (docs/math.md §11: a join
//! holds at every depth, so `B`'s level `d` is made from `A`'s level `d`).

use crate::error::KernelError;
use crate::grid::Grid;
use crate::levels::design::{Design, Level};
use crate::streamline::integrate::place_slice;
use crate::streamline::surface_mesh::SurfaceMesh;
use glam::DVec3;

/// The levels `0 ..= d` of a patch and their streamlines (`rows × (cols + 1)`
/// points each, Eq. 65).
#[derive(Debug, Clone, PartialEq)]
pub struct Stack {
    /// Levels `0 ..= d`.
    pub levels: Vec<Level>,
    /// The streamline points of each level.
    pub points: Vec<Grid<DVec3>>,
}

impl Stack {
    /// A design on its own initial curve, built at every depth up to `depth`
    /// (the same levels and points as [`Design::levels`] and
    /// [`Design::streamlines`]).
    pub fn build(design: &Design, depth: u32) -> Result<Self, KernelError> {
        let levels = design.levels(depth)?;
        let points = levels.iter().map(|l| design.streamlines(l)).collect();
        Ok(Stack { levels, points })
    }

    /// The finest depth `d`.
    pub fn depth(&self) -> u32 {
        (self.levels.len() - 1) as u32
    }

    /// The finest level.
    pub fn finest(&self) -> &Level {
        self.levels.last().expect("a stack has level 0")
    }

    /// The finest level's points.
    pub fn finest_points(&self) -> &Grid<DVec3> {
        self.points.last().expect("a stack has level 0")
    }

    /// The triangle mesh of level `d` (docs/math.md §4).
    pub fn mesh(&self, d: u32) -> SurfaceMesh {
        SurfaceMesh::from_points(&self.points[d as usize])
    }
}

/// The levels `0 ..= depth` of `design`, each passed to `fix` (with its
/// depth) before the next step is taken from it: the hook of the G1
/// constructions (docs/math.md §11.1, §11.2), which change a boundary column
/// between steps.
pub(crate) fn levels_with<E: From<KernelError>>(
    design: &Design,
    depth: u32,
    mut fix: impl FnMut(u32, &mut Level) -> Result<(), E>,
) -> Result<Vec<Level>, E> {
    let net = design.net();
    design.scheme().check_depth(net.rows(), net.cols(), depth)?;
    let mut level = design.base();
    fix(0, &mut level)?;
    let mut out = vec![level];
    for d in 1..=depth {
        let mut next = design.refine(out.last().expect("level 0"), d)?;
        fix(d, &mut next)?;
        out.push(next);
    }
    Ok(out)
}

/// The streamlines of `level`, row `j` integrated (Eq. 65) from its first
/// point placed at `starts[j]` (a joined patch's anchor is column 0 and its
/// start points are given, docs/math.md §11). The first point is `starts[j]`
/// bit for bit.
pub(crate) fn place_at_starts(level: &Level, starts: &[DVec3]) -> Grid<DVec3> {
    let (rows, cols) = (level.tangents.rows(), level.tangents.cols());
    debug_assert_eq!(starts.len(), rows);
    let mut data = vec![DVec3::ZERO; rows * (cols + 1)];
    for (r, out) in data.chunks_mut(cols + 1).enumerate() {
        let s = level.params.s.row(r);
        // σ = s₀: the anchor offset is t₀·0 = 0, so the shift is the start itself
        place_slice(level.tangents.row(r), s, s[0], starts[r], out);
    }
    Grid::new(rows, cols + 1, data).expect("sizes agree")
}
