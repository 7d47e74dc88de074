//! A document's patches in the world (docs/architecture.md, "Several
//! patches"): the first patch is spawned as a one-patch scene is
//! ([`crate::ecs::patch::spawn_patch`]), and [`spawn_joined`] adds the
//! others, each a [`Patch`] entity with its net handles as children, its
//! [`PatchStart`] and a [`JoinedDesign`] that [`super::build`] builds from.

use super::components::*;
use crate::ecs::patch::{ArcParam, Direction, Patch, PatchIndex, PatchName, SurfaceHandle};
use crate::scene::document::Document;
use bevy::prelude::*;
use std::collections::BTreeMap;
use streamline_kernel::Grid;

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
    world.entity_mut(first).insert((
        PatchSlot {
            name: doc.patches[0].name.clone(),
            index: 0,
        },
        PatchStart::Curve,
        PatchSurface::default(),
    ));
    for (i, p) in doc.patches.iter().enumerate().skip(1) {
        let start = match doc.parent(i) {
            Some((a, join)) => PatchStart::Edge {
                parent: ids[a],
                edge: join.edge,
                continuity: join.continuity,
            },
            None => PatchStart::Curve,
        };
        let e = world
            .spawn((
                Patch,
                PatchName(p.name.clone()),
                PatchSlot {
                    name: p.name.clone(),
                    index: i,
                },
                start,
                Joined,
                JoinedDesign(p.design.clone()),
                PatchSurface::default(),
                SeamState::default(),
            ))
            .id();
        let (net, s) = (p.design.net(), &p.design.params().s);
        let mut surface = Grid::filled(net.rows(), net.cols(), Entity::PLACEHOLDER);
        for row in 0..net.rows() {
            for col in 0..net.cols() {
                let h = world
                    .spawn((
                        SurfaceHandle { row, col },
                        Direction(net.get(row, col)),
                        ArcParam(s.get(row, col)),
                        JoinedHandle,
                        ChildOf(e),
                    ))
                    .id();
                surface.set(row, col, h);
            }
        }
        world.entity_mut(e).insert(PatchIndex {
            surface,
            initial: Vec::new(),
            details: BTreeMap::new(),
        });
        ids.push(e);
    }
    ids
}
