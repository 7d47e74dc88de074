//! Where a level's handles go, as pure functions of the level that is drawn
//! ([`DrawnLevel`]: its tangents, its `s` and its streamlines' points): a
//! handle at cell `(r, c)` stands at the point of streamline `r` at arc
//! length `s_{r,c}` (Eq. 65 of docs/math.md; with fine tuning, at the same
//! fraction of the tuned polyline's segment, §6), pointing the level's
//! tangent (at level 0 the designer's control tangent), drawn a part of the
//! level's mean control spacing long and no longer than the cap.
//!
//! The level is the one drawn for the patch: the first patch's incremental
//! levels, or a [`Stack`] that the joins built (a joined patch's, and the
//! first patch's cut of a G2 run, docs/math.md §11.1, which differs from its
//! one-patch levels near the seam).

use super::super::handle_id::{Handle, HandleId};
use crate::ecs::joined::PatchStart;
use streamline_kernel::finetune::streamline::point_by_fraction;
use streamline_kernel::joins::{Continuity, Edge, Stack};
use streamline_kernel::streamline::initial_curve::InitialCurve;
use streamline_kernel::{DVec3, Grid};

/// How long a control arrow (level 0) is drawn, in mean control spacings.
pub const CONTROL_SCALE: f64 = 0.7;
/// How long a refined arrow (the edit depth, above 0) is drawn.
pub const REFINED_SCALE: f64 = 0.8;

/// One level as it is drawn: `rows × cols` tangents and their `s`, and the
/// streamlines' points, `rows × (cols + 1)`, row-major.
#[derive(Debug, Clone, Copy)]
pub struct DrawnLevel<'a> {
    /// The level (0: the control net).
    pub level: u32,
    /// Its unit tangents.
    pub tangents: &'a Grid<DVec3>,
    /// Their arc-length parameters.
    pub s: &'a Grid<f64>,
    /// The streamlines' points, `cols + 1` per row.
    pub points: &'a [DVec3],
}

impl<'a> DrawnLevel<'a> {
    /// Level `level` of `stack`, when it has it with consistent shapes.
    pub fn of_stack(stack: &'a Stack, level: u32) -> Option<Self> {
        let l = stack.levels.get(level as usize)?;
        let p = stack.points.get(level as usize)?;
        let (rows, cols) = (l.tangents.rows(), l.tangents.cols());
        let fits = rows > 0
            && cols > 0
            && (l.params.s.rows(), l.params.s.cols()) == (rows, cols)
            && (p.rows(), p.cols()) == (rows, cols + 1);
        fits.then(|| DrawnLevel {
            level,
            tangents: &l.tangents,
            s: &l.params.s,
            points: p.data(),
        })
    }

    /// `(rows, cols)` of its tangents.
    pub fn shape(&self) -> (usize, usize) {
        (self.tangents.rows(), self.tangents.cols())
    }

    /// Streamline `r`'s points.
    fn row(&self, r: usize) -> &'a [DVec3] {
        let n = self.tangents.cols() + 1;
        &self.points[r * n..(r + 1) * n]
    }

    /// The point of streamline `r` at `s_{r,c}`: where handle `(r, c)` stands.
    pub fn base(&self, r: usize, c: usize) -> DVec3 {
        point_by_fraction(self.row(r), self.s.row(r), self.s.get(r, c))
    }

    /// The mean control spacing: each row's `s` span over its intervals,
    /// averaged over the rows.
    pub fn spacing(&self) -> f64 {
        let (rows, cols) = self.shape();
        let s = self.s;
        (0..rows)
            .map(|r| (s.get(r, cols - 1) - s.get(r, 0)) / (cols.max(2) - 1) as f64)
            .sum::<f64>()
            / rows.max(1) as f64
    }
}

/// Which cells of a level are handles: rows `reflected..` (the first
/// `reflected` rows, with the mirror on, are the reflected copies, docs/math.md
/// §9), at most `rows × cols` of the patch's own (a level a patch's edits
/// can name), from column `first_col` (1 where column 0 is the seam a chain
/// shares with its parent, docs/math.md §11.1).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Cells {
    /// Rows of the patch's own level.
    pub rows: usize,
    /// Columns of the patch's own level.
    pub cols: usize,
    /// The first column that is the patch's own handle.
    pub first_col: usize,
    /// Leading rows that are mirrored copies.
    pub reflected: usize,
}

