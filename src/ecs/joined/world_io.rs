//! A document's later patches and the world (docs/architecture.md, "Undo
//! of documents"): [`JoinedParts::read`] assembles the [`DocState`] of the
//! world (the first patch's scene is assembled by
//! [`crate::ecs::patch::scene_io`]), and [`JoinedParts::write`] writes a
//! state back, writing only what differs: a patch whose name, start and net
//! shape are the state's keeps its entity, and its design and handles are
//! written only where they differ (so a patch whose design did not change is
//! not rebuilt); a patch the world lacks is spawned, one the state lacks is
//! despawned. Patches are matched by name, then by place (a rename keeps
//! the entity); entity ids may change, so the state names the patch each
//! starts on by its index.

use super::components::*;
use super::spawn::spawn_joined_with;
use crate::ecs::edit_state::{DocState, JoinedState, StartState, same_design};
use crate::ecs::patch::{ArcParam, Direction, InitialHandle, Patch, PatchIndex, PatchName};
use crate::scene::design::document::{Document, MAIN_PATCH};
use bevy::ecs::system::SystemParam;
use bevy::prelude::*;

/// A later patch's own components, writable.
type JoinedRow = (
    Entity,
    &'static mut PatchSlot,
    &'static mut PatchName,
    &'static PatchStart,
    &'static mut JoinedDesign,
    &'static PatchIndex,
    Has<PatchHidden>,
    Option<&'static PatchInitial>,
    Option<&'static mut JoinedFeatures>,
);

/// The first patch's document components, writable.
type FirstRow = (
    Entity,
    Option<&'static mut PatchSlot>,
    Has<PatchHidden>,
    Has<PatchSurface>,
);

/// The first patch (not a joined one).
type FirstOnly = (With<Patch>, Without<Joined>);

/// A joined patch.
type JoinedOnly = (With<Patch>, With<Joined>);

/// A joined patch's net handle's values, writable.
type JoinedNetMut = (&'static mut Direction, &'static mut ArcParam);

/// A joined patch's net handle (never an initial-curve handle).
type JoinedNet = (With<JoinedHandle>, Without<InitialHandle>);

/// The document's patches beyond the first patch's scene, writable.
#[derive(SystemParam)]
pub(crate) struct JoinedParts<'w, 's> {
    first: Query<'w, 's, FirstRow, FirstOnly>,
    joined: Query<'w, 's, JoinedRow, JoinedOnly>,
    handles: Query<'w, 's, JoinedNetMut, JoinedNet>,
    active: ResMut<'w, ActivePatch>,
    commands: Commands<'w, 's>,
}

impl JoinedParts<'_, '_> {
    /// The patch entities in the document's order (the first patch first).
    pub(crate) fn entities(&self) -> Vec<Entity> {
        let mut v: Vec<(usize, Entity)> = self.joined.iter().map(|r| (r.1.index, r.0)).collect();
        v.sort();
        let first = self.first.iter().next().map(|r| r.0);
        first
            .into_iter()
            .chain(v.into_iter().map(|(_, e)| e))
            .collect()
    }

    /// The document's state with `first` as its first patch's scene, and
    /// the index of the active patch ([`ActivePatch`]; 0 when it names no patch).
    pub(crate) fn read(&self, first: crate::scene::Scene) -> (DocState, usize) {
        let ids = self.entities();
        let (first_name, first_hidden) = match self.first.iter().next() {
            Some((_, slot, hidden, _)) => (slot.map(|s| s.name.clone()), hidden),
            None => (None, false),
        };
        let state = assemble(first, first_name, first_hidden, &ids, |e| {
            self.joined.get(e).ok().map(|r| {
                (
                    r.1.clone(),
                    *r.3,
                    r.4.0.clone(),
                    r.6,
                    r.7.map(|i| i.0.clone()),
                    r.8.cloned().unwrap_or_default(),
                )
            })
        });
        let active = self
            .active
            .0
            .and_then(|e| ids.iter().position(|&x| x == e))
            .unwrap_or(0);
        (state, active)
    }

