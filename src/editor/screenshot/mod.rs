//! Screenshot mode: set up the view asked for (a panel open, an analysis
//! display, a selected handle), render a few frames after the first build,
//! save the primary window to a PNG, exit. For GUI tests it also writes
//! where the selected handle and the patches are on screen while it runs
//! (`positions`) and, on exit, a report of the model and the views
//! (`report`).

mod positions;
mod report;

use super::handles::sphere_view::SphereCamera;
use super::interaction::{HandleId, HandleQuery, MainCamera, Selection};
use super::panels::{PanelName, UiState};
use super::surface::analysis_display::{AnalysisSettings, SurfaceMode};
use super::surface::shaded::ShownSurface;
use bevy::prelude::*;
use bevy::render::view::screenshot::{Screenshot, ScreenshotCaptured, save_to_disk};
use positions::{write_handle_position, write_patch_positions};
use report::ReportSources;
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
pub(super) struct ShotProgress {
    pub(super) frame: u32,
    pub(super) requested: bool,
    pub(super) captured: Option<u32>,
    pub(super) position_written: bool,
    /// What `REPORT.at` holds ([`ScreenshotRequest::follow`]).
    pub(super) position_text: String,
    /// `REPORT.patches` is written.
    pub(super) patches_written: bool,
    pub(super) held: u32,
    /// Frames drawn while work ran off the frame (opening a mesh).
    pub(super) busy_frames: u32,
    /// The report's `shown_gap`, once measured.
    pub(super) shown_gap: Option<f64>,
    /// Frames in a row in which the render world had no pipeline left to
    /// compile.
    pub(super) settled: u32,
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
                (report::measure_shown_gap, drive)
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

/// Counts the frames, writes the positions, takes the picture when the
/// view is ready, then writes the report and exits.
#[allow(clippy::too_many_arguments)]
fn drive(
    mut commands: Commands,
    req: Res<ScreenshotRequest>,
    shown: Res<ShownSurface>,
    mut p: ResMut<ShotProgress>,
    mut exit: MessageWriter<AppExit>,
    selection: Res<Selection>,
    arrows: HandleQuery,
    camera: Query<(&Camera, &GlobalTransform), With<MainCamera>>,
    sphere: Query<(&Camera, &GlobalTransform), With<SphereCamera>>,
    pending: Res<PendingPipelines>,
    sources: ReportSources,
) {
    p.frame += 1;
    let busy = sources.mesh.busy();
    if busy {
        p.busy_frames += 1;
    }
    // GUI tests: hold the capture until their script says it is done, and
    // until work off the frame (opening a mesh) has finished
    let waiting = (req.wait_for.as_ref().is_some_and(|f| !f.exists()) || busy) && p.frame < 20_000;
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
        p.patches_written = write_patch_positions(&req, &sources.patches, &camera);
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
            report::write(path, &sources, &selection, &p);
        }
        exit.write(AppExit::Success);
    }
}
