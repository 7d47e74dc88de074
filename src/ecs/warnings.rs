//! What the last build blended about a fixed axis (docs/math.md §1): the
//! antipodal neighbours among the tangents each subdivision step blends,
//! found in the levels the blend stage built and in the initial curve's
//! control tangents, as warnings naming the tangents. The command line's
//! `build` report, `play` and the editor's status line and Stats read
//! [`BuildWarnings`].

use super::components::{JoinedChild, LevelData, LevelWindow, SubdivisionLevel};
use super::joined::{JoinedDesign, PatchSlot, PatchStart, PatchSurface, shows_run_cut};
use super::patch::{Joined, PatchRef};
use bevy::prelude::*;
use std::collections::{HashMap, HashSet};
use streamline_kernel::levels::antipodal::{AntipodalPair, antipodal_pairs, antipodal_pairs_from};
use streamline_kernel::levels::dirty_window::DirtyWindow;
use streamline_kernel::sphere::antipodal::antipodal_legs;
use streamline_kernel::{DVec3, Grid};

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

/// One level of a patch to scan: its depth, its tangents, whether they
/// changed since the last run and, when the change is known to lie in a
/// window of the level as last scanned, that window.
struct ToScan<'a> {
    depth: u32,
    tangents: &'a Grid<DVec3>,
    changed: bool,
    window: Option<DirtyWindow>,
}

impl LevelPairs {
    /// Brings the pairs up to date with `levels` (one patch's levels below
    /// its finest, sorted by depth): a changed level with a window only
    /// there (the pairs with a cell in the window), any other changed level
    /// all over, every level when their number or shapes changed. Returns
    /// every pair, in the order of the levels and cells.
    fn rescan(&mut self, levels: &[ToScan]) -> Vec<AntipodalPair> {
        let known = &mut self.levels;
        let shape = |l: &ToScan| (l.tangents.rows(), l.tangents.cols());
        let same_levels = known.len() == levels.len()
            && (known.iter().zip(levels)).all(|((s, _), l)| *s == shape(l));
        if !same_levels {
            known.clear();
            known.resize_with(levels.len(), Default::default);
        }
        for ((was, pairs), l) in known.iter_mut().zip(levels) {
            if same_levels && !l.changed {
                continue;
            }
            match l.window.filter(|_| same_levels) {
                Some(w) => {
                    // a pair's second cell is the right or lower neighbour of its
                    // first: the pairs that read the window start up to one row
                    // and one column before it
                    let rows = w.rows.lo.saturating_sub(1)..=w.rows.hi;
                    let cols = w.cols.lo.saturating_sub(1)..=w.cols.hi;
                    pairs.retain(|p| !(rows.contains(&p.a.0) && cols.contains(&p.a.1)));
                    antipodal_pairs_from(l.depth, l.tangents, rows, cols, pairs);
                    pairs.sort_unstable(); // the scan's order (row-major, right before below)
                }
                None => {
                    pairs.clear();
                    antipodal_pairs(l.depth, l.tangents, pairs);
                }
            }
            *was = shape(l);
        }
        known.iter().flat_map(|(_, p)| p.iter().copied()).collect()
    }
}

/// What the last run found: the first patch's pairs and lines, and each
/// joined patch's; and the patches whose levels changed while a drag
/// deferred the scan.
#[derive(Default)]
pub(crate) struct Known {
    first: LevelPairs,
    first_lines: Vec<String>,
    joined: HashMap<Entity, LevelPairs>,
    joined_lines: Vec<String>,
    behind: HashSet<Entity>,
}

/// The first patch's levels, with the window of their last change.
type Levels<'w, 's> = Query<
    'w,
    's,
    (
        &'static SubdivisionLevel,
        Ref<'static, LevelData>,
        Option<Ref<'static, LevelWindow>>,
    ),
>;

/// The joined patches' levels ([`crate::ecs::joined::entities`]): their
/// patch, depth and the window of their last change.
type JoinedLevels<'w, 's> = Query<
    'w,
    's,
    (
        &'static ChildOf,
        &'static SubdivisionLevel,
        Ref<'static, LevelWindow>,
    ),
    With<JoinedChild>,
>;

