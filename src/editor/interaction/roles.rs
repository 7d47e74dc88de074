//! Which patch each placed handle entity belongs to, as the views need it:
//! the one system that writes [`PatchRole`] (active, dimmed or hidden) on
//! every placed handle entity, from its parent patch, the placed active
//! patch ([`HandleLayout::active`]) and [`PatchHidden`].

use super::placed::{HandleLayout, PatchRole, Placed};
use crate::ecs::joined::PatchHidden;
use bevy::prelude::*;

/// The role of a handle of patch `parent`.
pub fn role_of(parent: Entity, active: Option<Entity>, hidden: bool) -> PatchRole {
    if hidden {
        PatchRole::Hidden
    } else if Some(parent) == active {
        PatchRole::Active
    } else {
        PatchRole::Dimmed
    }
}

/// Gives every placed handle entity its [`PatchRole`] when the active patch
/// changed, a patch was hidden or shown, or handles were newly placed; only
/// the roles that differ are written.
#[allow(clippy::type_complexity)]
pub(super) fn mark_roles(
    (meter, layout): (Res<crate::ecs::meter::CpuMeter>, Res<HandleLayout>),
    mut commands: Commands,
    hidden: Query<(), With<PatchHidden>>,
    hid: Query<(), Changed<PatchHidden>>,
    mut shown: RemovedComponents<PatchHidden>,
    fresh: Query<(), Added<Placed>>,
    mut handles: Query<(Entity, &ChildOf, Option<&mut PatchRole>), With<Placed>>,
) {
    let _meter = meter.start();
    let unhidden = shown.read().count() > 0;
    if !layout.is_changed() && !unhidden && hid.is_empty() && fresh.is_empty() {
        return;
    }
    for (e, parent, role) in &mut handles {
        let want = role_of(
            parent.parent(),
            layout.active,
            hidden.contains(parent.parent()),
        );
        match role {
            Some(mut r) => {
                r.set_if_neq(want);
            }
            None => {
                commands.entity(e).try_insert(want);
            }
        }
    }
}
