//! A full build (blend → integrate → mesh, docs/math.md §2–4) that keeps its buffers
//! from one build to the next.
//!
//! [`Design::build`] allocates every level, streamline and mesh buffer
//! afresh; on this size of surface the first touch of that memory costs
//! about as much as the geometry. A [`Builder`] reshapes the buffers it
//! already has, so a rebuild (a new scheme, ω, blend order or any change of
//! the net) recomputes every entry and allocates nothing. The numbers are the
//! same, bit for bit, as [`Design::build`]'s, which is a `Builder` used once.

use crate::error::KernelError;
use crate::grid::Grid;
use crate::levels::design::{Built, Design, Level};
use crate::levels::params::ParamGrid;
use crate::levels::surface::refine_grid_into;
use crate::streamline::surface_mesh::{SurfaceMesh, normals_rows, write_indices};
use glam::DVec3;

/// One level's buffers: the level and the grids of its first blend direction.
#[derive(Debug, Clone)]
struct Stage {
    half: Grid<DVec3>,
    half_s: Grid<f64>,
    level: Level,
}

impl Stage {
    fn empty() -> Self {
        Stage {
            half: Grid::filled(0, 0, DVec3::ZERO),
            half_s: Grid::filled(0, 0, 0.0),
            level: Level {
                tangents: Grid::filled(0, 0, DVec3::ZERO),
                params: ParamGrid {
                    s: Grid::filled(0, 0, 0.0),
                    t: Vec::new(),
                    sigma: Vec::new(),
                },
            },
        }
    }
}

/// Builds designs into buffers it keeps (see the module docs).
#[derive(Debug, Clone, Default)]
pub struct Builder {
    stages: Vec<Stage>,
    depth: usize,
    /// `rows × cols` of the point grid.
    shape: (usize, usize),
    /// The point-grid shape the triangle indices were written for.
    indexed: (usize, usize),
    mesh: SurfaceMesh,
}

impl Builder {
    /// An empty builder (buffers grow on the first build).
    pub fn new() -> Self {
        Self::default()
    }

    /// Builds `design` at `depth`: every level, every streamline, the mesh.
    /// On an error (depth past the cap, parameters that stop increasing) the
    /// builder's previous result is no longer valid.
    pub fn build(&mut self, design: &Design, depth: u32) -> Result<(), KernelError> {
        let (rows, cols) =
            design
                .scheme
                .check_depth(design.net.rows(), design.net.cols(), depth)?;
        let need = depth as usize + 1;
        while self.stages.len() < need {
            self.stages.push(Stage::empty());
        }
        self.shape = (0, 0);
        let first = &mut self.stages[0].level;
        first.tangents.clone_from(&design.net);
        first.params.clone_from(&design.params);
        for d in 1..need {
            let (done, rest) = self.stages.split_at_mut(d);
            let (prev, cur) = (&done[d - 1].level, &mut rest[0]);
            refine_grid_into(
                design.scheme,
                design.order,
                &prev.tangents,
                &mut cur.half,
                &mut cur.level.tangents,
            );
            prev.params.refine_into(
                design.scheme,
                design.order,
                d as u32,
                &mut cur.half_s,
                &mut cur.level.params,
            )?;
        }
        self.depth = depth as usize;
        let level = &self.stages[self.depth].level;
        debug_assert_eq!((level.tangents.rows(), level.tangents.cols()), (rows, cols));
        // streamlines (Eq. 65), written straight into the mesh's positions
        let width = cols + 1;
        let mesh = &mut self.mesh;
        mesh.positions.resize(rows * width, DVec3::ZERO);
        for (r, out) in mesh.positions.chunks_mut(width).enumerate() {
            design.place_row(level, r, out);
        }
        mesh.normals.resize(rows * width, DVec3::Z);
        normals_rows(&mesh.positions, width, 0, rows - 1, &mut mesh.normals);
        if self.indexed != (rows, width) {
            mesh.indices.clear();
            write_indices(rows, width, &mut mesh.indices);
            self.indexed = (rows, width);
        }
        self.shape = (rows, width);
        Ok(())
    }

    /// The finest level of the last build.
    pub fn level(&self) -> Option<&Level> {
        (self.shape != (0, 0)).then(|| &self.stages[self.depth].level)
    }

    /// The mesh of the last build; its positions are the streamline points,
    /// row-major, `Self::point_shape` wide.
    pub fn mesh(&self) -> &SurfaceMesh {
        &self.mesh
    }

    /// `(rows, points per row)` of the last build (`(0, 0)` before one).
    pub(crate) fn point_shape(&self) -> (usize, usize) {
        self.shape
    }

    /// The last build as a [`Built`] (copies the points out of the mesh).
    pub(crate) fn into_built(mut self) -> Option<Built> {
        let (rows, width) = self.shape;
        if rows == 0 {
            return None;
        }
        let level = self.stages.swap_remove(self.depth).level;
        let points = Grid::new(rows, width, self.mesh.positions.clone()).ok()?;
        Some(Built {
            level,
            points,
            mesh: self.mesh,
        })
    }
}

impl Design {
    /// Full build at `depth`: blend, integrate, mesh (a [`Builder`] used
    /// once; keep a `Builder` to rebuild without allocating). Defined here
    /// rather than in `design.rs` so that file does not import this one.
    pub fn build(&self, depth: u32) -> Result<Built, KernelError> {
        let mut b = Builder::new();
        b.build(self, depth)?;
        Ok(b.into_built().expect("a successful build has a result"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::levels::presets;
    use crate::levels::surface::{BlendOrder, SurfaceScheme};

    /// The build composed from the kernel's separate steps.
    fn by_steps(d: &Design, depth: u32) -> (Level, Grid<DVec3>, SurfaceMesh) {
        let level = d.level(depth).unwrap();
        let points = d.streamlines(&level);
        let mesh = SurfaceMesh::from_points(&points);
        (level, points, mesh)
    }

    #[test]
    fn a_reused_builder_matches_separate_steps_bitwise() {
        let mut b = Builder::new();
        let mut car = presets::car1();
        // deep, then shallow, then another scheme and order: buffers shrink and grow
        for (scheme, order, depth) in [
            (SurfaceScheme::default(), BlendOrder::SFirst, 4),
            (SurfaceScheme::default(), BlendOrder::SFirst, 1),
            (SurfaceScheme::CatmullClark, BlendOrder::TFirst, 3),
            (SurfaceScheme::Kobbelt { omega: 0.5 }, BlendOrder::TFirst, 4),
            (SurfaceScheme::DooSabin, BlendOrder::SFirst, 2),
        ] {
            car.scheme = scheme;
            car.order = order;
            b.build(&car, depth).unwrap();
            let (level, points, mesh) = by_steps(&car, depth);
            assert_eq!(b.level(), Some(&level), "{scheme:?} {order:?} d{depth}");
            assert_eq!(b.point_shape(), (points.rows(), points.cols()));
            assert_eq!(b.mesh(), &mesh, "{scheme:?} {order:?} d{depth}");
            let built = car.build(depth).unwrap();
            assert_eq!(
                (built.level, built.points, built.mesh),
                (level, points, mesh)
            );
        }
    }

    #[test]
    fn a_refused_depth_is_an_error() {
        let mut b = Builder::new();
        assert!(b.build(&presets::car1(), 40).is_err());
        assert_eq!(b.point_shape(), (0, 0));
        assert!(b.level().is_none());
    }
}
