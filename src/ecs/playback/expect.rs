//! A script's expectations ([`Expect`]), each checked against the headless
//! app by a function of its own. They share one shape: measure, compare with
//! what the script expects, and say so — `Ok` with what was measured, or
//! `Err` with what is wrong ([`within`], [`Fields`]).

use super::seam::Outcome;
use crate::ecs::resources::*;
use crate::scene::edits::script::expect::Expect;
use crate::scene::files::format::{Finite, OrderSpec, Point, SchemeSpec};
use bevy::prelude::*;
use std::collections::HashMap;
use std::fmt::{Debug, Display};
use streamline_kernel::{DVec3, Grid};

/// Every streamline point, remembered under a name by `Mark`.
pub(super) type Marks = HashMap<String, Grid<DVec3>>;

/// What the expectations read in the app.
struct Now<'w> {
    surface: &'w SurfaceData,
    scene: crate::scene::Scene,
    stats: &'w Stats,
    history: &'w History,
}

/// The first patch's points as drawn when it shows its G2 run's cut
/// ([`crate::ecs::joined::shows_run_cut`]); `None` when it shows its own
/// surface.
fn drawn_points(w: &World) -> Option<&Grid<DVec3>> {
    use crate::ecs::joined::{PatchStart, PatchSurface, shows_run_cut};
    let first = crate::ecs::patch::patch_entity(w)?;
    let surface = w.get::<PatchSurface>(first);
    let mut starts = w.try_query::<&PatchStart>()?;
    shows_run_cut(first, starts.iter(w), surface)
        .then(|| surface?.stack().map(|s| s.finest_points()))
        .flatten()
}

/// Checks `x` against `app`: `Ok` with what was measured, `Err` with what is
/// wrong. `Mark` remembers in `marks`; `ExpectError` takes the error the
/// previous step left in `pending`.
pub(super) fn check(
    app: &App,
    x: &Expect,
    marks: &mut Marks,
    pending: &mut Option<(usize, String)>,
) -> Result<String, String> {
    let w = app.world();
    let now = Now {
        surface: w.resource::<SurfaceData>(),
        scene: crate::ecs::patch::try_scene(w)?,
        stats: w.resource::<Stats>(),
        history: w.resource::<History>(),
    };
    // the first patch's drawn points: its G2 run's cut when it heads a
    // built run (its own pipeline then waits), else its own surface
    let points = drawn_points(w).unwrap_or(&now.surface.points);
    match x {
        Expect::ExpectPoint {
            row,
            index,
            near,
            tolerance,
        } => point(points, *row, *index, near, tolerance),
        Expect::ExpectStats {
            max_reblended,
            max_reintegrated,
            min_reintegrated,
            full_rebuild,
        } => stats(
            &now.stats.last,
            *max_reblended,
            *max_reintegrated,
            *min_reintegrated,
            *full_rebuild,
        ),
        Expect::ExpectScene { .. } => scene(&now, x),
        Expect::ExpectError(text) => error(pending.take(), text),
        Expect::Mark(name) => {
            marks.insert(name.clone(), points.clone());
            Ok(format!("({} points)", points.data().len()))
        }
        Expect::ExpectSame { mark, tolerance } => same(marks, points, mark, tolerance, true),
        Expect::ExpectChanged { mark, tolerance } => same(marks, points, mark, tolerance, false),
        Expect::ExpectEndsSame { mark, tolerance } => ends_same(marks, points, mark, tolerance),
        Expect::ExpectStreamlineLength {
            row,
            length,
            tolerance,
        } => streamline_length(&now.scene, *row, length, tolerance),
        Expect::ExpectMirrorSymmetric { tolerance } => mirror_symmetric(&now, tolerance),
        Expect::ExpectShifted {
            mark,
            by,
            tolerance,
        } => shifted(marks, points, mark, by, tolerance),
        // checked against the patch entities (`playback/seam.rs`)
        Expect::ExpectSeam { .. } => Err("a seam is checked by the playback's patch steps".into()),
        // its missing reference is the step's error ([`reference_deviation`])
        Expect::ExpectReferenceDeviation { .. } => {
            Err("a reference deviation is checked by its own playback step".into())
        }
    }
}

