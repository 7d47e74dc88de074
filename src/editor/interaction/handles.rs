//! Handles: what the pointer turns. A handle has a kind (a tangent of the
//! surface's net at a subdivision level, or a control tangent of the initial
//! curve), a place (its
//! streamline point, its unit direction on the Gaussian sphere, the length it
//! is drawn with) and whether it can be picked. Where a handle is on the
//! screen and on the sphere view, and which one lies under the pointer, is
//! answered here for every kind, so the views never need to know how many
//! kinds there are.

use crate::ecs::Edit;
use crate::ecs::authoring::AuthorEdit;
use crate::ecs::components::{LevelData, SubdivisionLevel};
use crate::ecs::patch::PatchRef;
use crate::ecs::patch::{ArcParam, Direction, InitialHandle, SurfaceHandle};
use bevy::prelude::*;
use streamline_kernel::DVec3;
use streamline_kernel::finetune::streamline::point_by_fraction;
use streamline_kernel::levels::incremental::{LevelState, place_row_tuned, place_rows_tuned};

/// What a handle is a handle of.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum HandleKind {
    /// A tangent of the surface's net at subdivision level `level`: a control
    /// tangent (level 0) or a multiresolution detail (deeper).
    SurfaceTangent {
        /// The level.
        level: u32,
    },
    /// A control tangent of the initial curve (its index in the id's `col`,
    /// `row` 0): drawn along the initial curve at its Greville abscissa,
    /// turned like a surface tangent; its edits re-place the streamlines
    /// without re-blending a tangent (Eq. 1, `docs/math.md §9`).
    InitialTangent,
}

/// One handle: its kind and its cell `(row, col)` in that kind's grid.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct HandleId {
    /// What it is a handle of.
    pub kind: HandleKind,
    /// Row (for a surface tangent: its streamline).
    pub row: usize,
    /// Column (for a surface tangent: its index along the streamline).
    pub col: usize,
}

impl HandleId {
    /// Surface tangent `(row, col)` of level `level`.
    pub fn tangent(level: u32, row: usize, col: usize) -> Self {
        HandleId {
            kind: HandleKind::SurfaceTangent { level },
            row,
            col,
        }
    }

    /// The initial curve's control tangent `index`.
    pub fn initial(index: usize) -> Self {
        HandleId {
            kind: HandleKind::InitialTangent,
            row: 0,
            col: index,
        }
    }

    /// Whether it is a tangent of the surface's net (not of the initial curve).
    pub fn is_surface(self) -> bool {
        matches!(self.kind, HandleKind::SurfaceTangent { .. })
    }

    /// How the status line and the panels name it: `(row, col)`, or `initial k`.
    pub fn name(self) -> String {
        match self.kind {
            HandleKind::SurfaceTangent { .. } => format!("({}, {})", self.row, self.col),
            HandleKind::InitialTangent => format!("initial tangent {}", self.col),
        }
    }

    /// Its cell `(row, col)`.
    pub fn cell(self) -> (usize, usize) {
        (self.row, self.col)
    }

    /// Its subdivision level (the initial curve has one: 0).
    pub fn level(self) -> u32 {
        match self.kind {
            HandleKind::SurfaceTangent { level } => level,
            HandleKind::InitialTangent => 0,
        }
    }

    /// The edit that points this handle at `dir` (unit).
    pub fn set_direction(self, dir: DVec3) -> Edit {
        match self.kind {
            // a tangent of the edit depth: the scene's control tangent or detail
            HandleKind::SurfaceTangent { .. } => Edit::SetDirection {
                row: self.row,
                col: self.col,
                dir,
            },
            HandleKind::InitialTangent => Edit::Author(AuthorEdit::SetInitialDirection {
                index: self.col,
                dir,
            }),
        }
    }

    /// The edit that turns this handle about `axis` (unit) by `radians`.
    pub fn rotate(self, axis: DVec3, radians: f64) -> Edit {
        match self.kind {
            HandleKind::SurfaceTangent { .. } => Edit::Rotate {
                row: self.row,
                col: self.col,
                axis,
                radians,
            },
            HandleKind::InitialTangent => Edit::Author(AuthorEdit::RotateInitial {
                index: self.col,
                axis,
                radians,
            }),
        }
    }
}

