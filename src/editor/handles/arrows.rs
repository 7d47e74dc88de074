//! Drawing the handle entities (placed by the interaction core, [`Placed`])
//! as arrows, each a retained gizmo of its own redrawn only when its
//! handle moved or its colour changed: the control tangents (level 0) as yellow arrows at their
//! streamline points, and the refined tangents of the edit depth as red arrows
//! (optionally every other one), and the initial curve with its control
//! tangents in cyan (a second kind of handle); with mirror symmetry on, the
//! reflected copies on the other half dimmed (they cannot be picked). With
//! several patches (docs/math.md §11) the active patch's handles are drawn
//! so, every other patch's thin and faint in their kind's colour (never
//! picked, never highlighted: the selection names the active patch's), and
//! a hidden patch's not at all ([`PatchRole`]). The head's shape tells the column index apart
//! (cone, ball, cross, ring, repeating, as the paper's prototype gives each
//! index its own head), and a number label names it.

use super::super::coords::to_view;
use super::super::interaction::{
    Drag, EditorMode, EditorSet, Handle, HandleId, HandleLayout, HandleQuery, HandleSettings,
    MainCamera, MirroredHandle, PatchRole, Placed, Selection,
};
use crate::ecs::patch::InitialHandle;
use bevy::gizmos::GizmoAsset;
use bevy::gizmos::config::GizmoLineConfig;
use bevy::gizmos::retained::Gizmo;
use bevy::prelude::*;
use bevy_egui::{EguiContexts, EguiPrimaryContextPass, egui};
use bevy_state::prelude::State;
use bevy_state::prelude::in_state;
use streamline_kernel::DVec3;

pub struct ArrowsPlugin;

/// The initial curve and its arrows: drawn over the surface (the curve is the
/// surface's edge, which would hide them) and a little wider.
#[derive(Default, Reflect, GizmoConfigGroup)]
pub struct InitialGizmos;

impl Plugin for ArrowsPlugin {
    fn build(&self, app: &mut App) {
        app.init_gizmo_group::<InitialGizmos>()
            .add_systems(Startup, |mut config: ResMut<GizmoConfigStore>| {
                let (cfg, _) = config.config_mut::<InitialGizmos>();
                cfg.depth_bias = -1.0;
                cfg.line.width = 2.5;
            })
            .init_resource::<ArrowRedraws>()
            .add_systems(
                Update,
                (
                    (attach, redraw).chain(),
                    draw_curve.run_if(in_state(EditorMode::Streamline)),
                )
                    .in_set(EditorSet::Present),
            )
            .add_systems(
                EguiPrimaryContextPass,
                labels.run_if(in_state(EditorMode::Streamline)),
            );
    }
}

const YELLOW: Color = Color::srgb(1.0, 0.85, 0.1);
const RED: Color = Color::srgb(0.95, 0.25, 0.2);
const SELECTED: Color = Color::srgb(1.0, 1.0, 1.0);
const HOVER: Color = Color::srgb(1.0, 0.6, 0.1);
/// The mirrored half's copies of the control arrows: the yellow, dimmed.
const MIRRORED: Color = Color::srgb(0.55, 0.47, 0.14);
const CYAN: Color = Color::srgb(0.2, 0.85, 0.95);
/// Also selected (a group; the primary is [`SELECTED`]).
const GROUP: Color = Color::srgb(0.75, 0.8, 1.0);

/// The arrow of a handle entity: a retained gizmo of its own, redrawn only
/// when the handle's [`Placed`] or the arrow's [`ArrowLook`] changed.
#[derive(Component, Debug)]
#[relationship(relationship_target = ArrowDrawn)]
pub struct ArrowOf(pub Entity);

/// The handle entity's arrow (despawned with it).
#[derive(Component, Debug)]
#[relationship_target(relationship = ArrowOf, linked_spawn)]
pub struct ArrowDrawn(Vec<Entity>);

