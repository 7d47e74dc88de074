//! The deviation map to the reference (docs/math.md §12): each shown point
//! of the first patch coloured by its distance to the face its
//! `reference` names, green at 0 to red at the tolerance and beyond, with
//! the largest and mean distance in the Analysis section.
//!
//! The file is read and its closest-point index built once per reference
//! (path and face) and kept in [`ReferenceField`], built again when the
//! reference changes; a file that cannot be read is the field's
//! [`ReferenceField::error`], shown in the panel. The distances are
//! measured again when the surface changes: during a drag only when the
//! shown points are at most [`LIVE_POINTS`] (about 14 ms at 0.7 µs a point),
//! else when the drag ends. As `reference_fit::measure` does, a mirrored
//! design measures its own half (the rows from the middle on); the
//! reflected rows show the distance of the point they reflect.
//!
//! The tolerance is [`TOLERANCE_SHARE`] of the diagonal of the face's
//! bounding box (of a 33 × 33 sample of the face): the relative tolerance a
//! fit to a reference takes by default (`fit::options::DEFAULT_RELATIVE_TOLERANCE`),
//! so a design fitted with the defaults is green where the fit held it
//! (1.80e-4 m for `scenes/references/hood.step`, whose fit's is 1.797e-4 m).

use super::super::interaction::{Drag, EditorSet};
use crate::ecs::patch::PatchRef;
use crate::ecs::{SurfaceChanges, SurfaceData};
use crate::scene::reference_fit::measured_points;
use crate::scene::reference_link::ReferenceLink;
use bevy::prelude::*;
use streamline_kernel::fit::{ClosestPoints, Distances, ReferenceSurface};
use streamline_kernel::{DVec3, Grid};

/// At most this many shown points are measured live during a drag.
pub const LIVE_POINTS: usize = 20_000;

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
    index: Option<ClosestPoints<'static>>,
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
}

impl ReferenceField {
    /// Reads the file of `link` and builds its index ([`Self::error`] when
    /// it cannot).
    fn load(&mut self, link: Option<ReferenceLink>) {
        self.index = None;
        self.error = None;
        self.values = None;
        self.stale = true;
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

    /// Measures the shown points `points` of the first patch (module
    /// documentation).
    fn measure(&mut self, points: &Grid<DVec3>, mirror: bool) {
        let Some(index) = &self.index else {
            return;
        };
        let t0 = std::time::Instant::now();
        let half = index.distances(measured_points(points, mirror));
        let values = shown_distances(&half, points.rows(), points.cols(), mirror);
        self.distances = Distances::of(&half);
        self.values = Some(values);
        self.seconds = t0.elapsed().as_secs_f64();
        self.stale = false;
        self.generation += 1;
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

/// The closest-point index of the face of `link` and the map's tolerance.
fn index_of(link: &ReferenceLink) -> Result<(ClosestPoints<'static>, f64), String> {
    let file = streamline_reference::read(&link.path).map_err(|e| e.to_string())?;
    let surface = file.surface(link.face).map_err(|e| e.to_string())?;
    let tolerance = TOLERANCE_SHARE * diagonal(surface);
    let index = ClosestPoints::shared(std::sync::Arc::new(surface.clone()))
        .map_err(|e| format!("{}: face {}: {e}", link.path.display(), link.face))?;
    Ok((index, tolerance))
}

/// The diagonal of the bounding box of a 33 × 33 sample of `surface`.
fn diagonal(surface: &dyn ReferenceSurface) -> f64 {
    let ([u0, u1], [v0, v1]) = surface.domain();
    let n = 32;
    let (mut lo, mut hi) = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
    for i in 0..=n {
        for j in 0..=n {
            let u = u0 + (u1 - u0) * i as f64 / n as f64;
            let v = v0 + (v1 - v0) * j as f64 / n as f64;
            let p = surface.point(u, v);
            lo = lo.min(p);
            hi = hi.max(p);
        }
    }
    (hi - lo).length()
}

/// Keeps the index for the design's reference and, while the map is
/// shown, the distances of the shown points (module documentation).
fn measure_reference(
    meter: Res<crate::ecs::meter::CpuMeter>,
    patch: PatchRef,
    data: Res<SurfaceData>,
    mut changes: SurfaceChanges,
    drag: Res<Drag>,
    mut field: ResMut<ReferenceField>,
) {
    let _meter = meter.start();
    if changes.take().any() {
        field.stale = true;
    }
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
    let dragging = drag.0.is_some();
    if dragging && data.points.data().len() > LIVE_POINTS {
        return; // when the drag ends
    }
    field.measure(&data.points, patch.structure().mirror);
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
}
