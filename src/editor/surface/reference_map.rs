//! The deviation map to the reference (docs/math.md §12): each shown point
//! of the first patch (its G2 run's cut when it heads one, as it is drawn)
//! coloured by its distance to the face its
//! `reference` names, green at 0 to red at the tolerance and beyond, with
//! the largest and mean distance in the Analysis section.
//!
//! The file is read and its closest-point index built once per reference
//! (path and face) and kept in [`ReferenceField`], built again when the
//! reference changes; a file that cannot be read is the field's
//! [`ReferenceField::error`], shown in the panel. The distances are
//! measured again when the surface changes, and only where it changed: the
//! mesh stage names the window of points it rewrote ([`SurfaceChanges`]),
//! and the map measures the streamlines (rows) and columns of that window
//! again and keeps every other point's distance, so its values are those
//! of a full measure, bit for bit (each point's distance depends on that
//! point alone). A new shape, a new reference, or changes the map did not
//! see are measured whole. During a drag the map is measured live when the
//! points to measure are at most [`LIVE_POINTS`] (a share of a 4 ms frame
//! at about 0.7 µs a point), else when the drag ends. As
//! `scene::fit::reference::measure` does, a mirrored design measures its own half
//! (the rows from the middle on); the reflected rows show the distance of
//! the point they reflect, and a change of a reflected row measures the row
//! it reflects.
//!
//! The tolerance is [`TOLERANCE_SHARE`] of the diagonal of the face's
//! bounding box (of a 33 × 33 sample of the face): the relative tolerance a
//! fit to a reference takes by default (`fit::options::DEFAULT_RELATIVE_TOLERANCE`),
//! so a design fitted with the defaults is green where the fit held it
//! (1.80e-4 m for `scenes/references/hood.step`, whose fit's is 1.797e-4 m).

use super::super::interaction::{Drag, EditorSet};
use crate::ecs::joined::{PatchStart, PatchSurface, shows_run_cut};
use crate::ecs::patch::PatchRef;
use crate::ecs::{SurfaceChange, SurfaceChanges, SurfaceData};
use crate::scene::files::reference_link::ReferenceLink;
use crate::scene::fit::reference::measured_points;
use bevy::prelude::*;
use streamline_kernel::fit::{Distances, ReferenceIndex};
use streamline_kernel::levels::dirty_window::{DirtyWindow, Span};
use streamline_kernel::{DVec3, Grid};

/// At most this many points are measured in a frame of a drag (the rows
/// and columns the drag moved, [`ReferenceField::update`]); a drag that moves
/// more is measured when it ends. About 2 ms at 0.7 µs a point: half the
/// 4 ms a drag's frame may take.
pub const LIVE_POINTS: usize = 3_000;

/// The map's tolerance as a share of the face's bounding-box diagonal: the
/// fit's default.
pub const TOLERANCE_SHARE: f64 = streamline_kernel::fit::options::DEFAULT_RELATIVE_TOLERANCE;

pub struct ReferenceMapPlugin;

impl Plugin for ReferenceMapPlugin {
    fn build(&self, app: &mut App) {
        app.init_resource::<ReferenceField>().add_systems(
            Update,
            measure_reference
                .in_set(EditorSet::Present)
                .in_set(ReferenceMeasure),
        );
    }
}

/// Where the distances are measured: the analysis display reads them after
/// it, and says before it whether the map is shown ([`ReferenceField::shown`]).
#[derive(SystemSet, Debug, Clone, PartialEq, Eq, Hash)]
pub struct ReferenceMeasure;

