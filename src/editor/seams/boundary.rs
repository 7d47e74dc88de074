//! A right click on a patch's boundary starts a new patch there: the edge
//! under the pointer (within [`BOUNDARY_PX`] on screen) of a shown patch
//! (its `End`, the curve of its streamlines' last points, or its `First`
//! or `Last` streamline, docs/math.md §11) becomes a [`NewPatchRequest`],
//! which the Patches section answers by choosing that patch and opening
//! its "New patch on edge…" form on that edge. A right click on a handle
//! is the handle's (its menu), and a right drag orbits, as before.

use super::super::coords::to_view;
use super::super::interaction::{
    EditorMode, EditorSet, MainCamera, Selection, SphereArea, segment_distance,
};
use super::super::surface::patches::{PatchMeshes, PickedPatches};
use crate::ecs::SurfaceData;
use bevy::prelude::*;
use bevy::window::PrimaryWindow;
use bevy_egui::input::egui_wants_any_pointer_input;
use bevy_state::prelude::in_state;
use streamline_kernel::joins::Edge;
use streamline_kernel::{DVec3, Grid};

/// How near (logical px) the pointer must be to an edge.
pub const BOUNDARY_PX: f32 = 8.0;

/// A right click on a patch's boundary, for the Patches section.
#[derive(Resource, Debug, Default, Clone, PartialEq)]
pub struct NewPatchRequest(pub Option<(String, Edge)>);

pub struct BoundaryPlugin;

impl Plugin for BoundaryPlugin {
    fn build(&self, app: &mut App) {
        app.init_resource::<NewPatchRequest>().add_systems(
            Update,
            right_click.in_set(EditorSet::Input).run_if(
                not(egui_wants_any_pointer_input).and_then(in_state(EditorMode::Streamline)),
            ),
        );
    }
}

/// The three edges of a point grid as polylines: `End` (the last point of
/// each row), `First` (row 0), `Last` (the last row).
pub fn edges(points: &Grid<DVec3>) -> [(Edge, Vec<DVec3>); 3] {
    let (rows, cols) = (points.rows(), points.cols());
    let end = if cols > 0 {
        points.column(cols - 1)
    } else {
        Vec::new()
    };
    let first = if rows > 0 {
        points.row(0).to_vec()
    } else {
        Vec::new()
    };
    let last = if rows > 0 {
        points.row(rows - 1).to_vec()
    } else {
        Vec::new()
    };
    [(Edge::End, end), (Edge::First, first), (Edge::Last, last)]
}

/// The distance on screen from `cursor` to a projected polyline.
pub fn screen_distance(cursor: Vec2, line: &[Option<Vec2>]) -> f32 {
    line.windows(2)
        .filter_map(|w| Some(segment_distance(cursor, w[0]?, w[1]?)))
        .fold(f32::INFINITY, f32::min)
}

#[allow(clippy::too_many_arguments)]
fn right_click(
    meter: Res<crate::ecs::meter::CpuMeter>,
    buttons: Res<ButtonInput<MouseButton>>,
    window: Single<&Window, With<PrimaryWindow>>,
    camera: Query<(&Camera, &GlobalTransform), With<MainCamera>>,
    (sphere, selection): (Res<SphereArea>, Res<Selection>),
    (kernel, data): (Res<PatchMeshes>, Res<SurfaceData>),
    patches: PickedPatches,
    mut press: Local<Option<Vec2>>,
    mut request: ResMut<NewPatchRequest>,
) {
    let _meter = meter.start();
    let Some(cursor) = window.cursor_position().filter(|p| !sphere.contains(*p)) else {
        return;
    };
    if buttons.just_pressed(MouseButton::Right) {
        // a press on a handle is the handle's
        *press = selection.hover.is_none().then_some(cursor);
    }
    if !buttons.just_released(MouseButton::Right) {
        return;
    }
    let Some(at) = press.take().filter(|at| at.distance(cursor) <= 3.0) else {
        return;
    };
    let Ok((camera, gt)) = camera.single() else {
        return;
    };
    let project = |p: DVec3| camera.world_to_viewport(gt, to_view(p)).ok();
    let mut best: Option<(f32, String, Edge)> = None;
    for (e, slot, joined, hidden, surface) in &patches {
        if hidden {
            continue;
        }
        let Some((grid, _)) = kernel.shown(e, joined, surface, &data) else {
            continue;
        };
        for (edge, line) in edges(grid) {
            let on_screen: Vec<Option<Vec2>> = line.iter().map(|&p| project(p)).collect();
            let d = screen_distance(at, &on_screen);
            if d <= BOUNDARY_PX && best.as_ref().is_none_or(|b| d < b.0) {
                best = Some((d, slot.name.clone(), edge));
            }
        }
    }
    if let Some((_, name, edge)) = best {
        request.0 = Some((name, edge));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 2 × 3 grid's edges, and distances to a projected polyline.
    #[test]
    fn edges_and_screen_distances() {
        let p = |x: f64, y: f64| DVec3::new(x, y, 0.0);
        let g = Grid::new(
            2,
            3,
            vec![
                p(0., 0.),
                p(1., 0.),
                p(2., 0.),
                p(0., 1.),
                p(1., 1.),
                p(2., 1.),
            ],
        )
        .unwrap();
        let [(e0, end), (e1, first), (e2, last)] = edges(&g);
        assert_eq!((e0, e1, e2), (Edge::End, Edge::First, Edge::Last));
        assert_eq!(end, vec![p(2., 0.), p(2., 1.)]);
        assert_eq!(first, vec![p(0., 0.), p(1., 0.), p(2., 0.)]);
        assert_eq!(last, vec![p(0., 1.), p(1., 1.), p(2., 1.)]);
        let line = [Some(Vec2::new(0.0, 0.0)), Some(Vec2::new(10.0, 0.0)), None];
        assert_eq!(screen_distance(Vec2::new(5.0, 3.0), &line), 3.0);
        assert_eq!(
            screen_distance(Vec2::new(5.0, 3.0), &[None, None]),
            f32::INFINITY
        );
    }
}
