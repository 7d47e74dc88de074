//! The main 3D camera: an orbit camera ([`OrbitCamera`], kept in the
//! interaction core) over the area the panels leave free.
//! Right drag orbits, middle drag pans, the wheel zooms; `A` (or Home) frames
//! everything, `F` frames the selected handle. Viewport input is ignored while
//! the pointer is over an egui panel.

use super::super::interaction::{
    EditorSet, FrameRequest, HandleQuery, MainCamera, OrbitCamera, SceneBounds, Selection, ViewArea,
};
use crate::ecs::joined::{PatchHidden, PatchStart, PatchSurface, shows_run_cut};
use crate::ecs::patch::PatchRef;
use crate::ecs::{SurfaceChanges, SurfaceData};
use crate::scene::files::format::ViewSpec;
use bevy::camera::Viewport;
use bevy::input::mouse::{AccumulatedMouseMotion, AccumulatedMouseScroll};
use bevy::prelude::*;
use bevy::window::PrimaryWindow;
use bevy_egui::input::{egui_wants_any_keyboard_input, egui_wants_any_pointer_input};
use std::collections::HashMap;
use streamline_kernel::DVec3;

pub struct OrbitCameraPlugin;

impl Plugin for OrbitCameraPlugin {
    fn build(&self, app: &mut App) {
        app.add_systems(Startup, spawn)
            .add_systems(
                Update,
                (
                    bounds,
                    follow_scene_view,
                    orbit.run_if(not(egui_wants_any_pointer_input)),
                    keys.run_if(
                        not(egui_wants_any_keyboard_input)
                            .and_then(super::super::files::open_save::no_file_dialog),
                    ),
                    apply_frame_and_view,
                )
                    .chain()
                    .in_set(EditorSet::Sync),
            )
            .add_systems(PostUpdate, set_viewport);
    }
}

fn spawn(mut commands: Commands, patch: PatchRef) {
    let cam = OrbitCamera::from_view(&patch.view());
    commands.spawn((
        Camera3d::default(),
        Camera {
            order: 0,
            ..default()
        },
        cam.transform(),
        cam,
        MainCamera,
    ));
}

/// The patches' surfaces, with whether they are hidden and joined.
type Surfaces<'w, 's> = Query<
    'w,
    's,
    (
        Entity,
        Ref<'static, PatchSurface>,
        Has<PatchHidden>,
        Has<crate::ecs::patch::Joined>,
    ),
>;

/// The box of every shown patch: the first patch's rows' boxes (kept by the
/// mesh stage as it writes each row), or its stack's when it is drawn as
/// its G2 run's cut (`crate::ecs::joined::shows_run_cut`), and each joined
/// patch's, made again only when that patch was rebuilt, hidden or shown
/// (so "frame all" frames every patch of a document).
#[allow(clippy::too_many_arguments)]
fn bounds(
    meter: Res<crate::ecs::meter::CpuMeter>,
    data: Res<SurfaceData>,
    mut changes: SurfaceChanges,
    surfaces: Surfaces,
    starts: Query<&PatchStart>,
    mut removed: RemovedComponents<PatchSurface>,
    mut boxes: Local<HashMap<Entity, Option<[DVec3; 2]>>>,
    mut b: ResMut<SceneBounds>,
) {
    let _meter = meter.start();
    let mut any = changes.take().any();
    for e in removed.read() {
        any |= boxes.remove(&e).is_some();
    }
    // whether the first patch is drawn as its run's cut (its box is then its stack's)
    let mut cut = false;
    for (e, surface, hidden, joined) in &surfaces {
        if !joined {
            cut = shows_run_cut(e, starts.iter(), Some(&*surface));
            if !cut {
                any |= boxes.remove(&e).is_some();
                continue;
            }
        }
        let known = boxes.get(&e);
        let shown = known.is_some_and(|b| b.is_some());
        if known.is_some() && !surface.is_changed() && shown != hidden {
            continue;
        }
        let points = surface.stack().map(|s| s.finest_points().data());
        let bx = match (hidden, points) {
            (false, Some(p)) if !p.is_empty() => Some(
                streamline_kernel::streamline::surface_mesh::bounds(p.iter().copied()),
            ),
            _ => None,
        };
        boxes.insert(e, bx);
        any = true;
    }
    if !any {
        return;
    }
    let own = if cut { None } else { data.bounds() };
    let Some([lo, hi]) = (boxes.values().flatten()).fold(own, |acc, &[l, h]| {
        Some(acc.map_or([l, h], |[lo, hi]| [lo.min(l), hi.max(h)]))
    }) else {
        return;
    };
    b.min = lo;
    b.max = hi;
}