/// The reference's index and the last distances measured against it.
#[derive(Resource, Default)]
pub struct ReferenceField {
    /// The reference the index was built for (also when that failed).
    loaded: Option<ReferenceLink>,
    /// The closest-point index of the face (it keeps its own copy of the
    /// face's surface).
    index: Option<ReferenceIndex>,
    /// Whether the map is shown (the Analysis mode "to reference", which
    /// `super::analysis` sets): only then is the file read and measured.
    pub shown: bool,
    /// Whether the design has a reference now.
    pub has_reference: bool,
    /// Why the reference could not be read or indexed.
    pub error: Option<String>,
    /// [`TOLERANCE_SHARE`] of the face's bounding-box diagonal.
    pub tolerance: f64,
    /// The distance of each shown point (row-major, as the surface's points).
    pub values: Option<Vec<f64>>,
    /// Largest and mean distance of the measured points.
    pub distances: Distances,
    /// Seconds the last measurement took.
    pub seconds: f64,
    /// Whether the last measurement was made during a drag (live).
    pub live: bool,
    /// The surface changed since the distances were measured.
    pub stale: bool,
    /// Counts the measurements (the map's coordinates follow it).
    pub generation: u64,
    /// Points the last measurement measured: all the measured points, or
    /// those of the window that changed.
    pub measured: usize,
    /// The shown rows and columns the last measurement measured (of the
    /// measured half when mirrored); `None`: every point.
    pub window: Option<DirtyWindow>,
    /// The changes not measured yet, merged (`All` after a new reference).
    pending: Pending,
    /// The distance of each measured point ([`measured_points`]), and the
    /// shown grid's `(rows, cols, mirror)` they were measured on.
    half: Vec<f64>,
    shape: (usize, usize, bool),
}

/// What the map must measure again.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
enum Pending {
    /// Nothing.
    #[default]
    None,
    /// These shown points (rows × columns).
    Window(DirtyWindow),
    /// Every point.
    All,
}

impl Pending {
    fn with(self, change: SurfaceChange) -> Pending {
        match (self, change) {
            (p, SurfaceChange::Unchanged) => p,
            (Pending::All, _) | (_, SurfaceChange::All) => Pending::All,
            (Pending::None, SurfaceChange::Window(w)) => Pending::Window(w),
            (Pending::Window(a), SurfaceChange::Window(w)) => Pending::Window(a.union(w)),
        }
    }
}

/// The measured rows (`lo..=hi`, of the shown grid) and the columns
/// (`lo..=hi`) that hold every point of `w`'s rows or of the rows they
/// reflect (with the mirror on, the measured rows are those from the middle
/// on, row `r` showing row `max(r, rows − 1 − r)`).
fn measured_window(w: DirtyWindow, rows: usize, mirror: bool) -> ((usize, usize), (usize, usize)) {
    let measured = |r: usize| if mirror { r.max(rows - 1 - r) } else { r };
    let (lo, hi) = w
        .rows
        .iter()
        .map(measured)
        .fold((usize::MAX, 0), |(lo, hi), m| (lo.min(m), hi.max(m)));
    ((lo, hi), (w.cols.lo, w.cols.hi))
}

impl ReferenceField {
    /// Reads the file of `link` and builds its index ([`Self::error`] when
    /// it cannot).
    fn load(&mut self, link: Option<ReferenceLink>) {
        self.index = None;
        self.error = None;
        self.values = None;
        self.stale = true;
        self.pending = Pending::All;
        if let Some(l) = &link {
            match index_of(l) {
                Ok((index, tolerance)) => {
                    self.index = Some(index);
                    self.tolerance = tolerance;
                }
                Err(e) => self.error = Some(e),
            }
        }
        self.loaded = link;
    }

    /// Measures every point again at the next update, as a new reference
    /// would (the incremental measure's check in the tests).
    pub fn remeasure_all(&mut self) {
        self.pending = Pending::All;
        self.stale = true;
    }

    /// Notes a change of the surface: measured by the next
    /// [`Self::update`].
    pub fn note(&mut self, change: SurfaceChange) {
        self.pending = self.pending.with(change);
        if self.pending != Pending::None {
            self.stale = true;
        }
    }

    /// The points the next [`Self::update`] of `points` measures: all the
    /// measured points, or the window that changed
    /// ([`measured_window`]) when the last measurement was of this shape;
    /// `None` when nothing changed.
    fn to_measure(&self, points: &Grid<DVec3>, mirror: bool) -> Option<Measure> {
        let (rows, cols) = (points.rows(), points.cols());
        let all = measured_points(points, mirror).len();
        match self.pending {
            Pending::None if self.values.is_some() => None,
            Pending::Window(w)
                if self.values.is_some()
                    && self.shape == (rows, cols, mirror)
                    && self.half.len() == all
                    && w.rows.hi < rows
                    && w.cols.hi < cols =>
            {
                let ((r0, r1), (c0, c1)) = measured_window(w, rows, mirror);
                Some(Measure::Window {
                    rows: (r0, r1),
                    cols: (c0, c1),
                    points: (r1 - r0 + 1) * (c1 - c0 + 1),
                })
            }
            _ => Some(Measure::All { points: all }),
        }
    }

