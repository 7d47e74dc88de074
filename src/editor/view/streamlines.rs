//! Every patch's streamlines as lines over the 3D view (Display ▸
//! streamlines; at most `OverlaySettings::max_streamlines` a patch, spread
//! evenly): a patch drawn from its [`PatchSurface`] (a joined patch, or the
//! first patch while it shows its G2 run's cut, [`shows_run_cut`]) from its
//! stack's display depth, the first patch otherwise from its incremental
//! surface ([`SurfaceData`]); none for a hidden patch.

use super::super::coords::to_view;
use super::super::interaction::{EditorMode, EditorSet};
use super::overlay::OverlaySettings;
use crate::ecs::SurfaceData;
use crate::ecs::joined::{PatchHidden, PatchStart, PatchSurface, shows_run_cut};
use crate::ecs::patch::{Joined, Patch};
use bevy::prelude::*;
use bevy_state::prelude::in_state;
use streamline_kernel::{DVec3, Grid};

pub struct StreamlinesPlugin;

impl Plugin for StreamlinesPlugin {
    fn build(&self, app: &mut App) {
        app.add_systems(
            Update,
            draw.in_set(EditorSet::Present)
                .run_if(in_state(EditorMode::Streamline)),
        );
    }
}

/// The rows drawn of `rows` streamlines, at most `max` of them spread
/// evenly, the last always.
pub fn chosen_rows(rows: usize, max: usize) -> Vec<usize> {
    if rows == 0 {
        return Vec::new();
    }
    let step = rows.div_ceil(max.max(1)).max(1);
    let mut out: Vec<usize> = (0..rows).step_by(step).collect();
    if out.last() != Some(&(rows - 1)) {
        out.push(rows - 1);
    }
    out
}

/// Every patch: whether it is joined, its surface, whether it is hidden.
type Patches<'w, 's> = Query<
    'w,
    's,
    (
        Entity,
        Has<Joined>,
        Option<&'static PatchSurface>,
        Has<PatchHidden>,
    ),
    With<Patch>,
>;

fn draw(
    meter: Res<crate::ecs::meter::CpuMeter>,
    settings: Res<OverlaySettings>,
    data: Res<SurfaceData>,
    patches: Patches,
    starts: Query<&PatchStart>,
    mut gizmos: Gizmos,
) {
    let _meter = meter.start();
    if !settings.streamlines {
        return;
    }
    for (e, joined, surface, hidden) in &patches {
        if hidden {
            continue;
        }
        let points: Option<&Grid<DVec3>> = match joined || shows_run_cut(e, starts.iter(), surface)
        {
            true => surface.and_then(|s| s.stack()).map(|s| s.finest_points()),
            false => Some(&data.points),
        };
        let Some(pts) = points else { continue };
        for r in chosen_rows(pts.rows(), settings.max_streamlines) {
            gizmos.linestrip(
                pts.row(r).iter().map(|&p| to_view(p)),
                Color::srgb(0.15, 0.3, 0.75),
            );
        }
    }
}
