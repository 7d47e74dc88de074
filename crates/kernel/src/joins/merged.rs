//! G2 chains (docs/math.md §11.1, Eqs. 68–70): the chained patches are
//! subdivided as **one net** `[A's columns | B's columns 1 …]`, `B`'s `s`
//! continuing `A`'s, and each level is cut at the seam column. `A`'s points
//! but its last are the merged streamline's first points, `B`'s points but its
//! first are the rest, and the seam point lies on the merged segment through
//! it (Eq. 65 splits that segment in two collinear halves). So the seam is as
//! smooth as the scheme is anywhere.

use crate::grid::Grid;
use crate::joins::chain::check_chain;
use crate::joins::error::JoinError;
use crate::joins::kinds::Continuity;
use crate::joins::parts::PatchParts;
use crate::joins::stack::Stack;
use crate::levels::design::{Design, Level};
use crate::levels::incremental::LevelState;
use crate::levels::multires::Details;
use crate::levels::params::ParamGrid;
use crate::levels::surface::SurfaceScheme;
use glam::DVec3;

/// A run of G2-chained patches as one design.
#[derive(Debug, Clone)]
pub struct MergedRun {
    /// The merged net: the first patch's columns, then every later patch's
    /// columns but its first; `s` continued (Eq. 68); the first patch's
    /// rows, anchor, scheme, blend order and initial curve.
    pub design: Design,
    /// The merged control column of each seam (the last column of every
    /// patch but the last).
    pub seams: Vec<usize>,
}

/// Merges a run of patches, each G2-chained on the previous one's edge
/// `End` (checked as [`crate::joins::chain::chain`] checks a chain, plus the
/// same blend order). Row `j` of patch `p ≥ 1` continues the merged `s` by
/// Eq. 68: `s[k] + (s_last − s_p[j][0])` for its columns `k ≥ 1`, `s_last`
/// the merged row's last `s` so far.
pub fn merge_g2(patches: &[&Design]) -> Result<MergedRun, JoinError> {
    let (first, rest) = patches.split_first().ok_or(JoinError::EmptyRun)?;
    for w in patches.windows(2) {
        check_chain(w[0], w[1], Continuity::G2)?;
    }
    let rows = first.net().rows();
    let mut net: Vec<Vec<DVec3>> = (0..rows).map(|r| first.net().row(r).to_vec()).collect();
    let mut s: Vec<Vec<f64>> = (0..rows)
        .map(|r| first.params().s.row(r).to_vec())
        .collect();
    let mut seams = Vec::with_capacity(rest.len());
    for p in rest {
        seams.push(net[0].len() - 1);
        for r in 0..rows {
            let last = *s[r].last().expect("a row has columns");
            let own = p.params().s.row(r);
            let offset = last - own[0];
            s[r].extend(own[1..].iter().map(|v| v + offset));
            net[r].extend_from_slice(&p.net().row(r)[1..]);
        }
    }
    let design = Design::new(
        &Grid::from_rows(&net)?,
        Grid::from_rows(&s)?,
        first.params().t.clone(),
        first.anchor(),
        first.scheme(),
        first.order(),
        first.initial().clone(),
    )?;
    Ok(MergedRun { design, seams })
}

/// A G2 run's members carry no fine tuning (module documentation).
pub(crate) fn check_no_tuning(patches: &[PatchParts]) -> Result<(), JoinError> {
    match patches.iter().position(|p| p.tuning.is_some()) {
        Some(member) => Err(JoinError::G2Tuning { member }),
        None => Ok(()),
    }
}

/// The members' details as details of the merged net, at every depth up to
/// `depth`: member `p`'s detail `(d, r, c)` at merged column `cuts[p] + c`
/// of depth `d` (Eq. 69), so a detail is applied in the frame of the
/// merged level, as the build subdivides it. A later member's column 0 is
/// the seam, the previous member's last column (one handle): a detail
/// there is the previous member's, and is skipped here (the file's checks
/// refuse it).
pub fn merged_details(run: &MergedRun, patches: &[PatchParts], depth: u32) -> Details {
    let scheme = run.design.scheme();
    let curve = scheme.curve();
    let mut out = Details::new();
    let mut cols = run.design.net().cols();
    for d in 1..=depth {
        cols = curve.refined_len(cols);
        let cuts = cuts(scheme, &run.seams, d, cols);
        for (p, part) in patches.iter().enumerate() {
            let Some(details) = part.details else {
                continue;
            };
            for (&(_, r, c), &local) in details.range((d, 0, 0)..=(d, usize::MAX, usize::MAX)) {
                if (p > 0 && c == 0) || cuts[p] + c > cuts[p + 1] {
                    continue;
                }
                out.insert((d, r, cuts[p] + c), local);
            }
        }
    }
    out
}

