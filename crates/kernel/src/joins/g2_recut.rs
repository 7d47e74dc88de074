//! The rows of a G2 run's merged level placed again and cut into its
//! patches' points (docs/math.md §11.1, Eqs. 65 and 70), for
//! [`super::g2_state::G2State`]'s update: four rows at a time where they
//! are summed again from the same point (one running sum is a chain of
//! additions that leaves most of the CPU's adders idle, four are four
//! chains it overlaps, [`crate::streamline::integrate::place_slices_from`]),
//! and many rows in two halves, one on the helper thread
//! ([`crate::parallel::join`]). Each row is placed into a small scratch
//! block, still in the cache when it is cut; the same sums per row, so the
//! same bits as placing the rows one by one.

use crate::joins::merged::cut_row_from;
use crate::joins::stack::{RowSpan, Stack};
use crate::levels::incremental::LevelState;
use crate::streamline::integrate::{SliceJob, sum_slices};
use crate::streamline::surface_mesh::PARALLEL_MIN_POINTS;
use glam::DVec3;

/// A merged row to place again and cut.
#[derive(Debug, Clone, Copy)]
pub(crate) struct RowJob {
    /// The merged row.
    pub r: usize,
    /// The first patch whose points it changes: every patch from it on
    /// (a patch left of the change reads nothing it changed).
    pub first: usize,
    /// The point it is summed again from (its points before are as they
    /// were); 0: the whole row.
    pub again: usize,
}

/// What placing rows changed of each patch: whether it was written, and
/// when `spans` is kept (the finest depth), the rows placed again and the
/// first column written.
#[derive(Debug, Clone)]
pub(crate) struct RowMarks {
    /// Per patch, written.
    pub changed: Vec<bool>,
    /// Per patch, the first and last row placed again.
    pub spans: Vec<Option<RowSpan>>,
    /// Per patch, the first point written in those rows (`usize::MAX`: none).
    pub cols: Vec<usize>,
}

impl RowMarks {
    /// Nothing written of `m` patches.
    pub fn new(m: usize) -> Self {
        RowMarks {
            changed: vec![false; m],
            spans: vec![None; m],
            cols: vec![usize::MAX; m],
        }
    }

    /// Both halves' marks.
    fn merge(mut self, o: RowMarks) -> RowMarks {
        for p in 0..self.changed.len() {
            self.changed[p] |= o.changed[p];
            self.spans[p] = RowSpan::join(self.spans[p], o.spans[p]);
            self.cols[p] = self.cols[p].min(o.cols[p]);
        }
        self
    }
}

/// Rows `jobs` of the merged `level` at depth `d` placed from their starts
/// `origins` (Eq. 65) and cut at `cuts` into each patch's points in
/// `stacks` (Eq. 70).
pub(crate) fn place_and_cut(
    level: &LevelState,
    origins: &[DVec3],
    cuts: &[usize],
    jobs: &[RowJob],
    stacks: &mut [Stack],
    d: usize,
) -> RowMarks {
    let m = stacks.len();
    // each job's row of each patch's points: `outs[i * m + p]`
    let mut rows: Vec<Vec<Option<&mut [DVec3]>>> = stacks
        .iter_mut()
        .map(|s| {
            let g = &mut s.points[d];
            let c = g.cols();
            g.data_mut().chunks_mut(c).map(Some).collect()
        })
        .collect();
    let mut outs: Vec<&mut [DVec3]> = Vec::with_capacity(jobs.len() * m);
    for j in jobs {
        for row in rows.iter_mut() {
            outs.push(row[j.r].take().expect("one job a row"));
        }
    }
    let cols = level.shape().1;
    let here = |jobs: &[RowJob], outs: &mut [&mut [DVec3]]| {
        place_here(level, origins, cuts, jobs, outs, m)
    };
    if jobs.len() >= 8 && jobs.len() * (cols + 1) >= PARALLEL_MIN_POINTS {
        let half = jobs.len() / 2;
        let (ja, jb) = jobs.split_at(half);
        let (oa, ob) = outs.split_at_mut(half * m);
        let (mut a, mut b) = (None, None);
        crate::parallel::join(|| a = Some(here(ja, oa)), || b = Some(here(jb, ob)));
        match (a, b) {
            (Some(a), Some(b)) => a.merge(b),
            _ => unreachable!("both halves ran"),
        }
    } else {
        here(jobs, &mut outs)
    }
}

/// [`place_and_cut`] on the calling thread, four rows at a time.
fn place_here(
    level: &LevelState,
    origins: &[DVec3],
    cuts: &[usize],
    jobs: &[RowJob],
    outs: &mut [&mut [DVec3]],
    m: usize,
) -> RowMarks {
    let mut marks = RowMarks::new(m);
    let cols = level.shape().1;
    let mut scratch = vec![DVec3::ZERO; 4 * (cols + 1)];
    for (batch, outs) in jobs.chunks(4).zip(outs.chunks_mut(4 * m)) {
        let mut sums: Vec<SliceJob> = batch
            .iter()
            .zip(scratch.chunks_mut(cols + 1))
            .enumerate()
            .map(|(b, (j, row))| {
                // summed again from the point before the change, read back
                // from the patch it was cut into
                if j.again > 0 {
                    row[j.again] = merged_point(&outs[b * m..(b + 1) * m], cuts, j.again);
                }
                SliceJob {
                    tangents: level.tangents.row(j.r),
                    s: level.params.s.row(j.r),
                    sigma: level.params.sigma[j.r],
                    origin: origins[j.r],
                    from: j.again,
                    out: row,
                    moved_from: 0,
                    bounds: [DVec3::ZERO; 2],
                }
            })
            .collect();
        sum_slices(&mut sums);
        for ((b, j), sum) in batch.iter().enumerate().zip(&sums) {
            let start = sum.moved_from;
            for p in j.first..m {
                cut_row_from(level, &*sum.out, j.r, cuts, p, start, outs[b * m + p]);
                marks.changed[p] = true;
                let row = RowSpan { lo: j.r, hi: j.r };
                marks.spans[p] = RowSpan::join(marks.spans[p], Some(row));
                // the first point `cut_row_from` writes
                let (lo, hi) = (cuts[p], cuts[p + 1]);
                let at = if start <= lo {
                    0
                } else {
                    (start - lo).min(hi - lo + 1)
                };
                marks.cols[p] = marks.cols[p].min(at);
            }
        }
    }
    marks
}

/// Merged point `k` (`1 ..=` the last tangent column) of a row, read back
/// from the patches' rows `outs` it was cut into
/// ([`super::merged::cut_row`]: patch `p`'s points `1 ..= hi − lo` are the
/// merged points `lo + 1 ..= hi`).
fn merged_point(outs: &[&mut [DVec3]], cuts: &[usize], k: usize) -> DVec3 {
    let p = cuts.partition_point(|&c| c < k) - 1;
    outs[p][k - cuts[p]]
}
