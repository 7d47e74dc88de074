//! A script's patch steps (docs/math.md §11) against the world's patch
//! entities: `AddPatch`, `SetPatch`, `RemovePatch`, `RenamePatch`,
//! `ExpectSeam`, and the edits of a joined patch (`SetDirection`, `Rotate`
//! on its net handles). A bad step is an error naming the patch and the fix;
//! the world is left as it was.

use crate::ecs::SurfaceData;
use crate::ecs::joined::{
    JoinedDesign, PatchSlot, PatchStart, PatchSurface, SeamState, adopt_first, spawn_joined_patch,
};
use crate::ecs::messages::Edit;
use crate::ecs::patch::{Direction, Joined, PatchIndex, PatchKernel, PatchName, patch_entity};
use crate::scene::document::MAIN_PATCH;
use crate::scene::format_v3::{EdgeSpec, patch_name_problem};
use crate::scene::patch_edit::PatchEdit;
use crate::scene::script::Expect;
use bevy::prelude::*;
use streamline_kernel::joins::{Continuity, Edge};
use streamline_kernel::streamline::integrate::polyline_length;
use streamline_kernel::{DQuat, DVec3, Design, Grid};

/// The patches by name, in the document's order (the first patch is `main`
/// until the world has a document).
fn named(world: &mut World) -> Vec<(String, Entity)> {
    let mut q = world.query::<(Entity, &PatchSlot)>();
    let mut v: Vec<_> = q
        .iter(world)
        .map(|(e, s)| (s.index, s.name.clone(), e))
        .collect();
    if v.is_empty()
        && let Some(first) = patch_entity(world)
    {
        return vec![(MAIN_PATCH.to_string(), first)];
    }
    v.sort();
    v.into_iter().map(|(_, n, e)| (n, e)).collect()
}

fn find(world: &mut World, name: &str) -> Result<Entity, String> {
    let all = named(world);
    match all.iter().find(|(n, _)| n == name) {
        Some(&(_, e)) => Ok(e),
        None => Err(format!(
            "no patch `{name}`; the patches are {}",
            all.iter()
                .map(|(n, _)| format!("`{n}`"))
                .collect::<Vec<_>>()
                .join(", ")
        )),
    }
}

fn fresh_name(world: &mut World, name: &str) -> Result<(), String> {
    if let Some(p) = patch_name_problem(name) {
        return Err(p);
    }
    if named(world).iter().any(|(n, _)| n == name) {
        return Err(format!(
            "a patch is already named `{name}`; choose another name"
        ));
    }
    Ok(())
}

fn design_of(world: &World, e: Entity) -> Option<Design> {
    (world.get::<PatchKernel>(e).map(|k| k.design.clone()))
        .or_else(|| world.get::<JoinedDesign>(e).map(|j| j.0.clone()))
}

/// Patch `e`'s streamline points at the display depth.
fn points_of(world: &World, e: Entity) -> Option<Grid<DVec3>> {
    if world.get::<Joined>(e).is_none() {
        return Some(world.resource::<SurfaceData>().points.clone());
    }
    world
        .get::<PatchSurface>(e)?
        .stack()
        .map(|s| s.finest_points().clone())
}

/// What a patch step that ran says: done, or (an expectation) not met.
pub(super) enum Outcome {
    /// Done, with what was done.
    Done(String),
    /// An expectation that does not hold, and why.
    Failed(String),
}