/// The frame of member `p`'s details of level `d ≥ 1` (docs/math.md §5):
/// the run's merged level `d` as subdivided from its level `d − 1` (built
/// with every member's details), before level `d`'s details, and the merged
/// column of the member's column 0 (Eq. 69). A detail of the member at
/// `(r, c)` is [`crate::levels::multires::to_local`] of this grid at
/// `(r, offset + c)`.
pub fn g2_detail_base(
    patches: &[PatchParts],
    p: usize,
    d: u32,
) -> Result<(Grid<DVec3>, usize), JoinError> {
    let designs: Vec<&Design> = patches.iter().map(|p| p.design).collect();
    let merged = merge_g2(&designs)?;
    if d == 0 || p >= patches.len() {
        return Err(JoinError::EmptyRun);
    }
    let details = merged_details(&merged, patches, d - 1);
    let prev = crate::joins::stack::levels_with(&merged.design, Some(&details), d - 1, |_, _| {
        Ok::<(), JoinError>(())
    })?;
    let base = merged
        .design
        .refine(prev.last().expect("level 0"), d)?
        .tangents;
    let cuts = cuts(merged.design.scheme(), &merged.seams, d, base.cols());
    Ok((base, cuts[p]))
}

/// The merged column at depth `depth` where a seam at merged control column
/// `col` (`≥ 1`) is cut (Eq. 69): `2^d col` for Kobbelt, which keeps the
/// control column at even indices; `2^d (col − 1) + 1` for Catmull–Clark (the
/// vertex point of the column, index `2c − 1` of a step) and Doo–Sabin (the
/// point `¾ t_{c−1} ⊕ … ` nearest the column from below, index `2c − 1`).
pub fn seam_column(scheme: SurfaceScheme, col: usize, depth: u32) -> usize {
    if scheme.is_interpolatory() {
        col << depth
    } else {
        ((col - 1) << depth) + 1
    }
}

/// A G2 run built to `depth`: one [`Stack`] per patch, each level and point
/// grid the merged design's cut at the seam columns of that depth (Eqs.
/// 69–70). Patch `p ≥ 1` keeps the merged `s` (its own plus the Eq. 68
/// offset) and its `σ` is its first column's `s`.
pub fn g2_run(patches: &[&Design], depth: u32) -> Result<Vec<Stack>, JoinError> {
    let parts: Vec<PatchParts> = patches.iter().map(|&d| d.into()).collect();
    g2_run_parts(&parts, depth)
}

/// [`g2_run`] of patches with their details: the merged net is subdivided
/// with every member's details at their merged places ([`merged_details`]).
/// A G2 run's patches have no fine tuning (it would scale each side's
/// curvature by its own `1/α`, docs/math.md §11.1): refused.
pub fn g2_run_parts(patches: &[PatchParts], depth: u32) -> Result<Vec<Stack>, JoinError> {
    check_no_tuning(patches)?;
    let designs: Vec<&Design> = patches.iter().map(|p| p.design).collect();
    let merged = merge_g2(&designs)?;
    let details = merged_details(&merged, patches, depth);
    let whole = Stack::build_parts(PatchParts::new(&merged.design, Some(&details), None), depth)?;
    let scheme = merged.design.scheme();
    let mut out: Vec<Stack> = (0..patches.len())
        .map(|_| Stack {
            levels: Vec::new(),
            points: Vec::new(),
        })
        .collect();
    for (d, (level, points)) in whole.levels.iter().zip(&whole.points).enumerate() {
        let cuts = cuts(scheme, &merged.seams, d as u32, level.tangents.cols());
        for (p, stack) in out.iter_mut().enumerate() {
            let (part, pts) = cut(&level.tangents, &level.params, points, &cuts, p);
            stack.levels.push(part);
            stack.points.push(pts);
        }
    }
    Ok(out)
}

/// The merged columns where a level of `cols` columns at depth `d` is cut:
/// `0`, each seam's (Eq. 69), `cols − 1`; patch `p` holds columns
/// `cuts[p] ..= cuts[p + 1]`.
pub(crate) fn cuts(scheme: SurfaceScheme, seams: &[usize], d: u32, cols: usize) -> Vec<usize> {
    let mut cuts = Vec::with_capacity(seams.len() + 2);
    cuts.push(0);
    cuts.extend(seams.iter().map(|&c| seam_column(scheme, c, d)));
    cuts.push(cols - 1);
    cuts
}

