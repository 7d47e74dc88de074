//! The Gaussian sphere view: an inset viewport in the 3D view's lower right
//! corner with its own camera (turned like the main one) and render layer. It
//! shows the unit sphere, the control tangents as points (the selected one
//! highlighted), great arcs between neighbours in blue, the handles of the edit
//! depth in red, and the subdivided tangents of the display depth as small
//! points (at most a level-4 density: [`CLOUD_LEVEL`]), all of the active
//! patch (docs/math.md §11: a joined patch's from its built stack, and so
//! the first patch's when it heads a G2 run, whose drawn surface is its cut
//! of the run, §11.1). Each handle entity's point (with its arcs) is a retained gizmo of
//! its own, redrawn only when the handle moved, a neighbour its arcs end at
//! moved, or it turned to or from the eye. Dragging a point moves that tangent to the point under the pointer.

use super::super::coords::{from_view, to_view};
use super::super::interaction::{
    Drag, DragKind, DragTo, EditorMode, EditorSet, HandleLayout, HandlePressed, HandleQuery,
    HandleSettings, MainCamera, OrbitCamera, Selection, SphereArea, ViewArea,
};
use crate::ecs::components::{LevelData, SubdivisionLevel};
use crate::ecs::joined::{PatchStart, PatchSurface, heads_g2_run};
use crate::ecs::patch::PatchRef;
use bevy::asset::RenderAssetUsages;
use bevy::camera::Viewport;
use bevy::camera::visibility::RenderLayers;
use bevy::gizmos::gizmos::GizmoBuffer;
use bevy::mesh::{PrimitiveTopology, VertexAttributeValues};
use bevy::prelude::*;
use bevy::window::PrimaryWindow;
use bevy_egui::input::egui_wants_any_pointer_input;
use bevy_state::prelude::{State, in_state};
use streamline_kernel::DVec3;

/// The render layer of the sphere view.
pub(super) const LAYER: usize = 1;

/// The control tangents' points.
pub(super) const YELLOW: Color = Color::srgb(1.0, 0.85, 0.1);
/// The edit depth's refined tangents' points.
pub(super) const RED: Color = Color::srgb(0.95, 0.25, 0.2);
/// The initial curve's control tangents' points and arcs.
pub(super) const CYAN: Color = Color::srgb(0.2, 0.85, 0.95);
/// The arcs between neighbouring control tangents.
pub(super) const BLUE: Color = Color::srgb(0.3, 0.5, 1.0);

/// Settings of the sphere view.
#[derive(Resource, Debug, Clone, PartialEq)]
pub struct SphereSettings {
    /// Show the inset.
    pub show: bool,
    /// Its side as a fraction of the 3D view's shorter side.
    pub fraction: f32,
    /// Show the subdivided tangents of the display depth.
    pub subdivided: bool,
}

impl Default for SphereSettings {
    fn default() -> Self {
        SphereSettings {
            show: true,
            fraction: 0.4,
            subdivided: true,
        }
    }
}

/// Gizmos drawn only in the sphere view.
#[derive(Default, Reflect, GizmoConfigGroup)]
pub struct SphereGizmos;

/// Marks the sphere view's camera.
#[derive(Component)]
pub struct SphereCamera;

/// Marks the point cloud of the display depth's tangents.
#[derive(Component)]
pub struct SubdividedPoints;

pub struct SphereViewPlugin;

impl Plugin for SphereViewPlugin {
    fn build(&self, app: &mut App) {
        app.init_resource::<SphereSettings>()
            .init_gizmo_group::<SphereGizmos>()
            .add_systems(Startup, setup)
            .add_systems(
                Update,
                (
                    press.run_if(
                        not(egui_wants_any_pointer_input)
                            .and_then(in_state(EditorMode::Streamline)),
                    ),
                    drag_move,
                )
                    .in_set(EditorSet::Input),
            )
            .add_systems(Update, update_points.in_set(EditorSet::Sync))
            .add_systems(
                Update,
                draw.run_if(in_state(EditorMode::Streamline))
                    .in_set(EditorSet::Present),
            )
            .add_systems(PostUpdate, place_camera);
    }
}