/// The shape of every measured expectation: it holds when `holds`, saying
/// `(ok MEASURED)`; otherwise it fails, saying `fail(MEASURED) (tolerance T)`.
/// The measure is written `{:.2e}` when it holds, `{:.3e}` when it fails.
fn verdict(
    holds: bool,
    measured: f64,
    tolerance: &Finite,
    ok: &str,
    fail: impl FnOnce(String) -> String,
) -> Result<String, String> {
    if holds {
        Ok(format!("({ok} {measured:.2e})"))
    } else {
        Err(format!(
            "{} (tolerance {})",
            fail(format!("{measured:.3e}")),
            tolerance.0
        ))
    }
}

/// [`verdict`] for a measure that must be at most the tolerance.
fn within(
    measured: f64,
    tolerance: &Finite,
    ok: &str,
    fail: impl FnOnce(String) -> String,
) -> Result<String, String> {
    verdict(measured <= tolerance.0, measured, tolerance, ok, fail)
}

/// The points remembered under `mark`.
fn mark<'m>(marks: &'m Marks, mark: &str) -> Result<&'m Grid<DVec3>, String> {
    marks
        .get(mark)
        .ok_or_else(|| format!("no mark `{mark}`; add a Mark(\"{mark}\") step first"))
}

/// The points under `mark`, if the surface still has their shape.
fn mark_shaped<'m>(
    marks: &'m Marks,
    points: &Grid<DVec3>,
    name: &str,
) -> Result<&'m Grid<DVec3>, String> {
    let m = mark(marks, name)?;
    if (m.rows(), m.cols()) != (points.rows(), points.cols()) {
        return Err(format!("the surface's shape differs from mark `{name}`"));
    }
    Ok(m)
}

/// The largest of some distances (0 for none).
fn largest(distances: impl Iterator<Item = f64>) -> f64 {
    distances.fold(0.0, f64::max)
}

/// `ExpectPoint`: one streamline point of the display depth.
fn point(
    p: &Grid<DVec3>,
    row: usize,
    index: usize,
    near: &Point,
    tolerance: &Finite,
) -> Result<String, String> {
    if row >= p.rows() || index >= p.cols() {
        return Err(format!(
            "no point ({row}, {index}): the surface has {} streamlines of {} points",
            p.rows(),
            p.cols()
        ));
    }
    let got = p.get(row, index);
    within((got - near.vec()).length(), tolerance, "distance", |d| {
        format!(
            "point ({row}, {index}) is ({:.6}, {:.6}, {:.6}), {d} from the expected point",
            got.x, got.y, got.z
        )
    })
}

/// `ExpectStats`: bounds on what the last edit recomputed.
fn stats(
    l: &EditStats,
    max_reblended: Option<usize>,
    max_reintegrated: Option<usize>,
    min_reintegrated: Option<usize>,
    full_rebuild: Option<bool>,
) -> Result<String, String> {
    let (blended, integrated) = (l.tangents_reblended, l.streamlines_reintegrated);
    let mut bad = Vec::new();
    if let Some(m) = max_reblended
        && blended > m
    {
        bad.push(format!("re-blended {blended} > {m}"));
    }
    if let Some(m) = max_reintegrated
        && integrated > m
    {
        bad.push(format!("re-integrated {integrated} > {m}"));
    }
    if let Some(m) = min_reintegrated
        && integrated < m
    {
        bad.push(format!("re-integrated {integrated} < {m}"));
    }
    if let Some(f) = full_rebuild
        && l.full_rebuild != f
    {
        bad.push(format!("full rebuild was {}", l.full_rebuild));
    }
    Fields(bad).verdict(format!(
        "(re-blended {blended}, re-integrated {integrated})"
    ))
}

/// The fields of an expectation that did not hold, each `what is GOT,
/// expected WANT`.
struct Fields(Vec<String>);

