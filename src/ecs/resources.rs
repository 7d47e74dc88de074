//! Resources: the scene being edited, history, the surface mesh, stats, the edit log.

use super::edit_state::DocState;
use bevy::prelude::*;
use std::collections::VecDeque;
use std::path::PathBuf;
use streamline_kernel::levels::dirty_window::DirtyWindow;
use streamline_kernel::streamline::surface_mesh::{SurfaceMesh, normals_window};
use streamline_kernel::{DVec3, Grid};

/// The document: the file it was loaded from or saved to, and whether it
/// changed since. The design itself lives in the patch entities and their
/// handles ([`super::patch`], [`super::joined`]); [`super::joined::document`]
/// assembles it.
#[derive(Resource, Debug, Default)]
pub struct Model {
    /// The file it was loaded from or saved to.
    pub path: Option<PathBuf>,
    /// Changed since the last save or load.
    pub unsaved: bool,
}

/// Settings of the model layer.
#[derive(Resource, Debug, Clone)]
pub struct ModelConfig {
    /// Undo steps kept.
    pub history_limit: usize,
}

impl Default for ModelConfig {
    fn default() -> Self {
        ModelConfig { history_limit: 200 }
    }
}

/// Undo and redo stacks of whole documents ([`DocState`]: the first
/// patch's scene, every later patch's name, start, design and hidden flag;
/// a 9×6 scene is a few kB). A one-patch design's steps are its scenes.
#[derive(Resource, Debug, Default)]
pub struct History {
    pub(crate) undo: VecDeque<DocState>,
    pub(crate) redo: Vec<DocState>,
    pub(crate) last_group: Option<u64>,
    /// Whether the scene had unsaved changes before the open group began.
    pub(crate) group_was_unsaved: bool,
}

impl History {
    /// Steps that can be undone.
    pub fn undo_len(&self) -> usize {
        self.undo.len()
    }

    /// Steps that can be redone.
    pub fn redo_len(&self) -> usize {
        self.redo.len()
    }

    /// Records `before` as an undo step unless `group` continues the last one.
    pub(crate) fn record(
        &mut self,
        before: &DocState,
        group: Option<u64>,
        limit: usize,
        was_unsaved: bool,
    ) {
        if group.is_some() && group == self.last_group {
            return;
        }
        self.last_group = group;
        self.group_was_unsaved = was_unsaved;
        self.undo.push_back(before.clone());
        while self.undo.len() > limit.max(1) {
            self.undo.pop_front();
        }
        self.redo.clear();
    }

    /// Undo (`undo`) or redo one step from `current`: returns the document to
    /// restore and moves `current` onto the other stack.
    pub(crate) fn step(&mut self, undo: bool, current: DocState) -> Option<DocState> {
        let target = if undo {
            self.undo.pop_back()
        } else {
            self.redo.pop()
        }?;
        if undo {
            self.redo.push(current);
        } else {
            self.undo.push_back(current);
        }
        self.last_group = None;
        Some(target)
    }

    /// Cancels the open group `group`: returns the scene from before its first
    /// edit, and whether it had unsaved changes then, and drops that undo step.
    pub(crate) fn cancel(&mut self, group: u64) -> Option<(DocState, bool)> {
        if self.last_group != Some(group) {
            return None;
        }
        self.last_group = None;
        self.undo.pop_back().map(|s| (s, self.group_was_unsaved))
    }

    /// Forgets everything (after a load).
    pub(crate) fn clear(&mut self) {
        self.undo.clear();
        self.redo.clear();
        self.last_group = None;
    }
}

/// What one edit cost, stage by stage.
#[derive(Debug, Clone, Default, PartialEq, serde::Serialize)]
pub struct EditStats {
    /// The edit (or edits) of the frame.
    pub edit: String,
    /// Everything was rebuilt.
    pub full_rebuild: bool,
    /// Tangents re-blended over all levels.
    pub tangents_reblended: usize,
    /// Details re-applied.
    pub details_reapplied: usize,
    /// Streamlines re-integrated.
    pub streamlines_reintegrated: usize,
    /// Streamlines placed again on a changed initial curve or anchor, with
    /// no tangent re-blended (an initial-curve edit moves each rigidly, Eq. 1).
    pub streamlines_replaced: usize,
    /// Mesh rows rewritten.
    pub mesh_rows: usize,
    /// Microseconds in each stage.
    pub us_edit: f64,
    /// Blend stage.
    pub us_blend: f64,
    /// Integrate stage.
    pub us_integrate: f64,
    /// Mesh stage.
    pub us_mesh: f64,
}

impl EditStats {
    /// Microseconds over all stages.
    pub fn us_total(&self) -> f64 {
        self.us_edit + self.us_blend + self.us_integrate + self.us_mesh
    }
}

/// Stats of the model.
#[derive(Resource, Debug, Clone, Default)]
pub struct Stats {
    /// The last frame that had an edit.
    pub last: EditStats,
    /// Tangents in all levels.
    pub tangents_total: usize,
    /// Streamlines at the display depth.
    pub streamlines: usize,
    /// `(rows, cols)` of each level.
    pub levels: Vec<(usize, usize)>,
    /// Whether the current frame is collecting an edit's stats.
    pub(crate) collecting: bool,
}

/// The outcome of each edit of the last frame that had edits.
#[derive(Resource, Debug, Clone, Default)]
pub struct EditLog {
    /// `Ok(what was done)` or `Err(why not)`, in order.
    pub entries: Vec<Result<String, super::EditError>>,
    /// Increases with each frame that had edits.
    pub frame: u64,
}