fn setup(
    mut commands: Commands,
    mut meshes: ResMut<Assets<Mesh>>,
    mut materials: ResMut<Assets<StandardMaterial>>,
    mut config: ResMut<GizmoConfigStore>,
) {
    let (cfg, _) = config.config_mut::<SphereGizmos>();
    cfg.render_layers = RenderLayers::layer(LAYER);
    cfg.line.width = 1.5;
    commands.spawn((
        Camera3d::default(),
        Camera {
            order: 1,
            clear_color: ClearColorConfig::Custom(Color::srgb(0.10, 0.11, 0.13)),
            is_active: false,
            ..default()
        },
        Transform::from_xyz(0.0, 0.0, 3.4).looking_at(Vec3::ZERO, Vec3::Y),
        RenderLayers::layer(LAYER),
        SphereCamera,
    ));
    commands.spawn((
        Mesh3d(meshes.add(Sphere::new(0.995).mesh().uv(48, 24))),
        MeshMaterial3d(materials.add(StandardMaterial {
            base_color: Color::srgba(0.45, 0.5, 0.6, 0.28),
            alpha_mode: AlphaMode::Blend,
            unlit: true,
            ..default()
        })),
        RenderLayers::layer(LAYER),
    ));
    let empty = Mesh::new(PrimitiveTopology::PointList, RenderAssetUsages::default())
        .with_inserted_attribute(Mesh::ATTRIBUTE_POSITION, vec![[0.0f32, 0.0, 0.0]]);
    commands.spawn((
        Mesh3d(meshes.add(empty)),
        MeshMaterial3d(materials.add(StandardMaterial {
            base_color: Color::srgb(0.85, 0.88, 0.95),
            unlit: true,
            ..default()
        })),
        Transform::from_scale(Vec3::splat(1.004)),
        RenderLayers::layer(LAYER),
        SubdividedPoints,
    ));
}

/// Places the inset in the lower right corner of the 3D view and turns its
/// camera like the main one.
#[allow(clippy::too_many_arguments)]
fn place_camera(
    meter: Res<crate::ecs::meter::CpuMeter>,
    settings: Res<SphereSettings>,
    area: Res<ViewArea>,
    window: Single<&Window, With<PrimaryWindow>>,
    main: Query<&OrbitCamera, With<MainCamera>>,
    mut cam: Query<(&mut Camera, &mut Transform), With<SphereCamera>>,
    mut sphere_area: ResMut<SphereArea>,
    mode: Res<State<EditorMode>>,
) {
    let _meter = meter.start();
    let Ok((mut camera, mut tf)) = cam.single_mut() else {
        return;
    };
    let view = area
        .0
        .unwrap_or(Rect::new(0.0, 0.0, window.width(), window.height()));
    let side = (view.width().min(view.height()) * settings.fraction).clamp(120.0, 420.0);
    let margin = 8.0;
    let rect = Rect::new(
        view.max.x - side - margin,
        view.max.y - side - margin,
        view.max.x - margin,
        view.max.y - margin,
    );
    // the inset belongs to the streamline surface: hidden in mesh mode
    let show = settings.show
        && *mode.get() == EditorMode::Streamline
        && view.width() > side + 2.0 * margin
        && view.height() > side + 2.0 * margin;
    if camera.is_active != show {
        camera.is_active = show;
    }
    sphere_area.0 = show.then_some(rect);
    if !show {
        return;
    }
    let s = window.scale_factor();
    let vp = Viewport {
        physical_position: (rect.min * s).as_uvec2(),
        physical_size: (rect.size() * s).as_uvec2().max(UVec2::ONE),
        ..default()
    };
    let same = camera.viewport.as_ref().is_some_and(|v| {
        v.physical_position == vp.physical_position && v.physical_size == vp.physical_size
    });
    if !same {
        camera.viewport = Some(vp);
    }
    if let Ok(o) = main.single() {
        let eye = to_view(o.eye_dir() * 3.4);
        let t = Transform::from_translation(eye).looking_at(Vec3::ZERO, Vec3::Y);
        if *tf != t {
            *tf = t;
        }
    }
}

