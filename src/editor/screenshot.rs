//! Screenshot mode: set up the view asked for (a panel open, an analysis
//! display, a selected handle), render a few frames after the first build,
//! save the primary window to a PNG, exit.

use super::coords::to_view;
use super::handles::sphere_view::{SphereCamera, SubdividedPoints, cloud_points};
use super::interaction::{HandleId, HandleQuery, MainCamera, Selection};
use super::panels::{PanelName, UiState};
use super::surface::analysis_display::{AnalysisSettings, SurfaceMode};
use super::surface::shaded::{ShownSurface, SurfaceEntity};
use crate::ecs::components::{LevelData, SubdivisionLevel};
use crate::ecs::{History, Model, Stats, SurfaceData};
use bevy::mesh::VertexAttributeValues;
use bevy::prelude::*;
use bevy::render::view::screenshot::{Screenshot, ScreenshotCaptured, save_to_disk};
use std::path::PathBuf;

/// Asks the editor to save a screenshot and exit.
#[derive(Resource, Clone, Debug)]
pub struct ScreenshotRequest {
    /// Where the PNG goes.
    pub path: PathBuf,
    /// Frames rendered after the first build before the capture
    /// (lets the mesh upload and egui lay out; llvmpipe needs a few).
    pub frames: u32,
    /// Open only this panel section.
    pub panel: Option<PanelName>,
    /// Surface display.
    pub analysis: Option<SurfaceMode>,
    /// Draw curvature combs.
    pub comb: bool,
    /// Select this handle `(row, col)`.
    pub select: Option<(usize, usize)>,
    /// Select the initial curve's control tangent `k` instead (`--select iK`).
    pub select_initial: Option<usize>,
    /// Write a JSON report here on exit (for GUI tests), and `REPORT.at` with
    /// the selected handle's shaft midpoint on screen (`x y`) once it is drawn.
    pub report: Option<PathBuf>,
    /// Take the picture only once this file exists (GUI tests create it when
    /// their pointer and keys are done); from `STREAMLINE_STUDIO_SHOT_WAIT`.
    pub wait_for: Option<PathBuf>,
    /// Open this OBJ in mesh mode.
    pub mesh: Option<PathBuf>,
    /// With these Loop boundary rules (else the panel's default, edge-and-corner).
    pub mesh_boundary: Option<streamline_kernel::loop_subdiv::subdivide::BoundaryRule>,
    /// Start running this script (the picture does not wait for it).
    pub script: Option<PathBuf>,
    /// Keep `REPORT.at` up to date (rewritten, whole, whenever the selected
    /// handle moves on screen: another design opened, the view framed)
    /// instead of writing it once; from `STREAMLINE_STUDIO_SHOT_FOLLOW`.
    pub follow: bool,
}

impl ScreenshotRequest {
    /// A plain screenshot to `path`.
    pub fn new(path: PathBuf) -> Self {
        ScreenshotRequest {
            path,
            frames: std::env::var("STREAMLINE_STUDIO_SHOT_FRAMES")
                .ok()
                .and_then(|v| v.parse().ok())
                .unwrap_or(30),
            panel: None,
            analysis: None,
            comb: false,
            select: None,
            select_initial: None,
            report: None,
            wait_for: std::env::var_os("STREAMLINE_STUDIO_SHOT_WAIT").map(PathBuf::from),
            mesh: None,
            mesh_boundary: None,
            script: None,
            follow: std::env::var_os("STREAMLINE_STUDIO_SHOT_FOLLOW").is_some(),
        }
    }
}

#[derive(Resource, Default)]
struct ShotProgress {
    frame: u32,
    requested: bool,
    captured: Option<u32>,
    position_written: bool,
    /// What `REPORT.at` holds ([`ScreenshotRequest::follow`]).
    position_text: String,
    /// `REPORT.patches` is written.
    patches_written: bool,
    held: u32,
    /// Frames drawn while work ran off the frame (opening a mesh).
    busy_frames: u32,
    /// [`Report::shown_gap`], once measured.
    shown_gap: Option<f64>,
    /// Frames in a row in which the render world had no pipeline left to
    /// compile.
    settled: u32,
}

/// How many render pipelines are still queued or being compiled, counted in
/// the render world each frame. On a software renderer (llvmpipe compiles
/// every shader on the CPU) a loaded machine can take longer than the
/// request's frame count to compile them, and a frame drawn before then
/// shows an empty 3D view: the capture waits for them.
#[derive(Resource, Clone, Default)]
struct PendingPipelines(std::sync::Arc<std::sync::atomic::AtomicUsize>);