/// The joined patches: their name, stack, design and start.
type JoinedPatches<'w, 's> = Query<
    'w,
    's,
    (
        Entity,
        &'static PatchSlot,
        &'static PatchSurface,
        Ref<'static, JoinedDesign>,
        Ref<'static, PatchStart>,
    ),
    With<Joined>,
>;

/// Scans the levels and the initial curve of every patch again whenever a
/// level changed: a level re-blended in a window ([`LevelWindow`]: the blend
/// stage's for the first patch, the rows its update placed again for a
/// joined patch, [`crate::ecs::joined::entities`]) only there (the pairs
/// with a cell in the window), a level built whole all over.
///
/// Every level but the finest is blended by the next step, along its rows and
/// its columns (docs/math.md §3), so those are the pairs scanned; level 0 of
/// a mirrored scene is the doubled net (docs/math.md §9), whose rows `m − 1 ±
/// j` are the scene's row `j`: its pairs are named by the scene's cells. In
/// a design of several patches each sentence names its patch. While the
/// editor defers a drag's work ([`super::resources::DeferNormals`]) nothing
/// is scanned: the patches whose levels changed are noted and scanned whole
/// on the first frame after it.
#[allow(clippy::too_many_arguments)]
pub(crate) fn find_antipodal_blends(
    meter: Res<super::meter::CpuMeter>,
    patch: PatchRef,
    levels: Levels,
    joined_levels: JoinedLevels,
    joined: JoinedPatches,
    first: Query<(&PatchSlot, Ref<PatchSurface>), Without<Joined>>,
    starts: Query<&PatchStart>,
    defer: Res<super::resources::DeferNormals>,
    mut warnings: ResMut<BuildWarnings>,
    mut known: Local<Known>,
) {
    let _meter = meter.start();
    // the first patch drawn as its G2 run's cut: its own levels wait
    // (docs/math.md §11.1), so the cut's are scanned
    let me = patch.entity();
    let head = first.get(me).ok();
    let cut = (head.as_ref())
        .filter(|(_, s)| shows_run_cut(me, starts.iter(), Some(s)))
        .map(|(_, s)| s);
    let first_now = levels.iter().any(|(_, d, _)| d.is_changed())
        || patch.design_changed()
        || cut.is_some_and(|s| s.is_changed());
    let mut joined_now: Vec<Entity> = (joined_levels.iter())
        .filter(|(.., w)| w.is_changed())
        .map(|(p, ..)| p.parent())
        .chain(
            (joined.iter())
                .filter(|r| r.3.is_changed() || r.4.is_changed())
                .map(|r| r.0),
        )
        .collect();
    // while the editor defers a drag's work, what changed is only noted,
    // and scanned whole once the drag ends
    if defer.0 {
        known.behind.extend(joined_now);
        if first_now {
            known.behind.insert(me);
        }
        return;
    }
    let first_whole = known.behind.remove(&me);
    joined_now.extend(known.behind.iter().copied());
    let behind = std::mem::take(&mut known.behind);
    let first_changed = first_now || first_whole;
    let joined_changed = !joined_now.is_empty() || joined.iter().count() != known.joined.len();
    if !first_changed && !joined_changed {
        return;
    }
    if first_changed {
        let cut = (cut.map(|s| &**s), cut.is_some_and(|s| s.is_changed()));
        known.first_lines = first_lines(&patch, &levels, cut, first_whole, &mut known.first);
    }
    if joined_changed {
        let mut of: HashMap<Entity, Vec<(u32, Ref<LevelWindow>)>> = HashMap::new();
        for (parent, l, w) in &joined_levels {
            of.entry(parent.parent()).or_default().push((l.0, w));
        }
        let mut rows: Vec<_> = joined.iter().collect();
        rows.sort_by_key(|r| r.1.index);
        let mut was = std::mem::take(&mut known.joined);
        let mut lines = Vec::new();
        for (e, slot, surface, design, start) in rows {
            let pairs = was.remove(&e).unwrap_or_default();
            let pairs = known.joined.entry(e).or_insert(pairs);
            let mut mine = Vec::new();
            if let Some(stack) = surface.stack() {
                let finest = stack.levels.len().saturating_sub(1) as u32;
                let mut ls: Vec<ToScan> = (of.get(&e).into_iter().flatten())
                    .filter(|(k, _)| *k < finest)
                    .filter_map(|(k, w)| {
                        let whole = behind.contains(&e);
                        Some(ToScan {
                            depth: *k,
                            tangents: &stack.levels.get(*k as usize)?.tangents,
                            changed: whole || w.is_changed(),
                            window: w.0.filter(|_| !w.is_added() && !whole),
                        })
                    })
                    .collect();
                ls.sort_by_key(|l| l.depth);
                mine = listed(&pairs.rescan(&ls));
            }
            if *start == PatchStart::Curve {
                mine.extend(curve_lines(design.0.initial().qi().tangents()));
            }
            lines.extend(
                mine.into_iter()
                    .map(|l| format!("patch `{}`: {l}", slot.name)),
            );
        }
        known.joined_lines = lines;
    }
    // in a design of several patches the first patch's sentences name it
    let first = match head {
        Some((s, _)) if !joined.is_empty() => (known.first_lines.iter())
            .map(|l| format!("patch `{}`: {l}", s.name))
            .collect(),
        _ => known.first_lines.clone(),
    };
    let lines = first
        .into_iter()
        .chain(known.joined_lines.iter().cloned())
        .collect();
    warnings.set_if_neq(BuildWarnings { lines });
}

