//! The ECS layer (docs/architecture.md, "The shape in one picture"): a
//! patch entity owns its tangent handles (one entity per control tangent of
//! the net, per detail, per control tangent of the initial curve), its
//! subdivision levels and its streamlines ([`patch`]). Edits arrive as
//! [`EditMessage`]s; the edit stage writes the handles' and the patch's
//! components, and only what differs; change detection does the rest:
//! [`patch::track`] turns the changed components into the dirty windows of
//! each level, the blend stage re-blends them, changed streamline
//! components mark what to integrate, and the mesh stage announces each
//! change of the surface as a [`SurfaceChanged`] message, which every reader
//! follows with its own cursor ([`SurfaceChanges`]). Runs headless under
//! `MinimalPlugins` ([`headless_app`]).

pub mod authoring;
mod blend;
pub mod census;
pub mod components;
mod edit;
mod edit_error;
pub mod edit_state;
pub mod exchange;
mod integrate;
pub mod joined;
pub(crate) mod mesh;
pub mod messages;
pub mod meter;
mod output;
pub mod patch;
pub mod playback;
pub mod resources;
pub mod runner;
pub mod vertex_mirror;
pub mod warnings;

use crate::scene::Scene;
use bevy::prelude::*;
pub use edit_error::EditError;
pub use messages::{Edit, EditMessage};
pub use resources::*;

/// The pipeline's phases, run in this order in `Update`.
#[derive(SystemSet, Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ModelSet {
    /// Edit messages write the patch's and its handles' components.
    Edit,
    /// Changed components become dirty windows ([`patch::track`]), which
    /// are re-blended.
    Blend,
    /// Changed streamlines are re-integrated.
    Integrate,
    /// Changed mesh rows are rewritten.
    Mesh,
    /// Saving and exporting.
    Output,
}

/// The model: scene, pipeline, history and stats.
pub struct ModelPlugin {
    /// The scene to start with.
    pub scene: Scene,
    /// Settings (history length).
    pub config: ModelConfig,
}

impl ModelPlugin {
    /// With the default settings.
    pub fn new(scene: Scene) -> Self {
        ModelPlugin {
            scene,
            config: ModelConfig::default(),
        }
    }
}

impl Plugin for ModelPlugin {
    fn build(&self, app: &mut App) {
        app.add_message::<EditMessage>()
            .add_message::<SurfaceChanged>()
            .init_resource::<Model>()
            .insert_resource(self.config.clone())
            .init_resource::<History>()
            .init_resource::<Stats>()
            .init_resource::<meter::CpuMeter>()
            .init_resource::<EditLog>()
            .init_resource::<SurfaceData>()
            .init_resource::<DeferNormals>()
            .init_resource::<warnings::BuildWarnings>()
            .init_resource::<exchange::ExportSettings>()
            .init_resource::<exchange::LastExport>()
            .configure_sets(
                Update,
                (
                    ModelSet::Edit,
                    ModelSet::Blend,
                    ModelSet::Integrate,
                    ModelSet::Mesh,
                    ModelSet::Output,
                )
                    .chain(),
            )
            .add_systems(Update, edit::apply_edits.in_set(ModelSet::Edit))
            .add_systems(
                Update,
                (patch::track::track_handles, blend::reblend)
                    .chain()
                    .in_set(ModelSet::Blend),
            )
            .add_systems(
                Update,
                (integrate::retune, integrate::integrate)
                    .chain()
                    .in_set(ModelSet::Integrate),
            )
            .add_systems(Update, mesh::patch_mesh.in_set(ModelSet::Mesh))
            // after the joined patches' build: every patch's levels are scanned
            .add_systems(
                Update,
                (warnings::find_antipodal_blends, output::write_files)
                    .chain()
                    .in_set(ModelSet::Output),
            )
            .add_plugins(joined::JoinedPlugin);
        patch::spawn_patch(app.world_mut(), &self.scene);
    }
}

/// A windowless app with the model on `scene`, built once (one update run).
pub fn headless_app(scene: Scene) -> App {
    headless_app_with(scene, ModelConfig::default())
}

/// [`headless_app`] with settings.
pub fn headless_app_with(scene: Scene, config: ModelConfig) -> App {
    let mut app = App::new();
    app.add_plugins(MinimalPlugins)
        .add_plugins(ModelPlugin { scene, config });
    // The model's systems run one after another (the sets are chained), so a
    // multi-threaded executor only adds thread hand-offs (~0.3 ms a frame here).
    app.edit_schedule(Update, |s| {
        s.set_executor(bevy::ecs::schedule::SingleThreadedExecutor::new());
    });
    app.update();
    app
}

/// A windowless app with the model on a document of one or more patches
/// (docs/math.md §11), built once: its first patch is a one-patch scene's
/// world ([`headless_app_with`] on [`Document::patch_scene`]`(0)`, with
/// `display_depth` when given), the others are added
/// ([`joined::spawn_joined`]) and built through the kernel's joins. A
/// document of one patch gives exactly [`headless_app_with`]'s world.
pub fn headless_document_app(
    doc: &crate::scene::Document,
    display_depth: Option<u32>,
    config: ModelConfig,
) -> App {
    let mut scene = doc.patch_scene(0);
    if let Some(d) = display_depth {
        scene.display_depth = d;
    }
    let mut app = headless_app_with(scene, config);
    if doc.patches.len() > 1 {
        let first = patch::patch_entity(app.world()).expect("the first patch was spawned");
        joined::spawn_joined(app.world_mut(), doc, first);
        app.update();
    }
    app
}

/// Sends one edit and runs one update; returns the edit's outcome.
pub fn apply(app: &mut App, edit: Edit) -> Result<String, EditError> {
    send(app, edit);
    app.update();
    let log = app.world().resource::<EditLog>();
    match log.entries.iter().find(|e| e.is_err()) {
        Some(Err(e)) => Err(e.clone()),
        _ => Ok(log
            .entries
            .iter()
            .filter_map(|e| e.as_ref().ok().cloned())
            .collect::<Vec<_>>()
            .join("; ")),
    }
}

/// Sends one edit.
pub fn send(app: &mut App, edit: Edit) {
    app.world_mut().write_message(EditMessage::from(edit));
}
