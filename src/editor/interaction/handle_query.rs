//! [`HandleQuery`]: the handle entities, read: which handle an id names,
//! the ones the pointer may pick, and which lies under the pointer on the
//! screen or on the sphere view, for every kind, so that the views never
//! need to know how many kinds there are. Ids name the handles of the
//! active patch ([`HandleLayout::active`], the first patch until a
//! placement ran); the other patches' handles are drawn dimmed and never
//! found nor picked here, and a hidden active patch has none to pick.

use super::handle_id::{Handle, HandleId, HandleKind, HandleSettings, segment_distance};
use super::placed::{HandleLayout, MirroredHandle, Placed};
use crate::ecs::joined::PatchHidden;
use crate::ecs::patch::{Joined, Patch, PatchIndex};
use bevy::ecs::system::SystemParam;
use bevy::prelude::*;
use streamline_kernel::DVec3;

/// The placed handle entities, queried.
#[derive(SystemParam)]
pub struct HandleQuery<'w, 's> {
    layout: Res<'w, HandleLayout>,
    index: Query<'w, 's, (&'static PatchIndex, Has<PatchHidden>), With<Patch>>,
    first: Query<'w, 's, Entity, (With<Patch>, Without<Joined>)>,
    placed: Query<'w, 's, (&'static HandleId, &'static Placed)>,
    copies: Query<'w, 's, (&'static MirroredHandle, &'static Placed)>,
}

impl HandleQuery<'_, '_> {
    /// The edit depth the handles belong to.
    pub fn edit_depth(&self) -> u32 {
        self.layout.edit_depth
    }

    /// What the placement knows that is not one handle's.
    pub fn layout(&self) -> &HandleLayout {
        &self.layout
    }

    /// Whether the layout changed (a placement of every handle) since the
    /// reading system last ran.
    pub fn layout_changed(&self) -> bool {
        self.layout.is_changed()
    }

    /// The patch whose handles these are (the placed active patch, else
    /// the first).
    pub fn active_patch(&self) -> Option<Entity> {
        self.layout.active.or_else(|| self.first.single().ok())
    }

    /// Whether the active patch is a joined one (docs/math.md §11).
    pub fn active_joined(&self) -> bool {
        self.layout.active_joined
    }

    /// Whether the active patch is hidden: then none of its handles is picked.
    pub fn active_hidden(&self) -> bool {
        self.active_patch()
            .and_then(|e| self.index.get(e).ok())
            .is_some_and(|(_, h)| h)
    }

    /// The active patch's index of handle entities.
    fn index(&self) -> Option<&PatchIndex> {
        self.index.get(self.active_patch()?).ok().map(|(i, _)| i)
    }

    /// The entity of handle `id` (of the net, the initial curve, or a
    /// refined cell of the edit depth), if it has one.
    pub fn entity(&self, id: HandleId) -> Option<Entity> {
        let index = self.index()?;
        match id.kind {
            HandleKind::SurfaceTangent { level: 0 } => (id.row < index.surface.rows()
                && id.col < index.surface.cols())
            .then(|| index.surface.get(id.row, id.col)),
            HandleKind::SurfaceTangent { level } => self.layout.refined_at(level, id.cell()),
            HandleKind::InitialTangent => index.initial.get(id.col).copied(),
        }
    }

    /// The handle on entity `e`, where it is placed.
    pub fn get(&self, e: Entity) -> Option<Handle> {
        self.placed.get(e).ok().map(|(id, p)| p.handle(*id))
    }

    /// The handle `id`, if it is one of the edit depth's (or of the initial curve).
    pub fn find(&self, id: HandleId) -> Option<Handle> {
        if id.is_surface() && id.level() != self.layout.edit_depth {
            return None;
        }
        self.get(self.entity(id)?)
    }

    /// The handle of the edit depth at `(row, col)`.
    pub fn at(&self, cell: (usize, usize)) -> Option<Handle> {
        self.find(self.id_at(cell))
    }

    /// The id of the edit depth's handle at `(row, col)` (which may not exist).
    pub fn id_at(&self, (row, col): (usize, usize)) -> HandleId {
        HandleId::tangent(self.layout.edit_depth, row, col)
    }

