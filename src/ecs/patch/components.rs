//! The components of a patch and of its tangent handles (docs/architecture.md,
//! "Entities"). A [`Patch`] entity holds what belongs to the whole surface;
//! its children are one entity per control tangent of the net
//! ([`SurfaceHandle`]), per multiresolution detail ([`DetailHandle`]) and per
//! control tangent of the initial curve ([`InitialHandle`]), next to its
//! subdivision levels and streamlines. The handles' components are the one
//! place the design's tangents, parameters and details live at run time;
//! [`PatchKernel`] is derived from them (by [`super::track`] alone), as the
//! levels are.
//!
//! The value components compare bit for bit, so that `set_if_neq` writes (and
//! marks changed) exactly the values that differ, and an undo restores the
//! very bits it saved.

use crate::scene::files::format::ViewSpec;
use crate::scene::files::reference_link::ReferenceLink;
use bevy::prelude::*;
use std::collections::BTreeMap;
use streamline_kernel::finetune::SurfaceTuning;
use streamline_kernel::levels::multires::Details;
use streamline_kernel::{BlendOrder, DVec3, Design, Grid, SurfaceScheme};

/// The root entity of one streamline surface.
#[derive(Component, Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Patch;

/// Marks a patch that is built through the kernel's joins rather than the
/// incremental pipeline (every patch of a document but the first); the
/// first patch's systems skip it (`Without<Joined>`).
#[derive(Component, Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Joined;

/// Marks a net handle of a [`Joined`] patch, so that the first patch's
/// change tracking skips it.
#[derive(Component, Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct JoinedHandle;

/// The patch's display name (the scene's `name`).
#[derive(Component, Debug, Clone, PartialEq, Eq)]
pub struct PatchName(pub String);

/// What the levels' shapes follow: the net's size and row parameters `t`,
/// the scheme, the blend order, the depths, tangent interpolation and the
/// mirror. A change of it asks for a full build.
#[derive(Component, Debug, Clone, PartialEq)]
pub struct PatchStructure {
    /// Streamlines of the net.
    pub rows: usize,
    /// Control tangents per streamline.
    pub cols: usize,
    /// The row parameters `t` (one per streamline, Eq. 1).
    pub t: Vec<f64>,
    /// The tensor-product scheme.
    pub scheme: SurfaceScheme,
    /// Which direction is blended first.
    pub order: BlendOrder,
    /// Levels shown.
    pub display_depth: u32,
    /// Level of the handles.
    pub edit_depth: u32,
    /// Approximating schemes pass through the interior control tangents (docs/math.md §7).
    pub interpolate_tangents: bool,
    /// Mirror symmetry (docs/math.md §9).
    pub mirror: bool,
}

impl PatchStructure {
    /// The deepest level the patch needs.
    pub fn max_depth(&self) -> u32 {
        self.display_depth.max(self.edit_depth)
    }
}

/// Where the streamlines start: the anchor column (Eq. 2) and the initial
/// curve's QI order, arc length and start point (its control tangents are
/// [`InitialHandle`] children). A change places every streamline again
/// (Eq. 1) and re-blends no tangent.
#[derive(Component, Debug, Clone, Copy)]
pub struct PatchPlacement {
    /// The anchor column at level 0.
    pub anchor: usize,
    /// QI order of the initial curve.
    pub initial_order: usize,
    /// Arc length of the initial curve.
    pub initial_length: f64,
    /// Start point of the initial curve.
    pub initial_origin: DVec3,
}

impl PartialEq for PatchPlacement {
    fn eq(&self, o: &Self) -> bool {
        self.anchor == o.anchor
            && self.initial_order == o.initial_order
            && self.initial_length.to_bits() == o.initial_length.to_bits()
            && bits(self.initial_origin) == bits(o.initial_origin)
    }
}

/// Fine tuning (docs/math.md §6), `None` when off.
#[derive(Component, Debug, Clone, Default, PartialEq)]
pub struct PatchTuning(pub Option<SurfaceTuning>);

/// The camera the patch's scene opens with.
#[derive(Component, Debug, Clone, Copy, PartialEq)]
pub struct PatchView(pub ViewSpec);

/// The reference the design was fitted to or is measured against
/// (docs/math.md §12), `None` when there is none: the scene's, kept on the
/// first patch so that it is saved, snapshotted for undo and recovered with it.
#[derive(Component, Debug, Clone, Default, PartialEq, Eq)]
pub struct PatchReference(pub Option<ReferenceLink>);

/// A control tangent of the net: its cell (row = streamline, col = index
/// along it). Its values are [`Direction`] and [`ArcParam`].
#[derive(Component, Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct SurfaceHandle {
    /// Row (streamline).
    pub row: usize,
    /// Column (index along the streamline).
    pub col: usize,
}

/// A control tangent of the initial curve: its index. Its value is [`Direction`].
#[derive(Component, Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct InitialHandle {
    /// Index among the initial curve's control tangents.
    pub index: usize,
}

/// A multiresolution detail (docs/math.md §5): its level and cell. Its value
/// is [`DetailRotation`].
#[derive(Component, Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct DetailHandle {
    /// Subdivision level (≥ 1).
    pub level: u32,
    /// Row at that level.
    pub row: usize,
    /// Column at that level.
    pub col: usize,
}

impl DetailHandle {
    /// Its key in the kernel's [`Details`].
    pub fn key(self) -> (u32, usize, usize) {
        (self.level, self.row, self.col)
    }
}

/// A tangent handle's unit direction (a point of the Gaussian sphere).
#[derive(Component, Debug, Clone, Copy)]
pub struct Direction(pub DVec3);

/// A control tangent's arc-length parameter `s` along its streamline.
#[derive(Component, Debug, Clone, Copy)]
pub struct ArcParam(pub f64);

/// A detail's rotation: the detailed tangent in the local frame of the
/// subdivided one (docs/math.md §5, Eq. 40), a unit vector.
#[derive(Component, Debug, Clone, Copy)]
pub struct DetailRotation(pub DVec3);

fn bits(v: DVec3) -> [u64; 3] {
    v.to_array().map(f64::to_bits)
}

impl PartialEq for Direction {
    fn eq(&self, o: &Self) -> bool {
        bits(self.0) == bits(o.0)
    }
}

impl PartialEq for ArcParam {
    fn eq(&self, o: &Self) -> bool {
        self.0.to_bits() == o.0.to_bits()
    }
}

impl PartialEq for DetailRotation {
    fn eq(&self, o: &Self) -> bool {
        bits(self.0) == bits(o.0)
    }
}

/// The patch's handle entities by cell, written with them (spawned or
/// despawned): how the edit stage finds the entity of a cell.
#[derive(Component, Debug, Clone)]
pub struct PatchIndex {
    /// The net's handles, by cell.
    pub surface: Grid<Entity>,
    /// The initial curve's handles, by index.
    pub initial: Vec<Entity>,
    /// The details' handles, by key.
    pub details: BTreeMap<(u32, usize, usize), Entity>,
}

/// The kernel's input, derived from the handles and the patch's components
/// by [`super::track::track_handles`] (its only writer), as the levels are
/// derived from it: the design (net, parameters, scheme, anchor, initial
/// curve) and the details. Read it for kernel calls; edits write the handles.
#[derive(Component, Debug, Clone)]
pub struct PatchKernel {
    /// The design.
    pub design: Design,
    /// The details.
    pub details: Details,
}