    /// Writes the later patches, the first patch's name and hidden flag of
    /// `target`, and `active` as the [`ActivePatch`] (module documentation).
    pub(crate) fn write(&mut self, target: &DocState, active: usize) {
        let Some((first, _, _, _)) = self.first.iter().next() else {
            return;
        };
        self.write_first(first, target);
        let mut cur: Vec<(usize, Entity)> = self.joined.iter().map(|r| (r.1.index, r.0)).collect();
        cur.sort();
        let cur: Vec<Entity> = cur.into_iter().map(|(_, e)| e).collect();
        let mut used = vec![false; cur.len()];
        let mut ids = vec![first];
        for (k, t) in target.joined.iter().enumerate() {
            let want = match &t.start {
                StartState::Edge {
                    parent,
                    edge,
                    continuity,
                } => PatchStart::Edge {
                    // an earlier patch (a state names no later one; never panics)
                    parent: ids.get(*parent).copied().unwrap_or(first),
                    edge: *edge,
                    continuity: *continuity,
                },
                StartState::Curve(_) => PatchStart::Curve,
            };
            let fits = |e: Entity| {
                self.joined.get(e).is_ok_and(|r| {
                    let curve = match &t.start {
                        StartState::Curve(c) => r.7.map(|i| &i.0) == Some(c),
                        StartState::Edge { .. } => true,
                    };
                    *r.3 == want
                        && curve
                        && r.5.surface.rows() == t.design.net().rows()
                        && r.5.surface.cols() == t.design.net().cols()
                })
            };
            let by_name = (0..cur.len()).find(|&j| {
                !used[j]
                    && self.joined.get(cur[j]).is_ok_and(|r| r.1.name == t.name)
                    && fits(cur[j])
            });
            let by_place = (k < cur.len() && !used[k] && fits(cur[k])).then_some(k);
            let e = match by_name.or(by_place) {
                Some(j) => {
                    used[j] = true;
                    self.update(cur[j], k + 1, t);
                    cur[j]
                }
                None => {
                    let e = spawn_joined_with(
                        &mut self.commands,
                        &t.name,
                        k + 1,
                        want,
                        t.design.clone(),
                        JoinedFeatures::of(t),
                    );
                    match &t.start {
                        StartState::Curve(c) => {
                            self.commands.entity(e).insert(PatchInitial(c.clone()));
                        }
                        StartState::Edge { .. } => {}
                    }
                    if t.hidden {
                        self.commands.entity(e).insert(PatchHidden);
                    }
                    e
                }
            };
            ids.push(e);
        }
        for (j, &e) in cur.iter().enumerate() {
            if !used[j] {
                self.commands.entity(e).despawn();
            }
        }
        let want = (active > 0).then(|| ids.get(active).copied()).flatten();
        if self.active.0 != want {
            self.active.0 = want;
        }
    }

    /// The first patch's slot (a document of several patches needs one,
    /// with its start and surface; a one-patch document keeps only its
    /// name, when renamed) and hidden flag.
    fn write_first(&mut self, first: Entity, target: &DocState) {
        let Ok((_, slot, hidden, has_surface)) = self.first.get_mut(first) else {
            return;
        };
        let several = !target.joined.is_empty();
        match slot {
            Some(mut slot) if slot.name != target.first_name => {
                slot.name.clone_from(&target.first_name);
            }
            Some(_) => {}
            None if several || target.first_name != MAIN_PATCH => {
                self.commands.entity(first).insert(PatchSlot {
                    name: target.first_name.clone(),
                    index: 0,
                });
            }
            None => {}
        }
        if several && !has_surface {
            self.commands
                .entity(first)
                .insert((PatchStart::Curve, PatchSurface::default()));
        } else if !several && has_surface {
            self.commands
                .entity(first)
                .remove::<(PatchStart, PatchSurface)>();
        }
        if hidden != target.first_hidden {
            if target.first_hidden {
                self.commands.entity(first).insert(PatchHidden);
            } else {
                self.commands.entity(first).remove::<PatchHidden>();
            }
        }
    }

    /// Writes `t` into the kept patch `e` at document index `index`: only what differs.
    fn update(&mut self, e: Entity, index: usize, t: &JoinedState) {
        let Ok((_, mut slot, mut name, _, mut design, patch_index, hidden, _, features)) =
            self.joined.get_mut(e)
        else {
            return;
        };
        let want = JoinedFeatures::of(t);
        match features {
            Some(mut f) => {
                f.set_if_neq(want);
            }
            None => {
                self.commands.entity(e).insert(want);
            }
        }
        if slot.name != t.name || slot.index != index {
            *slot = PatchSlot {
                name: t.name.clone(),
                index,
            };
        }
        if name.0 != t.name {
            name.0.clone_from(&t.name);
        }
        if !same_design(&design.0, &t.design) {
            design.0 = t.design.clone();
            let (net, s) = (t.design.net(), &t.design.params().s);
            let cells = patch_index.surface.clone();
            for r in 0..net.rows() {
                for c in 0..net.cols() {
                    if let Ok((mut d, mut a)) = self.handles.get_mut(cells.get(r, c)) {
                        d.set_if_neq(Direction(net.get(r, c)));
                        a.set_if_neq(ArcParam(s.get(r, c)));
                    }
                }
            }
        }
        if hidden != t.hidden {
            if t.hidden {
                self.commands.entity(e).insert(PatchHidden);
            } else {
                self.commands.entity(e).remove::<PatchHidden>();
            }
        }
    }
}

/// The world's document: its first patch's scene (assembled from its
/// entities) and its later patches (for callers outside the schedule: the
/// command line, tests, the editor's autosave).
pub fn document(world: &World) -> Result<Document, String> {
    Ok(doc_state(world)?.to_document())
}

/// What [`assemble`] reads of a later patch: its slot, start, design,
/// hidden flag, (starting on its own curve) initial curve and features.
type JoinedValues = (
    PatchSlot,
    PatchStart,
    streamline_kernel::Design,
    bool,
    Option<crate::scene::files::format::InitialSpec>,
    JoinedFeatures,
);

