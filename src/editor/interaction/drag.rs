//! The one drag state machine. The views report what the pointer does (a
//! press on a handle, the direction the pointer now asks for); this system
//! alone starts a drag, steers it (one `SetDirection`-style edit of the
//! drag's undo group per step, so the drag is one undo step), ends it on
//! release, and cancels it on Esc (`CancelGroup` restores the direction and
//! forgets the step). With several handles selected, dragging one of them
//! turns them all by the same rotation: each step sends the rotation since
//! the last one as one `RotateMany` of the surface tangents (and a rotate of
//! each initial-curve tangent), all in the drag's undo group. Shift-click
//! adds a handle to the selection or takes it out, and starts no drag.

use super::handle_id::HandleId;
use super::handle_query::HandleQuery;
use super::selection::Selection;
use crate::ecs::{Edit, EditMessage};
use bevy::prelude::*;
use streamline_kernel::{DQuat, DVec3};

/// How a drag turns its handle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum DragKind {
    /// A trackball about the arrow's base in the 3D view.
    Trackball {
        /// The base on screen (logical px).
        center: Vec2,
        /// The trackball's radius on screen (px).
        radius: f32,
        /// Where the drag started.
        start: Vec2,
        /// The camera's rotation when it started.
        camera: Quat,
    },
    /// The point follows the pointer on the Gaussian sphere view.
    Sphere,
}

/// A drag in progress.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ActiveDrag {
    /// The handle dragged.
    pub handle: HandleId,
    /// Undo group of its edits.
    pub group: u64,
    /// The direction when it started (Esc restores it).
    pub start_dir: DVec3,
    /// The last direction sent.
    pub last: DVec3,
    /// Whether any edit was sent.
    pub sent: bool,
    /// Trackball or sphere.
    pub kind: DragKind,
    /// The rotation applied so far to a group of selected handles (from
    /// `start_dir` to `last`).
    pub turned: DQuat,
}

impl ActiveDrag {
    /// Points the dragged handle at `dir`: one edit of the drag's undo group,
    /// unless it barely moved.
    fn steer(
        &mut self,
        dir: DVec3,
        selection: &Selection,
        handles: &HandleQuery,
        edits: &mut MessageWriter<EditMessage>,
    ) {
        if (dir - self.last).length() < 1e-7 {
            return;
        }
        self.last = dir;
        let group = Some(self.group);
        if selection.len() < 2 || !selection.contains(self.handle) {
            self.sent = true;
            edits.write(EditMessage {
                edit: self.handle.set_direction(dir),
                group,
            });
            return;
        }
        // the group: the rotation from the start to `dir`, less what was sent
        let total = DQuat::from_rotation_arc(self.start_dir, dir);
        let (axis, radians) = (total * self.turned.inverse()).to_axis_angle();
        if !(radians.abs() > 1e-12 && axis.is_finite()) {
            return;
        }
        self.turned = total;
        self.sent = true;
        // only handles that exist (a refused RotateMany would turn none)
        let members: Vec<HandleId> = selection
            .iter()
            .filter(|&h| handles.find(h).is_some())
            .collect();
        let surface: Vec<(usize, usize)> = members
            .iter()
            .filter(|h| h.is_surface())
            .map(|h| h.cell())
            .collect();
        if !surface.is_empty() {
            edits.write(EditMessage {
                edit: Edit::RotateMany {
                    handles: surface,
                    axis,
                    radians,
                },
                group,
            });
        }
        for h in members.iter().filter(|h| !h.is_surface()) {
            edits.write(EditMessage {
                edit: h.rotate(axis, radians),
                group,
            });
        }
    }
}

/// The drag in progress, if any (written only by the drag state machine).
#[derive(Resource, Debug, Default)]
pub struct Drag(pub Option<ActiveDrag>);

/// Hands out undo groups for drags and slider drags.
#[derive(Resource, Debug, Default)]
pub struct DragGroups(u64);

impl DragGroups {
    /// A group no earlier drag used.
    pub fn fresh(&mut self) -> u64 {
        self.0 += 1;
        // keep clear of groups other tools might pick (small numbers)
        (1 << 40) + self.0
    }
}

/// A left press in a view: on `handle` (a drag of kind `drag` starts when
/// given), or on empty space (`handle: None`: the selection is cleared).
#[derive(Message, Debug, Clone, Copy, PartialEq)]
pub struct HandlePressed {
    /// The handle under the pointer.
    pub handle: Option<HandleId>,
    /// How a drag of it turns it (`None`: select only).
    pub drag: Option<DragKind>,
}

/// The direction the pointer asks the dragged handle for this frame.
#[derive(Message, Debug, Clone, Copy, PartialEq)]
pub struct DragTo(pub DVec3);

/// The drag state machine: press, steer, Esc, release, in this order.
#[allow(clippy::too_many_arguments)]
pub(super) fn run(
    meter: Res<crate::ecs::meter::CpuMeter>,
    buttons: Res<ButtonInput<MouseButton>>,
    keys: Res<ButtonInput<KeyCode>>,
    handles: HandleQuery,
    mut presses: MessageReader<HandlePressed>,
    mut targets: MessageReader<DragTo>,
    mut drag: ResMut<Drag>,
    mut selection: ResMut<Selection>,
    mut groups: ResMut<DragGroups>,
    mut edits: MessageWriter<EditMessage>,
) {
    let _meter = meter.start();
    let shift = keys.any_pressed([KeyCode::ShiftLeft, KeyCode::ShiftRight]);
    for p in presses.read() {
        if drag.0.is_some() {
            continue;
        }
        let Some(h) = p.handle else {
            // with Shift, empty space starts a box that adds to the selection
            if !shift {
                selection.clear();
            }
            continue;
        };
        if shift {
            selection.toggle(h);
            continue;
        }
        if selection.contains(h) {
            selection.make_primary(h);
        } else {
            selection.select(h);
        }
        if let (Some(kind), Some(a)) = (p.drag, handles.find(h)) {
            drag.0 = Some(ActiveDrag {
                handle: h,
                group: groups.fresh(),
                start_dir: a.dir,
                last: a.dir,
                sent: false,
                kind,
                turned: DQuat::IDENTITY,
            });
        }
    }
    if let (Some(d), Some(DragTo(dir))) = (drag.0.as_mut(), targets.read().last()) {
        d.steer(*dir, &selection, &handles, &mut edits);
    }
    if keys.just_pressed(KeyCode::Escape) {
        match drag.0.take() {
            Some(d) if d.sent => {
                edits.write(EditMessage::from(Edit::CancelGroup(d.group)));
            }
            Some(_) => {}
            None => selection.clear(),
        }
        return;
    }
    if drag.0.is_some() && !buttons.pressed(MouseButton::Left) {
        drag.0 = None;
    }
}
