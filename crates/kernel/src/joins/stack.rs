//! A patch built at every depth `0 ..= d`: its levels and the point grid of
//! each, which is what a patch joined to it reads (docs/math.md §11: a join
//! holds at every depth, so `B`'s level `d` is made from `A`'s level `d`).

use crate::error::KernelError;
use crate::finetune::SurfaceTuning;
use crate::grid::Grid;
use crate::joins::parts::PatchParts;
use crate::levels::design::{Design, Level};
use crate::levels::incremental::surface_rows;
use crate::levels::multires::{self, Details};
use crate::streamline::integrate::place_slice;
use crate::streamline::surface_mesh::SurfaceMesh;
use glam::DVec3;

/// The levels `0 ..= d` of a patch and their streamlines (`rows × (cols + 1)`
/// points each, Eq. 65).
#[derive(Debug, Clone, PartialEq)]
pub struct Stack {
    /// Levels `0 ..= d`.
    pub levels: Vec<Level>,
    /// The streamline points of each level.
    pub points: Vec<Grid<DVec3>>,
}

impl Stack {
    /// A design on its own initial curve, built at every depth up to `depth`
    /// (the same levels and points as [`Design::levels`] and
    /// [`Design::streamlines`]).
    pub fn build(design: &Design, depth: u32) -> Result<Self, KernelError> {
        let levels = design.levels(depth)?;
        let points = levels.iter().map(|l| design.streamlines(l)).collect();
        Ok(Stack { levels, points })
    }

    /// A patch on its own initial curve with its details and fine tuning
    /// (docs/math.md §5, §6), built at every depth up to `depth`: the levels
    /// of [`crate::levels::incremental::reference_levels`] and the points of
    /// [`crate::levels::incremental::tuned_points`], what one patch's
    /// pipeline builds. With neither, exactly [`Stack::build`].
    pub fn build_parts(parts: PatchParts, depth: u32) -> Result<Self, KernelError> {
        let design = parts.design;
        let levels = levels_with(design, parts.details, depth, |_, _| {
            Ok::<(), KernelError>(())
        })?;
        let points = levels
            .iter()
            .map(|l| match parts.tuning {
                None => design.streamlines(l),
                Some(t) => crate::levels::incremental::tuned_points(
                    design.initial(),
                    &l.tangents,
                    &l.params,
                    Some(t),
                ),
            })
            .collect();
        Ok(Stack { levels, points })
    }

    /// The finest depth `d`.
    pub fn depth(&self) -> u32 {
        (self.levels.len() - 1) as u32
    }

    /// The finest level.
    pub fn finest(&self) -> &Level {
        self.levels.last().expect("a stack has level 0")
    }

    /// The finest level's points.
    pub fn finest_points(&self) -> &Grid<DVec3> {
        self.points.last().expect("a stack has level 0")
    }

    /// The triangle mesh of level `d` (docs/math.md §4).
    pub fn mesh(&self, d: u32) -> SurfaceMesh {
        SurfaceMesh::from_points(&self.points[d as usize])
    }
}

/// The levels `0 ..= depth` of `design`, each level `d ≥ 1` given its
/// `details` (docs/math.md §5: each in the frame of the subdivided level,
/// as [`crate::levels::incremental::reference_levels`] applies them) and
/// then passed to `fix` (with its depth) before the next step is taken from
/// it: the hook of the G1 constructions (docs/math.md §11.1, §11.2), which
/// change a boundary column between steps, so a side G1 projection applies
/// after the detail.
pub(crate) fn levels_with<E: From<KernelError>>(
    design: &Design,
    details: Option<&Details>,
    depth: u32,
    mut fix: impl FnMut(u32, &mut Level) -> Result<(), E>,
) -> Result<Vec<Level>, E> {
    let net = design.net();
    design.scheme().check_depth(net.rows(), net.cols(), depth)?;
    let mut level = design.base();
    fix(0, &mut level)?;
    let mut out = vec![level];
    for d in 1..=depth {
        let mut next = design.refine(out.last().expect("level 0"), d)?;
        if let Some(details) = details.filter(|m| !m.is_empty()) {
            apply_details(details, d, &mut next);
        }
        fix(d, &mut next)?;
        out.push(next);
    }
    Ok(out)
}

/// Level `d`'s details written into `level` (just subdivided), each from
/// the frame of the subdivided grid (docs/math.md §5); a detail outside
/// the level is skipped (the file's checks refuse it).
fn apply_details(details: &Details, d: u32, level: &mut Level) {
    let base = level.tangents.clone();
    for (&(_, r, c), &local) in details.range((d, 0, 0)..=(d, usize::MAX, usize::MAX)) {
        if r < base.rows() && c < base.cols() {
            level
                .tangents
                .set(r, c, multires::from_local(&base, r, c, local));
        }
    }
}

/// The streamlines of `level`, row `j` integrated (Eq. 65) from its first
/// point placed at `starts[j]` (a joined patch's anchor is column 0 and its
/// start points are given, docs/math.md §11). The first point is `starts[j]`
/// bit for bit. With `tuning`, each row is fine-tuned (docs/math.md §6)
/// from that start.
pub(crate) fn place_at_starts(
    level: &Level,
    starts: &[DVec3],
    tuning: Option<&SurfaceTuning>,
) -> Grid<DVec3> {
    let (rows, cols) = (level.tangents.rows(), level.tangents.cols());
    debug_assert_eq!(starts.len(), rows);
    if let Some(tuning) = tuning {
        let mut data = Vec::with_capacity(rows * (cols + 1));
        crate::finetune::surface::fine_tune_rows_into(
            surface_rows(&level.tangents, &level.params),
            starts,
            tuning,
            &mut data,
        );
        return Grid::new(rows, cols + 1, data).expect("sizes agree");
    }
    let mut data = vec![DVec3::ZERO; rows * (cols + 1)];
    for (r, out) in data.chunks_mut(cols + 1).enumerate() {
        let s = level.params.s.row(r);
        // σ = s₀: the anchor offset is t₀·0 = 0, so the shift is the start itself
        place_slice(level.tangents.row(r), s, s[0], starts[r], out);
    }
    Grid::new(rows, cols + 1, data).expect("sizes agree")
}

/// The first and last row (inclusive) of a grid that an update placed
/// again (`crate::joins::patch_state`, `crate::joins::g2_state`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct RowSpan {
    /// The first moved row.
    pub lo: usize,
    /// The last moved row.
    pub hi: usize,
}

impl RowSpan {
    /// The span of both (`None`: no row).
    pub fn join(a: Option<RowSpan>, b: Option<RowSpan>) -> Option<RowSpan> {
        match (a, b) {
            (Some(a), Some(b)) => Some(RowSpan {
                lo: a.lo.min(b.lo),
                hi: a.hi.max(b.hi),
            }),
            (a, b) => a.or(b),
        }
    }
}

impl From<crate::levels::dirty_window::Span> for RowSpan {
    /// A window's rows.
    fn from(s: crate::levels::dirty_window::Span) -> Self {
        RowSpan { lo: s.lo, hi: s.hi }
    }
}
