//! Screenshot mode: render a few frames, save the primary window to a PNG, exit.

use super::state::DesignState;
use bevy::prelude::*;
use bevy::render::view::screenshot::{Screenshot, ScreenshotCaptured, save_to_disk};
use std::path::PathBuf;

/// Asks the editor to save a screenshot and exit.
#[derive(Resource, Clone)]
pub struct ScreenshotRequest {
    /// Where the PNG goes.
    pub path: PathBuf,
    /// Frames rendered after the first successful build before the capture
    /// (lets the mesh upload and egui lay out; llvmpipe needs a few).
    pub frames: u32,
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
            .add_systems(Last, drive.run_if(resource_exists::<ScreenshotRequest>));
    }
}

fn drive(
    mut commands: Commands,
    req: Res<ScreenshotRequest>,
    state: Res<DesignState>,
    mut p: ResMut<ShotProgress>,
    mut exit: MessageWriter<AppExit>,
) {
    if state.built.is_none() && state.error.is_none() {
        return;
    }
    p.frame += 1;
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
    if p.frame > req.frames + 600 {
        error!("screenshot: no frame was captured after 600 frames");
        exit.write(AppExit::error());
    }
}
