//! A headless editor for the interaction tests: the model and the
//! interaction core under `MinimalPlugins`, with input injected as the views
//! and the input plugin would report it.

use bevy::prelude::*;
use streamline_kernel::{DVec3, levels::presets};
use streamline_studio::ecs::{History, ModelPlugin};
use streamline_studio::editor::interaction::{
    DragKind, DragTo, HandleId, HandlePressed, InteractionPlugin,
};
use streamline_studio::scene::Scene;

/// The car at display depth 2, edited at depth 0, one frame run.
pub fn app() -> App {
    let mut s = Scene::from_design("car1", presets::car1(), 2);
    s.edit_depth = 0;
    let mut app = App::new();
    app.add_plugins(MinimalPlugins)
        .init_resource::<ButtonInput<MouseButton>>()
        .init_resource::<ButtonInput<KeyCode>>()
        .add_plugins(ModelPlugin::new(s))
        .add_plugins(InteractionPlugin);
    frame(&mut app);
    app
}

/// One frame; then the input is as the input plugin leaves it for the next
/// (presses no longer "just" pressed).
pub fn frame(app: &mut App) {
    app.update();
    let w = app.world_mut();
    w.resource_mut::<ButtonInput<MouseButton>>().clear();
    w.resource_mut::<ButtonInput<KeyCode>>().clear();
}

/// Undo steps on record.
pub fn undo_steps(app: &App) -> usize {
    app.world().resource::<History>().undo_len()
}

/// The left button pressed on `handle` (as a view reports it), one frame.
pub fn press(app: &mut App, handle: Option<HandleId>, drag: Option<DragKind>) {
    let w = app.world_mut();
    w.resource_mut::<ButtonInput<MouseButton>>()
        .press(MouseButton::Left);
    w.write_message(HandlePressed { handle, drag });
    frame(app);
}

/// The left button released, one frame.
pub fn release(app: &mut App) {
    app.world_mut()
        .resource_mut::<ButtonInput<MouseButton>>()
        .release(MouseButton::Left);
    frame(app);
}

/// The drag steered to `dir` (as a view reports it), one frame.
pub fn steer(app: &mut App, dir: DVec3) {
    app.world_mut().write_message(DragTo(dir));
    frame(app);
}

/// `k` pressed for a frame and released for the next.
pub fn key(app: &mut App, k: KeyCode) {
    app.world_mut()
        .resource_mut::<ButtonInput<KeyCode>>()
        .press(k);
    frame(app);
    app.world_mut()
        .resource_mut::<ButtonInput<KeyCode>>()
        .release(k);
    frame(app);
}

/// Reads the handle entities as the editor's views do ([`HandleQuery`]).
pub fn handles<R>(
    app: &mut App,
    f: impl FnOnce(&streamline_studio::editor::interaction::HandleQuery) -> R,
) -> R {
    let mut state = bevy::ecs::system::SystemState::<
        streamline_studio::editor::interaction::HandleQuery,
    >::new(app.world_mut());
    let q = state.get(app.world()).expect("the patch and its handles");
    f(&q)
}