    /// Measures the shown points `points` of the first patch again where
    /// they changed (module documentation), or all of them; the largest
    /// and mean distance are those of every measured point.
    pub fn update(&mut self, points: &Grid<DVec3>, mirror: bool) {
        let Some(what) = self.to_measure(points, mirror) else {
            return;
        };
        let Some(index) = &self.index else {
            return;
        };
        let t0 = std::time::Instant::now();
        let (rows, cols) = (points.rows(), points.cols());
        match what {
            Measure::All { points: n } => {
                self.half = index.distances(measured_points(points, mirror));
                self.values = Some(shown_distances(&self.half, rows, cols, mirror));
                self.shape = (rows, cols, mirror);
                self.measured = n;
                self.window = None;
            }
            Measure::Window {
                rows: (r0, r1),
                cols: (c0, c1),
                points: n,
            } => {
                let data = points.data();
                let width = c1 - c0 + 1;
                // one call, so that a large window is measured on two threads
                let mut window = Vec::with_capacity(n);
                for r in r0..=r1 {
                    window.extend_from_slice(&data[r * cols + c0..=r * cols + c1]);
                }
                let d = index.distances(&window);
                let first = if mirror { rows / 2 } else { 0 };
                let values = self.values.get_or_insert_with(Vec::new);
                for (k, r) in (r0..=r1).enumerate() {
                    let row = &d[k * width..(k + 1) * width];
                    let h = (r - first) * cols;
                    self.half[h + c0..=h + c1].copy_from_slice(row);
                    values[r * cols + c0..=r * cols + c1].copy_from_slice(row);
                    if mirror {
                        let m = rows - 1 - r;
                        values[m * cols + c0..=m * cols + c1].copy_from_slice(row);
                    }
                }
                self.measured = n;
                self.window = Some(DirtyWindow {
                    rows: Span::new(r0, r1),
                    cols: Span::new(c0, c1),
                });
            }
        }
        self.distances = Distances::of(&self.half);
        self.pending = Pending::None;
        self.seconds = t0.elapsed().as_secs_f64();
        self.stale = false;
        self.generation += 1;
    }
}

/// What [`ReferenceField::update`] measures.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Measure {
    /// Every measured point (`points` of them).
    All { points: usize },
    /// The shown rows `rows` and columns `cols` (inclusive), `points` in all.
    Window {
        rows: (usize, usize),
        cols: (usize, usize),
        points: usize,
    },
}

impl Measure {
    fn points(self) -> usize {
        match self {
            Measure::All { points } | Measure::Window { points, .. } => points,
        }
    }
}

/// The distance of each shown point from those of the measured points
/// `half` (`rows × cols` shown): the same, or with the mirror on, each
/// reflected row `r` before the measured ones that of row `rows − 1 − r`
/// (`measured_points`).
fn shown_distances(half: &[f64], rows: usize, cols: usize, mirror: bool) -> Vec<f64> {
    if !mirror {
        return half.to_vec();
    }
    let first = rows / 2;
    (0..rows)
        .flat_map(|r| {
            let h = r.max(rows - 1 - r) - first;
            half[h * cols..(h + 1) * cols].iter().copied()
        })
        .collect()
}

/// The closest-point index of the face of `link` (a surface's or a
/// triangle mesh's, `scene::fit::reference::reference_index`) and the map's
/// tolerance.
fn index_of(link: &ReferenceLink) -> Result<(ReferenceIndex, f64), String> {
    let index = crate::scene::fit::reference::reference_index(link)?;
    let tolerance = TOLERANCE_SHARE * diagonal(&index);
    Ok((index, tolerance))
}

/// The reference's size: the diagonal of the bounding box of a 33 × 33
/// sample of the surface, or of a mesh's vertices.
fn diagonal(index: &ReferenceIndex) -> f64 {
    index.diagonal()
}