/// A handle where it is: at its streamline point, pointing its way.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Handle {
    /// Which handle.
    pub id: HandleId,
    /// Its streamline point (kernel coordinates).
    pub base: DVec3,
    /// The unit tangent: its point on the Gaussian sphere.
    pub dir: DVec3,
    /// Drawn length.
    pub length: f64,
}

impl Handle {
    /// The arrow's tip.
    pub fn tip(&self) -> DVec3 {
        self.base + self.dir * self.length
    }

    /// Its subdivision level.
    pub fn level(&self) -> u32 {
        self.id.level()
    }

    /// Its arrow on the screen (logical px), given how a point of the 3D
    /// view projects (`None`: behind the camera).
    pub fn on_screen(&self, project: impl Fn(DVec3) -> Option<Vec2>) -> Option<(Vec2, Vec2)> {
        Some((project(self.base)?, project(self.tip())?))
    }

    /// Where framing this handle looks: its base, and a radius that shows it
    /// in its surroundings (`scene`: the scene's size).
    pub fn framing(&self, scene: f64) -> (DVec3, f64) {
        (self.base, (self.length * 4.0).max(0.05 * scene))
    }
}

/// How handles are shown.
#[derive(Resource, Debug, Clone, PartialEq)]
pub struct HandleSettings {
    /// Show the level-0 control tangents.
    pub controls: bool,
    /// Show the refined tangents of the edit depth (when it is above 0).
    pub refined: bool,
    /// Show only every other refined tangent (in both directions).
    pub every_other: bool,
    /// Number labels on the control arrows.
    pub labels: bool,
    /// Show (and pick) the initial curve's control tangents.
    pub initial: bool,
}

impl Default for HandleSettings {
    fn default() -> Self {
        HandleSettings {
            controls: true,
            refined: true,
            every_other: false,
            labels: true,
            initial: true,
        }
    }
}

impl HandleSettings {
    /// Whether a handle of the edit depth is shown (and so pickable).
    pub fn shows(&self, h: &Handle) -> bool {
        let (row, col) = h.id.cell();
        h.level() == 0 || !self.every_other || (row.is_multiple_of(2) && col.is_multiple_of(2))
    }
}

/// The handles to draw and pick, rebuilt when a level or the surface changes.
#[derive(Resource, Debug, Default)]
pub struct Handles {
    /// Level-0 control tangents (shown; picked only at edit depth 0).
    pub controls: Vec<Handle>,
    /// The handles of the edit depth (the same as `controls` at depth 0): the
    /// ones the pointer picks.
    pub editable: Vec<Handle>,
    /// The edit depth they belong to.
    pub edit_depth: u32,
    /// With mirror symmetry on (`docs/math.md §9`): the reflected copies of
    /// the control tangents, on the other half; shown dimmed, never picked.
    /// Each has the id of the control tangent it reflects.
    pub mirrored: Vec<Handle>,
    /// The initial curve's control tangents, along the initial curve.
    pub initial: Vec<Handle>,
    /// Handles placed again by the last update (all of them, or the rows
    /// of the control tangents whose handle entities changed).
    pub moved: usize,
    /// The cap on the arrows' length the handles were drawn with.
    cap: f64,
}

impl Handles {
    /// The handle `id`, if it is one of the edit depth's.
    pub fn find(&self, id: HandleId) -> Option<&Handle> {
        match id.kind {
            HandleKind::SurfaceTangent { .. } => self.editable.iter().find(|a| a.id == id),
            HandleKind::InitialTangent => self.initial.iter().find(|a| a.id == id),
        }
    }

    /// The handle of the edit depth at `(row, col)`.
    pub fn at(&self, (row, col): (usize, usize)) -> Option<&Handle> {
        self.editable
            .iter()
            .find(|a| a.id.row == row && a.id.col == col)
    }

