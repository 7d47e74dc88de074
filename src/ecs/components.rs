//! Components: subdivision levels and streamlines are entities (the
//! control tangents and details live in the scene, [`super::Model`]).

use bevy::prelude::*;
use streamline_kernel::DVec3;
use streamline_kernel::finetune::Constraint;
use streamline_kernel::finetune::bspline::BSpline;
use streamline_kernel::levels::dirty_window::DirtyWindow;
use streamline_kernel::levels::incremental::LevelState;

/// A subdivision level entity.
#[derive(Component, Debug, Clone, Copy, PartialEq, Eq)]
pub struct SubdivisionLevel(pub u32);

/// The data of a level, updated in place inside dirty windows.
#[derive(Component, Debug, Clone)]
pub struct LevelData(pub LevelState);

impl LevelData {
    /// Row `r`'s unit tangents and their arc-length parameters `s`.
    pub fn row(&self, r: usize) -> (&[DVec3], &[f64]) {
        (self.0.tangents.row(r), self.0.params.s.row(r))
    }
}

/// Which cells of a level its last change recomputed: `Some(window)` when
/// the blend stage re-blended a dirty window, `None` when the level was
/// built whole. Written with each change of [`LevelData`] by the blend stage,
/// so that a reader of that change can look at the window alone (the
/// antipodal scan of [`super::warnings`]).
#[derive(Component, Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct LevelWindow(pub Option<DirtyWindow>);

impl LevelWindow {
    /// Rows `r` of a level `cols` columns wide, every column (what a joined
    /// patch's update says of a level, [`crate::ecs::joined::entities`]).
    pub fn rows(r: streamline_kernel::joins::RowSpan, cols: usize) -> Self {
        use streamline_kernel::levels::dirty_window::Span;
        LevelWindow(Some(DirtyWindow {
            rows: Span { lo: r.lo, hi: r.hi },
            cols: Span {
                lo: 0,
                hi: cols.saturating_sub(1),
            },
        }))
    }
}

/// Marks a level or streamline entity of a joined patch (docs/math.md §11),
/// whose values are its patch's stack
/// ([`crate::ecs::joined::entities`]); the first patch's pipeline skips it
/// (`Without<JoinedChild>`).
#[derive(Component, Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct JoinedChild;

/// A streamline of the display depth: row `row`.
#[derive(Component, Debug, Clone, Copy, PartialEq, Eq)]
pub struct Streamline {
    /// Its row at the display depth.
    pub row: usize,
}

/// What a streamline is integrated from, besides its row of the display
/// level ([`LevelData::row`], read there, not copied); written (so marked
/// changed) exactly when that row's tangents or parameters change.
#[derive(Component, Debug, Clone, PartialEq)]
pub struct StreamlineTangents {
    /// The anchor arc length.
    pub sigma: f64,
    /// The initial curve's point at the row's `t`.
    pub origin: DVec3,
    /// The row's parameter `t` (across the streamlines).
    pub t: f64,
    /// The first tangent of the row changed since its points were last
    /// integrated, when only tangents from there on changed (`s`, σ and the
    /// start point as they were); `0` asks for the whole row. The integrate
    /// stage sums again only the points after it (Eq. 65 is a running sum)
    /// and sets it back to `usize::MAX` (nothing pending).
    pub changed_from: usize,
}

/// The fine-tuning function of one streamline (docs/math.md §6), `None` when fine
/// tuning is off: the surface function restricted to the row's `v`, and the
/// constraint. Written with `set_if_neq`, so an edit of a control value
/// re-integrates only the streamlines whose function changed.
#[derive(Component, Debug, Clone, Default, PartialEq)]
pub struct StreamlineAlpha(pub Option<(BSpline, Constraint)>);

/// The integrated, placed streamline: its `n + 2` points (Eq. 65) are row
/// `row` of [`super::SurfaceData::points`] (the mesh's vertices, kept once);
/// this component is marked changed when they move.
#[derive(Component, Debug, Clone, Default, PartialEq)]
pub struct StreamlinePoints {
    /// The first point the last integration rewrote (`0`: all of them); the
    /// ones before it are as they were.
    pub moved_from: usize,
}