/// How an arrow looks: its colour (the kind's, or the selection's),
/// whether it is shown, and whether it is drawn thin (another patch's).
#[derive(Component, Debug, Clone, Copy, PartialEq, Default)]
pub struct ArrowLook {
    /// Its colour.
    pub color: Color,
    /// Shown (a hidden arrow's gizmo is empty).
    pub shown: bool,
    /// Thin: a handle of a patch that is not the active one.
    pub thin: bool,
}

/// The alpha of another patch's arrows.
const DIMMED_ALPHA: f32 = 0.3;
/// The line width of another patch's arrows (px; the active's are 2 and 2.5).
const DIMMED_WIDTH: f32 = 1.0;

/// The line width of an arrow: the initial curve's a little wider, another
/// patch's thin.
fn width(initial: bool, thin: bool) -> f32 {
    match (thin, initial) {
        (true, _) => DIMMED_WIDTH,
        (false, true) => 2.5,
        (false, false) => 2.0,
    }
}

/// Arrows redrawn by the last frame (a meter of the incremental drawing).
#[derive(Resource, Debug, Default, Clone, Copy, PartialEq, Eq)]
pub struct ArrowRedraws(pub usize);

/// Placed handle entities without an arrow yet (and whether they are the
/// initial curve's).
type Bare<'w, 's> =
    Query<'w, 's, (Entity, Has<InitialHandle>), (With<Placed>, Without<ArrowDrawn>)>;

/// Gives every placed handle entity (net, initial curve, refined cell,
/// mirrored copy) an arrow entity with an empty gizmo of its own.
fn attach(mut commands: Commands, mut assets: ResMut<Assets<GizmoAsset>>, bare: Bare) {
    for (h, initial) in &bare {
        // the initial curve's arrows: over the surface, a little wider
        let (width, depth_bias) = (width(initial, false), if initial { -1.0 } else { 0.0 });
        commands.spawn((
            ArrowOf(h),
            Gizmo {
                handle: assets.add(GizmoAsset::new()),
                line_config: GizmoLineConfig { width, ..default() },
                depth_bias,
            },
            ArrowLook::default(),
        ));
    }
}

/// What an arrow's look is read from.
#[derive(bevy::ecs::system::SystemParam)]
struct LookInputs<'w> {
    settings: Res<'w, HandleSettings>,
    selection: Res<'w, Selection>,
    drag: Res<'w, Drag>,
    mode: Res<'w, State<EditorMode>>,
    layout: Res<'w, HandleLayout>,
}

impl LookInputs<'_> {
    /// Whether any arrow's look may have changed since `active` was the
    /// handle shown as active.
    fn changed(&self, active: Option<HandleId>) -> bool {
        self.settings.is_changed()
            || self.selection.is_changed()
            || self.mode.is_changed()
            || self.layout.is_changed()
            || active != self.active()
    }

    /// The handle drawn as the active one: the dragged, else the primary.
    fn active(&self) -> Option<HandleId> {
        self.drag
            .0
            .as_ref()
            .map(|d| d.handle)
            .or(self.selection.primary())
    }

    /// The look of handle `id` (`None`: a mirrored copy) placed as `a`, a
    /// handle of a patch in `role`.
    fn look(&self, id: Option<HandleId>, a: &Handle, role: PatchRole) -> ArrowLook {
        let s = &*self.settings;
        let edit = self.layout.edit_depth;
        let streamline = *self.mode.get() == EditorMode::Streamline;
        let thin = role == PatchRole::Dimmed;
        let picked = |base: Color| {
            if thin {
                // the selection and the hover name the active patch's handles
                base.with_alpha(DIMMED_ALPHA)
            } else if Some(a.id) == self.active() {
                SELECTED
            } else if Some(a.id) == self.selection.hover {
                HOVER
            } else if self.selection.contains(a.id) {
                GROUP
            } else {
                base
            }
        };
        let (color, shown) = match id {
            None if thin => (MIRRORED.with_alpha(DIMMED_ALPHA), s.controls || edit == 0),
            None => (MIRRORED, s.controls || edit == 0),
            Some(id) if !id.is_surface() => (picked(CYAN), s.initial),
            Some(id) if id.level() == 0 => (
                if edit == 0 || thin {
                    picked(YELLOW)
                } else {
                    YELLOW
                },
                s.controls || edit == 0,
            ),
            Some(_) => (picked(RED), edit > 0 && s.refined && s.shows(a)),
        };
        ArrowLook {
            color,
            shown: shown && streamline && role != PatchRole::Hidden,
            thin,
        }
    }
}

