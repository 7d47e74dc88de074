//! The interaction core: what the user points at and turns, owned in one
//! place. It places the handle entities (their kinds, their places on the
//! screen and on the Gaussian sphere: [`Placed`], written by one system),
//! reads them for the views ([`HandleQuery`]: the active patch's, see
//! [`crate::ecs::joined::ActivePatch`]; every other patch's are dimmed,
//! [`PatchRole`]), and holds the selection, the one drag state machine, the
//! editor's mode (a Bevy `States`), the state the views share about the main
//! view, and the public [`EditorSet`]s that order the editor. The camera,
//! the arrows, picking, the sphere view, mesh mode and the panels depend on
//! this module and not on each other; a new kind of handle is a new
//! [`HandleKind`] here.

mod active_switch;
mod drag;
mod handle_id;
mod handle_query;
mod mode;
mod placed;
mod placement;
mod roles;
mod selection;
mod view;

use crate::ecs::ModelSet;
use bevy::prelude::*;
use bevy_state::app::{AppExtStates, StatesPlugin};
pub use drag::{ActiveDrag, Drag, DragGroups, DragKind, DragTo, HandlePressed};
pub use handle_id::{Handle, HandleId, HandleKind, HandleSettings, segment_distance};
pub use handle_query::HandleQuery;
pub use mode::EditorMode;
pub use placed::{HandleLayout, MirroredHandle, PatchRole, Placed, RefinedHandle};
pub use placement::{DrawnLevel, shares_first_column, stack_handles};
pub use roles::role_of;
pub use selection::{Selected, Selection};
pub use view::{FrameRequest, MainCamera, OrbitCamera, SceneBounds, SphereArea, ViewArea};

/// The editor's phases in `Update`, in this order around the model's
/// [`ModelSet`]s: input before the edit stage, presentation after the
/// output stage.
#[derive(SystemSet, Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum EditorSet {
    /// The pointer and keys read by the views: hover, presses, the direction
    /// a drag asks for, camera moves.
    Input,
    /// The drag state machine turns what the views read into edits.
    Drag,
    /// Derived state the drawing reads: the handles' places, the Bevy mesh,
    /// the bounds, the selection kept valid.
    Sync,
    /// Drawing: arrows, the sphere view, curvature maps, overlays.
    Present,
}

/// The interaction core's resources, messages, sets, mode and systems.
pub struct InteractionPlugin;

impl Plugin for InteractionPlugin {
    fn build(&self, app: &mut App) {
        if !app.is_plugin_added::<StatesPlugin>() {
            app.add_plugins(StatesPlugin);
        }
        app.init_state::<EditorMode>()
            .init_resource::<HandleLayout>()
            .init_resource::<HandleSettings>()
            .init_resource::<Selection>()
            .init_resource::<Drag>()
            .init_resource::<DragGroups>()
            .init_resource::<SceneBounds>()
            .init_resource::<ViewArea>()
            .init_resource::<FrameRequest>()
            .init_resource::<SphereArea>()
            .add_message::<HandlePressed>()
            .add_message::<DragTo>()
            .configure_sets(
                Update,
                (
                    (EditorSet::Input, EditorSet::Drag)
                        .chain()
                        .before(ModelSet::Edit),
                    (EditorSet::Sync, EditorSet::Present)
                        .chain()
                        .after(ModelSet::Output),
                ),
            )
            .add_systems(Update, drag::run.in_set(EditorSet::Drag))
            .add_systems(
                Update,
                (
                    placement::place,
                    roles::mark_roles,
                    active_switch::follow_active,
                    selection::keep_valid,
                    selection::mark_selected,
                )
                    .chain()
                    .in_set(EditorSet::Sync),
            );
    }
}