/// The state of a document whose first patch is `first` (named
/// `first_name`, [`MAIN_PATCH`] when it has no slot) and whose patch
/// entities are `ids` in order (the first patch first); `get` reads a later one.
fn assemble(
    first: crate::scene::Scene,
    first_name: Option<String>,
    first_hidden: bool,
    ids: &[Entity],
    get: impl Fn(Entity) -> Option<JoinedValues>,
) -> DocState {
    let at = |e: Entity| ids.iter().position(|&x| x == e);
    let joined = (ids.iter().skip(1))
        .filter_map(|&e| get(e))
        .map(
            |(slot, start, design, hidden, initial, features)| JoinedState {
                name: slot.name,
                start: match start {
                    PatchStart::Edge {
                        parent,
                        edge,
                        continuity,
                    } if at(parent).is_some() => StartState::Edge {
                        parent: at(parent).unwrap_or(0),
                        edge,
                        continuity,
                    },
                    _ => StartState::Curve(
                        initial.unwrap_or_else(crate::scene::files::format_v3::placeholder_initial),
                    ),
                },
                design,
                details: features.details,
                tuning: features.tuning,
                interpolate_tangents: features.interpolate_tangents,
                hidden,
            },
        )
        .collect();
    DocState {
        first,
        first_name: first_name.unwrap_or_else(|| MAIN_PATCH.to_string()),
        first_hidden,
        joined,
    }
}

/// The world's [`DocState`] (outside the schedule).
pub fn doc_state(world: &World) -> Result<DocState, String> {
    let first = crate::ecs::patch::scene_io::try_scene(world)?;
    let first_e = crate::ecs::patch::patch_entity(world).ok_or("the world has no patch")?;
    let mut v: Vec<(usize, Entity)> =
        match world.try_query_filtered::<(Entity, &PatchSlot), With<Joined>>() {
            Some(mut q) => q.iter(world).map(|(e, s)| (s.index, e)).collect(),
            None => Vec::new(),
        };
    v.sort();
    let ids: Vec<Entity> = std::iter::once(first_e)
        .chain(v.into_iter().map(|(_, e)| e))
        .collect();
    Ok(assemble(
        first,
        world.get::<PatchSlot>(first_e).map(|s| s.name.clone()),
        world.get::<PatchHidden>(first_e).is_some(),
        &ids,
        |e| {
            Some((
                world.get::<PatchSlot>(e)?.clone(),
                *world.get::<PatchStart>(e)?,
                world.get::<JoinedDesign>(e)?.0.clone(),
                world.get::<PatchHidden>(e).is_some(),
                world.get::<PatchInitial>(e).map(|i| i.0.clone()),
                world.get::<JoinedFeatures>(e).cloned().unwrap_or_default(),
            ))
        },
    ))
}

/// The document's patches beyond the first patch's scene, read-only (the
/// output stage, the editor's autosave).
#[derive(SystemParam)]
pub struct JoinedRead<'w, 's> {
    first: Query<'w, 's, FirstRead, FirstOnly>,
    joined: Query<'w, 's, JoinedReadRow, JoinedOnly>,
}

/// The first patch's document components.
type FirstRead = (Entity, Option<&'static PatchSlot>, Has<PatchHidden>);

/// A joined patch's document components.
type JoinedReadRow = (
    Entity,
    &'static PatchSlot,
    &'static PatchStart,
    &'static JoinedDesign,
    Has<PatchHidden>,
    Option<&'static PatchInitial>,
    Option<&'static JoinedFeatures>,
);

impl JoinedRead<'_, '_> {
    /// The patch entities in the document's order: the first patch, then
    /// the joined ones by their slot (the order of [`Self::document`]'s
    /// patches).
    pub fn ids(&self) -> Vec<Entity> {
        let mut v: Vec<(usize, Entity)> = self.joined.iter().map(|r| (r.1.index, r.0)).collect();
        v.sort();
        (self.first.iter().next().map(|r| r.0).into_iter())
            .chain(v.into_iter().map(|(_, e)| e))
            .collect()
    }

    /// The document's state with `first` as its first patch's scene.
    pub fn state(&self, first: crate::scene::Scene) -> DocState {
        let head = self.first.iter().next();
        let ids = self.ids();
        assemble(
            first,
            head.and_then(|r| r.1.map(|s| s.name.clone())),
            head.is_some_and(|r| r.2),
            &ids,
            |e| {
                self.joined.get(e).ok().map(|r| {
                    (
                        r.1.clone(),
                        *r.2,
                        r.3.0.clone(),
                        r.4,
                        r.5.map(|i| i.0.clone()),
                        r.6.cloned().unwrap_or_default(),
                    )
                })
            },
        )
    }

    /// Whether the document has patches after the first.
    pub fn several(&self) -> bool {
        !self.joined.is_empty()
    }

    /// The document with `first` as its first patch's scene.
    pub fn document(&self, first: crate::scene::Scene) -> Document {
        self.state(first).to_document()
    }
}
