//! A document's several patches in the 3D view (docs/math.md §11;
//! docs/editor.md, "Several patches"): each join's seam drawn along its
//! shared edge with its continuity label (`G0`/`G1`/`G2`) in a colour that
//! says whether the seam's measured figures meet it ([`verdict`]); and
//! choosing a patch by clicking its surface
//! ([`pick`]), or starting a new patch by right-clicking its boundary
//! ([`boundary`]). What the seams are is collected once a frame into [`Seams`],
//! which the Analysis section's seam table and the screenshot report read.
//! The shaded surfaces themselves are in `surface::patches`.

pub mod boundary;
pub mod draw;
pub mod pick;
pub mod verdict;

use super::interaction::{EditorSet, SceneBounds};
use crate::ecs::joined::{PatchHidden, PatchSlot, PatchStart, PatchSurface, SeamState};
use bevy::prelude::*;
use streamline_kernel::DVec3;
use streamline_kernel::joins::{Continuity, Edge, SeamReport};
pub use verdict::Verdict;

/// What the seams overlay draws (the Display section edits it).
#[derive(Resource, Debug, Clone, PartialEq)]
pub struct SeamSettings {
    /// Draw the seams and their labels.
    pub show: bool,
}

impl Default for SeamSettings {
    fn default() -> Self {
        SeamSettings { show: true }
    }
}

/// One join's seam, as drawn and tabled.
#[derive(Debug, Clone)]
pub struct SeamLine {
    /// `A`'s name.
    pub a_name: String,
    /// `B`'s name.
    pub b_name: String,
    /// The edge of `A`.
    pub edge: Edge,
    /// The continuity built.
    pub continuity: Continuity,
    /// The shared edge at the display depth: `B`'s start points (on a
    /// chain `A`'s last points, Eq. 66; on a side `A`'s streamline, Eq. 71).
    pub points: Vec<DVec3>,
    /// The measured figures (docs/math.md §11.3), `None` while a side is not built.
    pub report: Option<SeamReport>,
    /// What they say of the continuity.
    pub verdict: Verdict,
    /// Either patch is hidden.
    pub hidden: bool,
}

/// The document's seams, in the order of the patches that start on them.
#[derive(Resource, Debug, Default)]
pub struct Seams {
    /// One per join.
    pub lines: Vec<SeamLine>,
}

pub struct SeamsPlugin;

impl Plugin for SeamsPlugin {
    fn build(&self, app: &mut App) {
        app.init_resource::<SeamSettings>()
            .init_resource::<Seams>()
            .add_systems(Update, collect.in_set(EditorSet::Sync))
            .add_plugins((
                draw::SeamDrawPlugin,
                boundary::BoundaryPlugin,
                pick::PatchPickPlugin,
            ));
    }
}

/// What [`collect`] reads of every patch of a document.
type PatchRow = (
    Entity,
    &'static PatchSlot,
    &'static PatchStart,
    &'static PatchSurface,
    Option<&'static SeamState>,
    Has<PatchHidden>,
);

/// Collects the seams of the world's patches into [`Seams`] (a handful of
/// joins of a few dozen points each: cheaper than tracking what changed).
fn collect(
    meter: Res<crate::ecs::meter::CpuMeter>,
    patches: Query<PatchRow>,
    bounds: Res<SceneBounds>,
    mut seams: ResMut<Seams>,
) {
    let _meter = meter.start();
    let mut rows: Vec<_> = patches.iter().collect();
    rows.sort_by_key(|r| r.1.index);
    let mut lines = Vec::new();
    for &(_, slot, start, surface, state, b_hidden) in &rows {
        let PatchStart::Edge {
            parent,
            edge,
            continuity,
        } = *start
        else {
            continue;
        };
        let Ok((_, a_slot, _, _, _, a_hidden)) = patches.get(parent) else {
            continue;
        };
        let points = surface
            .stack()
            .map(|s| s.finest_points().column(0))
            .unwrap_or_default();
        let report = state.and_then(|s| s.report.clone());
        let verdict = verdict::judge(report.as_ref(), continuity, bounds.size());
        lines.push(SeamLine {
            a_name: a_slot.name.clone(),
            b_name: slot.name.clone(),
            edge,
            continuity,
            points,
            report,
            verdict,
            hidden: a_hidden || b_hidden,
        });
    }
    seams.lines = lines;
}