/// Frames without a pending pipeline before the capture (a new mesh or
/// material is specialised a frame or two after it appears).
const SETTLED_FRAMES: u32 = 5;

fn count_pending_pipelines(
    cache: Res<bevy::render::render_resource::PipelineCache>,
    pending: Res<PendingPipelines>,
) {
    use bevy::render::render_resource::CachedPipelineState;
    let n = cache
        .pipelines()
        .filter(|p| {
            matches!(
                p.state,
                CachedPipelineState::Queued | CachedPipelineState::Creating(_)
            )
        })
        .count();
    pending.0.store(n, std::sync::atomic::Ordering::Relaxed);
}

pub struct ScreenshotPlugin;

impl Plugin for ScreenshotPlugin {
    fn build(&self, app: &mut App) {
        let pending = PendingPipelines::default();
        if let Some(render) = app.get_sub_app_mut(bevy::render::RenderApp) {
            render.insert_resource(pending.clone()).add_systems(
                bevy::render::Render,
                count_pending_pipelines.in_set(bevy::render::RenderSystems::Cleanup),
            );
        }
        app.insert_resource(pending)
            .init_resource::<ShotProgress>()
            .add_systems(
                Startup,
                set_up_view.run_if(resource_exists::<ScreenshotRequest>),
            )
            .add_systems(
                Last,
                (measure_shown_gap, drive)
                    .chain()
                    .run_if(resource_exists::<ScreenshotRequest>),
            );
    }
}

fn set_up_view(
    req: Res<ScreenshotRequest>,
    mut mesh: ResMut<super::loop_mesh::MeshView>,
    mut ui: ResMut<UiState>,
    mut analysis: ResMut<AnalysisSettings>,
    mut selection: ResMut<Selection>,
    mut script: ResMut<crate::ecs::runner::ScriptRun>,
    patch: crate::ecs::patch::PatchRef,
) {
    if let Some(path) = &req.script {
        script.input = path.display().to_string();
        script.start(path.clone());
    }
    if let Some(p) = req.panel {
        ui.open = vec![p];
        ui.force = true;
    }
    if let Some(m) = req.analysis {
        analysis.mode = m;
    }
    analysis.comb |= req.comb;
    if let Some((row, col)) = req.select {
        selection.select(HandleId::tangent(patch.structure().edit_depth, row, col));
    }
    if let Some(b) = req.mesh_boundary {
        mesh.settings.boundary = b;
    }
    if let Some(k) = req.select_initial {
        selection.select(HandleId::initial(k));
    }
    if let Some(path) = &req.mesh {
        mesh.text.input = path.display().to_string();
        mesh.open(path.clone());
    }
}

/// What a GUI test reads back after the run.
#[derive(serde::Serialize)]
struct Report {
    /// The file the scene was opened from or saved to.
    path: Option<PathBuf>,
    /// The scene's name.
    scene: String,
    undo: usize,
    redo: usize,
    unsaved: bool,
    selection: Option<(usize, usize)>,
    last_edit: String,
    net: Vec<[f64; 3]>,
    cols: usize,
    /// The initial curve's control tangents.
    initial: Vec<[f64; 3]>,
    /// The model's systems in frames with an edit: last and largest (ms).
    model_ms: (f64, f64),
    /// All our systems (model and editor) in frames with an edit: last and largest (ms).
    ours_ms: (f64, f64),
    /// Display depth.
    depth: u32,
    /// Per system over frames with an edit: total ms, largest ms, frames
    /// (`STREAMLINE_STUDIO_METER_DETAIL=1`).
    detail: Vec<(String, f64, f64, u32)>,
    /// The dearest frame with an edit, system by system (ms), with the detail.
    worst_frame: Vec<(String, f64)>,
    /// All our systems in each frame with an edit (ms), oldest first.
    ours_frames: Vec<f64>,
    /// With the detail: page faults and involuntary context switches in our
    /// systems in each of those frames.
    frame_faults: Vec<[u64; 2]>,
    /// With the detail: a fixed piece of work's CPU µs at four points of
    /// each of those frames (how fast the machine was).
    frame_probe: Vec<Vec<f64>>,
    /// Frames drawn while a mesh was being opened off the frame.
    busy_frames: u32,
    /// The Loop mesh panel's last error, if any.
    mesh_error: Option<String>,
    /// The largest gap between what the views show and the model, when the
    /// picture was taken: the surface mesh's positions and normals against
    /// the model's points and normals, the sphere view's points against the
    /// display depth's tangents it shows (`sphere_view::cloud_points`; each
    /// made `f32` as the views make it; `0`
    /// when every row and column that edits rewrote in place got there).
    shown_gap: Option<f64>,
    /// A document's patches as drawn: name, shown, vertices of its mesh
    /// (0 for the first patch while its incremental mesh shows it).
    patches: Vec<(String, bool, usize)>,
    /// The active patch's name.
    active_patch: Option<String>,
    /// The seams as drawn: A, B, edge, continuity, verdict, gap, angle (°),
    /// curvature deviation (`NaN` when not measured).
    seams: Vec<SeamShown>,
    /// The map to the reference (Analysis ▸ to reference), once measured.
    reference: Option<ReferenceShown>,
}