/// The surface at the display depth: points (rows × (cols + 1)), which are
/// the mesh's positions (kept once), the mesh's normals and triangles, and
/// each row's bounding box. Every change of it is announced by a
/// [`SurfaceChanged`] message (read with [`SurfaceChanges`]).
#[derive(Resource, Debug, Clone)]
pub struct SurfaceData {
    /// Streamline points, one row per streamline: the mesh's vertices, row-major.
    pub points: Grid<DVec3>,
    /// Unit vertex normals, one per point: every one exact, except in
    /// [`SurfaceData::normals_behind`] while the editor defers them
    /// ([`DeferNormals`]).
    pub normals: Vec<DVec3>,
    /// Triangles, three indices into the points each.
    pub indices: Vec<u32>,
    /// Each row's bounding box `[min, max]`, written with the row.
    pub row_bounds: Vec<[DVec3; 2]>,
    /// Set by the integrate stage when it gave the points a new shape (the
    /// mesh stage then makes the normals and triangles afresh).
    pub(crate) reshaped: bool,
    /// The points whose `normals` the mesh stage left unwritten while
    /// [`DeferNormals`] was on (the renderer's `f32` staging pair has them,
    /// or nothing draws the surface); written as soon as it is off.
    pub(crate) normals_behind: Option<DirtyWindow>,
}

/// Whether the mesh stage may leave the surface's `f64` normals
/// ([`SurfaceData::normals`]) unwritten, in the window of a drag's steady
/// frames, writing only the renderer's `f32` staging pair
/// ([`super::vertex_mirror::VertexMirror`]) that it makes them for. The
/// editor turns it on while a handle is dragged and nothing reads those
/// normals (no zebra stripes, and no joined patches unless the first patch
/// heads a G2 run); off (the default, and always headless), the mesh stage
/// first writes whatever it left behind.
/// On the car at depth 6 that is 4 MB of stores less in a drag's frame.
#[derive(Resource, Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct DeferNormals(pub bool);

impl Default for SurfaceData {
    fn default() -> Self {
        SurfaceData {
            points: Grid::filled(0, 0, DVec3::ZERO),
            normals: Vec::new(),
            indices: Vec::new(),
            row_bounds: Vec::new(),
            reshaped: false,
            normals_behind: None,
        }
    }
}

impl SurfaceData {
    /// The mesh as the kernel's type (a copy, for export), its normals all
    /// exact (those left behind, [`DeferNormals`], made for the copy).
    pub fn mesh(&self) -> SurfaceMesh {
        let mut normals = self.normals.clone();
        if let Some(w) = self.normals_behind {
            normals_window(
                self.points.data(),
                self.points.cols(),
                w.rows.lo,
                w.rows.hi,
                w.cols.lo,
                &mut normals,
            );
        }
        SurfaceMesh {
            positions: self.points.data().to_vec(),
            normals,
            indices: self.indices.clone(),
        }
    }

    /// The points whose [`Self::normals`] are not written yet (`None`: every
    /// normal is exact); see [`DeferNormals`].
    pub fn normals_behind(&self) -> Option<DirtyWindow> {
        self.normals_behind
    }

    /// Number of triangles.
    pub fn triangle_count(&self) -> usize {
        self.indices.len() / 3
    }

    /// The bounding box `[min, max]` of all points (`None` when there are none).
    pub fn bounds(&self) -> Option<[DVec3; 2]> {
        self.row_bounds
            .iter()
            .copied()
            .reduce(|[a, b], [c, d]| [a.min(c), b.max(d)])
    }
}

/// A change of [`SurfaceData`], written by the mesh stage: the points whose
/// position or normal it rewrote, `None` when the surface was made afresh (a
/// new shape: new triangles too).
#[derive(Message, Debug, Clone, Copy, PartialEq)]
pub struct SurfaceChanged {
    /// Points (rows × columns of [`SurfaceData::points`]) rewritten; `None`: all.
    pub window: Option<DirtyWindow>,
}

/// What a reader of the surface must redo since it last looked.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SurfaceChange {
    /// Nothing changed.
    Unchanged,
    /// Only these points (the union of the windows of the changes).
    Window(DirtyWindow),
    /// Everything (a new surface, or changes the reader did not see).
    All,
}

impl SurfaceChange {
    /// Whether anything changed.
    pub fn any(self) -> bool {
        self != SurfaceChange::Unchanged
    }
}

/// A reader of [`SurfaceChanged`] with its own cursor: a system that takes
/// [`SurfaceChanges::take`] learns everything that changed since it last
/// ran, however many frames it skipped (messages it was too late to see
/// count as a change of everything), so what it derives stays exact.
#[derive(bevy::ecs::system::SystemParam)]
pub struct SurfaceChanges<'w, 's> {
    messages: Res<'w, Messages<SurfaceChanged>>,
    cursor: Local<'s, bevy::ecs::message::MessageCursor<SurfaceChanged>>,
}

impl SurfaceChanges<'_, '_> {
    /// The changes since the last call, merged.
    pub fn take(&mut self) -> SurfaceChange {
        let missed = self.cursor.missed_messages(&self.messages) > 0;
        let mut out = if missed {
            SurfaceChange::All
        } else {
            SurfaceChange::Unchanged
        };
        for m in self.cursor.read(&self.messages) {
            out = match (out, m.window) {
                (SurfaceChange::All, _) | (_, None) => SurfaceChange::All,
                (SurfaceChange::Unchanged, Some(w)) => SurfaceChange::Window(w),
                (SurfaceChange::Window(a), Some(w)) => SurfaceChange::Window(a.union(w)),
            };
        }
        out
    }
}