/// The deepest level whose tangents the cloud shows every one of: at a
/// deeper display depth `d` it shows every `2^(d − 4)`-th tangent along and
/// across (and the last row and column), so at most a level-4 density (about
/// 10,000 points on the car at depth 6 instead of 165,000; a few pixels apart
/// in the inset, where the full cloud is a solid patch). Each point shown is
/// a display-depth tangent as it is, so the cloud covers the same part of
/// the sphere with the same outline.
pub const CLOUD_LEVEL: u32 = 4;

/// The indices of `n` that the cloud shows at a step of `step`: `0, step,
/// 2·step, …` and the last one.
pub fn sampled(n: usize, step: usize) -> impl Iterator<Item = usize> + Clone {
    let step = step.max(1);
    (0..n)
        .step_by(step)
        .chain((n > 0 && !(n - 1).is_multiple_of(step)).then(|| n - 1))
}

/// The tangents of a `rows × cols` grid (row-major) that the cloud of a
/// level at `depth` shows, in the cloud's order.
pub fn cloud_points(
    tangents: &[DVec3],
    rows: usize,
    cols: usize,
    depth: u32,
) -> impl Iterator<Item = DVec3> + Clone + '_ {
    let step = 1usize << depth.saturating_sub(CLOUD_LEVEL).min(16);
    let across = sampled(cols, step);
    sampled(rows, step).flat_map(move |r| across.clone().map(move |c| tangents[r * cols + c]))
}

/// How many points [`cloud_points`] yields (without reading them).
pub fn cloud_count(rows: usize, cols: usize, depth: u32) -> usize {
    let step = 1usize << depth.saturating_sub(CLOUD_LEVEL).min(16);
    sampled(rows, step).count() * sampled(cols, step).count()
}

/// The display depth's tangents as a point cloud ([`cloud_points`]: at most
/// a level-4 density), of the active patch (a joined one's from its built
/// stack, docs/math.md §11, and a G2 run's head's from its cut), rewritten
/// when that level changes.
#[allow(clippy::too_many_arguments)]
fn update_points(
    meter: Res<crate::ecs::meter::CpuMeter>,
    patch: PatchRef,
    settings: Res<SphereSettings>,
    layout: Res<HandleLayout>,
    levels: Query<(&SubdivisionLevel, Ref<LevelData>)>,
    joined: Query<Ref<PatchSurface>>,
    starts: Query<&PatchStart>,
    points: Single<(&Mesh3d, &mut Visibility), With<SubdividedPoints>>,
    mut meshes: ResMut<Assets<Mesh>>,
    mut shown: Local<Option<(u32, Option<Entity>)>>,
) {
    let _meter = meter.start();
    let (mesh, mut vis) = points.into_inner();
    let want = if settings.subdivided {
        Visibility::Inherited
    } else {
        Visibility::Hidden
    };
    if *vis != want {
        *vis = want;
    }
    let depth = patch.structure().display_depth;
    // a G2 run's head is drawn as its cut of the run: its stack's level
    let first = patch.entity();
    let cut = heads_g2_run(first, starts.iter())
        && joined
            .get(first)
            .is_ok_and(|s| s.stack().is_some_and(|s| s.levels.len() > depth as usize));
    let of = match layout.active_joined {
        true => layout.active,
        false => cut.then_some(first),
    };
    let (tangents, changed) = match of {
        Some(e) => {
            let Ok(surface) = joined.get(e) else {
                return;
            };
            let changed = surface.is_changed();
            let Some(level) = surface
                .into_inner()
                .stack()
                .and_then(|s| s.levels.get(depth as usize))
            else {
                return;
            };
            (&level.tangents, changed)
        }
        None => {
            let Some((_, data)) = levels.iter().find(|(l, _)| l.0 == depth) else {
                return;
            };
            let changed = data.is_changed();
            (&data.into_inner().0.tangents, changed)
        }
    };
    if !changed && *shown == Some((depth, of)) {
        return;
    }
    *shown = Some((depth, of));
    let Some(mut m) = meshes.get_mut(&mesh.0) else {
        return;
    };
    let (rows, cols) = (tangents.rows(), tangents.cols());
    let cloud = cloud_points(tangents.data(), rows, cols, depth);
    // same count (a drag): rewrite the points in place, no new buffer
    let n = cloud_count(rows, cols, depth);
    if let Some(VertexAttributeValues::Float32x3(p)) = m.attribute_mut(Mesh::ATTRIBUTE_POSITION)
        && p.len() == n
    {
        for (p, t) in p.iter_mut().zip(cloud) {
            *p = to_view(t).to_array();
        }
        return;
    }
    let pos: Vec<[f32; 3]> = cloud.map(|t| to_view(t).to_array()).collect();
    m.insert_attribute(Mesh::ATTRIBUTE_POSITION, pos);
}