/// Keeps the index for the design's reference and, while the map is
/// shown, the distances of the shown points (module documentation).
#[allow(clippy::too_many_arguments)]
fn measure_reference(
    meter: Res<crate::ecs::meter::CpuMeter>,
    patch: PatchRef,
    data: Res<SurfaceData>,
    mut changes: SurfaceChanges,
    (starts, surfaces): (Query<&PatchStart>, Query<Ref<PatchSurface>>),
    drag: Res<Drag>,
    mut field: ResMut<ReferenceField>,
    mut was_cut: Local<bool>,
) {
    let _meter = meter.start();
    field.note(changes.take());
    // the first patch as drawn: the cut of the G2 run it heads, whose
    // moved rows its surface names, or its own incremental surface
    let first = patch.entity();
    let cut = (surfaces.get(first).ok()).filter(|s| shows_run_cut(first, starts.iter(), Some(s)));
    if cut.is_some() != *was_cut {
        *was_cut = cut.is_some();
        field.note(SurfaceChange::All);
    }
    if let Some(s) = cut.as_ref().filter(|s| s.is_changed()) {
        let cols = s.stack().map_or(0, |s| s.finest_points().cols());
        field.note(match s.rows {
            Some(r) if cols > 0 => SurfaceChange::Window(DirtyWindow {
                rows: Span::new(r.lo, r.hi),
                cols: Span::new(0, cols - 1),
            }),
            _ => SurfaceChange::All,
        });
    }
    let points = cut
        .as_ref()
        .and_then(|s| s.into_inner().stack())
        .map_or(&data.points, |s| s.finest_points());
    let link = patch.reference().cloned();
    let has = link.is_some();
    if field.has_reference != has {
        field.has_reference = has;
    }
    if !field.shown {
        return;
    }
    if field.loaded != link {
        field.load(link);
    }
    if field.index.is_none() || !field.stale {
        return;
    }
    let mirror = patch.structure().mirror;
    let Some(what) = field.to_measure(points, mirror) else {
        field.stale = false;
        return;
    };
    let dragging = drag.0.is_some();
    if dragging && what.points() > LIVE_POINTS {
        return; // when the drag ends
    }
    field.update(points, mirror);
    field.live = dragging;
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A mirrored design's reflected rows show the distance of the row they
    /// reflect; unmirrored, every point its own.
    #[test]
    fn reflected_rows_show_the_distance_they_reflect() {
        // 5 rows of 2 shown, the middle row 2: measured rows 2, 3, 4
        let half = [0.0, 0.1, 1.0, 1.1, 2.0, 2.1];
        let shown = shown_distances(&half, 5, 2, true);
        assert_eq!(
            shown,
            [2.0, 2.1, 1.0, 1.1, 0.0, 0.1, 1.0, 1.1, 2.0, 2.1].to_vec()
        );
        assert_eq!(shown_distances(&half, 3, 2, false), half.to_vec());
        // 4 rows: measured rows 2, 3; row 0 reflects row 3
        let even = shown_distances(&[5.0, 6.0], 4, 1, true);
        assert_eq!(even, [6.0, 5.0, 5.0, 6.0].to_vec());
    }

    /// A changed window is measured on the rows it changed, or with the
    /// mirror on on the measured rows they reflect; changes merge.
    #[test]
    fn a_window_is_measured_on_the_rows_it_reflects() {
        let w = |r0, r1, c0, c1| DirtyWindow {
            rows: Span::new(r0, r1),
            cols: Span::new(c0, c1),
        };
        assert_eq!(measured_window(w(0, 1, 2, 3), 5, false), ((0, 1), (2, 3)));
        // 5 rows, the middle row 2: rows 0, 1 show rows 4, 3
        assert_eq!(measured_window(w(0, 1, 2, 3), 5, true), ((3, 4), (2, 3)));
        assert_eq!(measured_window(w(1, 3, 0, 0), 5, true), ((2, 3), (0, 0)));
        assert_eq!(measured_window(w(3, 4, 0, 0), 5, true), ((3, 4), (0, 0)));
        let p = Pending::None.with(SurfaceChange::Window(w(0, 1, 0, 0)));
        let p = p.with(SurfaceChange::Unchanged);
        assert_eq!(p, Pending::Window(w(0, 1, 0, 0)));
        let p = p.with(SurfaceChange::Window(w(3, 3, 2, 2)));
        assert_eq!(p, Pending::Window(w(0, 3, 0, 2)));
        assert_eq!(p.with(SurfaceChange::All), Pending::All);
        assert_eq!(
            Pending::All.with(SurfaceChange::Window(w(0, 0, 0, 0))),
            Pending::All
        );
    }
}
