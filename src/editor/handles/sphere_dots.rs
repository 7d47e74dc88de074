//! The handle entities' points on the Gaussian sphere view
//! ([`super::sphere_view`]): each handle's point, with the great arcs to its
//! next neighbours, is a retained gizmo of its own, redrawn only when the
//! handle moved, a neighbour its arcs end at moved, or it turned to or from
//! the eye. Only the active patch's handles have their points shown (the
//! sphere view is the active patch's, [`PatchRole`]).

use super::super::coords::to_view;
use super::super::interaction::{
    EditorSet, Handle, HandleId, HandleKind, HandleQuery, HandleSettings, MainCamera, OrbitCamera,
    PatchRole, Placed,
};
use super::sphere_view::{BLUE, CYAN, LAYER, RED, YELLOW};
use bevy::camera::visibility::RenderLayers;
use bevy::gizmos::GizmoAsset;
use bevy::gizmos::config::GizmoLineConfig;
use bevy::gizmos::retained::Gizmo;
use bevy::prelude::*;
use streamline_kernel::DVec3;

/// The handles' points on the sphere view, kept up to date.
pub struct SphereDotsPlugin;

impl Plugin for SphereDotsPlugin {
    fn build(&self, app: &mut App) {
        app.init_resource::<DotRedraws>()
            .add_systems(Update, (attach, redraw).chain().in_set(EditorSet::Present));
    }
}

/// The point of a handle entity on the sphere view, with the great arcs to
/// its next neighbours (along its row and its column for a control tangent,
/// to the next one for the initial curve's): a retained gizmo of its own,
/// redrawn only when its [`DotLook`] changed.
#[derive(Component, Debug)]
#[relationship(relationship_target = DotDrawn)]
pub struct DotOf(pub Entity);

/// The handle entity's point on the sphere view (despawned with it).
#[derive(Component, Debug)]
#[relationship_target(relationship = DotOf, linked_spawn)]
pub struct DotDrawn(Vec<Entity>);

/// What a handle's point is drawn from: its direction, colour, radius,
/// whether it faces the eye, whether it is shown, and its neighbours'
/// directions its arcs end at.
#[derive(Component, Debug, Clone, Copy, PartialEq, Default)]
pub struct DotLook {
    dir: DVec3,
    color: Color,
    radius: f32,
    front: bool,
    shown: bool,
    arcs: [Option<(DVec3, Color)>; 2],
}

/// Points redrawn by the last frame (a meter of the incremental drawing).
#[derive(Resource, Debug, Default, Clone, Copy, PartialEq, Eq)]
pub struct DotRedraws(pub usize);

/// Placed handle entities (not copies) without a point yet.
type Bare<'w, 's> = Query<'w, 's, Entity, (With<Placed>, With<HandleId>, Without<DotDrawn>)>;

/// Gives every placed handle entity but the mirrored copies a point of its
/// own in the sphere view's layer.
fn attach(mut commands: Commands, mut assets: ResMut<Assets<GizmoAsset>>, bare: Bare) {
    for h in &bare {
        commands.spawn((
            DotOf(h),
            Gizmo {
                handle: assets.add(GizmoAsset::new()),
                line_config: GizmoLineConfig {
                    width: 1.5,
                    ..default()
                },
                depth_bias: 0.0,
            },
            RenderLayers::layer(LAYER),
            DotLook::default(),
        ));
    }
}

/// The look of handle `id`'s point (`handles` to find its neighbours),
/// a handle of a patch in `role`.
fn dot_look(
    handles: &HandleQuery,
    settings: &HandleSettings,
    (id, role): (HandleId, PatchRole),
    dir: DVec3,
    eye: DVec3,
) -> DotLook {
    if role != PatchRole::Active {
        return DotLook {
            dir,
            ..DotLook::default()
        };
    }
    let edit = handles.edit_depth();
    let neighbour = |id: HandleId| handles.entity(id).and_then(|e| handles.get(e));
    let (color, radius, shown, arcs) = match id.kind {
        HandleKind::InitialTangent => {
            let next = neighbour(HandleId::initial(id.col + 1)).map(|a| (a.dir, CYAN));
            (CYAN, 0.03, settings.initial, [next, None])
        }
        HandleKind::SurfaceTangent { level: 0 } => {
            let right = neighbour(HandleId::tangent(0, id.row, id.col + 1)).map(|a| (a.dir, BLUE));
            let down = neighbour(HandleId::tangent(0, id.row + 1, id.col))
                .map(|a| (a.dir, BLUE.with_alpha(0.45)));
            (YELLOW, 0.025, true, [right, down])
        }
        HandleKind::SurfaceTangent { level } => {
            let a = Handle {
                id,
                base: DVec3::ZERO,
                dir,
                length: 0.0,
            };
            let shown = level == edit && edit > 0 && settings.refined && settings.shows(&a);
            (RED, 0.012, shown, [None, None])
        }
    };
    DotLook {
        dir,
        color,
        radius,
        front: dir.dot(eye) >= 0.0,
        shown,
        arcs,
    }
}