impl Fields {
    /// Compares one field given as `want` with `got`, written as `show` writes them.
    /// (Compared as written, as they are shown.)
    fn field<T>(
        &mut self,
        what: &str,
        want: &Option<T>,
        got: T,
        show: impl Fn(&T) -> String,
    ) -> &mut Self {
        if let Some(w) = want {
            let (want, got) = (show(w), show(&got));
            if want != got {
                self.0.push(format!("{what} is {got}, expected {want}"));
            }
        }
        self
    }

    /// A field written by `Display`.
    fn shown<T: Display>(&mut self, what: &str, want: &Option<T>, got: T) -> &mut Self {
        self.field(what, want, got, T::to_string)
    }

    /// A field written by `Debug`.
    fn debug<T: Debug>(&mut self, what: &str, want: &Option<T>, got: T) -> &mut Self {
        self.field(what, want, got, |x| format!("{x:?}"))
    }

    /// Holds, saying `ok`, when every field did.
    fn verdict(&self, ok: String) -> Result<String, String> {
        if self.0.is_empty() {
            Ok(ok)
        } else {
            Err(self.0.join(", "))
        }
    }
}

/// `ExpectScene`: properties of the scene, each optional.
fn scene(now: &Now, x: &Expect) -> Result<String, String> {
    let Expect::ExpectScene {
        display_depth,
        edit_depth,
        scheme,
        blend_order,
        streamlines,
        details,
        can_undo,
        can_redo,
        tuning,
        interpolate_tangents,
        rows,
        cols,
        mirror,
        anchor,
        initial_order,
    } = x
    else {
        unreachable!("scene is called for ExpectScene only")
    };
    let s = &now.scene;
    let d = &s.design;
    Fields(Vec::new())
        .shown("display depth", display_depth, s.display_depth)
        .shown("edit depth", edit_depth, s.edit_depth)
        .debug("scheme", scheme, SchemeSpec::from_kernel(d.scheme()))
        .debug(
            "blend order",
            blend_order,
            OrderSpec::from_kernel(d.order()),
        )
        .shown("streamlines", streamlines, now.surface.points.rows())
        .shown("details", details, s.details.len())
        .shown("can undo", can_undo, now.history.undo_len() > 0)
        .shown("can redo", can_redo, now.history.redo_len() > 0)
        .shown("fine tuning on", tuning, s.tuning.is_some())
        .shown(
            "interpolate tangents",
            interpolate_tangents,
            s.interpolate_tangents,
        )
        .shown("control rows", rows, d.net().rows())
        .shown("control columns", cols, d.net().cols())
        .shown("mirror", mirror, s.mirror)
        .shown("anchor", anchor, d.anchor())
        .shown(
            "initial curve order",
            initial_order,
            d.initial().qi().order(),
        )
        .verdict(String::new())
}

/// `ExpectError`: the previous step failed with a message containing `text`.
fn error(pending: Option<(usize, String)>, text: &str) -> Result<String, String> {
    match pending {
        Some((_, e)) if e.contains(text) => Ok(format!("({e})")),
        Some((_, e)) => Err(format!(
            "the error was `{e}`, which does not contain `{text}`"
        )),
        None => Err("the previous step succeeded, but an error was expected".into()),
    }
}

/// `ExpectSame` (`same`) and `ExpectChanged`: every point within `tolerance`
/// of the mark, or some point beyond it.
fn same(
    marks: &Marks,
    points: &Grid<DVec3>,
    name: &str,
    tolerance: &Finite,
    same: bool,
) -> Result<String, String> {
    let m = mark(marks, name)?;
    if (m.rows(), m.cols()) != (points.rows(), points.cols()) {
        return if same {
            Err(format!("the surface's shape differs from mark `{name}`"))
        } else {
            Ok("(shape changed)".into())
        };
    }
    let d = largest(
        m.data()
            .iter()
            .zip(points.data())
            .map(|(x, y)| (*x - *y).length()),
    );
    verdict(
        (d <= tolerance.0) == same,
        d,
        tolerance,
        "max difference",
        |d| format!("max difference from `{name}` is {d}"),
    )
}