    /// The id of the edit depth's handle at `(row, col)` (which may not exist).
    pub fn id_at(&self, (row, col): (usize, usize)) -> HandleId {
        HandleId::tangent(self.edit_depth, row, col)
    }

    /// `(rows, cols)` of the edit depth's handles.
    pub fn shape(&self) -> (usize, usize) {
        self.editable
            .last()
            .map_or((0, 0), |a| (a.id.row + 1, a.id.col + 1))
    }

    /// The handles the pointer may pick (shown ones of the edit depth).
    pub fn pickable<'a>(
        &'a self,
        settings: &'a HandleSettings,
    ) -> impl Iterator<Item = &'a Handle> {
        let refined_hidden = self.edit_depth > 0 && !settings.refined;
        let initial: &[Handle] = if settings.initial { &self.initial } else { &[] };
        self.editable
            .iter()
            .filter(move |a| !refined_hidden && settings.shows(a))
            .chain(initial)
    }

    /// The pickable handle whose arrow passes nearest `cursor` on the screen,
    /// within `max_px`.
    pub fn pick_on_screen(
        &self,
        settings: &HandleSettings,
        cursor: Vec2,
        project: impl Fn(DVec3) -> Option<Vec2>,
        max_px: f32,
    ) -> Option<HandleId> {
        let mut best: Option<(HandleId, f32)> = None;
        for a in self.pickable(settings) {
            let Some((p0, p1)) = a.on_screen(&project) else {
                continue;
            };
            let d = segment_distance(cursor, p0, p1);
            if d <= max_px && best.is_none_or(|(_, bd)| d < bd) {
                best = Some((a.id, d));
            }
        }
        best.map(|(h, _)| h)
    }

    /// The pickable handle whose point on the sphere view lies nearest
    /// `cursor`, closer than `max_px`, on the side facing `eye` (unit).
    pub fn pick_on_sphere<'a>(
        &'a self,
        settings: &'a HandleSettings,
        cursor: Vec2,
        eye: DVec3,
        project: impl Fn(DVec3) -> Option<Vec2>,
        max_px: f32,
    ) -> Option<&'a Handle> {
        let mut best: Option<(&Handle, f32)> = None;
        for a in self.pickable(settings) {
            if a.dir.dot(eye) < 0.0 {
                continue;
            }
            let Some(p) = project(a.dir) else {
                continue;
            };
            let d = p.distance(cursor);
            if d < max_px && best.is_none_or(|(_, bd)| d < bd) {
                best = Some((a, d));
            }
        }
        best.map(|(a, _)| a)
    }
}

/// Distance from `p` to the segment `a`–`b` (screen px).
pub fn segment_distance(p: Vec2, a: Vec2, b: Vec2) -> f32 {
    let ab = b - a;
    let t = ((p - a).dot(ab) / ab.length_squared().max(1e-9)).clamp(0.0, 1.0);
    (a + ab * t).distance(p)
}

/// The handles of one level, placed on the streamlines of `initial`; with
/// the mirror on (level 0 of the doubled net, `docs/math.md §9`) its first
/// `reflected` rows are the reflected copies, returned apart.
fn level_handles(
    patch: &PatchRef,
    l: &LevelState,
    scale: f64,
    initial: &streamline_kernel::streamline::initial_curve::InitialCurve,
    reflected: usize,
) -> (Vec<Handle>, Vec<Handle>) {
    let (rows, cols) = l.shape();
    let tuning = patch.tuning();
    let s = &l.params.s;
    let span: f64 = (0..rows)
        .map(|r| (s.get(r, cols - 1) - s.get(r, 0)) / (cols.max(2) - 1) as f64)
        .sum::<f64>()
        / rows.max(1) as f64;
    let length = (span * scale).max(1e-6);
    let mut all = Vec::new();
    place_rows_tuned(initial, &l.tangents, &l.params, tuning, &mut all);
    let mut out = Vec::with_capacity(rows * cols);
    let mut copies = Vec::with_capacity(reflected * cols);
    // the designer's control tangents, read from their handle entities
    let net = patch.net();
    for r in 0..rows {
        let pts = &all[r * (cols + 1)..(r + 1) * (cols + 1)];
        for c in 0..cols {
            let base = point_by_fraction(pts, s.row(r), s.get(r, c));
            if r < reflected {
                // row r of the doubled net reflects control row `reflected − r`
                copies.push(Handle {
                    id: HandleId::tangent(0, reflected - r, c),
                    base,
                    dir: l.tangents.get(r, c),
                    length,
                });
                continue;
            }
            let row = r - reflected;
            // control arrows show the designer's tangents (the interpolated
            // net, when that option is on, is what subdivision starts from)
            let dir = if l.level == 0 && row < net.rows() && c < net.cols() {
                net.get(row, c)
            } else {
                l.tangents.get(r, c)
            };
            out.push(Handle {
                id: HandleId::tangent(l.level, row, c),
                base,
                dir,
                length,
            });
        }
    }
    (out, copies)
}

