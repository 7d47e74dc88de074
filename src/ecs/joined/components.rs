//! The components of a design of several patches (docs/math.md §11;
//! docs/architecture.md, "Several patches"). Every patch entity of a
//! document carries its [`PatchSlot`] (its name and place in the document),
//! its [`PatchStart`] and its kernel-built [`PatchSurface`]; a patch that
//! starts on an edge also carries [`Joined`], its [`JoinedDesign`] (derived
//! from its handles), its [`JoinedFeatures`] and its [`SeamState`]. A one-patch design has none of
//! them, so today's pipeline sees exactly what it saw.

pub use crate::ecs::patch::{Joined, JoinedHandle};
use bevy::prelude::*;
use streamline_kernel::Design;
use streamline_kernel::joins::RowSpan;
use streamline_kernel::joins::{Continuity, Edge, SeamReport, Stack};

/// A patch's name in the document (`main` for a version-1 or -2 design)
/// and its index in the document's list (a patch starts on an earlier one).
#[derive(Component, Debug, Clone, PartialEq, Eq)]
pub struct PatchSlot {
    /// Unique in the document.
    pub name: String,
    /// Its place in the document's list.
    pub index: usize,
}

/// Where a patch starts (docs/math.md §11).
#[derive(Component, Debug, Clone, Copy, PartialEq, Eq)]
pub enum PatchStart {
    /// On its own initial curve.
    Curve,
    /// On an edge of an earlier patch.
    Edge {
        /// The patch entity it starts on (`A`).
        parent: Entity,
        /// The edge of `A`.
        edge: Edge,
        /// The continuity across it.
        continuity: Continuity,
    },
}

/// Whether patch `first` heads a G2 run: some patch among `starts` is
/// G2-chained on its `End` (docs/math.md §11.1). Its drawn surface is then
/// the run's cut of the merged net, not its own one-patch surface.
pub fn heads_g2_run<'a>(first: Entity, starts: impl IntoIterator<Item = &'a PatchStart>) -> bool {
    starts.into_iter().any(|s| {
        matches!(s, PatchStart::Edge { parent, edge: Edge::End, continuity: Continuity::G2 }
            if *parent == first)
    })
}

/// Whether patch `first` is drawn as its G2 run's cut: it heads a run
/// ([`heads_g2_run`]) and the run is built (`surface`, its
/// [`PatchSurface`]). Its own one-patch pipeline then waits (the blend
/// stage builds it afresh once it no longer heads a built run), and
/// whatever reads its surface reads the cut: the editor's drawing and
/// handles, a script's `Mark` and `Expect…`.
pub fn shows_run_cut<'a>(
    first: Entity,
    starts: impl IntoIterator<Item = &'a PatchStart>,
    surface: Option<&PatchSurface>,
) -> bool {
    heads_g2_run(first, starts) && surface.is_some_and(|s| s.stack().is_some())
}

/// A joined patch's kernel design, derived from its handles by
/// [`super::build::track_joined`] (its only writer after spawning).
#[derive(Component, Debug, Clone)]
pub struct JoinedDesign(pub Design);

/// What a later patch adds to its control net: its multiresolution details
/// (docs/math.md §5), its fine tuning (§6) and its tangent interpolation
/// (§7), written by the edit stage and read by [`super::build`]. (The
/// first patch keeps them as its handles and components,
/// [`crate::ecs::patch`].)
#[derive(Component, Debug, Clone, Default, PartialEq)]
pub struct JoinedFeatures {
    /// Details, by `(level, row, column)`, in the level's local frame.
    pub details: streamline_kernel::levels::multires::Details,
    /// Fine tuning, if on.
    pub tuning: Option<streamline_kernel::finetune::SurfaceTuning>,
    /// Progressive interpolation of the control tangents.
    pub interpolate_tangents: bool,
}

impl JoinedFeatures {
    /// A state's features.
    pub fn of(j: &crate::ecs::edit_state::JoinedState) -> Self {
        JoinedFeatures {
            details: j.details.clone(),
            tuning: j.tuning.clone(),
            interpolate_tangents: j.interpolate_tangents,
        }
    }
}

/// A patch built through the kernel's joins at the display depth: its
/// levels and points at every depth `0 ..= d` ([`Stack`]), or why it could
/// not be built (naming both patches and the fix). Written only when it
/// was rebuilt, so `Changed<PatchSurface>` means "moved".
#[derive(Component, Debug, Clone, Default)]
pub struct PatchSurface {
    /// The built stack, `Err` with a located message when the join failed.
    pub built: Option<Result<Stack, String>>,
    /// The unit vertex normals of the display depth's mesh, row-major, as
    /// [`streamline_kernel::streamline::surface_mesh::SurfaceMesh`] makes
    /// them from the stack's finest points (docs/math.md §4): written with
    /// `built`, read by the seam reports and by whatever draws the patch.
    pub normals: Vec<streamline_kernel::DVec3>,
    /// The rows of the finest points and normals that the last write
    /// changed (a rejoin's moved rows ± 1, whose normals read them), when
    /// the grid kept its shape; `None`: all of them (a whole build). What
    /// draws the patch may rewrite only these.
    pub rows: Option<RowSpan>,
    /// The rows of the finest points that the last write placed again
    /// (`None`: all of them, a whole build) and the first column placed
    /// again in them (the points before it kept their bits): what its
    /// streamline entities' [`crate::ecs::components::StreamlinePoints`]
    /// say ([`super::entities`]).
    pub placed: Option<RowSpan>,
    /// The first column of [`Self::placed`]'s rows placed again.
    pub placed_from: usize,
    /// Per depth `0 ..= d`, the rows of the level whose tangents or
    /// parameters the last write may have changed (`None` at a depth: none
    /// of them); `None`: any of them (a whole build).
    pub level_rows: Option<Vec<Option<RowSpan>>>,
}

impl PatchSurface {
    /// The stack, when built.
    pub fn stack(&self) -> Option<&Stack> {
        self.built.as_ref().and_then(|b| b.as_ref().ok())
    }
}

/// The seam report of a joined patch's join at the display depth
/// (docs/math.md §11, "Seam report"), updated when either side is rebuilt.
#[derive(Component, Debug, Clone, Default)]
pub struct SeamState {
    /// Largest gap, normal angle, curvature deviation; `None` while either
    /// side is not built.
    pub report: Option<SeamReport>,
}

/// The patch that edits of handles act on and whose handles the editor
/// shows and picks: `None` is the document's first patch. The editor sets
/// it when a patch is selected (its Patches section, or a click on a
/// surface); a script's `SetPatch` step sets it. Choosing a patch is not an
/// edit of the design, so it is not an undo step (as selection is not, in
/// Rhino or Alias).
#[derive(Resource, Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct ActivePatch(pub Option<Entity>);

/// Marks a patch the designer hid: its surface, seams and handles are not
/// drawn nor picked. Hiding is an undo step; it is not written to the file.
#[derive(Component, Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct PatchHidden;

/// The initial curve (its file form) of a later patch that starts on its
/// own curve rather than on an edge, kept to be saved as it was read.
#[derive(Component, Debug, Clone, PartialEq)]
pub struct PatchInitial(pub crate::scene::files::format::InitialSpec);
