//! A script's `ExpectSeam` (docs/math.md §11), checked against the world's
//! patch entities and their seam reports. Naming no seam is the step's
//! error (which `ExpectError` can expect); a seam over its bounds fails.

use crate::ecs::joined::{PatchSlot, PatchStart, SeamState};
use crate::ecs::patch::patch_entity;
use crate::scene::design::document::MAIN_PATCH;
use crate::scene::edits::script::expect::Expect;
use bevy::prelude::*;

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

/// What an expectation whose subject may be missing says when it ran (a
/// seam, `ExpectSeam`; the reference, `ExpectReferenceDeviation` in
/// `playback/expect.rs`): done, or not met. A missing subject is the step's
/// error instead.
pub(super) enum Outcome {
    /// Done, with what was done.
    Done(String),
    /// An expectation that does not hold, and why.
    Failed(String),
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
