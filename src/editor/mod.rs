//! The interactive editor: a Bevy window with an egui panel over the 3D view.
//! The top-level [`EditorPlugin`] only composes one plugin per feature.

mod camera;
mod panel;
mod screenshot;
mod state;
mod view;

use bevy::prelude::*;
use bevy::window::WindowResolution;
pub use screenshot::ScreenshotRequest;
pub use state::DesignState;
use streamline_kernel::Design;

/// How to open the editor.
pub struct EditorOptions {
    /// The design to open.
    pub design: Design,
    /// The design's name, shown in the title.
    pub name: String,
    /// Display depth to start at.
    pub depth: u32,
    /// Window size in logical pixels.
    pub size: (u32, u32),
    /// Take a screenshot and exit instead of staying open.
    pub screenshot: Option<ScreenshotRequest>,
}

/// Composes the editor's feature plugins.
pub struct EditorPlugin;

impl Plugin for EditorPlugin {
    fn build(&self, app: &mut App) {
        app.add_plugins((
            state::DesignStatePlugin,
            view::SurfaceViewPlugin,
            camera::OrbitCameraPlugin,
            panel::PanelPlugin,
            screenshot::ScreenshotPlugin,
        ));
    }
}

/// Why the editor could not start.
#[derive(Debug)]
pub struct NoDisplay;

impl std::fmt::Display for NoDisplay {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "no display found (DISPLAY and WAYLAND_DISPLAY are unset): run the editor on a desktop, \
             or under a virtual display with `xvfb-run -a -s \"-screen 0 1280x800x24\" streamline-studio` \
             (bash scripts/editor.sh does this), or use the headless subcommands (see --help)"
        )
    }
}

/// Opens the editor window and runs until it is closed.
pub fn run(opts: EditorOptions) -> Result<(), NoDisplay> {
    let has_display = std::env::var_os("DISPLAY").is_some_and(|d| !d.is_empty())
        || std::env::var_os("WAYLAND_DISPLAY").is_some_and(|d| !d.is_empty());
    if !has_display {
        return Err(NoDisplay);
    }
    let title = format!("Streamline Studio — {}", opts.name);
    let mut app = App::new();
    app.add_plugins(DefaultPlugins.set(WindowPlugin {
        primary_window: Some(Window {
            title,
            resolution: WindowResolution::new(opts.size.0, opts.size.1),
            ..default()
        }),
        ..default()
    }))
    .add_plugins(bevy_egui::EguiPlugin::default())
    .insert_resource(ClearColor(Color::srgb(0.16, 0.17, 0.19)))
    .insert_resource(DesignState::new(opts.design, opts.name, opts.depth))
    .add_plugins(EditorPlugin);
    if let Some(req) = opts.screenshot {
        app.insert_resource(req);
    }
    app.run();
    Ok(())
}