/// Runs a patch step; `acting` is the patch later edits act on (`None`:
/// the first). `Err`: the step is bad (a located message).
pub(super) fn run(
    app: &mut App,
    step: &PatchEdit,
    acting: &mut Option<Entity>,
) -> Result<Outcome, String> {
    let world = app.world_mut();
    match step {
        PatchEdit::AddPatch {
            name,
            from: (a, edge),
            continuity,
            rows,
            cols,
            length,
        } => {
            fresh_name(world, name)?;
            let parent = find(world, a)?;
            let design = new_design(
                world,
                parent,
                *edge,
                continuity.to_kernel(),
                *rows,
                *cols,
                length.0,
            )
            .map_err(|m| format!("AddPatch `{name}` on `{a}`: {m}"))?;
            let first = patch_entity(world).ok_or("the world has no patch")?;
            let all = named(world);
            adopt_first(world, first, &all[0].0);
            let index = 1
                + (world
                    .query::<&PatchSlot>()
                    .iter(world)
                    .map(|s| s.index)
                    .max())
                .unwrap_or(0);
            let start = PatchStart::Edge {
                parent,
                edge: edge.to_kernel(),
                continuity: continuity.to_kernel(),
            };
            let e = spawn_joined_patch(world, name, index, start, design);
            app.update();
            let world = app.world_mut();
            if let Some(Err(m)) = world.get::<PatchSurface>(e).and_then(|s| s.built.clone()) {
                world.entity_mut(e).despawn();
                return Err(m);
            }
            Ok(Outcome::Done(format!(
                "added patch `{name}` on `{a}` ({}, {})",
                edge.to_kernel().name(),
                continuity.to_kernel().name()
            )))
        }
        PatchEdit::SetPatch(name) => {
            let e = find(world, name)?;
            *acting = world.get::<Joined>(e).map(|_| e);
            Ok(Outcome::Done(format!("edits act on `{name}`")))
        }
        PatchEdit::RemovePatch(name) => {
            let e = find(world, name)?;
            if world.get::<Joined>(e).is_none() {
                return Err(format!(
                    "`{name}` is the first patch, which every other starts from; remove the others instead"
                ));
            }
            let children: Vec<String> = (world.query::<(&PatchSlot, &PatchStart)>().iter(world))
                .filter(|(_, s)| matches!(s, PatchStart::Edge { parent, .. } if *parent == e))
                .map(|(slot, _)| format!("`{}`", slot.name))
                .collect();
            if !children.is_empty() {
                return Err(format!(
                    "{} starts on `{name}`; remove {} first",
                    children.join(", "),
                    if children.len() == 1 { "it" } else { "them" }
                ));
            }
            world.entity_mut(e).despawn();
            if *acting == Some(e) {
                *acting = None;
            }
            app.update();
            Ok(Outcome::Done(format!("removed patch `{name}`")))
        }
        PatchEdit::RenamePatch(from, to) => {
            let e = find(world, from)?;
            fresh_name(world, to)?;
            if let Some(first) = patch_entity(world) {
                let all = named(world);
                adopt_first(world, first, &all[0].0);
            }
            if let Some(mut slot) = world.get_mut::<PatchSlot>(e) {
                slot.name.clone_from(to);
            }
            if world.get::<Joined>(e).is_some()
                && let Some(mut n) = world.get_mut::<PatchName>(e)
            {
                n.0.clone_from(to);
            }
            Ok(Outcome::Done(format!("renamed `{from}` to `{to}`")))
        }
        PatchEdit::HidePatch(name, hide) => {
            let e = find(world, name)?;
            if *hide {
                world.entity_mut(e).insert(crate::ecs::joined::PatchHidden);
            } else {
                world
                    .entity_mut(e)
                    .remove::<crate::ecs::joined::PatchHidden>();
            }
            Ok(Outcome::Done(step.label()))
        }
    }
}

/// An `ExpectSeam` step: `Err` when it names no seam (the step's error).
pub(super) fn expect_seam(app: &mut App, x: &Expect) -> Result<Outcome, String> {
    let world = app.world_mut();
    match x {
        Expect::ExpectSeam {
            a,
            b,
            continuity,
            max_gap,
            max_angle_deg,
        } => {
            let (ea, eb) = (find(world, a)?, find(world, b)?);
            let Some(&PatchStart::Edge {
                parent,
                continuity: c,
                ..
            }) = world.get::<PatchStart>(eb)
            else {
                return Err(format!("`{b}` starts on its own curve, not on `{a}`"));
            };
            if parent != ea {
                return Err(format!("`{b}` does not start on `{a}`"));
            }
            if c != continuity.to_kernel() {
                return Err(format!(
                    "the seam `{a}`–`{b}` is {}, not {}",
                    c.name(),
                    continuity.to_kernel().name()
                ));
            }
            let r =
                (world.get::<SeamState>(eb).and_then(|s| s.report.clone())).ok_or_else(|| {
                    format!("the seam `{a}`–`{b}` is not measured (a side is not built)")
                })?;
            if r.gap <= max_gap.0 && r.angle_deg <= max_angle_deg.0 {
                Ok(Outcome::Done(format!(
                    "gap {:.3e}, angle {:.3e}°",
                    r.gap, r.angle_deg
                )))
            } else {
                Ok(Outcome::Failed(format!(
                    "the seam `{a}`–`{b}` has gap {:.3e} (at most {:.3e}) and angle {:.3e}° (at most {:.3e}°)",
                    r.gap, max_gap.0, r.angle_deg, max_angle_deg.0
                )))
            }
        }
        _ => Err("not a seam expectation".into()),
    }
}

