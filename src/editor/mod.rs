//! The interactive editor: a Bevy window with egui panels over the 3D view,
//! built on the ECS layer ([`crate::ecs::ModelPlugin`]): every change it makes
//! is an [`crate::ecs::EditMessage`], the same that scripts send. The
//! top-level [`EditorPlugin`] only composes one plugin per feature, around
//! the [`interaction`] core that owns handles, selection, the drag and the
//! editor's mode, and whose [`interaction::EditorSet`]s order the rest.
//!
//! The features stand in rooms by concern, each importing only the rooms
//! below it (no circle: `tests/module_graph.rs`). From the ground up: `coords`
//! (the kernel's axes and Bevy's) and the [`interaction`] core; `surface`
//! (the shaded surface and its analysis displays); [`loop_mesh`] (the Loop
//! mesh mode); [`files`] (the file dialogs: open, save, export, new design,
//! import, reference, the file browser); `handles`
//! (arrows, picking, box selection, the sphere view, structure edits) and
//! [`view`] (camera, pacing, anti-aliasing, frame timing, overlay); `seams`
//! (a document's several patches: seams, their streamlines, picking a patch); `panels`;
//! then the screenshot run (`screenshot`) and [`autosave`], which read the rest.

pub mod autosave;
mod coords;
pub mod files;
mod handles;
pub mod interaction;
pub mod loop_mesh;
mod panels;
mod screenshot;
mod seams;
mod surface;
pub mod view;

use crate::ecs::{Model, ModelPlugin};
use crate::scene::Document;
use bevy::prelude::*;
use bevy::window::WindowResolution;
pub use files::open_save::EditorDirs;
pub use interaction::Selection;
pub use panels::{PanelName, UiState};
pub use screenshot::ScreenshotRequest;
use std::path::PathBuf;
pub use surface::analysis_display::{AnalysisSettings, SurfaceMode};
pub use surface::reference_ghost::{GHOST_SAMPLES, ReferenceGhost, ReferenceGhostPlugin};
pub use surface::reference_map::{ReferenceField, ReferenceMapPlugin};

/// How to open the editor.
pub struct EditorOptions {
    /// The design to open: one patch or several (docs/math.md §11).
    pub document: Document,
    /// The file it came from (`None`: a built-in scene).
    pub path: Option<PathBuf>,
    /// Window size in logical pixels.
    pub size: (u32, u32),
    /// Take a screenshot and exit instead of staying open.
    pub screenshot: Option<ScreenshotRequest>,
    /// Where recent files and the recovery file live.
    pub dirs: EditorDirs,
    /// MSAA samples of the 3D views (`None`: off on a software renderer, 4× on a GPU).
    pub msaa: Option<u32>,
}

/// Composes the editor's feature plugins (the model plugin comes separately).
pub struct EditorPlugin;