/// The map to the reference in the report: its largest and mean distance,
/// its tolerance, and its last measurement's points, whether it was made
/// during a drag, and how many there were
/// ([`super::surface::reference_map::ReferenceField`]).
#[derive(serde::Serialize)]
struct ReferenceShown {
    max: f64,
    mean: f64,
    tolerance: f64,
    measured: usize,
    live: bool,
    generation: u64,
}

/// A seam in the report: A, B, edge, continuity, verdict, gap, angle (°),
/// curvature deviation.
type SeamShown = (String, String, String, String, String, f64, f64, f64);

/// The patches and seams a GUI test reads back.
type PatchReport<'w, 's> = (
    Res<'w, super::seams::Seams>,
    Res<'w, super::surface::patches::PatchMeshes>,
    Res<'w, crate::ecs::joined::ActivePatch>,
    Query<
        'w,
        's,
        (
            Entity,
            &'static crate::ecs::joined::PatchSlot,
            Has<crate::ecs::joined::PatchHidden>,
            Option<&'static crate::ecs::joined::PatchSurface>,
        ),
    >,
);

fn write_report(path: &std::path::Path, r: &Report) {
    if let Ok(text) = serde_json::to_string_pretty(r) {
        let _ = std::fs::write(path, text);
    }
}

/// Writes `REPORT.patches`: for each patch drawn from its stack, its name
/// and its middle vertex in window pixels (`name x y` a line), where a GUI
/// test clicks to choose it.
fn write_patch_positions(
    req: &ScreenshotRequest,
    (_, patch_meshes, _, slots): &PatchReport,
    camera: &Query<(&Camera, &GlobalTransform), With<MainCamera>>,
) -> bool {
    let Some(report) = &req.report else {
        return true;
    };
    let Ok((cam, gt)) = camera.single() else {
        return false;
    };
    let mut text = String::new();
    for (e, slot, _, surface) in slots {
        let Some((points, _)) = surface.and_then(|s| patch_meshes.mesh(e, s)) else {
            continue;
        };
        let Some(mid) = points.data().get(points.data().len() / 2) else {
            continue;
        };
        if let Ok(q) = cam.world_to_viewport(gt, to_view(*mid)) {
            text += &format!("{} {} {}\n", slot.name, q.x.round(), q.y.round());
        }
    }
    let mut at = report.clone().into_os_string();
    at.push(".patches");
    std::fs::write(at, text).is_ok()
}

/// Writes `REPORT.at`: the selected handle's shaft midpoint in window
/// pixels, unless it holds that already (`last`, what it holds).
fn write_handle_position(
    req: &ScreenshotRequest,
    selection: &Selection,
    arrows: &HandleQuery,
    camera: &Query<(&Camera, &GlobalTransform), With<MainCamera>>,
    sphere: &Query<(&Camera, &GlobalTransform), With<SphereCamera>>,
    last: &mut String,
) -> bool {
    let (Some(report), Some(h)) = (&req.report, selection.primary()) else {
        return true;
    };
    let (Some(a), Ok((cam, gt))) = (arrows.find(h), camera.single()) else {
        return false;
    };
    let mid = a.base + a.dir * (a.length * 0.6);
    let Ok(p) = cam.world_to_viewport(gt, to_view(mid)) else {
        return false;
    };
    // second line: the handle's point on the sphere view
    let Ok((scam, sgt)) = sphere.single() else {
        return false;
    };
    let Ok(q) = scam.world_to_viewport(sgt, to_view(a.dir)) else {
        return false;
    };
    let mut at = report.clone().into_os_string();
    at.push(".at");
    let text = format!(
        "{} {}\n{} {}\n",
        p.x.round(),
        p.y.round(),
        q.x.round(),
        q.y.round()
    );
    if text == *last {
        return true;
    }
    // whole or not at all: a script may be reading it
    let mut tmp = at.clone();
    tmp.push(".tmp");
    let ok = std::fs::write(&tmp, &text).is_ok() && std::fs::rename(&tmp, &at).is_ok();
    if ok {
        *last = text;
    }
    ok
}