/// The initial curve's control tangents, each at the curve's point at its
/// Greville abscissa `ξ_i = (u_{i+1} + … + u_{i+k−1}) / (k − 1)` of the QI
/// knot vector (where the QI curve's tangent is nearest `t_i`), drawn `length` long.
fn initial_handles(patch: &PatchRef, length: f64) -> Vec<Handle> {
    let curve = patch.design().initial();
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

/// Control tangents whose handle entity's direction changed.
type TurnedNet<'w, 's> = Query<'w, 's, &'static SurfaceHandle, Changed<Direction>>;

/// What else moves every handle: a new `s`, a new initial curve.
#[derive(bevy::ecs::system::SystemParam)]
pub(super) struct MovesAll<'w, 's> {
    s: Query<'w, 's, (), (With<SurfaceHandle>, Changed<ArcParam>)>,
    curve: Query<'w, 's, (), (With<InitialHandle>, Changed<Direction>)>,
}

/// Places the handles again when what they are drawn from changed. A turn
/// of control tangents at edit depth 0 moves only their rows' handles (a
/// streamline is a running sum along its row, Eq. 65); a new shape, `s`,
/// initial curve, tuning under a constraint or mirror moves every handle.
pub(super) fn rebuild(
    meter: Res<crate::ecs::meter::CpuMeter>,
    patch: PatchRef,
    levels: Query<(&SubdivisionLevel, Ref<LevelData>)>,
    turned: TurnedNet,
    all: MovesAll,
    mut handles: ResMut<Handles>,
) {
    let _meter = meter.start();
    let st = patch.structure();
    let edit = st.edit_depth;
    let whole = patch.structure_changed()
        || patch.placement_changed()
        || patch.tuning_changed()
        || !all.s.is_empty()
        || !all.curve.is_empty()
        || handles.edit_depth != edit
        || handles.controls.is_empty();
    let changed = levels
        .iter()
        .any(|(l, d)| (l.0 == 0 || l.0 == edit) && d.is_changed());
    if !whole && !changed {
        return;
    }
    let find = |level: u32| levels.iter().find(|(l, _)| l.0 == level).map(|(_, d)| d);
    let Some(base) = find(0) else {
        return;
    };
    let by_rows = !whole
        && edit == 0
        && !st.mirror
        && patch.tuning().is_none()
        && !crate::scene::model::interpolates(patch.design(), st.interpolate_tangents);
    if by_rows && !turned.is_empty() {
        let mut rows: Vec<usize> = turned.iter().map(|h| h.row).collect();
        rows.sort_unstable();
        rows.dedup();
        if let Some(n) = move_rows(&patch, &base.0, &rows, &mut handles) {
            handles.moved = n;
            return;
        }
    }
    // mirrored: the levels are the doubled design's, placed on its initial
    // curve (the scene's own, reflected for the other half)
    let shown = if st.mirror {
        match crate::scene::model::shown_design(patch.design(), st.interpolate_tangents, true) {
            Ok(d) => Some(d),
            Err(_) => return,
        }
    } else {
        None
    };
    let initial = shown
        .as_ref()
        .map_or(patch.design().initial(), |d| d.initial());
    let reflected = match &shown {
        Some(_) => st.rows.saturating_sub(1),
        None => 0,
    };
    let (mut controls, mut mirrored) = level_handles(&patch, &base.0, 0.7, initial, reflected);
    // long intervals (a 3×3 net) would give arrows as large as the scene: cap
    // them at a tenth of the surface's size
    let cap = length_cap(&base.0, initial);
    let clamp = |v: &mut Vec<Handle>| {
        for a in v.iter_mut() {
            a.length = a.length.min(cap);
        }
    };
    clamp(&mut controls);
    clamp(&mut mirrored);
    let editable = if edit == 0 {
        controls.clone()
    } else {
        match find(edit) {
            Some(d) => {
                let (mut h, _) = level_handles(&patch, &d.0, 0.8, initial, 0);
                clamp(&mut h);
                h
            }
            None => return,
        }
    };
    // the initial curve's arrows: a good part of its spacing between
    // tangents, so they stand out of the column of control arrows there
    let curve = patch.design().initial();
    let spacing = curve.length() / (curve.qi().tangents().len().max(2) - 1) as f64;
    let initial = initial_handles(&patch, (0.6 * spacing).min(2.0 * cap).max(1e-6));
    let moved =
        controls.len() + mirrored.len() + initial.len() + (edit > 0) as usize * editable.len();
    *handles = Handles {
        controls,
        editable,
        edit_depth: edit,
        mirrored,
        initial,
        moved,
        cap,
    };
}

/// The longest an arrow is drawn: a tenth of the surface's size, taken as
/// the diagonal of its longest streamline (`s` at level 0) and its initial
/// curve, which no turn of a tangent changes (so a turn moves only its row's
/// handles, [`move_rows`]).
fn length_cap(
    level: &LevelState,
    initial: &streamline_kernel::streamline::initial_curve::InitialCurve,
) -> f64 {
    let s = &level.params.s;
    let longest = (0..s.rows())
        .map(|r| s.get(r, s.cols() - 1) - s.get(r, 0))
        .fold(0.0, f64::max);
    (longest.hypot(initial.length()) * 0.1).max(1e-6)
}

/// Places the control handles of `rows` again (edit depth 0, no mirror, no
/// fine tuning), their directions read from the handle entities;
/// `None` when the arrows' length cap moved, so that every handle must be
/// drawn afresh. Returns how many handles moved.
fn move_rows(
    patch: &PatchRef,
    level: &LevelState,
    rows: &[usize],
    handles: &mut Handles,
) -> Option<usize> {
    let (nr, cols) = level.shape();
    if handles.controls.len() != nr * cols || handles.editable.len() != nr * cols {
        return None;
    }
    let initial = patch.design().initial();
    let tuning = patch.tuning();
    let index = &patch.index().surface;
    let s = &level.params.s;
    let mut pts = Vec::new();
    for &r in rows.iter().filter(|&&r| r < nr) {
        place_row_tuned(initial, &level.tangents, &level.params, r, tuning, &mut pts);
        for c in 0..cols {
            let a = &mut handles.controls[r * cols + c];
            a.base = point_by_fraction(&pts, s.row(r), s.get(r, c));
            a.dir = patch.direction(index.get(r, c))?;
        }
    }
    if length_cap(level, initial).to_bits() != handles.cap.to_bits() {
        return None;
    }
    for &r in rows.iter().filter(|&&r| r < nr) {
        let span = r * cols..(r + 1) * cols;
        let (src, dst) = (&handles.controls[span.clone()], span);
        let src = src.to_vec();
        handles.editable[dst].copy_from_slice(&src);
    }
    Some(rows.len() * cols)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn segment_distance_is_euclidean() {
        let (a, b) = (Vec2::ZERO, Vec2::new(10.0, 0.0));
        assert_eq!(segment_distance(Vec2::new(5.0, 3.0), a, b), 3.0);
        assert_eq!(segment_distance(Vec2::new(-4.0, 3.0), a, b), 5.0);
    }
}
