//! When the editor draws: like a desktop application, not a game. A scene
//! that nobody touches is not drawn again and again — under Mesa's software
//! renderer that kept both cores busy while the editor sat idle — but the
//! window wakes on input and keeps drawing for a moment after it (new
//! pipelines compile, the Stats text catches up), and it keeps drawing while
//! a drag, a mesh being opened or a script is under way. Screenshot runs (and
//! the GUI tests built on them) draw continuously, as they count frames.

use super::super::interaction::Drag;
use super::super::loop_mesh::MeshView;
use crate::ecs::EditLog;
use crate::ecs::runner::ScriptRun;
use bevy::input::keyboard::KeyboardInput;
use bevy::input::mouse::{MouseButtonInput, MouseWheel};
use bevy::prelude::*;
use bevy::window::{CursorMoved, RequestRedraw, WindowFocused, WindowResized};
use bevy::winit::{UpdateMode, WinitSettings};
use std::time::{Duration, Instant};

/// How long the editor keeps drawing after the last sign of activity.
pub const SETTLE: Duration = Duration::from_millis(1500);
/// After start: the first scene's pipelines compile (seconds on llvmpipe).
pub const STARTUP: Duration = Duration::from_secs(8);

/// The update modes of an interactive editor: woken by input, and at least
/// every 5 s when focused (autosave checks its timer then) or 60 s when not.
pub fn interactive() -> WinitSettings {
    WinitSettings {
        focused_mode: UpdateMode::reactive(Duration::from_secs(5)),
        unfocused_mode: UpdateMode::reactive_low_power(Duration::from_secs(60)),
    }
}

/// Whether to ask for another frame now.
pub fn keep_drawing(now: Instant, last_activity: Instant, busy: bool) -> bool {
    busy || now.duration_since(last_activity) < SETTLE
}

/// The last time something happened that the picture may still be catching up with.
#[derive(Resource, Debug)]
struct Activity {
    last: Instant,
    seen_edits: u64,
}

pub struct PacingPlugin {
    /// Draw every frame (screenshot runs).
    pub continuous: bool,
}

impl Plugin for PacingPlugin {
    fn build(&self, app: &mut App) {
        use bevy_egui::{EguiInputSet, EguiPreUpdateSet};
        app.add_systems(
            PreUpdate,
            drop_unchanged_modifiers
                .after(EguiInputSet::WriteEguiEvents)
                .before(EguiPreUpdateSet::BeginPass),
        );
        if self.continuous {
            app.insert_resource(WinitSettings::continuous());
            return;
        }
        app.insert_resource(interactive())
            .insert_resource(Activity {
                // counts the start as activity for STARTUP
                last: Instant::now() + STARTUP.saturating_sub(SETTLE),
                seen_edits: 0,
            })
            .add_systems(Last, request_frames);
    }
}

/// bevy_egui 0.42 tells egui the modifier keys in every frame
/// (`Event::ModifiersChanged`, changed or not), and any event makes egui ask
/// for the next frame: the editor would never rest. Only a change is passed
/// on (all of them again after a focus change, where egui clears its keys).
fn drop_unchanged_modifiers(
    mut inputs: Query<&mut bevy_egui::EguiInput>,
    mut last: Local<Option<bevy_egui::egui::Modifiers>>,
) {
    use bevy_egui::egui::Event;
    for mut input in &mut inputs {
        if input
            .events
            .iter()
            .any(|e| matches!(e, Event::WindowFocused(_)))
        {
            *last = None;
            continue;
        }
        input.events.retain(|e| match e {
            Event::ModifiersChanged(m) => last.replace(*m) != Some(*m),
            _ => true,
        });
    }
}

#[allow(clippy::too_many_arguments)]
fn request_frames(
    mut activity: ResMut<Activity>,
    mut redraw: MessageWriter<RequestRedraw>,
    log: Res<EditLog>,
    drag: Res<Drag>,
    mesh: Res<MeshView>,
    script: Res<ScriptRun>,
    mut cursor: MessageReader<CursorMoved>,
    mut buttons: MessageReader<MouseButtonInput>,
    mut wheel: MessageReader<MouseWheel>,
    mut keys: MessageReader<KeyboardInput>,
    mut resized: MessageReader<WindowResized>,
    mut focused: MessageReader<WindowFocused>,
) {
    let now = Instant::now();
    let input = cursor.read().count()
        + buttons.read().count()
        + wheel.read().count()
        + keys.read().count()
        + resized.read().count()
        + focused.read().count()
        > 0;
    if input || log.frame != activity.seen_edits {
        activity.seen_edits = log.frame;
        activity.last = activity.last.max(now);
    }
    let busy = drag.0.is_some() || mesh.busy() || script.busy();
    if keep_drawing(now, activity.last, busy) {
        redraw.write(RequestRedraw);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn draws_while_busy_and_for_a_moment_after_activity() {
        let t0 = Instant::now();
        assert!(keep_drawing(t0, t0, false));
        assert!(keep_drawing(t0 + SETTLE / 2, t0, false));
        assert!(!keep_drawing(t0 + SETTLE, t0, false));
        assert!(!keep_drawing(t0 + Duration::from_secs(60), t0, false));
        assert!(keep_drawing(t0 + Duration::from_secs(60), t0, true));
        // the start counts for STARTUP, then the editor rests
        let start = t0 + STARTUP.saturating_sub(SETTLE);
        assert!(keep_drawing(
            t0 + STARTUP - Duration::from_millis(1),
            start,
            false
        ));
        assert!(!keep_drawing(t0 + STARTUP, start, false));
        let w = interactive();
        assert!(
            matches!(w.focused_mode, UpdateMode::Reactive { wait, .. } if wait == Duration::from_secs(5))
        );
    }
}