#[allow(clippy::too_many_arguments)]
fn drive(
    mut commands: Commands,
    req: Res<ScreenshotRequest>,
    shown: Res<ShownSurface>,
    mut p: ResMut<ShotProgress>,
    mut exit: MessageWriter<AppExit>,
    (model, patch): (Res<Model>, crate::ecs::patch::PatchRef),
    history: Res<History>,
    stats: Res<Stats>,
    timing: Res<super::view::frame_timing::FrameTiming>,
    selection: Res<Selection>,
    arrows: HandleQuery,
    camera: Query<(&Camera, &GlobalTransform), With<MainCamera>>,
    sphere: Query<(&Camera, &GlobalTransform), With<SphereCamera>>,
    (mesh, reference): (
        Res<super::loop_mesh::MeshView>,
        Res<super::surface::reference_map::ReferenceField>,
    ),
    pending: Res<PendingPipelines>,
    patch_report: PatchReport,
) {
    p.frame += 1;
    if mesh.busy() {
        p.busy_frames += 1;
    }
    // GUI tests: hold the capture until their script says it is done, and
    // until work off the frame (opening a mesh) has finished
    let waiting =
        (req.wait_for.as_ref().is_some_and(|f| !f.exists()) || mesh.busy()) && p.frame < 20_000;
    if waiting {
        p.held += 1;
    }
    if p.frame > req.frames + p.held + 600 {
        error!("screenshot: no frame was captured after {} frames", p.frame);
        exit.write(AppExit::error());
        return;
    }
    if !shown.built {
        return; // not built yet
    }
    if (!p.position_written || req.follow) && p.frame >= 10 {
        let mut text = std::mem::take(&mut p.position_text);
        let written = write_handle_position(&req, &selection, &arrows, &camera, &sphere, &mut text);
        p.position_written |= written;
        p.position_text = text;
    }
    if !p.patches_written && p.frame >= 10 {
        p.patches_written = write_patch_positions(&req, &patch_report, &camera);
    }
    // and until the render world has compiled its pipelines
    if pending.0.load(std::sync::atomic::Ordering::Relaxed) == 0 {
        p.settled += 1;
    } else {
        p.settled = 0;
    }
    let compiling = p.settled < SETTLED_FRAMES && p.frame < 20_000;
    if compiling && !p.requested && p.frame >= req.frames {
        p.held += 1;
    }
    if !p.requested && !waiting && !compiling && p.frame >= req.frames {
        p.requested = true;
        commands
            .spawn(Screenshot::primary_window())
            .observe(save_to_disk(req.path.clone()))
            .observe(|_: On<ScreenshotCaptured>, mut p: ResMut<ShotProgress>| {
                p.captured = Some(p.frame)
            });
    }
    if let Some(at) = p.captured
        && p.frame > at + 2
    {
        if let Some(path) = &req.report {
            let (seams, patch_meshes, active, slots) = &patch_report;
            // the control net, read from its handle entities
            let net = patch.net();
            write_report(
                path,
                &Report {
                    path: model.path.clone(),
                    scene: patch.name().to_string(),
                    undo: history.undo_len(),
                    redo: history.redo_len(),
                    unsaved: model.unsaved,
                    selection: selection.cell(),
                    last_edit: stats.last.edit.clone(),
                    net: net.data().iter().map(|v| v.to_array()).collect(),
                    cols: net.cols(),
                    initial: patch
                        .design()
                        .initial()
                        .qi()
                        .tangents()
                        .iter()
                        .map(|v| v.to_array())
                        .collect(),
                    model_ms: (timing.last_ms, timing.max_ms),
                    ours_ms: (timing.ours_last_ms, timing.ours_max_ms),
                    depth: patch.structure().display_depth,
                    detail: timing
                        .detail
                        .iter()
                        .map(|(k, v)| (k.clone(), v.0, v.1, v.2))
                        .collect(),
                    worst_frame: timing.worst_frame.clone(),
                    ours_frames: timing.recent_frames.0.iter().copied().collect(),
                    frame_faults: timing.recent_detail.iter().map(|d| d.faults).collect(),
                    frame_probe: timing
                        .recent_detail
                        .iter()
                        .map(|d| d.probe.clone())
                        .collect(),
                    busy_frames: p.busy_frames,
                    mesh_error: mesh.text.error.clone(),
                    shown_gap: p.shown_gap,
                    patches: {
                        let mut v: Vec<_> = slots.iter().collect();
                        v.sort_by_key(|r| r.1.index);
                        v.into_iter()
                            .map(|(e, slot, hidden, surface)| {
                                let n = surface
                                    .and_then(|s| patch_meshes.mesh(e, s))
                                    .map_or(0, |(p, _)| p.data().len());
                                (slot.name.clone(), !hidden, n)
                            })
                            .collect()
                    },
                    active_patch: slots
                        .iter()
                        .find(|r| match active.0 {
                            Some(e) => r.0 == e,
                            None => r.1.index == 0,
                        })
                        .map(|r| r.1.name.clone()),
                    seams: seams
                        .lines
                        .iter()
                        .map(|l| {
                            let r = l.report.as_ref();
                            (
                                l.a_name.clone(),
                                l.b_name.clone(),
                                l.edge.name().to_string(),
                                l.continuity.name().to_string(),
                                l.verdict.name().to_string(),
                                r.map_or(f64::NAN, |r| r.gap),
                                r.map_or(f64::NAN, |r| r.angle_deg),
                                r.map_or(f64::NAN, |r| r.curvature_dev),
                            )
                        })
                        .collect(),
                    reference: reference.values.as_ref().map(|_| ReferenceShown {
                        max: reference.distances.max,
                        mean: reference.distances.mean,
                        tolerance: reference.tolerance,
                        measured: reference.measured,
                        live: reference.live,
                        generation: reference.generation,
                    }),
                },
            );
        }
        exit.write(AppExit::Success);
    }
}