impl Plugin for EditorPlugin {
    fn build(&self, app: &mut App) {
        app.add_plugins((
            interaction::InteractionPlugin,
            surface::shaded::SurfacePlugin,
            view::overlay::OverlayPlugin,
            handles::arrows::ArrowsPlugin,
            handles::picking::PickingPlugin,
            handles::sphere_view::SphereViewPlugin,
            view::camera::OrbitCameraPlugin,
            surface::analysis_display::AnalysisPlugin,
            view::antialias::AntiAliasPlugin,
            view::frame_timing::FrameTimingPlugin,
            panels::PanelPlugin,
            files::open_save::FilesPlugin,
            autosave::AutosavePlugin,
            loop_mesh::MeshModePlugin,
            screenshot::ScreenshotPlugin,
        ))
        .add_plugins((
            handles::sphere_dots::SphereDotsPlugin,
            files::new_design::NewDesignPlugin,
            handles::structure::StructurePlugin,
            handles::box_select::BoxSelectPlugin,
            files::file_browser::FileBrowserPlugin,
            files::import::ImportPlugin,
            files::dialogs::DialogsPlugin,
            files::reference::ReferencePlugin,
            surface::patches::PatchSurfacesPlugin,
            surface::maps::MapsPlugin,
            surface::combs::CombsPlugin,
            surface::reference_map::ReferenceMapPlugin,
            surface::reference_ghost::ReferenceGhostPlugin,
            seams::SeamsPlugin,
            view::streamlines::StreamlinesPlugin,
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

/// The message for a machine where the renderer finds no graphics adapter.
pub const NO_ADAPTER: &str = "no usable graphics adapter (Vulkan or OpenGL) was found: install a \
    driver, or Mesa's software Vulkan (Debian: `apt-get install mesa-vulkan-drivers`, which \
    scripts/setup.sh does) and run under `xvfb-run`; the headless subcommands need no graphics \
    (see --help)";

/// Turns the renderer's panic on a machine without a graphics adapter into
/// [`NO_ADAPTER`] and exit code 2; other panics keep the default report.
fn install_adapter_hook() {
    let default = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        let msg = info
            .payload()
            .downcast_ref::<&str>()
            .map(|s| s.to_string())
            .or_else(|| info.payload().downcast_ref::<String>().cloned())
            .unwrap_or_default();
        let lower = msg.to_lowercase();
        if lower.contains("adapter") || lower.contains("unable to find a gpu") {
            eprintln!("streamline-studio: {NO_ADAPTER} (renderer: {msg})");
            std::process::exit(2);
        }
        default(info);
    }));
}

/// Whether the editor lends the kernel its helper thread. The renderer and
/// Bevy's own threads need cores too: with fewer than 4, waking the helper
/// costs more than the half it takes over (on a 2-core VM an interior edit of
/// the car at depth 5 took 1.23 ms of CPU with the helper and 0.96 ms
/// without, and more wall time with it). `STREAMLINE_STUDIO_ONE_THREAD=1`
/// keeps the kernel on one thread anywhere; `=0` lends the helper anyway.
pub fn kernel_helper_wanted(one_thread: Option<&str>, cores: usize) -> bool {
    match one_thread {
        Some("1") => false,
        Some("0") => true,
        _ => cores >= 4,
    }
}

/// Opens the editor window and runs until it is closed.
pub fn run(opts: EditorOptions) -> Result<(), NoDisplay> {
    let has_display = std::env::var_os("DISPLAY").is_some_and(|d| !d.is_empty())
        || std::env::var_os("WAYLAND_DISPLAY").is_some_and(|d| !d.is_empty());
    if !has_display {
        return Err(NoDisplay);
    }
    install_adapter_hook();
    streamline_kernel::parallel::set_enabled(kernel_helper_wanted(
        std::env::var("STREAMLINE_STUDIO_ONE_THREAD")
            .ok()
            .as_deref(),
        std::thread::available_parallelism().map_or(1, usize::from),
    ));
    let title = format!("Streamline Studio — {}", opts.document.name);
    let mut app = App::new();
    app.add_plugins(DefaultPlugins.set(WindowPlugin {
        primary_window: Some(Window {
            title,
            resolution: WindowResolution::new(opts.size.0, opts.size.1),
            ..default()
        }),
        // closing asks about unsaved changes first (files/open_save.rs)
        close_when_requested: false,
        ..default()
    }))
    .add_plugins(bevy_egui::EguiPlugin::default())
    .insert_resource(ClearColor(Color::srgb(0.16, 0.17, 0.19)))
    .add_plugins(ModelPlugin::new(opts.document.patch_scene(0)))
    .add_plugins(crate::ecs::runner::ScriptRunPlugin)
    .insert_resource(opts.dirs)
    .insert_resource(view::antialias::AntiAliasing::new(opts.msaa))
    .add_plugins(view::pacing::PacingPlugin {
        continuous: opts.screenshot.is_some(),
    })
    .add_plugins(EditorPlugin);
    if opts.document.patches.len() > 1
        && let Some(first) = crate::ecs::patch::patch_entity(app.world())
    {
        crate::ecs::joined::spawn_joined(app.world_mut(), &opts.document, first);
    }
    app.world_mut().resource_mut::<Model>().path = opts.path;
    if let Some(req) = opts.screenshot {
        app.insert_resource(req);
    }
    app.run();
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::kernel_helper_wanted;

    #[test]
    fn the_helper_needs_four_cores_unless_told() {
        assert!(!kernel_helper_wanted(None, 2));
        assert!(!kernel_helper_wanted(None, 3));
        assert!(kernel_helper_wanted(None, 4));
        assert!(!kernel_helper_wanted(Some("1"), 16));
        assert!(kernel_helper_wanted(Some("0"), 2));
        // anything else: the default
        assert!(kernel_helper_wanted(Some("yes"), 8));
        assert!(!kernel_helper_wanted(Some(""), 2));
    }
}
