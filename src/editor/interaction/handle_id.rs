//! What a handle is, apart from its entity: its identity ([`HandleId`]:
//! a tangent of the surface's net at a subdivision level, or a control
//! tangent of the initial curve, and its cell), the edits that turn it, a
//! handle where it is placed ([`Handle`]: its streamline point, its unit
//! direction on the Gaussian sphere, the length it is drawn with, as
//! [`super::placed::Placed`] holds them on its entity), and which handles
//! are shown and so can be picked ([`HandleSettings`]). The drawing and
//! picking of handles is `crate::editor::handles`.

use crate::ecs::Edit;
use crate::ecs::authoring::AuthorEdit;
use bevy::prelude::*;
use streamline_kernel::DVec3;

/// What a handle is a handle of.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum HandleKind {
    /// A tangent of the surface's net at subdivision level `level`: a control
    /// tangent (level 0) or a multiresolution detail (deeper).
    SurfaceTangent {
        /// The level.
        level: u32,
    },
    /// A control tangent of the initial curve (its index in the id's `col`,
    /// `row` 0): drawn along the initial curve at its Greville abscissa,
    /// turned like a surface tangent; its edits re-place the streamlines
    /// without re-blending a tangent (Eq. 1, `docs/math.md §9`).
    InitialTangent,
}

/// One handle: its kind and its cell `(row, col)` in that kind's grid. As a
/// component, the identity of a handle entity the editor shows and picks
/// (the selection, the drag and the edits name handles by it).
#[derive(Component, Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct HandleId {
    /// What it is a handle of.
    pub kind: HandleKind,
    /// Row (for a surface tangent: its streamline).
    pub row: usize,
    /// Column (for a surface tangent: its index along the streamline).
    pub col: usize,
}

impl HandleId {
    /// Surface tangent `(row, col)` of level `level`.
    pub fn tangent(level: u32, row: usize, col: usize) -> Self {
        HandleId {
            kind: HandleKind::SurfaceTangent { level },
            row,
            col,
        }
    }

    /// The initial curve's control tangent `index`.
    pub fn initial(index: usize) -> Self {
        HandleId {
            kind: HandleKind::InitialTangent,
            row: 0,
            col: index,
        }
    }

    /// Whether it is a tangent of the surface's net (not of the initial curve).
    pub fn is_surface(self) -> bool {
        matches!(self.kind, HandleKind::SurfaceTangent { .. })
    }

    /// How the status line and the panels name it: `(row, col)`, or `initial k`.
    pub fn name(self) -> String {
        match self.kind {
            HandleKind::SurfaceTangent { .. } => format!("({}, {})", self.row, self.col),
            HandleKind::InitialTangent => format!("initial tangent {}", self.col),
        }
    }

    /// Its cell `(row, col)`.
    pub fn cell(self) -> (usize, usize) {
        (self.row, self.col)
    }

    /// Its subdivision level (the initial curve has one: 0).
    pub fn level(self) -> u32 {
        match self.kind {
            HandleKind::SurfaceTangent { level } => level,
            HandleKind::InitialTangent => 0,
        }
    }

    /// The edit that points this handle at `dir` (unit).
    pub fn set_direction(self, dir: DVec3) -> Edit {
        match self.kind {
            // a tangent of the edit depth: the scene's control tangent or detail
            HandleKind::SurfaceTangent { .. } => Edit::SetDirection {
                row: self.row,
                col: self.col,
                dir,
            },
            HandleKind::InitialTangent => Edit::Author(AuthorEdit::SetInitialDirection {
                index: self.col,
                dir,
            }),
        }
    }

    /// The edit that turns this handle about `axis` (unit) by `radians`.
    pub fn rotate(self, axis: DVec3, radians: f64) -> Edit {
        match self.kind {
            HandleKind::SurfaceTangent { .. } => Edit::Rotate {
                row: self.row,
                col: self.col,
                axis,
                radians,
            },
            HandleKind::InitialTangent => Edit::Author(AuthorEdit::RotateInitial {
                index: self.col,
                axis,
                radians,
            }),
        }
    }
}

/// A handle where it is: at its streamline point, pointing its way.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Handle {
    /// Which handle.
    pub id: HandleId,
    /// Its streamline point (kernel coordinates).
    pub base: DVec3,
    /// The unit tangent: its point on the Gaussian sphere.
    pub dir: DVec3,
    /// Drawn length.
    pub length: f64,
}

impl Handle {
    /// The arrow's tip.
    pub fn tip(&self) -> DVec3 {
        self.base + self.dir * self.length
    }

    /// Its subdivision level.
    pub fn level(&self) -> u32 {
        self.id.level()
    }

    /// Its arrow on the screen (logical px), given how a point of the 3D
    /// view projects (`None`: behind the camera).
    pub fn on_screen(&self, project: impl Fn(DVec3) -> Option<Vec2>) -> Option<(Vec2, Vec2)> {
        Some((project(self.base)?, project(self.tip())?))
    }

    /// Where framing this handle looks: its base, and a radius that shows it
    /// in its surroundings (`scene`: the scene's size).
    pub fn framing(&self, scene: f64) -> (DVec3, f64) {
        (self.base, (self.length * 4.0).max(0.05 * scene))
    }
}

/// How handles are shown.
#[derive(Resource, Debug, Clone, PartialEq)]
pub struct HandleSettings {
    /// Show the level-0 control tangents.
    pub controls: bool,
    /// Show the refined tangents of the edit depth (when it is above 0).
    pub refined: bool,
    /// Show only every other refined tangent (in both directions).
    pub every_other: bool,
    /// Number labels on the control arrows.
    pub labels: bool,
    /// Show (and pick) the initial curve's control tangents.
    pub initial: bool,
}

impl Default for HandleSettings {
    fn default() -> Self {
        HandleSettings {
            controls: true,
            refined: true,
            every_other: false,
            labels: true,
            initial: true,
        }
    }
}

impl HandleSettings {
    /// Whether a handle of the edit depth is shown (and so pickable).
    pub fn shows(&self, h: &Handle) -> bool {
        let (row, col) = h.id.cell();
        h.level() == 0 || !self.every_other || (row.is_multiple_of(2) && col.is_multiple_of(2))
    }
}

/// Distance from `p` to the segment `a`–`b` (screen px).
pub fn segment_distance(p: Vec2, a: Vec2, b: Vec2) -> f32 {
    let ab = b - a;
    let t = ((p - a).dot(ab) / ab.length_squared().max(1e-9)).clamp(0.0, 1.0);
    (a + ab * t).distance(p)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn segment_distance_is_euclidean() {
        let (a, b) = (Vec2::ZERO, Vec2::new(10.0, 0.0));
        assert_eq!(segment_distance(Vec2::new(5.0, 3.0), a, b), 3.0);
        assert_eq!(segment_distance(Vec2::new(-4.0, 3.0), a, b), 5.0);
    }
}
