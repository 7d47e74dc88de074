//! A document's patches in the world (docs/architecture.md, "Several
//! patches"): the first patch is spawned as a one-patch scene is
//! ([`crate::ecs::patch::spawn_patch`]), and [`spawn_joined`] adds the
//! others, each a [`Patch`] entity with its net handles as children, its
//! [`PatchStart`] and a [`JoinedDesign`] that [`super::build`] builds from.

use super::components::*;
use crate::ecs::patch::scene_io::spawn_net_handles;
use crate::ecs::patch::{Patch, PatchIndex, PatchName};
use crate::scene::design::document::Document;
use bevy::prelude::*;
use std::collections::BTreeMap;
use streamline_kernel::Design;

/// Adds the patches of `doc` after its first to a world whose patch
/// `first` is the document's first patch (spawned from
/// [`Document::patch_scene`]`(0)`). A document of one patch adds nothing,
/// so the world is exactly a one-patch scene's. Returns every patch's
/// entity, in the document's order.
pub fn spawn_joined(world: &mut World, doc: &Document, first: Entity) -> Vec<Entity> {
    let mut ids = vec![first];
    if doc.patches.len() < 2 {
        return ids;
    }
    adopt_first(world, first, &doc.patches[0].name);
    for (i, p) in doc.patches.iter().enumerate().skip(1) {
        let start = match doc.parent(i) {
            Some((a, join)) => PatchStart::Edge {
                parent: ids[a],
                edge: join.edge,
                continuity: join.continuity,
            },
            None => PatchStart::Curve,
        };
        let features = JoinedFeatures {
            details: p.details.clone(),
            tuning: p.tuning.clone(),
            interpolate_tangents: p.interpolate_tangents,
        };
        let e = spawn_joined_patch(world, &p.name, i, start, p.design.clone(), features);
        if let crate::scene::design::document::Start::Curve(c) = &p.start {
            world.entity_mut(e).insert(PatchInitial(c.clone()));
        }
        ids.push(e);
    }
    ids
}

/// Makes the first patch a document's first: its [`PatchSlot`] `name` at
/// index 0, [`PatchStart::Curve`] and a [`PatchSurface`] for the patches
/// that start on it. Nothing when it has a slot already.
pub fn adopt_first(world: &mut World, first: Entity, name: &str) {
    if world.get::<PatchSlot>(first).is_some() {
        return;
    }
    world.entity_mut(first).insert((
        PatchSlot {
            name: name.to_string(),
            index: 0,
        },
        PatchStart::Curve,
        PatchSurface::default(),
    ));
}

/// Spawns a joined patch `name` at document index `index`: the [`Patch`]
/// entity with its [`JoinedDesign`], its [`JoinedFeatures`] and its net
/// handles as children. The next update builds it ([`super::build`]).
pub fn spawn_joined_patch(
    world: &mut World,
    name: &str,
    index: usize,
    start: PatchStart,
    design: Design,
    features: JoinedFeatures,
) -> Entity {
    let e = spawn_joined_with(&mut world.commands(), name, index, start, design, features);
    world.flush();
    e
}

/// [`spawn_joined_patch`] through `commands` (the edit stage's way: the
/// entities exist once the commands are applied, before the build).
pub fn spawn_joined_with(
    commands: &mut Commands,
    name: &str,
    index: usize,
    start: PatchStart,
    design: Design,
    features: JoinedFeatures,
) -> Entity {
    let e = commands
        .spawn((
            Patch,
            PatchName(name.to_string()),
            PatchSlot {
                name: name.to_string(),
                index,
            },
            start,
            Joined,
            PatchSurface::default(),
            SeamState::default(),
            features,
        ))
        .id();
    let surface = spawn_net_handles(commands, e, &design, JoinedHandle);
    commands.entity(e).insert((
        JoinedDesign(design),
        PatchIndex {
            surface,
            initial: Vec::new(),
            details: BTreeMap::new(),
        },
    ));
    e
}
