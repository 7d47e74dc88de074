//! What a patch's blend stage must redo ([`Dirty`]).

use bevy::prelude::*;
use streamline_kernel::levels::dirty_window::DirtyWindow;

/// What the blend stage must redo for a patch: written by
/// [`super::track::track_handles`] alone, from the changes of the handles'
/// and the patch's components (docs/architecture.md, "Incremental rebuild,
/// exactly"), and taken by the blend stage. Three kinds of change:
/// - cells of a level (a control tangent or its `s`, a detail): the blend
///   stage re-blends the window they make dirty, level by level;
/// - every streamline's start point (an edit of the initial curve): each
///   streamline is placed again, nothing is re-blended;
/// - everything (a new net shape, scheme, depth or scene): the levels and
///   streamlines are built afresh.
#[derive(Component, Debug)]
pub struct Dirty {
    full: bool,
    replace: bool,
    windows: Vec<Option<DirtyWindow>>,
}

impl Default for Dirty {
    /// Asks for a full build (nothing is built yet).
    fn default() -> Self {
        Dirty {
            full: true,
            replace: false,
            windows: Vec::new(),
        }
    }
}

impl Dirty {
    /// Cell `(row, col)` of level `level` changed.
    pub(crate) fn cell(&mut self, level: u32, row: usize, col: usize) {
        let l = level as usize;
        if self.windows.len() <= l {
            self.windows.resize(l + 1, None);
        }
        self.windows[l] = Some(DirtyWindow::merge(
            self.windows[l],
            DirtyWindow::cell(row, col),
        ));
    }

    /// Every streamline must be placed again on the initial curve (its
    /// tangents, `s` and `σ` are as they were).
    pub(crate) fn replace_streamlines(&mut self) {
        self.replace = true;
    }

    /// Everything must be built afresh (the levels' shapes may change).
    pub(crate) fn rebuild(&mut self) {
        self.full = true;
    }

    /// Whether nothing is pending.
    pub fn is_clean(&self) -> bool {
        !self.full && !self.replace && self.windows.iter().all(Option::is_none)
    }

    /// Mirror symmetry (`docs/math.md §9`): the level-0 cells marked so far
    /// are rows of the half, whose `m` rows are rows `m − 1 ..` of the
    /// doubled net the levels are built from, and whose reflections are rows
    /// `.. m − 1`: a window of half rows `lo ..= hi` becomes doubled rows
    /// `m − 1 − hi ..= m − 1 + hi` (both copies and the rows between).
    pub(crate) fn mirror_rows(&mut self, m: usize) {
        if let Some(Some(w)) = self.windows.first_mut() {
            let (lo, hi) = (m - 1 - w.rows.hi.min(m - 1), m - 1 + w.rows.hi);
            w.rows = streamline_kernel::levels::dirty_window::Span::new(lo, hi);
        }
    }

    /// Takes what is pending, leaving nothing: `(full, replace, windows)`.
    pub(crate) fn take(&mut self) -> (bool, bool, Vec<Option<DirtyWindow>>) {
        let full = std::mem::take(&mut self.full);
        let replace = std::mem::take(&mut self.replace);
        (full, replace, std::mem::take(&mut self.windows))
    }
}
