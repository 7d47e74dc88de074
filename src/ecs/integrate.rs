//! The integrate stage: streamlines whose tangents or fine-tuning function
//! changed are integrated again (Eq. 65, or its fine-tuned form, docs/math.md §6) and
//! placed on the initial curve (Eqs. 1–2), into their row of the surface's
//! points ([`SurfaceData`]).

use super::components::*;
use super::patch::PatchRef;
use super::resources::{Stats, SurfaceData};
use bevy::prelude::*;
use std::time::Instant;
use streamline_kernel::finetune::{Constraint, SurfaceTuning, fine_tune_into};
use streamline_kernel::levels::incremental::surface_rows;
use streamline_kernel::streamline::integrate::{SliceJob, place_slice, place_slices_from};
use streamline_kernel::streamline::surface_mesh::slice_bounds;
use streamline_kernel::{DVec3, Grid};

/// Gives every streamline its function of the scene's fine tuning; only rows
/// whose function differs are marked changed. Free: the row's restriction of
/// the tensor function. Under a constraint: the restriction changed by the
/// correction field that meets every streamline's constraint and is smooth
/// across the streamlines (docs/math.md §6, (T4)–(T6)), solved over the
/// display level at once; the component then holds that function, applied
/// as it is (`Constraint::Free`).
pub(crate) fn retune(
    meter: Res<super::meter::CpuMeter>,
    patch: PatchRef,
    levels: Query<(&SubdivisionLevel, Ref<LevelData>)>,
    mut lines: Query<(&Streamline, &StreamlineTangents, &mut StreamlineAlpha)>,
    added: Query<(), (Added<Streamline>, Without<JoinedChild>)>,
) {
    let _meter = meter.start();
    let depth = patch.structure().display_depth;
    // under a constraint the functions follow the display level's tangents
    let shown_changed = || levels.iter().any(|(l, d)| l.0 == depth && d.is_changed());
    if !patch.tuning_changed()
        && added.is_empty()
        && !(patch
            .tuning()
            .is_some_and(|t| t.constraint != Constraint::Free)
            && shown_changed())
    {
        return;
    }
    let Some(tuning) = patch.tuning() else {
        for (_, _, mut a) in &mut lines {
            a.set_if_neq(StreamlineAlpha(None));
        }
        return;
    };
    if tuning.constraint != Constraint::Free
        && let Some((_, level)) = levels.iter().find(|(l, _)| l.0 == depth)
    {
        let fs = tuning.row_functions(surface_rows(&level.0.tangents, &level.0.params));
        for (line, _, mut a) in &mut lines {
            if let Some(f) = fs.get(line.row) {
                a.set_if_neq(StreamlineAlpha(Some((f.clone(), Constraint::Free))));
            }
        }
        return;
    }
    let (lo, hi) = lines
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), (_, t, _)| {
            (lo.min(t.t), hi.max(t.t))
        });
    for (_, t, mut a) in &mut lines {
        let v = SurfaceTuning::row_v(t.t, lo, hi);
        let f = tuning.row_function(v);
        a.set_if_neq(StreamlineAlpha(Some((f, tuning.constraint))));
    }
}

/// Streamlines whose tangents or fine-tuning function changed.
type ChangedLines<'w, 's> = Query<
    'w,
    's,
    (
        &'static Streamline,
        &'static mut StreamlineTangents,
        Ref<'static, StreamlineAlpha>,
        &'static mut StreamlinePoints,
    ),
    Or<(Changed<StreamlineTangents>, Changed<StreamlineAlpha>)>,
>;

pub(crate) fn integrate(
    meter: Res<super::meter::CpuMeter>,
    patch: PatchRef,
    levels: Query<(&SubdivisionLevel, &LevelData)>,
    mut lines: ChangedLines,
    mut surface: ResMut<SurfaceData>,
    mut stats: ResMut<Stats>,
    mut tuned: Local<Vec<DVec3>>,
) {
    let _meter = meter.start();
    let t0 = Instant::now();
    let depth = patch.structure().display_depth;
    let Some((_, level)) = levels.iter().find(|(l, _)| l.0 == depth) else {
        return;
    };
    if lines.is_empty() {
        return;
    }
    let (rows, cols) = level.0.shape();
    let surface = &mut *surface;
    // a new shape (a new depth, a new net): every row is new and integrated below
    let reshaped = surface.points.rows() != rows || surface.points.cols() != cols + 1;
    if reshaped {
        surface.points = Grid::filled(rows, cols + 1, DVec3::ZERO);
        surface.row_bounds = vec![[DVec3::ZERO; 2]; rows];
        surface.reshaped = true;
    }
    let mut n = 0;
    // the rows only summed again from a point (every row of a drag's
    // frame): all together below, four at a time
    let mut summed = Vec::new();
    for (line, mut t, alpha, mut p) in &mut lines {
        if line.row >= rows {
            continue;
        }
        let (tangents, s) = level.row(line.row);
        let out = surface.points.row_mut(line.row);
        p.moved_from = match &alpha.0 {
            // only the tangents from `changed_from` on moved: the running
            // sum (Eq. 65) goes on from the point there
            None if !alpha.is_changed() && !reshaped => {
                summed.push((line.row, t, p));
                continue;
            }
            None => {
                place_slice(tangents, s, t.sigma, t.origin, out);
                0
            }
            Some((f, c)) => {
                fine_tune_into(tangents, s, t.sigma, t.origin, f, *c, &mut tuned);
                out.copy_from_slice(&tuned);
                0
            }
        };
        // the row's box, while its points are in the cache
        surface.row_bounds[line.row] = slice_bounds(surface.points.row(line.row));
        // integrated: nothing pending (not an edit of the row, so not marked)
        t.bypass_change_detection().changed_from = usize::MAX;
        n += 1;
    }
    if !summed.is_empty() {
        let SurfaceData {
            points, row_bounds, ..
        } = surface;
        let mut outs: Vec<Option<&mut [DVec3]>> =
            points.data_mut().chunks_mut(cols + 1).map(Some).collect();
        // (one streamline per row: a row is not taken twice)
        let (index, mut jobs): (Vec<usize>, Vec<SliceJob>) = summed
            .iter()
            .enumerate()
            .filter_map(|(k, (row, t, _))| {
                let (tangents, s) = level.row(*row);
                let job = SliceJob {
                    tangents,
                    s,
                    sigma: t.sigma,
                    origin: t.origin,
                    from: t.changed_from,
                    out: outs[*row].take()?,
                    moved_from: 0,
                    bounds: [DVec3::ZERO; 2],
                };
                Some((k, job))
            })
            .unzip();
        place_slices_from(&mut jobs);
        for (job, k) in jobs.iter().zip(index) {
            let (row, t, p) = &mut summed[k];
            row_bounds[*row] = job.bounds;
            p.moved_from = job.moved_from;
            t.bypass_change_detection().changed_from = usize::MAX;
            n += 1;
        }
    }
    if n > 0 {
        stats.last.streamlines_reintegrated += n;
        stats.last.us_integrate += t0.elapsed().as_secs_f64() * 1e6;
    }
}
