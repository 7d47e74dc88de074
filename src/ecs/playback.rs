//! Scripted playback: each step of a [`Script`] is an edit message sent to a
//! headless app (one update per step) or an expectation checked against it.

use super::messages::Edit;
use super::resources::*;
use super::{headless_app, send};
use crate::scene::format::{OrderSpec, SchemeSpec};
use crate::scene::script::{Expect, Script, Step};
use crate::scene::{Scene, builtin};
use bevy::prelude::*;
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use streamline_kernel::{DVec3, Grid};

/// The outcome of a script.
#[derive(Debug, Clone, Default)]
pub struct PlayReport {
    /// One line per step.
    pub lines: Vec<String>,
    /// Steps that failed.
    pub failures: usize,
}

impl PlayReport {
    /// Every step held.
    pub fn passed(&self) -> bool {
        self.failures == 0
    }
}

/// Runs `script`, whose relative paths are resolved against `dir`, starting
/// from `scene`.
pub fn play(script: &Script, dir: &Path, scene: Scene) -> PlayReport {
    let mut app = headless_app(scene);
    let mut report = PlayReport::default();
    let mut marks: HashMap<String, Grid<DVec3>> = HashMap::new();
    let mut pending: Option<(usize, String)> = None;
    for (i, step) in script.steps.iter().enumerate() {
        let n = i + 1;
        if !matches!(step, Step::Expect(Expect::ExpectError(_)))
            && let Some((at, err)) = pending.take()
        {
            report.failures += 1;
            report
                .lines
                .push(format!("step {at:>3}: FAIL unexpected error: {err}"));
        }
        if let Step::Expect(x) = step {
            let res = check(&app, x, &mut marks, &mut pending);
            let label = short(step);
            match res {
                Ok(m) => report.lines.push(format!("step {n:>3} {label}: ok {m}")),
                Err(m) => {
                    report.failures += 1;
                    report.lines.push(format!("step {n:>3} {label}: FAIL {m}"));
                }
            }
            continue;
        }
        let edit = match to_edit(step, dir) {
            Ok(e) => e,
            Err(m) => {
                pending = Some((n, m.clone()));
                report
                    .lines
                    .push(format!("step {n:>3} {}: error {m}", short(step)));
                continue;
            }
        };
        let label = edit.label();
        send(&mut app, edit);
        app.update();
        let w = app.world();
        let log = w.resource::<EditLog>();
        let stats = &w.resource::<Stats>().last;
        let errors: Vec<&String> = log
            .entries
            .iter()
            .filter_map(|e| e.as_ref().err())
            .collect();
        if let Some(e) = errors.first() {
            pending = Some((n, (*e).clone()));
            report.lines.push(format!("step {n:>3} {label}: error {e}"));
        } else {
            report.lines.push(format!(
                "step {n:>3} {label}: ok (re-blended {}, re-integrated {}{}, {:.0} µs{})",
                stats.tangents_reblended,
                stats.streamlines_reintegrated,
                if stats.streamlines_replaced > 0 {
                    format!(", {} placed again", stats.streamlines_replaced)
                } else {
                    String::new()
                },
                stats.us_total(),
                if stats.full_rebuild {
                    ", full rebuild"
                } else {
                    ""
                }
            ));
        }
    }
    if let Some((at, err)) = pending {
        report.failures += 1;
        report
            .lines
            .push(format!("step {at:>3}: FAIL unexpected error: {err}"));
    }
    report
}

fn short(step: &Step) -> String {
    let s = format!("{step:?}");
    let head: String = s.chars().take(60).collect();
    if s.chars().count() > 60 {
        head + "…"
    } else {
        head
    }
}

fn resolve(dir: &Path, p: &str) -> PathBuf {
    dir.join(p)
}

/// An output path of a script, its folder created: inside the script's
/// folder, links resolved ([`crate::scene::script::output_path`], [`crate::scene::script::confine`]).
fn output(dir: &Path, p: &str) -> Result<PathBuf, String> {
    let path = crate::scene::script::output_path(dir, p)?;
    crate::scene::script::confine(dir, &path)?;
    Ok(path)
}

/// The edit a step sends: file names resolved against the script's folder
/// `dir` (outputs confined to it), a fine-tuning function checked, any other
/// edit as it is.
pub(crate) fn to_edit(step: &Step, dir: &Path) -> Result<Edit, String> {
    Ok(match step {
        Step::Load(p) => match p.strip_prefix("builtin:") {
            Some(name) => Edit::Replace(Box::new(builtin::scene(name).map_err(|e| e.to_string())?)),
            None => Edit::Load(resolve(dir, p)),
        },
        Step::Save(p) => Edit::Save(output(dir, p)?),
        Step::Export(p) => Edit::Export(output(dir, p)?),
        Step::SetTuning(t) => Edit::SetTuning(t.as_ref().map(|t| t.to_kernel()).transpose()?),
        Step::Edit(e) => e.clone(),
        Step::Expect(_) => return Err("not an edit".into()),
    })
}