/// Measures [`Report::shown_gap`] once the picture is taken (reports only).
#[allow(clippy::too_many_arguments)]
fn measure_shown_gap(
    req: Res<ScreenshotRequest>,
    mut p: ResMut<ShotProgress>,
    patch: crate::ecs::patch::PatchRef,
    data: Res<SurfaceData>,
    meshes: Res<Assets<Mesh>>,
    (surface, shown): (Query<&Mesh3d, With<SurfaceEntity>>, Res<ShownSurface>),
    points: Query<&Mesh3d, With<SubdividedPoints>>,
    levels: Query<(&SubdivisionLevel, &LevelData)>,
) {
    if req.report.is_none() || p.captured.is_none() || p.shown_gap.is_some() {
        return;
    }
    let attr = |m: &Mesh3d, a| f32x3(&meshes, m, a);
    let mut worst = 0.0f64;
    // (a G2 run's first patch, shaded, shows its stack's cut instead)
    if let Ok(m) = surface.single()
        && !shown.from_stack
    {
        let (Some(pos), Some(nrm)) = (
            attr(m, Mesh::ATTRIBUTE_POSITION),
            attr(m, Mesh::ATTRIBUTE_NORMAL),
        ) else {
            return;
        };
        worst = worst.max(gap(pos, data.points.data().iter().map(|q| q.as_vec3())));
        worst = worst.max(gap(nrm, data.normals.iter().map(|q| q.as_vec3())));
    }
    let depth = patch.structure().display_depth;
    if let (Ok(m), Some((_, level))) = (points.single(), levels.iter().find(|(l, _)| l.0 == depth))
        && let Some(pos) = attr(m, Mesh::ATTRIBUTE_POSITION)
    {
        // the cloud shows at most a depth-4 density (`cloud_points`)
        let (rows, cols) = level.0.shape();
        let want: Vec<Vec3> = cloud_points(level.0.tangents.data(), rows, cols, depth)
            .map(to_view)
            .collect();
        worst = worst.max(gap(pos, want.into_iter()));
    }
    p.shown_gap = Some(worst);
}

/// A mesh's `Float32x3` attribute, if it has one.
fn f32x3<'a>(
    meshes: &'a Assets<Mesh>,
    m: &Mesh3d,
    attribute: bevy::mesh::MeshVertexAttribute,
) -> Option<&'a [[f32; 3]]> {
    match meshes.get(&m.0)?.attribute(attribute)? {
        VertexAttributeValues::Float32x3(v) => Some(v),
        _ => None,
    }
}

/// The largest coordinate gap between what a view shows and what it should
/// (`f64::MAX` when their sizes differ).
fn gap(shown: &[[f32; 3]], want: impl ExactSizeIterator<Item = Vec3>) -> f64 {
    if shown.len() != want.len() {
        return f64::MAX;
    }
    shown
        .iter()
        .zip(want)
        .map(|(a, b)| (Vec3::from_array(*a) - b).abs().max_element() as f64)
        .fold(0.0, f64::max)
}