    /// `(rows, cols)` of the edit depth's handles.
    pub fn shape(&self) -> (usize, usize) {
        if !self.layout.placed {
            return (0, 0);
        }
        match (&self.layout.refined, self.layout.edit_depth) {
            (Some((shape, _)), d) if d > 0 => *shape,
            // no refined cells placed (a stack without the edit depth's level)
            (None, d) if d > 0 => (0, 0),
            _ => self
                .index()
                .map_or((0, 0), |i| (i.surface.rows(), i.surface.cols())),
        }
    }

    /// The level-0 control tangents, row-major (shown; picked only at edit depth 0).
    pub fn controls(&self) -> impl Iterator<Item = Handle> + '_ {
        let cells = self.index().map_or(&[][..], |i| i.surface.data());
        cells.iter().filter_map(|&e| self.get(e))
    }

    /// The handles of the edit depth, row-major: the control tangents at
    /// depth 0, the refined cells deeper (none while none are placed).
    pub fn editable(&self) -> Box<dyn Iterator<Item = Handle> + '_> {
        match &self.layout.refined {
            Some((_, v)) if self.layout.edit_depth > 0 => {
                Box::new(v.iter().filter_map(|&e| self.get(e)))
            }
            _ if self.layout.edit_depth > 0 => Box::new(std::iter::empty()),
            _ => Box::new(self.controls()),
        }
    }

    /// The initial curve's control tangents, in order.
    pub fn initial(&self) -> impl Iterator<Item = Handle> + '_ {
        let v = self.index().map_or(&[][..], |i| &i.initial[..]);
        v.iter().filter_map(|&e| self.get(e))
    }

    /// With the mirror on: the reflected copies of the control tangents,
    /// each with the id of the one it reflects (never picked).
    pub fn mirrored(&self) -> impl Iterator<Item = Handle> + '_ {
        self.layout
            .mirrored
            .iter()
            .filter_map(|&e| self.copies.get(e).ok())
            .map(|(m, p)| p.handle(m.of))
    }

    /// The handles the pointer may pick (shown ones of the edit depth, of
    /// the active patch unless it is hidden).
    pub fn pickable<'a>(
        &'a self,
        settings: &'a HandleSettings,
    ) -> impl Iterator<Item = Handle> + 'a {
        let hidden = self.active_hidden();
        // a hidden patch's, or refined cells not shown: none of the edit depth's
        let none = hidden || (self.layout.edit_depth > 0 && !settings.refined);
        let initial = (settings.initial && !hidden)
            .then(|| self.initial())
            .into_iter()
            .flatten();
        self.editable()
            .filter(move |a| !none && settings.shows(a))
            .chain(initial)
    }

    /// The pickable handle whose arrow passes nearest `cursor` on the screen,
    /// within `max_px`.
    pub fn pick_on_screen(
        &self,
        settings: &HandleSettings,
        cursor: Vec2,
        project: impl Fn(DVec3) -> Option<Vec2>,
        max_px: f32,
    ) -> Option<HandleId> {
        let mut best: Option<(HandleId, f32)> = None;
        for a in self.pickable(settings) {
            let Some((p0, p1)) = a.on_screen(&project) else {
                continue;
            };
            let d = segment_distance(cursor, p0, p1);
            if d <= max_px && best.is_none_or(|(_, bd)| d < bd) {
                best = Some((a.id, d));
            }
        }
        best.map(|(h, _)| h)
    }

    /// The pickable handle whose point on the sphere view lies nearest
    /// `cursor`, closer than `max_px`, on the side facing `eye` (unit).
    pub fn pick_on_sphere(
        &self,
        settings: &HandleSettings,
        cursor: Vec2,
        eye: DVec3,
        project: impl Fn(DVec3) -> Option<Vec2>,
        max_px: f32,
    ) -> Option<Handle> {
        let mut best: Option<(Handle, f32)> = None;
        for a in self.pickable(settings) {
            if a.dir.dot(eye) < 0.0 {
                continue;
            }
            let Some(p) = project(a.dir) else {
                continue;
            };
            let d = p.distance(cursor);
            if d < max_px && best.is_none_or(|(_, bd)| d < bd) {
                best = Some((a, d));
            }
        }
        best.map(|(a, _)| a)
    }
}