/// A newly opened scene brings its own view (edits never change the view).
fn follow_scene_view(
    meter: Res<crate::ecs::meter::CpuMeter>,
    patch: PatchRef,
    mut shown: Local<Option<ViewSpec>>,
    mut q: Query<&mut OrbitCamera, With<MainCamera>>,
) {
    let _meter = meter.start();
    let v = patch.view();
    if *shown == Some(v) {
        return;
    }
    let first = shown.is_none();
    *shown = Some(v);
    if !first {
        for mut cam in &mut q {
            *cam = OrbitCamera::from_view(&v);
        }
    }
}

fn orbit(
    meter: Res<crate::ecs::meter::CpuMeter>,
    buttons: Res<ButtonInput<MouseButton>>,
    motion: Res<AccumulatedMouseMotion>,
    scroll: Res<AccumulatedMouseScroll>,
    area: Res<ViewArea>,
    window: Single<&Window, With<PrimaryWindow>>,
    mut q: Query<&mut OrbitCamera, With<MainCamera>>,
) {
    let _meter = meter.start();
    let Ok(mut cam) = q.single_mut() else {
        return;
    };
    // the wheel zooms only over the 3D view
    let over_view = match (window.cursor_position(), area.0) {
        (Some(p), Some(r)) => r.contains(p),
        (Some(_), None) => true,
        _ => false,
    };
    let d = motion.delta.as_dvec2();
    if buttons.pressed(MouseButton::Right) && d != bevy::math::DVec2::ZERO {
        cam.yaw -= d.x * 0.008;
        cam.pitch = (cam.pitch + d.y * 0.008).clamp(-1.55, 1.55);
    }
    if buttons.pressed(MouseButton::Middle) && d != bevy::math::DVec2::ZERO {
        let e = cam.eye_dir();
        let right = DVec3::Z.cross(e).try_normalize().unwrap_or(DVec3::X);
        let up = e.cross(right);
        let k = cam.distance * 0.0015;
        cam.target += (-right * d.x + up * d.y) * k;
    }
    if over_view && scroll.delta.y != 0.0 {
        let f = (1.0 - scroll.delta.y as f64 * 0.1).clamp(0.5, 1.5);
        cam.distance = (cam.distance * f).clamp(1e-3, 1e5);
    }
}

fn keys(
    meter: Res<crate::ecs::meter::CpuMeter>,
    keys: Res<ButtonInput<KeyCode>>,
    bounds: Res<SceneBounds>,
    handles: HandleQuery,
    selection: Res<Selection>,
    mut req: ResMut<FrameRequest>,
) {
    let _meter = meter.start();
    if keys.just_pressed(KeyCode::KeyA) || keys.just_pressed(KeyCode::Home) {
        req.0 = Some(bounds.all());
    }
    if keys.just_pressed(KeyCode::KeyF) {
        req.0 = Some(match selection.primary().and_then(|h| handles.find(h)) {
            Some(a) => a.framing(bounds.size()),
            None => bounds.all(),
        });
    }
}

fn apply_frame_and_view(
    meter: Res<crate::ecs::meter::CpuMeter>,
    mut req: ResMut<FrameRequest>,
    mut q: Query<(&mut OrbitCamera, &mut Transform), With<MainCamera>>,
) {
    let _meter = meter.start();
    let Ok((mut cam, mut tf)) = q.single_mut() else {
        return;
    };
    if let Some((c, r)) = req.0.take() {
        cam.frame(c, r);
    }
    let t = cam.transform();
    if *tf != t {
        *tf = t;
    }
}

/// Fits the main camera's viewport to the area the panels leave free.
fn set_viewport(
    meter: Res<crate::ecs::meter::CpuMeter>,
    area: Res<ViewArea>,
    window: Single<&Window, With<PrimaryWindow>>,
    mut q: Query<&mut Camera, With<MainCamera>>,
) {
    let _meter = meter.start();
    let Ok(mut camera) = q.single_mut() else {
        return;
    };
    let viewport = area.0.and_then(|r| {
        let s = window.scale_factor();
        let (w, h) = (window.physical_width(), window.physical_height());
        let min = (r.min * s).as_uvec2().min(UVec2::new(w, h));
        let max = (r.max * s).as_uvec2().min(UVec2::new(w, h));
        let size = max.saturating_sub(min);
        (size.x >= 16 && size.y >= 16).then_some(Viewport {
            physical_position: min,
            physical_size: size,
            ..default()
        })
    });
    let same = match (&camera.viewport, &viewport) {
        (Some(a), Some(b)) => {
            a.physical_position == b.physical_position && a.physical_size == b.physical_size
        }
        (None, None) => true,
        _ => false,
    };
    if !same {
        camera.viewport = viewport;
    }
}