/// The net of a new patch on `parent`'s `edge`: a chain takes its rows and
/// `t` and continues its last column; a side join's rows leave the
/// streamline across it, their `t` spread over 5–95 % of its length.
fn new_design(
    world: &World,
    parent: Entity,
    edge: EdgeSpec,
    continuity: Continuity,
    rows: usize,
    cols: usize,
    length: f64,
) -> Result<Design, String> {
    if cols < 2 || rows < 2 {
        return Err(format!(
            "a net of {rows} × {cols}; give at least 2 rows and 2 columns"
        ));
    }
    if !(length.is_finite() && length > 0.0) {
        return Err(format!("length {length}; give a positive length"));
    }
    let a = design_of(world, parent).ok_or("the patch started on has no design")?;
    let (ar, ac) = (a.net().rows(), a.net().cols());
    let (t, dirs): (Vec<f64>, Vec<DVec3>) = match edge.to_kernel() {
        Edge::End => {
            if rows != ar {
                return Err(format!(
                    "a chain has the rows of the patch it starts on: give rows: {ar}"
                ));
            }
            (
                a.params().t.clone(),
                (0..ar).map(|r| a.net().get(r, ac - 1)).collect(),
            )
        }
        side => {
            if continuity == Continuity::G2 {
                return Err(
                    "G2 on a side edge is refused (future work, docs/math.md §11); use G1".into(),
                );
            }
            let pts = points_of(world, parent).ok_or("the patch started on is not built")?;
            let r = if side == Edge::First {
                0
            } else {
                pts.rows() - 1
            };
            let inner = if side == Edge::First {
                1.min(pts.rows() - 1)
            } else {
                pts.rows().saturating_sub(2)
            };
            let len = polyline_length(pts.row(r));
            let mid = pts.cols() / 2;
            let across = (pts.get(r, mid) - pts.get(inner, mid))
                .try_normalize()
                .unwrap_or(DVec3::Z);
            let t = (0..rows)
                .map(|j| len * (0.05 + 0.9 * j as f64 / (rows - 1) as f64))
                .collect();
            (t, vec![across; rows])
        }
    };
    let mut net = Grid::filled(rows, cols, DVec3::X);
    let mut s = Grid::filled(rows, cols, 0.0);
    for (r, &dir) in dirs.iter().enumerate() {
        for c in 0..cols {
            net.set(r, c, dir);
            s.set(r, c, length * c as f64 / (cols - 1) as f64);
        }
    }
    Design::new(&net, s, t, 0, a.scheme(), a.order(), a.initial().clone())
        .map_err(|e| e.to_string())
}

/// An edit of the joined patch `e`: `SetDirection` and `Rotate` write its
/// net handle; any other edit acts on the first patch only.
pub(super) fn edit_joined(app: &mut App, e: Entity, edit: &Edit) -> Result<String, String> {
    let world = app.world_mut();
    let name = world
        .get::<PatchSlot>(e)
        .map_or_else(String::new, |s| s.name.clone());
    let (row, col) = match edit {
        Edit::SetDirection { row, col, .. } | Edit::Rotate { row, col, .. } => (*row, *col),
        other => {
            return Err(format!(
                "`{}` acts on the first patch only; on `{name}` use SetDirection or Rotate, or SetPatch to the first patch before it",
                other.label()
            ));
        }
    };
    let index = world
        .get::<PatchIndex>(e)
        .ok_or("the patch has no handles")?;
    let (rows, cols) = (index.surface.rows(), index.surface.cols());
    if row >= rows || col >= cols {
        return Err(format!(
            "`{name}` has a {rows} × {cols} net; ({row}, {col}) is outside it"
        ));
    }
    let h = index.surface.get(row, col);
    let now = world
        .get::<Direction>(h)
        .map(|d| d.0)
        .ok_or("the handle is missing")?;
    let v = match edit {
        Edit::SetDirection { dir, .. } => dir.try_normalize(),
        Edit::Rotate { axis, radians, .. } => axis
            .try_normalize()
            .map(|ax| (DQuat::from_axis_angle(ax, *radians) * now).normalize()),
        _ => None,
    }
    .ok_or("the direction or axis is zero; give a nonzero one")?;
    if let Some(mut d) = world.get_mut::<Direction>(h) {
        d.set_if_neq(Direction(v));
    }
    app.update();
    match app
        .world()
        .get::<PatchSurface>(e)
        .and_then(|s| s.built.clone())
    {
        Some(Err(m)) => Err(m),
        _ => Ok(format!("{} on `{name}`", edit.label())),
    }
}
