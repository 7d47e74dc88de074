//! A joined patch's subdivision levels and streamlines as entities, as the
//! first patch's are (docs/architecture.md, "Several patches"): one
//! [`SubdivisionLevel`] child per depth `0 ..= d` of its built stack and one
//! [`Streamline`] child per row of its display depth. Their values are the
//! stack's ([`PatchSurface`]: a level's tangents and parameters, a row of
//! the finest points), as the first patch's streamline points are rows of
//! its [`crate::ecs::SurfaceData`]; the entities say what the last build
//! changed, by change detection:
//! * a level's [`LevelWindow`] is written exactly when its tangents or
//!   parameters may have changed: the rows the build says
//!   ([`PatchSurface::level_rows`]: every row a patch's update placed
//!   again, whose tangents, parameters or start moved; a G2 run's merged
//!   window's rows), or `None` when it was built whole;
//! * a streamline's [`StreamlinePoints`] is written exactly when its points
//!   were placed again ([`PatchSurface::placed`]), with the first point
//!   that moved.
//!
//! The antipodal scan ([`crate::ecs::warnings`]) reads the levels' windows,
//! and the census counts them with the first patch's. The first patch's
//! pipeline skips them ([`JoinedChild`]).

use super::components::PatchSurface;
use crate::ecs::components::{
    JoinedChild, LevelWindow, Streamline, StreamlinePoints, SubdivisionLevel,
};
use crate::ecs::patch::Joined;
use bevy::prelude::*;

/// A joined patch's level entities (depth `k` at `levels[k]`) and
/// streamline entities (row `r` at `streamlines[r]`).
#[derive(Component, Debug, Clone, Default, PartialEq, Eq)]
pub struct JoinedEntities {
    /// One per depth of its stack.
    pub levels: Vec<Entity>,
    /// One per row of its display depth.
    pub streamlines: Vec<Entity>,
}

/// What a joined patch's entities are synchronised from.
type JoinedRow = (
    Entity,
    Ref<'static, PatchSurface>,
    Option<&'static mut JoinedEntities>,
);

/// Keeps every joined patch's level and streamline entities one per depth
/// and one per row of its stack, and marks changed those its last build
/// changed (module documentation). A patch whose join failed has none.
pub(crate) fn sync_joined_entities(
    mut commands: Commands,
    mut patches: Query<JoinedRow, With<Joined>>,
    mut levels: Query<&mut LevelWindow, With<JoinedChild>>,
    mut lines: Query<&mut StreamlinePoints, With<JoinedChild>>,
) {
    for (patch, surface, entities) in &mut patches {
        if !surface.is_changed() && entities.is_some() {
            continue;
        }
        let mut fresh = None;
        let have = match entities {
            Some(e) => e.into_inner(),
            None => fresh.insert(JoinedEntities::default()),
        };
        let (depths, rows, cols) = surface.stack().map_or((0, 0, 0), |s| {
            let p = s.finest_points();
            (s.levels.len(), p.rows(), p.cols())
        });
        // the rows of each level the build changed, when it says
        let changed_rows = (surface.level_rows.as_ref()).filter(|l| l.len() == depths);
        resize(&mut commands, patch, &mut have.levels, depths, |k| {
            (SubdivisionLevel(k as u32), LevelWindow(None))
        });
        let width = |k: usize| surface.stack().map_or(1, |s| s.levels[k].tangents.cols());
        for (k, &e) in have.levels.iter().enumerate() {
            let window = match changed_rows {
                Some(l) => match l[k] {
                    Some(r) => LevelWindow::rows(r, width(k)),
                    None => continue,
                },
                None => LevelWindow(None),
            };
            if let Ok(mut lw) = levels.get_mut(e) {
                *lw = window;
            }
        }
        resize(&mut commands, patch, &mut have.streamlines, rows, |r| {
            (Streamline { row: r }, StreamlinePoints::default())
        });
        let (placed, from) = match surface.placed {
            Some(p) if p.hi < rows => (p.lo..=p.hi, surface.placed_from.min(cols)),
            _ => (0..=rows.saturating_sub(1), 0),
        };
        for &e in have.streamlines.get(placed).into_iter().flatten() {
            if let Ok(mut p) = lines.get_mut(e) {
                *p = StreamlinePoints { moved_from: from };
            }
        }
        if let Some(fresh) = fresh {
            commands.entity(patch).try_insert(fresh);
        }
    }
}

/// `have` made `n` long: the entities past `n` despawned, the missing ones
/// spawned as children of `patch` with `make(index)` and [`JoinedChild`].
fn resize<B: Bundle>(
    commands: &mut Commands,
    patch: Entity,
    have: &mut Vec<Entity>,
    n: usize,
    make: impl Fn(usize) -> B,
) {
    for e in have.drain(n.min(have.len())..) {
        commands.entity(e).despawn();
    }
    for i in have.len()..n {
        let e = commands.spawn((make(i), JoinedChild, ChildOf(patch))).id();
        have.push(e);
    }
}