/// The first patch's sentences: its levels' pairs (named by the scene's
/// cells when mirrored), or those of its G2 run's `cut` (scanned whole when
/// it changed), and its initial curve's.
fn first_lines(
    patch: &PatchRef,
    levels: &Levels,
    (cut, surface_changed): (Option<&PatchSurface>, bool),
    whole: bool,
    known: &mut LevelPairs,
) -> Vec<String> {
    if let Some((surface, stack)) = cut.and_then(|s| Some((s, s.stack()?))) {
        let below = stack.levels.len().saturating_sub(1);
        // what its last build changed, when it says (docs/math.md §11.1:
        // the run's merged window, whose rows every member shares)
        let rows =
            (surface.level_rows.as_ref()).filter(|r| !whole && r.len() == stack.levels.len());
        let ls: Vec<ToScan> = (stack.levels[..below].iter().enumerate())
            .map(|(k, l)| {
                let r = rows.map(|r| r[k]);
                ToScan {
                    depth: k as u32,
                    tangents: &l.tangents,
                    changed: whole || (surface_changed && r != Some(None)),
                    window: r
                        .flatten()
                        .and_then(|r| LevelWindow::rows(r, l.tangents.cols()).0),
                }
            })
            .collect();
        let mut lines = listed(&known.rescan(&ls));
        lines.extend(curve_lines(patch.design().initial().qi().tangents()));
        return lines;
    }
    let finest = levels.iter().map(|(l, ..)| l.0).max().unwrap_or(0);
    let mut ls: Vec<ToScan> = levels
        .iter()
        .filter(|(l, ..)| l.0 < finest)
        .map(|(l, d, w)| {
            // the window the blend stage recomputed with this change, if it says
            let window = (w.as_ref())
                .filter(|w| w.is_changed() && !d.is_added() && !whole)
                .and_then(|w| w.0);
            let changed = whole || d.is_changed();
            ToScan {
                depth: l.0,
                tangents: &d.into_inner().0.tangents,
                changed,
                window,
            }
        })
        .collect();
    ls.sort_by_key(|l| l.depth);
    let mut pairs = known.rescan(&ls);
    if patch.structure().mirror {
        let m = patch.structure().rows;
        fold_mirror(&mut pairs, m);
    }
    let mut lines = listed(&pairs);
    lines.extend(curve_lines(patch.design().initial().qi().tangents()));
    lines
}

/// The pairs as sentences, at most [`MAX_LISTED`] one by one and the rest
/// counted in one last line.
fn listed(pairs: &[AntipodalPair]) -> Vec<String> {
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
    lines
}

/// The antipodal legs of an initial curve's control tangents.
fn curve_lines(tangents: &[DVec3]) -> impl Iterator<Item = String> {
    antipodal_legs(tangents).into_iter().map(|k| {
        format!(
            "antipodal blend between initial-curve tangents {k} and {}: they point in opposite directions, so the initial curve between them turns about a fixed axis; turn one of them",
            k + 1
        )
    })
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