/// The sphere's circles and axes, and the selected and hovered handles'
/// points drawn larger over their own (a few, drawn each frame).
#[allow(clippy::too_many_arguments)]
fn draw(
    meter: Res<crate::ecs::meter::CpuMeter>,
    arrows: HandleQuery,
    selection: Res<Selection>,
    area: Res<SphereArea>,
    main: Query<&OrbitCamera, With<MainCamera>>,
    mut gizmos: Gizmos<SphereGizmos>,
) {
    let _meter = meter.start();
    if area.0.is_none() {
        return;
    }
    let eye = main.single().map(|o| o.eye_dir()).unwrap_or(DVec3::X);
    let faint = Color::srgba(0.7, 0.75, 0.85, 0.35);
    for rot in [
        Quat::IDENTITY,
        Quat::from_rotation_x(std::f32::consts::FRAC_PI_2),
        Quat::from_rotation_y(std::f32::consts::FRAC_PI_2),
    ] {
        gizmos
            .circle(Isometry3d::from_rotation(rot), 1.0, faint)
            .resolution(64);
    }
    // kernel x and y axes, as in the main view
    gizmos.line(
        Vec3::ZERO,
        to_view(DVec3::X) * 1.15,
        Color::srgb(0.9, 0.2, 0.2),
    );
    gizmos.line(
        Vec3::ZERO,
        to_view(DVec3::Y) * 1.15,
        Color::srgb(0.2, 0.85, 0.3),
    );
    for h in selection.iter().skip(1) {
        if let Some(a) = arrows.find(h) {
            dot(&mut gizmos, a.dir, eye, 0.038, Color::srgb(0.75, 0.8, 1.0));
        }
    }
    for h in [selection.hover, selection.primary()].into_iter().flatten() {
        if let Some(a) = arrows.find(h) {
            dot(&mut gizmos, a.dir, eye, 0.045, Color::WHITE);
        }
    }
}

/// A handle's point on the sphere: a small ball, dimmed on the far side.
fn dot(
    gizmos: &mut GizmoBuffer<SphereGizmos, ()>,
    d: DVec3,
    eye: DVec3,
    radius: f32,
    color: Color,
) {
    let color = if d.dot(eye) >= 0.0 {
        color
    } else {
        color.with_alpha(0.35)
    };
    gizmos
        .sphere(Isometry3d::from_translation(to_view(d)), radius, color)
        .resolution(8);
}

/// The point of the unit sphere under a ray: the first hit, or the closest
/// point of the silhouette when the ray misses.
pub fn sphere_point(origin: DVec3, dir: DVec3) -> DVec3 {
    let dir = dir.normalize_or(DVec3::Z);
    let b = origin.dot(dir);
    let c = origin.length_squared() - 1.0;
    let disc = b * b - c;
    let p = if disc >= 0.0 {
        origin + dir * (-b - disc.sqrt())
    } else {
        origin - dir * b
    };
    p.try_normalize().unwrap_or(DVec3::Z)
}

/// A left press on the inset: on the nearest handle's point (a sphere drag).
#[allow(clippy::too_many_arguments)]
fn press(
    meter: Res<crate::ecs::meter::CpuMeter>,
    buttons: Res<ButtonInput<MouseButton>>,
    window: Single<&Window, With<PrimaryWindow>>,
    area: Res<SphereArea>,
    cam: Query<(&Camera, &GlobalTransform), With<SphereCamera>>,
    handles: HandleQuery,
    settings: Res<HandleSettings>,
    drag: Res<Drag>,
    mut presses: MessageWriter<HandlePressed>,
) {
    let _meter = meter.start();
    if !buttons.just_pressed(MouseButton::Left) || drag.0.is_some() {
        return;
    }
    let Some(cursor) = window.cursor_position().filter(|p| area.contains(*p)) else {
        return;
    };
    let Ok((camera, gt)) = cam.single() else {
        return;
    };
    let eye = from_view(gt.translation()).normalize_or(DVec3::Z);
    let project = |d: DVec3| camera.world_to_viewport(gt, to_view(d)).ok();
    if let Some(a) = handles.pick_on_sphere(&settings, cursor, eye, project, 10.0) {
        presses.write(HandlePressed {
            handle: Some(a.id),
            drag: Some(DragKind::Sphere),
        });
    }
}