/// Redraws the points whose look changed: those of the handles that moved
/// and of their neighbours before them (whose arcs end at them), or, when
/// the eye, the settings or the edit depth changed, those that changed look.
#[allow(clippy::too_many_arguments)]
fn redraw(
    meter: Res<crate::ecs::meter::CpuMeter>,
    handles: HandleQuery,
    settings: Res<HandleSettings>,
    main: Query<Ref<OrbitCamera>, With<MainCamera>>,
    moved: Query<(&HandleId, Option<&PatchRole>), Changed<Placed>>,
    roles: Query<&PatchRole>,
    recast: Query<(), Changed<PatchRole>>,
    drawn: Query<&DotDrawn>,
    added: Query<(), Added<DotOf>>,
    mut dots: Query<(&DotOf, &mut DotLook, &Gizmo)>,
    mut assets: ResMut<Assets<GizmoAsset>>,
    mut redraws: ResMut<DotRedraws>,
) {
    let _meter = meter.start();
    let cam = main.single().ok();
    let eye = cam.as_ref().map_or(DVec3::X, |o| o.eye_dir());
    let everything = settings.is_changed()
        || handles.layout_changed()
        || cam.is_some_and(|o| o.is_changed())
        || !recast.is_empty()
        || !added.is_empty();
    let candidates: Vec<Entity> = if everything {
        drawn.iter().flat_map(|d| d.0.iter().copied()).collect()
    } else {
        let mut ids: Vec<HandleId> = Vec::new();
        for (&id, _) in moved
            .iter()
            .filter(|(_, r)| r.is_none_or(|r| *r == PatchRole::Active))
        {
            ids.push(id);
            match id.kind {
                HandleKind::SurfaceTangent { level: 0 } => {
                    if id.col > 0 {
                        ids.push(HandleId::tangent(0, id.row, id.col - 1));
                    }
                    if id.row > 0 {
                        ids.push(HandleId::tangent(0, id.row - 1, id.col));
                    }
                }
                HandleKind::InitialTangent if id.col > 0 => ids.push(HandleId::initial(id.col - 1)),
                _ => {}
            }
        }
        ids.sort_unstable_by_key(|h| (h.level(), h.is_surface(), h.row, h.col));
        ids.dedup();
        ids.iter()
            .filter_map(|&id| handles.entity(id))
            .filter_map(|e| drawn.get(e).ok())
            .flat_map(|d| d.0.iter().copied())
            .collect()
    };
    let mut n = 0;
    for v in candidates {
        let Ok((of, mut look, gizmo)) = dots.get_mut(v) else {
            continue;
        };
        let Some(a) = handles.get(of.0) else {
            continue;
        };
        let role = roles.get(of.0).copied().unwrap_or_default();
        let new = dot_look(&handles, &settings, (a.id, role), a.dir, eye);
        if *look == new {
            continue;
        }
        *look = new;
        let Some(mut asset) = assets.get_mut(&gizmo.handle) else {
            continue;
        };
        asset.clear();
        if new.shown {
            let at = to_view(new.dir);
            for (to, color) in new.arcs.into_iter().flatten() {
                asset.short_arc_3d_between(Vec3::ZERO, at, to_view(to), color);
            }
            let color = if new.front {
                new.color
            } else {
                new.color.with_alpha(0.35)
            };
            asset
                .sphere(Isometry3d::from_translation(at), new.radius, color)
                .resolution(8);
        }
        n += 1;
    }
    redraws.set_if_neq(DotRedraws(n));
}