/// A placed handle entity as its arrow is drawn from it.
type Drawn<'w, 's> = Query<
    'w,
    's,
    (
        Ref<'static, Placed>,
        Option<&'static HandleId>,
        Option<&'static MirroredHandle>,
        Option<&'static PatchRole>,
        Has<InitialHandle>,
    ),
>;

/// The arrows of handle entities that moved or changed role.
type Moved<'w, 's> = Query<'w, 's, &'static ArrowDrawn, Or<(Changed<Placed>, Changed<PatchRole>)>>;

/// Redraws the arrows whose handle moved or whose look changed (a turn at
/// edit depth 0 redraws its row's arrows; a selection, the two arrows whose
/// colour changed; a patch hidden or shown, its arrows), and only those.
#[allow(clippy::too_many_arguments)]
fn redraw(
    meter: Res<crate::ecs::meter::CpuMeter>,
    inputs: LookInputs,
    handles: Drawn,
    moved: Moved,
    added: Query<(), Added<ArrowOf>>,
    mut arrows: Query<(Entity, &ArrowOf, &mut ArrowLook, &mut Gizmo)>,
    mut assets: ResMut<Assets<GizmoAsset>>,
    mut redraws: ResMut<ArrowRedraws>,
    mut shown_active: Local<Option<HandleId>>,
) {
    let _meter = meter.start();
    let everything = inputs.changed(*shown_active) || !added.is_empty();
    *shown_active = inputs.active();
    let candidates: Vec<Entity> = if everything {
        arrows.iter().map(|(e, ..)| e).collect()
    } else {
        moved.iter().flat_map(|d| d.0.iter().copied()).collect()
    };
    let mut n = 0;
    for v in candidates {
        let Ok((_, of, mut look, mut gizmo)) = arrows.get_mut(v) else {
            continue;
        };
        let Ok((placed, id, copy, role, initial)) = handles.get(of.0) else {
            continue;
        };
        let Some(shown_id) = id.copied().or(copy.map(|m| m.of)) else {
            continue;
        };
        let a = placed.handle(shown_id);
        let new = inputs.look(id.copied(), &a, role.copied().unwrap_or_default());
        if *look == new && !placed.is_changed() {
            continue;
        }
        if *look != new {
            *look = new;
        }
        let w = width(initial, new.thin);
        if gizmo.line_config.width != w {
            gizmo.line_config.width = w;
        }
        let Some(mut asset) = assets.get_mut(&gizmo.handle) else {
            continue;
        };
        asset.clear();
        if new.shown {
            arrow(&mut asset, &a, new.color);
        }
        n += 1;
    }
    redraws.set_if_neq(ArrowRedraws(n));
}

/// The initial curve itself (the first patch's), over the surface: faint
/// while a joined patch is the active one, not drawn while the first patch
/// is hidden.
fn draw_curve(
    meter: Res<crate::ecs::meter::CpuMeter>,
    patch: crate::ecs::patch::PatchRef,
    settings: Res<HandleSettings>,
    layout: Res<HandleLayout>,
    hidden: Query<(), With<crate::ecs::joined::PatchHidden>>,
    mut initial: Gizmos<InitialGizmos>,
) {
    let _meter = meter.start();
    if settings.initial && !hidden.contains(patch.entity()) {
        let curve = patch.design().initial();
        let line: Vec<Vec3> = curve.polyline(96).into_iter().map(to_view).collect();
        let alpha = if layout.active_joined {
            DIMMED_ALPHA * 0.6
        } else {
            0.6
        };
        initial.linestrip(line, CYAN.with_alpha(alpha));
    }
}