/// The direction a sphere drag asks for: the point of the sphere under the pointer.
fn drag_move(
    meter: Res<crate::ecs::meter::CpuMeter>,
    window: Single<&Window, With<PrimaryWindow>>,
    area: Res<SphereArea>,
    cam: Query<(&Camera, &GlobalTransform), With<SphereCamera>>,
    drag: Res<Drag>,
    mut to: MessageWriter<DragTo>,
) {
    let _meter = meter.start();
    let Some(d) = drag.0.as_ref() else {
        return;
    };
    if d.kind != DragKind::Sphere {
        return;
    }
    // outside the inset the pointer still steers: clamp it to the inset's edge
    let Some(p) = window.cursor_position() else {
        return;
    };
    let Some(rect) = area.0 else {
        return;
    };
    let p = p.clamp(rect.min, rect.max - Vec2::ONE);
    let Ok((camera, gt)) = cam.single() else {
        return;
    };
    let Ok(ray) = camera.viewport_to_world(gt, p) else {
        return;
    };
    to.write(DragTo(sphere_point(
        from_view(ray.origin),
        from_view(*ray.direction),
    )));
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_cloud_is_every_tangent_to_depth_4_then_a_level_4_density() {
        let (rows, cols) = (321, 514);
        let grid: Vec<DVec3> = (0..rows * cols)
            .map(|i| DVec3::new(i as f64, 0.0, 1.0))
            .collect();
        // independently: the kept indices by a filter over all of them
        let kept = |n: usize, step: usize| (0..n).filter(move |i| i % step == 0 || *i == n - 1);
        let g = &grid;
        for (depth, step) in [(0, 1), (3, 1), (4, 1), (5, 2), (6, 4), (7, 8)] {
            let want: Vec<DVec3> = kept(rows, step)
                .flat_map(|r| kept(cols, step).map(move |c| g[r * cols + c]))
                .collect();
            let got: Vec<DVec3> = cloud_points(&grid, rows, cols, depth).collect();
            assert_eq!(got, want, "depth {depth}");
            assert_eq!(cloud_count(rows, cols, depth), want.len());
        }
        // the car at depth 6: 81 rows × 130 columns (the last one too), not 165k
        assert_eq!(cloud_points(&grid, rows, cols, 6).count(), 81 * 130);
        assert_eq!(cloud_points(&grid, rows, cols, 4).count(), rows * cols);
        assert_eq!(sampled(0, 4).count(), 0);
        assert_eq!(sampled(1, 4).collect::<Vec<_>>(), [0]);
        assert_eq!(sampled(9, 4).collect::<Vec<_>>(), [0, 4, 8]);
        assert_eq!(sampled(10, 4).collect::<Vec<_>>(), [0, 4, 8, 9]);
    }

    #[test]
    fn sphere_point_hits_the_front_or_the_silhouette() {
        let p = sphere_point(DVec3::new(0.0, 0.0, 5.0), DVec3::new(0.0, 0.0, -1.0));
        assert!((p - DVec3::Z).length() < 1e-12);
        let p = sphere_point(DVec3::new(3.0, 0.0, 5.0), DVec3::new(0.0, 0.0, -1.0));
        assert!((p - DVec3::X).length() < 1e-12);
        let p = sphere_point(DVec3::new(0.5, 0.0, 5.0), DVec3::new(0.0, 0.0, -1.0));
        assert!((p.length() - 1.0).abs() < 1e-12 && p.z > 0.0 && (p.x - 0.5).abs() < 1e-12);
    }
}
