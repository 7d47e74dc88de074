//! Screenshot mode: set up the view asked for (a panel open, an analysis
//! display, a selected handle), render a few frames after the first build,
//! save the primary window to a PNG, exit.

use super::analysis::{AnalysisSettings, SurfaceMode};
use super::panels::{PanelName, UiState};
use super::picking::Selection;
use super::surface::ShownSurface;
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
        }
    }
}

#[derive(Resource, Default)]
struct ShotProgress {
    frame: u32,
    requested: bool,
    captured: Option<u32>,
}

pub struct ScreenshotPlugin;

impl Plugin for ScreenshotPlugin {
    fn build(&self, app: &mut App) {
        app.init_resource::<ShotProgress>()
            .add_systems(
                Startup,
                set_up_view.run_if(resource_exists::<ScreenshotRequest>),
            )
            .add_systems(Last, drive.run_if(resource_exists::<ScreenshotRequest>));
    }
}

fn set_up_view(
    req: Res<ScreenshotRequest>,
    mut ui: ResMut<UiState>,
    mut analysis: ResMut<AnalysisSettings>,
    mut selection: ResMut<Selection>,
) {
    if let Some(p) = req.panel {
        ui.open = vec![p];
        ui.force = true;
    }
    if let Some(m) = req.analysis {
        analysis.mode = m;
    }
    analysis.comb |= req.comb;
    if req.select.is_some() {
        selection.handle = req.select;
    }
}

fn drive(
    mut commands: Commands,
    req: Res<ScreenshotRequest>,
    shown: Res<ShownSurface>,
    mut p: ResMut<ShotProgress>,
    mut exit: MessageWriter<AppExit>,
) {
    p.frame += 1;
    if p.frame > req.frames + 600 {
        error!("screenshot: no frame was captured after {} frames", p.frame);
        exit.write(AppExit::error());
        return;
    }
    if shown.generation == 0 {
        return; // not built yet
    }
    if !p.requested && p.frame >= req.frames {
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
        exit.write(AppExit::Success);
    }
}