/// A shaft and a head whose shape follows the column index: cone, ball, cross, ring.
fn arrow(gizmos: &mut GizmoAsset, a: &Handle, color: Color) {
    let base = to_view(a.base);
    let tip = to_view(a.tip());
    let dir = to_view(a.dir).normalize_or(Vec3::X);
    let head = (a.length as f32) * 0.22;
    match a.id.col % 4 {
        0 => {
            gizmos.arrow(base, tip, color).with_tip_length(head);
        }
        1 => {
            gizmos.line(base, tip, color);
            gizmos
                .sphere(Isometry3d::from_translation(tip), head * 0.45, color)
                .resolution(10);
        }
        2 => {
            gizmos.line(base, tip, color);
            let side = dir.any_orthonormal_vector();
            let other = dir.cross(side);
            for v in [side, other, dir] {
                gizmos.line(tip - v * head * 0.5, tip + v * head * 0.5, color);
            }
        }
        _ => {
            gizmos.line(base, tip, color);
            let iso = Isometry3d::new(tip, Quat::from_rotation_arc(Vec3::Z, dir));
            gizmos.circle(iso, head * 0.5, color).resolution(12);
        }
    }
}

/// Column numbers at the control arrows' tips, and the selected handle's index.
fn labels(
    meter: Res<crate::ecs::meter::CpuMeter>,
    mut contexts: EguiContexts,
    arrows: HandleQuery,
    settings: Res<HandleSettings>,
    selection: Res<Selection>,
    camera: Query<(&Camera, &GlobalTransform), With<MainCamera>>,
) -> Result {
    let _meter = meter.start();
    let Ok((camera, gt)) = camera.single() else {
        return Ok(());
    };
    if arrows.active_hidden() {
        return Ok(());
    }
    let ctx = contexts.ctx_mut()?;
    let painter = ctx.layer_painter(egui::LayerId::new(
        egui::Order::Background,
        egui::Id::new("arrow_labels"),
    ));
    let clip = camera.logical_viewport_rect().map(|r| {
        egui::Rect::from_min_max(egui::pos2(r.min.x, r.min.y), egui::pos2(r.max.x, r.max.y))
    });
    let painter = match clip {
        Some(c) => painter.with_clip_rect(c),
        None => painter,
    };
    let put = |p: DVec3, text: String, color: egui::Color32| {
        if let Ok(v) = camera.world_to_viewport(gt, to_view(p)) {
            painter.text(
                egui::pos2(v.x + 4.0, v.y - 4.0),
                egui::Align2::LEFT_BOTTOM,
                text,
                egui::FontId::proportional(11.0),
                color,
            );
        }
    };
    if settings.labels && (settings.controls || arrows.edit_depth() == 0) {
        for a in arrows.controls().filter(|a| a.id.row == 0) {
            put(
                a.tip(),
                a.id.col.to_string(),
                egui::Color32::from_rgb(255, 217, 26),
            );
        }
    }
    if settings.initial && settings.labels {
        for a in arrows.initial() {
            put(
                a.tip(),
                format!("i{}", a.id.col),
                egui::Color32::from_rgb(51, 217, 242),
            );
        }
    }
    if let Some(a) = selection.primary().and_then(|h| arrows.find(h)) {
        let text = if a.id.is_surface() {
            format!("({}, {}) L{}", a.id.row, a.id.col, a.level())
        } else {
            format!("initial {}", a.id.col)
        };
        put(a.tip(), text, egui::Color32::WHITE);
    }
    Ok(())
}