/// Patch `p`'s part of a merged level (its tangents, parameters and points)
/// and its points (Eq. 70), the columns `cuts[p] ..= cuts[p + 1]`
/// ([`cut_row`]).
pub(crate) fn cut(
    tangents: &Grid<DVec3>,
    params: &ParamGrid,
    points: &Grid<DVec3>,
    cuts: &[usize],
    p: usize,
) -> (Level, Grid<DVec3>) {
    let (lo, hi) = (cuts[p], cuts[p + 1]);
    let rows = tangents.rows();
    let s = columns(&params.s, lo, hi);
    let sigma = if p == 0 {
        params.sigma.clone()
    } else {
        (0..rows).map(|r| s.get(r, 0)).collect()
    };
    let mut data = vec![DVec3::ZERO; rows * (hi - lo + 2)];
    for (r, out) in data.chunks_mut(hi - lo + 2).enumerate() {
        cut_row(tangents, &params.s, points.row(r), r, cuts, p, out);
    }
    let part = Level {
        tangents: columns(tangents, lo, hi),
        params: ParamGrid {
            s,
            t: params.t.clone(),
            sigma,
        },
    };
    let pts = Grid::new(rows, hi - lo + 2, data).expect("sizes agree");
    (part, pts)
}

/// Patch `p`'s points of merged row `r` (`row`, Eq. 70) into `out`
/// (`cuts[p + 1] − cuts[p] + 2` points): the merged points `lo + 1 ..= hi`,
/// after the merged first point (the first patch) or the seam point at
/// `lo`, and before the merged last point (the last patch) or the seam point
/// at `hi`.
pub(crate) fn cut_row(
    tangents: &Grid<DVec3>,
    s: &Grid<f64>,
    row: &[DVec3],
    r: usize,
    cuts: &[usize],
    p: usize,
    out: &mut [DVec3],
) {
    let (lo, hi) = (cuts[p], cuts[p + 1]);
    let last = p + 2 == cuts.len();
    let seam = |k: usize| seam_point(tangents, s, row, r, k);
    out[0] = if p == 0 { row[0] } else { seam(lo) };
    out[1..=hi - lo].copy_from_slice(&row[lo + 1..=hi]);
    out[hi - lo + 1] = if last { row[hi + 1] } else { seam(hi) };
}

/// [`cut_row`] of a merged `level` when only the merged points from `start`
/// on changed (`out` holding the patch's points as cut before; `start` 0:
/// all of them): what the patch reads before `start` is kept, the rest
/// written, the same values as `cut_row`. `row` needs only its points from
/// `start − 1` on.
pub(crate) fn cut_row_from(
    level: &LevelState,
    row: &[DVec3],
    r: usize,
    cuts: &[usize],
    p: usize,
    start: usize,
    out: &mut [DVec3],
) {
    let (tangents, s) = (&level.tangents, &level.params.s);
    let (lo, hi) = (cuts[p], cuts[p + 1]);
    // the first point (the seam at `lo` reads the merged point `lo`) too
    if start <= lo {
        cut_row(tangents, s, row, r, cuts, p, out);
        return;
    }
    if start <= hi {
        out[start - lo..=hi - lo].copy_from_slice(&row[start..=hi]);
    }
    out[hi - lo + 1] = if p + 2 == cuts.len() {
        row[hi + 1]
    } else {
        seam_point(tangents, s, row, r, hi)
    };
}

/// Columns `lo ..= hi` of `g`.
pub(crate) fn columns<T: Copy>(g: &Grid<T>, lo: usize, hi: usize) -> Grid<T> {
    let data = (0..g.rows())
        .flat_map(|r| g.row(r)[lo..=hi].iter().copied())
        .collect();
    Grid::new(g.rows(), hi - lo + 1, data).expect("sizes agree")
}

/// The seam point of merged row `r` at column `k ≥ 1`: Eq. 65's last point of
/// the row cut after `k`, `p_k + ½(s_k − s_{k−1}) t_k`, the middle of the
/// merged segment `k` at arc length `s_k` (Eq. 70).
fn seam_point(tangents: &Grid<DVec3>, s: &Grid<f64>, row: &[DVec3], r: usize, k: usize) -> DVec3 {
    let s = s.row(r);
    row[k] + tangents.get(r, k) * (0.5 * (s[k] - s[k - 1]))
}
