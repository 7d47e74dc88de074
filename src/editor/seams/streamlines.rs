//! The other patches' streamlines as lines, as the overlay draws the first
//! patch's (the same setting, count and colour: Display ▸ streamlines),
//! from each patch's [`PatchSurface`] at the display depth; none for a
//! hidden patch.

use super::super::coords::to_view;
use super::super::interaction::{EditorMode, EditorSet};
use super::super::view::overlay::OverlaySettings;
use crate::ecs::joined::{Joined, PatchHidden, PatchSurface};
use bevy::prelude::*;
use bevy_state::prelude::in_state;

pub struct PatchStreamlinesPlugin;

impl Plugin for PatchStreamlinesPlugin {
    fn build(&self, app: &mut App) {
        app.add_systems(
            Update,
            draw.in_set(EditorSet::Present)
                .run_if(in_state(EditorMode::Streamline)),
        );
    }
}

/// The rows drawn of `rows` streamlines, at most `max` of them spread
/// evenly, the last always (as the overlay picks the first patch's).
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

fn draw(
    meter: Res<crate::ecs::meter::CpuMeter>,
    settings: Res<OverlaySettings>,
    patches: Query<&PatchSurface, (With<Joined>, Without<PatchHidden>)>,
    mut gizmos: Gizmos,
) {
    let _meter = meter.start();
    if !settings.streamlines {
        return;
    }
    for s in &patches {
        let Some(stack) = s.stack() else { continue };
        let pts = stack.finest_points();
        for r in chosen_rows(pts.rows(), settings.max_streamlines) {
            gizmos.linestrip(
                pts.row(r).iter().map(|&p| to_view(p)),
                Color::srgb(0.15, 0.3, 0.75),
            );
        }
    }
}

#[cfg(test)]
mod tests {
    use super::chosen_rows;

    #[test]
    fn rows_spread_evenly_with_the_last() {
        assert_eq!(chosen_rows(0, 4), Vec::<usize>::new());
        assert_eq!(chosen_rows(5, 48), vec![0, 1, 2, 3, 4]);
        assert_eq!(chosen_rows(10, 4), vec![0, 3, 6, 9]);
        assert_eq!(chosen_rows(9, 4), vec![0, 3, 6, 8]);
    }
}
