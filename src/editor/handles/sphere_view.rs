//! The Gaussian sphere view: an inset viewport in the 3D view's lower right
//! corner with its own camera (turned like the main one) and render layer. It
//! shows the unit sphere, the control tangents as points (the selected one
//! highlighted), great arcs between neighbours in blue, the handles of the edit
//! depth in red, and the subdivided tangents of the display depth as small
//! points. Each handle entity's point (with its arcs) is a retained gizmo of
//! its own, redrawn only when the handle moved, a neighbour its arcs end at
//! moved, or it turned to or from the eye. Dragging a point moves that tangent to the point under the pointer.

use super::super::coords::{from_view, to_view};
use super::super::interaction::{
    Drag, DragKind, DragTo, EditorMode, EditorSet, HandlePressed, HandleQuery, HandleSettings,
    MainCamera, OrbitCamera, Selection, SphereArea, ViewArea,
};
use crate::ecs::components::{LevelData, SubdivisionLevel};
use crate::ecs::patch::PatchRef;
use crate::ecs::{SurfaceChange, SurfaceChanges};
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

/// The display depth's tangents as a point cloud, rebuilt when that level changes.
#[allow(clippy::too_many_arguments)]
fn update_points(
    meter: Res<crate::ecs::meter::CpuMeter>,
    patch: PatchRef,
    settings: Res<SphereSettings>,
    levels: Query<(&SubdivisionLevel, Ref<LevelData>)>,
    points: Single<(&Mesh3d, &mut Visibility), With<SubdividedPoints>>,
    mut surface: SurfaceChanges,
    mut meshes: ResMut<Assets<Mesh>>,
    mut shown: Local<Option<u32>>,
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
    // an edit of the display level moves its streamlines too: the rows the
    // mesh stage rewrote since the last run hold every row whose tangents changed
    let changed = surface.take();
    let depth = patch.structure().display_depth;
    let Some((_, data)) = levels.iter().find(|(l, _)| l.0 == depth) else {
        return;
    };
    if !data.is_changed() && *shown == Some(depth) {
        return;
    }
    let same_depth = *shown == Some(depth);
    *shown = Some(depth);
    let Some(mut m) = meshes.get_mut(&mesh.0) else {
        return;
    };
    let tangents = data.0.tangents.data();
    // same count (a drag): rewrite the points in place, no new buffer; only
    // the rows that changed when the mesh stage says which
    if let Some(VertexAttributeValues::Float32x3(p)) = m.attribute_mut(Mesh::ATTRIBUTE_POSITION)
        && p.len() == tangents.len()
    {
        let cols = data.0.shape().1;
        match changed {
            // tangent j moves points j + 1 on: the window's columns (points,
            // from one before the first that moved) hold every changed tangent
            SurfaceChange::Window(w) if same_depth && w.rows.hi * cols < p.len() => {
                for r in w.rows.iter() {
                    let range = r * cols + w.cols.lo.min(cols)..(r + 1) * cols;
                    for (p, &t) in p[range.clone()].iter_mut().zip(&tangents[range]) {
                        *p = to_view(t).to_array();
                    }
                }
            }
            _ => {
                for (p, &t) in p.iter_mut().zip(tangents) {
                    *p = to_view(t).to_array();
                }
            }
        }
        return;
    }
    let pos: Vec<[f32; 3]> = tangents.iter().map(|&t| to_view(t).to_array()).collect();
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
    fn sphere_point_hits_the_front_or_the_silhouette() {
        let p = sphere_point(DVec3::new(0.0, 0.0, 5.0), DVec3::new(0.0, 0.0, -1.0));
        assert!((p - DVec3::Z).length() < 1e-12);
        let p = sphere_point(DVec3::new(3.0, 0.0, 5.0), DVec3::new(0.0, 0.0, -1.0));
        assert!((p - DVec3::X).length() < 1e-12);
        let p = sphere_point(DVec3::new(0.5, 0.0, 5.0), DVec3::new(0.0, 0.0, -1.0));
        assert!((p.length() - 1.0).abs() < 1e-12 && p.z > 0.0 && (p.x - 0.5).abs() < 1e-12);
    }
}