fn max_diff(a: &Grid<DVec3>, b: &Grid<DVec3>) -> Option<f64> {
    if (a.rows(), a.cols()) != (b.rows(), b.cols()) {
        return None;
    }
    Some(
        a.data()
            .iter()
            .zip(b.data())
            .map(|(x, y)| (*x - *y).length())
            .fold(0.0, f64::max),
    )
}

fn check(
    app: &App,
    step: &Expect,
    marks: &mut HashMap<String, Grid<DVec3>>,
    pending: &mut Option<(usize, String)>,
) -> Result<String, String> {
    let w = app.world();
    let surface = w.resource::<SurfaceData>();
    let model = w.resource::<Model>();
    let stats = w.resource::<Stats>();
    let history = w.resource::<History>();
    match step {
        Expect::ExpectPoint {
            row,
            index,
            near,
            tolerance,
        } => {
            let p = &surface.points;
            if *row >= p.rows() || *index >= p.cols() {
                return Err(format!(
                    "no point ({row}, {index}): the surface has {} streamlines of {} points",
                    p.rows(),
                    p.cols()
                ));
            }
            let got = p.get(*row, *index);
            let d = (got - near.vec()).length();
            if d <= tolerance.0 {
                Ok(format!("(distance {d:.2e})"))
            } else {
                Err(format!(
                    "point ({row}, {index}) is ({:.6}, {:.6}, {:.6}), {d:.3e} from the expected point (tolerance {})",
                    got.x, got.y, got.z, tolerance.0
                ))
            }
        }
        Expect::ExpectStats {
            max_reblended,
            max_reintegrated,
            min_reintegrated,
            full_rebuild,
        } => {
            let l = &stats.last;
            let mut bad = Vec::new();
            if let Some(m) = max_reblended
                && l.tangents_reblended > *m
            {
                bad.push(format!("re-blended {} > {m}", l.tangents_reblended));
            }
            if let Some(m) = max_reintegrated
                && l.streamlines_reintegrated > *m
            {
                bad.push(format!(
                    "re-integrated {} > {m}",
                    l.streamlines_reintegrated
                ));
            }
            if let Some(m) = min_reintegrated
                && l.streamlines_reintegrated < *m
            {
                bad.push(format!(
                    "re-integrated {} < {m}",
                    l.streamlines_reintegrated
                ));
            }
            if let Some(f) = full_rebuild
                && l.full_rebuild != *f
            {
                bad.push(format!("full rebuild was {}", l.full_rebuild));
            }
            if bad.is_empty() {
                Ok(format!(
                    "(re-blended {}, re-integrated {})",
                    l.tangents_reblended, l.streamlines_reintegrated
                ))
            } else {
                Err(bad.join(", "))
            }
        }
        Expect::ExpectScene {
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
        } => {
            let s = &model.scene;
            let mut bad = Vec::new();
            let mut cmp = |what: &str, want: Option<String>, got: String| {
                if let Some(w) = want
                    && w != got
                {
                    bad.push(format!("{what} is {got}, expected {w}"));
                }
            };
            cmp(
                "display depth",
                display_depth.map(|d| d.to_string()),
                s.display_depth.to_string(),
            );
            cmp(
                "edit depth",
                edit_depth.map(|d| d.to_string()),
                s.edit_depth.to_string(),
            );
            cmp(
                "scheme",
                scheme.map(|x| format!("{x:?}")),
                format!("{:?}", SchemeSpec::from_kernel(s.design.scheme())),
            );
            cmp(
                "blend order",
                blend_order.map(|x| format!("{x:?}")),
                format!("{:?}", OrderSpec::from_kernel(s.design.order())),
            );
            cmp(
                "streamlines",
                streamlines.map(|x| x.to_string()),
                surface.points.rows().to_string(),
            );
            cmp(
                "details",
                details.map(|x| x.to_string()),
                s.details.len().to_string(),
            );
            cmp(
                "can undo",
                can_undo.map(|x| x.to_string()),
                (history.undo_len() > 0).to_string(),
            );
            cmp(
                "can redo",
                can_redo.map(|x| x.to_string()),
                (history.redo_len() > 0).to_string(),
            );
            cmp(
                "fine tuning on",
                tuning.map(|x| x.to_string()),
                s.tuning.is_some().to_string(),
            );
            cmp(
                "interpolate tangents",
                interpolate_tangents.map(|x| x.to_string()),
                s.interpolate_tangents.to_string(),
            );
            cmp(
                "control rows",
                rows.map(|x| x.to_string()),
                s.design.net().rows().to_string(),
            );
            cmp(
                "control columns",
                cols.map(|x| x.to_string()),
                s.design.net().cols().to_string(),
            );
            cmp(
                "mirror",
                mirror.map(|x| x.to_string()),
                s.mirror.to_string(),
            );
            cmp(
                "anchor",
                anchor.map(|x| x.to_string()),
                s.design.anchor().to_string(),
            );
            cmp(
                "initial curve order",
                initial_order.map(|x| x.to_string()),
                s.design.initial().qi().order().to_string(),
            );
            if bad.is_empty() {
                Ok(String::new())
            } else {
                Err(bad.join(", "))
            }
        }
        Expect::ExpectError(text) => match pending.take() {
            Some((_, e)) if e.contains(text.as_str()) => Ok(format!("({e})")),
            Some((_, e)) => Err(format!(
                "the error was `{e}`, which does not contain `{text}`"
            )),
            None => Err("the previous step succeeded, but an error was expected".into()),
        },
        Expect::Mark(name) => {
            marks.insert(name.clone(), surface.points.clone());
            Ok(format!("({} points)", surface.points.data().len()))
        }
        Expect::ExpectSame { mark, tolerance } | Expect::ExpectChanged { mark, tolerance } => {
            let m = marks
                .get(mark)
                .ok_or_else(|| format!("no mark `{mark}`; add a Mark(\"{mark}\") step first"))?;
            let same = matches!(step, Expect::ExpectSame { .. });
            match max_diff(m, &surface.points) {
                None => {
                    if same {
                        Err(format!("the surface's shape differs from mark `{mark}`"))
                    } else {
                        Ok("(shape changed)".into())
                    }
                }
                Some(d) if (d <= tolerance.0) == same => Ok(format!("(max difference {d:.2e})")),
                Some(d) => Err(format!(
                    "max difference from `{mark}` is {d:.3e} (tolerance {})",
                    tolerance.0
                )),
            }
        }
        Expect::ExpectEndsSame { mark, tolerance } => {
            let m = marks
                .get(mark)
                .ok_or_else(|| format!("no mark `{mark}`; add a Mark(\"{mark}\") step first"))?;
            let p = &surface.points;
            if (m.rows(), m.cols()) != (p.rows(), p.cols()) {
                return Err(format!("the surface's shape differs from mark `{mark}`"));
            }
            let last = p.cols() - 1;
            let d = (0..p.rows())
                .flat_map(|r| [(r, 0), (r, last)])
                .map(|(r, c)| (p.get(r, c) - m.get(r, c)).length())
                .fold(0.0, f64::max);
            if d <= tolerance.0 {
                Ok(format!("(ends moved at most {d:.2e})"))
            } else {
                Err(format!(
                    "an end moved by {d:.3e} from `{mark}` (tolerance {})",
                    tolerance.0
                ))
            }
        }
        Expect::ExpectStreamlineLength {
            row,
            length,
            tolerance,
        } => {
            let d = &model.scene.design;
            let got = d.streamline_length(*row).ok_or_else(|| {
                format!("no control row {row}: the net has {} rows", d.net().rows())
            })?;
            let e = (got - length.0).abs();
            if e <= tolerance.0 {
                Ok(format!("({got}, off by {e:.2e})"))
            } else {
                Err(format!(
                    "streamline {row} is {got} long, {e:.3e} from {} (tolerance {})",
                    length.0, tolerance.0
                ))
            }
        }
        Expect::ExpectMirrorSymmetric { tolerance } => {
            if !model.scene.mirror {
                return Err("the mirror is off".into());
            }
            let plane = model.scene.design.mirror_plane();
            let p = &surface.points;
            let n = p.rows();
            let mut worst = 0.0_f64;
            for r in 0..n {
                for k in 0..p.cols() {
                    let e = (plane.reflect_point(p.get(r, k)) - p.get(n - 1 - r, k)).length();
                    worst = worst.max(e);
                }
            }
            if worst <= tolerance.0 {
                Ok(format!("(largest asymmetry {worst:.2e})"))
            } else {
                Err(format!(
                    "the surface differs from its reflection by {worst:.3e} (tolerance {})",
                    tolerance.0
                ))
            }
        }
        Expect::ExpectShifted {
            mark,
            by,
            tolerance,
        } => {
            let m = marks
                .get(mark)
                .ok_or_else(|| format!("no mark `{mark}`; add a Mark(\"{mark}\") step first"))?;
            let p = &surface.points;
            if (m.rows(), m.cols()) != (p.rows(), p.cols()) {
                return Err(format!("the surface's shape differs from mark `{mark}`"));
            }
            let d = m
                .data()
                .iter()
                .zip(p.data())
                .map(|(a, b)| (*b - *a - by.vec()).length())
                .fold(0.0, f64::max);
            if d <= tolerance.0 {
                Ok(format!("(off by at most {d:.2e})"))
            } else {
                Err(format!(
                    "a point is {d:.3e} off the mark `{mark}` moved by ({}, {}, {}) (tolerance {})",
                    by.0, by.1, by.2, tolerance.0
                ))
            }
        }
    }
}
