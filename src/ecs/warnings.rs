//! What the last build blended about a fixed axis (docs/math.md §1): the
//! antipodal neighbours among the tangents each subdivision step blends,
//! found in the levels the blend stage built and in the initial curve's
//! control tangents, as warnings naming the tangents. The command line's
//! `build` report, `play` and the editor's status line and Stats read
//! [`BuildWarnings`].

use super::components::{LevelData, SubdivisionLevel};
use super::patch::PatchRef;
use bevy::prelude::*;
use streamline_kernel::sphere::antipodal::{AntipodalPair, antipodal_legs, antipodal_pairs};

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

/// Scans the levels and the initial curve again whenever a level changed.
///
/// Every level but the finest is blended by the next step, along its rows and
/// its columns (docs/math.md §3), so those are the pairs scanned; level 0 of
/// a mirrored scene is the doubled net (docs/math.md §9), whose rows `m − 1 ±
/// j` are the scene's row `j`: its pairs are named by the scene's cells.
pub(crate) fn find_antipodal_blends(
    patch: PatchRef,
    levels: Query<(&SubdivisionLevel, Ref<LevelData>)>,
    mut warnings: ResMut<BuildWarnings>,
) {
    if !levels.iter().any(|(_, d)| d.is_changed()) && !patch.design_changed() {
        return;
    }
    let finest = levels.iter().map(|(l, _)| l.0).max().unwrap_or(0);
    let mut pairs = Vec::new();
    let mut sorted: Vec<_> = levels.iter().filter(|(l, _)| l.0 < finest).collect();
    sorted.sort_by_key(|(l, _)| l.0);
    for (l, d) in sorted {
        antipodal_pairs(l.0, &d.0.tangents, &mut pairs);
    }
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
