//! Placing the handles of the joined patches (docs/math.md §11): each
//! joined patch's net handles ([`SurfaceHandle`] children with
//! [`JoinedHandle`]) are placed on level 0 of its built [`PatchSurface`]
//! stack, as the first patch's control tangents are on its level 0
//! ([`super::placement`]): at the point of streamline `r` (Eq. 65) at arc
//! length `s_{r,c}`, pointing the handle's [`Direction`], drawn 0.7 of the
//! mean control spacing long and no longer than the first patch's cap.
//!
//! The editor edits a joined patch's base net: only level 0 is placed,
//! whatever the edit depth (its details, fine tuning and interpolated
//! tangents are kept and built, docs/math.md §11.4, and are made in scripts
//! and on the command line). It has no initial curve: it starts on its parent's edge. In
//! a G1 or G2 chain (`edge: End`) its first column is its parent's last
//! (one handle of both, docs/math.md §11.1): those cells are not placed, so
//! they are neither drawn nor picked on the joined patch (turn them on the
//! parent).
//!
//! Every handle is computed again when its patch's stack was rebuilt, its
//! directions changed, the active patch or the cap changed, and written
//! with `set_if_neq`: only the handles whose place differs bit for bit are
//! marked changed.

use super::handles::HandleId;
use super::placed::{HandleLayout, Placed};
use crate::ecs::joined::{PatchStart, PatchSurface};
use crate::ecs::patch::{Direction, Joined, JoinedHandle, Patch, PatchIndex};
use bevy::prelude::*;
use streamline_kernel::finetune::streamline::point_by_fraction;
use streamline_kernel::joins::{Continuity, Edge, Stack};

/// The joined patches, with what their handles are placed from.
type JoinedPatches<'w, 's> = Query<
    'w,
    's,
    (
        Entity,
        Ref<'static, PatchSurface>,
        &'static PatchIndex,
        &'static PatchStart,
    ),
    (With<Patch>, With<Joined>),
>;

/// Whether column 0 of a patch starting at `start` is its parent's last
/// column (a G1 or G2 chain), so not a handle of its own.
pub fn shares_first_column(start: &PatchStart) -> bool {
    matches!(
        start,
        PatchStart::Edge {
            edge: Edge::End,
            continuity: Continuity::G1 | Continuity::G2,
            ..
        }
    )
}

/// The places of a joined patch's level-0 handles on `stack`, row-major,
/// `(row, col, base, length)`, `cap` the longest an arrow is drawn; the
/// cells of the first column are left out when `skip_first`. Empty when
/// the stack's level 0 is not `rows × cols`.
pub fn joined_places(
    stack: &Stack,
    (rows, cols): (usize, usize),
    cap: f64,
    skip_first: bool,
) -> Vec<(usize, usize, streamline_kernel::DVec3, f64)> {
    let (Some(level), Some(points)) = (stack.levels.first(), stack.points.first()) else {
        return Vec::new();
    };
    let s = &level.params.s;
    if (level.tangents.rows(), level.tangents.cols()) != (rows, cols)
        || points.rows() != rows
        || points.cols() != cols + 1
        || rows == 0
        || cols == 0
    {
        return Vec::new();
    }
    // the first patch's rule: 0.7 of the mean control spacing, capped
    let span: f64 = (0..rows)
        .map(|r| (s.get(r, cols - 1) - s.get(r, 0)) / (cols.max(2) - 1) as f64)
        .sum::<f64>()
        / rows as f64;
    let length = (span * 0.7).max(1e-6).min(cap.max(1e-6));
    let first = usize::from(skip_first);
    let mut out = Vec::with_capacity(rows * cols);
    for r in 0..rows {
        for c in first..cols {
            let base = point_by_fraction(points.row(r), s.row(r), s.get(r, c));
            out.push((r, c, base, length));
        }
    }
    out
}

/// What placed the joined handles last: the active patch and the cap.
#[derive(Debug, Default)]
pub(super) struct LastPlaced {
    active: Option<Entity>,
    cap: u64,
}

/// Places the joined patches' handles that may have moved (module doc).
#[allow(clippy::too_many_arguments)]
pub(super) fn place_joined(
    meter: Res<crate::ecs::meter::CpuMeter>,
    layout: Res<HandleLayout>,
    patches: JoinedPatches,
    directions: Query<&Direction, With<JoinedHandle>>,
    turned: Query<&ChildOf, (With<JoinedHandle>, Changed<Direction>)>,
    unplaced: Query<&ChildOf, (With<JoinedHandle>, Without<Placed>)>,
    mut placed: Query<&mut Placed, With<JoinedHandle>>,
    mut commands: Commands,
    mut last: Local<LastPlaced>,
) {
    if patches.is_empty() || !layout.placed {
        return;
    }
    let _meter = meter.start();
    let every = last.active != layout.active || last.cap != layout.cap.to_bits();
    let mut wanted: Vec<Entity> = turned
        .iter()
        .chain(unplaced.iter())
        .map(ChildOf::parent)
        .collect();
    wanted.sort_unstable();
    wanted.dedup();
    for (patch, surface, index, start) in &patches {
        if !(every || surface.is_changed() || wanted.binary_search(&patch).is_ok()) {
            continue;
        }
        let Some(stack) = surface.stack() else {
            continue;
        };
        let shape = (index.surface.rows(), index.surface.cols());
        for (r, c, base, length) in
            joined_places(stack, shape, layout.cap, shares_first_column(start))
        {
            let e = index.surface.get(r, c);
            let Ok(dir) = directions.get(e) else {
                continue;
            };
            let p = Placed {
                base,
                dir: dir.0,
                length,
            };
            match placed.get_mut(e) {
                Ok(mut old) => {
                    old.set_if_neq(p);
                }
                Err(_) => {
                    commands
                        .entity(e)
                        .try_insert((HandleId::tangent(0, r, c), p));
                }
            }
        }
    }
    last.active = layout.active;
    last.cap = layout.cap.to_bits();
}
