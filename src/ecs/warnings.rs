//! What the last build blended about a fixed axis (docs/math.md §1): the
//! antipodal neighbours among the tangents each subdivision step blends,
//! found in the levels the blend stage built and in the initial curve's
//! control tangents, as warnings naming the tangents. The command line's
//! `build` report, `play` and the editor's status line and Stats read
//! [`BuildWarnings`].

use super::components::{LevelData, LevelWindow, SubdivisionLevel};
use super::patch::PatchRef;
use bevy::prelude::*;
use streamline_kernel::levels::antipodal::{AntipodalPair, antipodal_pairs, antipodal_pairs_from};
use streamline_kernel::sphere::antipodal::antipodal_legs;

/// The most pairs named one by one; more are counted in one last line.
pub const MAX_LISTED: usize = 8;

/// The warnings of the current build, each a sentence that names the
/// tangents and what to do. Written only when they change (so
/// `Res::is_changed` tells a reader there is something new to say).
#[derive(Resource, Debug, Clone, Default, PartialEq)]
pub struct BuildWarnings {
    /// The sentences, in the order of the levels and cells.
    pub lines: Vec<String>,
}

/// The pairs of each level below the finest, as the last run found them:
/// what an edit did not touch is not scanned again.
#[derive(Default)]
pub(crate) struct LevelPairs {
    /// Per level (sorted by level): its shape and its pairs, in scan order.
    levels: Vec<((usize, usize), Vec<AntipodalPair>)>,
}

/// The levels, with the window of their last change.
type Levels<'w, 's> = Query<
    'w,
    's,
    (
        &'static SubdivisionLevel,
        Ref<'static, LevelData>,
        Option<Ref<'static, LevelWindow>>,
    ),
>;

/// Scans the levels and the initial curve again whenever a level changed:
/// a level the blend stage re-blended in a window ([`LevelWindow`]) only
/// there (the pairs with a cell in the window), a level built whole all over.
///
/// Every level but the finest is blended by the next step, along its rows and
/// its columns (docs/math.md §3), so those are the pairs scanned; level 0 of
/// a mirrored scene is the doubled net (docs/math.md §9), whose rows `m − 1 ±
/// j` are the scene's row `j`: its pairs are named by the scene's cells.
pub(crate) fn find_antipodal_blends(
    meter: Res<super::meter::CpuMeter>,
    patch: PatchRef,
    levels: Levels,
    mut warnings: ResMut<BuildWarnings>,
    mut known: Local<LevelPairs>,
) {
    let _meter = meter.start();
    if !levels.iter().any(|(_, d, _)| d.is_changed()) && !patch.design_changed() {
        return;
    }
    let finest = levels.iter().map(|(l, ..)| l.0).max().unwrap_or(0);
    let mut sorted: Vec<_> = levels.iter().filter(|(l, ..)| l.0 < finest).collect();
    sorted.sort_by_key(|(l, ..)| l.0);
    let known = &mut known.levels;
    let same_levels = known.len() == sorted.len()
        && (known.iter().zip(&sorted)).all(|((shape, _), (_, d, _))| *shape == d.0.shape());
    if !same_levels {
        known.clear();
        known.resize_with(sorted.len(), Default::default);
    }
    for ((shape, pairs), (l, d, w)) in known.iter_mut().zip(&sorted) {
        if same_levels && !d.is_changed() {
            continue;
        }
        // the window the blend stage recomputed with this change, if it says
        let window = w
            .as_ref()
            .filter(|w| same_levels && w.is_changed() && !d.is_added())
            .and_then(|w| w.0);
        match window {
            Some(w) => {
                // a pair's second cell is the right or lower neighbour of its
                // first: the pairs that read the window start up to one row
                // and one column before it
                let rows = w.rows.lo.saturating_sub(1)..=w.rows.hi;
                let cols = w.cols.lo.saturating_sub(1)..=w.cols.hi;
                pairs.retain(|p| !(rows.contains(&p.a.0) && cols.contains(&p.a.1)));
                antipodal_pairs_from(l.0, &d.0.tangents, rows, cols, pairs);
                pairs.sort_unstable(); // the scan's order (row-major, right before below)
            }
            None => {
                pairs.clear();
                antipodal_pairs(l.0, &d.0.tangents, pairs);
            }
        }
        *shape = d.0.shape();
    }
    let mut pairs: Vec<AntipodalPair> = known.iter().flat_map(|(_, p)| p.iter().copied()).collect();
    if patch.structure().mirror {
        let m = patch.structure().rows;
        fold_mirror(&mut pairs, m);
    }
    let mut lines: Vec<String> = pairs
        .iter()
        .take(MAX_LISTED)
        .map(|p| p.to_string())
        .collect();
    if pairs.len() > MAX_LISTED {
        lines.push(format!(
            "… and {} more antipodal blends",
            pairs.len() - MAX_LISTED
        ));
    }
    for k in antipodal_legs(patch.design().initial().qi().tangents()) {
        lines.push(format!(
            "antipodal blend between initial-curve tangents {k} and {}: they point in opposite directions, so the initial curve between them turns about a fixed axis; turn one of them",
            k + 1
        ));
    }
    warnings.set_if_neq(BuildWarnings { lines });
}

/// Names level-0 pairs of the doubled net by the scene's rows (row `i` of
/// the doubled net is the scene's row `|i − (m − 1)|`), each pair once.
fn fold_mirror(pairs: &mut Vec<AntipodalPair>, m: usize) {
    let fold = |(r, c): (usize, usize)| (r.abs_diff(m - 1), c);
    for p in pairs.iter_mut().filter(|p| p.level == 0) {
        let (a, b) = (fold(p.a), fold(p.b));
        (p.a, p.b) = if a <= b { (a, b) } else { (b, a) };
    }
    let mut seen = std::collections::HashSet::new();
    pairs.retain(|p| seen.insert(*p));
}