impl Cells {
    /// Every cell of a `rows × cols` level.
    pub fn all((rows, cols): (usize, usize)) -> Self {
        Cells {
            rows,
            cols,
            first_col: 0,
            reflected: 0,
        }
    }
}

/// The handles of level `l` on `cells`, drawn `scale` mean control spacings
/// long and at most `cap`: each points `dir(row, col)` when it gives a
/// direction (the designer's control tangent at level 0), else the level's
/// tangent. Returns the handles and, apart, the mirrored copies (whose id
/// names the control tangent each reflects).
pub fn level_handles(
    l: &DrawnLevel,
    scale: f64,
    cap: f64,
    cells: Cells,
    dir: impl Fn(usize, usize) -> Option<DVec3>,
) -> (Vec<Handle>, Vec<Handle>) {
    let (rows, cols) = l.shape();
    let length = (l.spacing() * scale).max(1e-6).min(cap.max(1e-6));
    let k = cells.reflected;
    let mut out = Vec::with_capacity(rows * cols);
    let mut copies = Vec::with_capacity(k.min(rows) * cols);
    for r in 0..rows {
        if r < k {
            // row r of the doubled net reflects control row `k − r`
            for c in 0..cols {
                copies.push(Handle {
                    id: HandleId::tangent(0, k - r, c),
                    base: l.base(r, c),
                    dir: l.tangents.get(r, c),
                    length,
                });
            }
            continue;
        }
        let row = r - k;
        if row >= cells.rows {
            break;
        }
        for c in cells.first_col..cols.min(cells.cols) {
            out.push(Handle {
                id: HandleId::tangent(l.level, row, c),
                base: l.base(r, c),
                dir: dir(row, c).unwrap_or_else(|| l.tangents.get(r, c)),
                length,
            });
        }
    }
    (out, copies)
}

/// The handles of a patch drawn from `stack` at `level`, each pointing the
/// level's tangent: `own` is the patch's own shape at that level (the cells
/// its edits can name; a G2 run's cut may have more columns, docs/math.md
/// §11.1), `skip_first` leaves out the seam column a chain shares with its
/// parent. Empty when the stack has no such level.
pub fn stack_handles(
    stack: &Stack,
    level: u32,
    own: (usize, usize),
    cap: f64,
    skip_first: bool,
) -> Vec<Handle> {
    let Some(l) = DrawnLevel::of_stack(stack, level) else {
        return Vec::new();
    };
    let cells = Cells {
        first_col: usize::from(skip_first),
        ..Cells::all(own)
    };
    level_handles(&l, scale_of(level), cap, cells, |_, _| None).0
}

/// How long an arrow of `level` is drawn, in mean control spacings.
pub fn scale_of(level: u32) -> f64 {
    if level == 0 {
        CONTROL_SCALE
    } else {
        REFINED_SCALE
    }
}

/// Whether column 0 of a patch starting at `start` is its parent's last
/// column (a G1 or G2 chain, docs/math.md §11.1), so not a handle of its own.
pub fn shares_first_column(start: &PatchStart) -> bool {
    matches!(
        start,
        PatchStart::Edge {
            edge: Edge::End,
            continuity: Continuity::G1 | Continuity::G2,
            ..
        }
    )
}

/// The initial curve's control tangents, each at the curve's point at its
/// Greville abscissa `ξ_i = (u_{i+1} + … + u_{i+k−1}) / (k − 1)` of the QI
/// knot vector (where the QI curve's tangent is nearest `t_i`), drawn `length` long.
pub fn initial_handles(curve: &InitialCurve, length: f64) -> Vec<Handle> {
    let qi = curve.qi();
    let (k, u) = (qi.order(), qi.knots());
    qi.tangents()
        .iter()
        .enumerate()
        .map(|(i, &dir)| {
            let xi = u[i + 1..i + k].iter().sum::<f64>() / (k - 1) as f64;
            Handle {
                id: HandleId::initial(i),
                base: curve.point(xi * curve.length()),
                dir,
                length,
            }
        })
        .collect()
}

/// The longest an arrow is drawn: a tenth of the surface's size, taken as
/// the diagonal of its longest streamline (`s` at level 0) and its initial
/// curve, which no turn of a tangent changes (so a turn moves only its row's
/// handles).
pub fn length_cap(s: &Grid<f64>, initial: &InitialCurve) -> f64 {
    let longest = (0..s.rows())
        .map(|r| s.get(r, s.cols() - 1) - s.get(r, 0))
        .fold(0.0, f64::max);
    (longest.hypot(initial.length()) * 0.1).max(1e-6)
}