/// `ExpectEndsSame`: the first and last point of every streamline.
fn ends_same(
    marks: &Marks,
    p: &Grid<DVec3>,
    name: &str,
    tolerance: &Finite,
) -> Result<String, String> {
    let m = mark_shaped(marks, p, name)?;
    let last = p.cols() - 1;
    let d = largest(
        (0..p.rows())
            .flat_map(|r| [(r, 0), (r, last)])
            .map(|(r, c)| (p.get(r, c) - m.get(r, c)).length()),
    );
    within(d, tolerance, "ends moved at most", |d| {
        format!("an end moved by {d} from `{name}`")
    })
}

/// `ExpectShifted`: every point is the mark's moved by `by`.
fn shifted(
    marks: &Marks,
    p: &Grid<DVec3>,
    name: &str,
    by: &Point,
    tolerance: &Finite,
) -> Result<String, String> {
    let m = mark_shaped(marks, p, name)?;
    let d = largest(
        m.data()
            .iter()
            .zip(p.data())
            .map(|(a, b)| (*b - *a - by.vec()).length()),
    );
    within(d, tolerance, "off by at most", |d| {
        format!(
            "a point is {d} off the mark `{name}` moved by ({}, {}, {})",
            by.0, by.1, by.2
        )
    })
}

/// `ExpectStreamlineLength`: control row `row`'s streamline length.
fn streamline_length(
    scene: &crate::scene::Scene,
    row: usize,
    length: &Finite,
    tolerance: &Finite,
) -> Result<String, String> {
    let d = &scene.design;
    let got = d
        .streamline_length(row)
        .ok_or_else(|| format!("no control row {row}: the net has {} rows", d.net().rows()))?;
    within(
        (got - length.0).abs(),
        tolerance,
        &format!("{got}, off by"),
        |e| format!("streamline {row} is {got} long, {e} from {}", length.0),
    )
}

/// `ExpectMirrorSymmetric`: the surface shown equals its reflection.
fn mirror_symmetric(now: &Now, tolerance: &Finite) -> Result<String, String> {
    let scene = &now.scene;
    if !scene.mirror {
        return Err("the mirror is off".into());
    }
    let plane = scene.design.mirror_plane();
    let p = &now.surface.points;
    let n = p.rows();
    let worst = largest((0..n).flat_map(|r| {
        (0..p.cols())
            .map(move |k| (plane.reflect_point(p.get(r, k)) - p.get(n - 1 - r, k)).length())
    }));
    within(worst, tolerance, "largest asymmetry", |w| {
        format!("the surface differs from its reflection by {w}")
    })
}

/// `ExpectReferenceDeviation`: the first patch's streamline points at the
/// display depth (the own half when mirrored) measured against the face the
/// design's reference names ([`crate::scene::fit::reference::measure`],
/// docs/math.md §12): the largest distance at most `max`, and above `min`
/// when it is given. A design without a reference, or a reference file that
/// cannot be read, is the step's error (`Err`, which `ExpectError` can
/// expect); a distance out of bounds fails it.
pub(super) fn reference_deviation(
    app: &App,
    max: &Finite,
    min: &Option<Finite>,
) -> Result<Outcome, String> {
    let w = app.world();
    let scene = crate::ecs::patch::try_scene(w)?;
    let link = scene.reference.as_ref().ok_or(
        "the design has no reference to measure against; fit it to a face with a `Fit` step first, or open a scene whose `reference` names one (docs/scenes.md)",
    )?;
    let points = drawn_points(w).unwrap_or(&w.resource::<SurfaceData>().points);
    let d = crate::scene::fit::reference::measure(link, points, scene.mirror)?;
    let named = format!("{} face {}", link.path.display(), link.face);
    let held = within(d.max, max, "largest distance", |m| {
        format!("the design is up to {m} from {named} (mean {:.3e})", d.mean)
    });
    Ok(match (held, min) {
        (Err(m), _) => Outcome::Failed(m),
        (Ok(_), Some(m)) if d.max <= m.0 => Outcome::Failed(format!(
            "the design is at most {:.3e} from {named}, not more than min {}",
            d.max, m.0
        )),
        (Ok(_), _) => Outcome::Done(format!(
            "largest distance {:.2e}, mean {:.2e}, from {named}",
            d.max, d.mean
        )),
    })
}
