//! [`PatchRef`]: what a system reads of the patch.

use super::components::*;
use crate::scene::Scene;
use crate::scene::files::format::ViewSpec;
use crate::scene::files::reference_link::ReferenceLink;
use bevy::ecs::system::SystemParam;
use bevy::prelude::*;
use streamline_kernel::Design;
use streamline_kernel::finetune::SurfaceTuning;
use streamline_kernel::levels::multires::Details;

/// The patch's own components, read.
type PatchData = (
    Entity,
    &'static PatchName,
    Ref<'static, PatchStructure>,
    Ref<'static, PatchPlacement>,
    Ref<'static, PatchTuning>,
    &'static PatchView,
    &'static PatchReference,
    &'static PatchIndex,
    Ref<'static, PatchKernel>,
);

/// A handle's values, whichever kind it is.
type HandleValues = (
    Option<&'static Direction>,
    Option<&'static ArcParam>,
    Option<&'static DetailRotation>,
);

/// Any handle entity.
type AnyHandle = Or<(With<SurfaceHandle>, With<InitialHandle>, With<DetailHandle>)>;

/// The patch, read: its components, the derived kernel design, and its
/// scene assembled from the handles on demand. A system that takes it runs
/// only while the world has its patch.
#[derive(SystemParam)]
pub struct PatchRef<'w, 's> {
    patch: Single<'w, 's, PatchData, With<Patch>>,
    handles: Query<'w, 's, HandleValues, AnyHandle>,
}

impl PatchRef<'_, '_> {
    /// The patch entity.
    pub fn entity(&self) -> Entity {
        self.patch.0
    }

    /// Its name.
    pub fn name(&self) -> &str {
        &self.patch.1.0
    }

    /// Its structure (net size, scheme, depths, mirror).
    pub fn structure(&self) -> &PatchStructure {
        &self.patch.2
    }

    /// Whether the structure changed since the reading system last ran.
    pub fn structure_changed(&self) -> bool {
        self.patch.2.is_changed()
    }

    /// Its anchor and initial curve's order, length and origin.
    pub fn placement(&self) -> &PatchPlacement {
        &self.patch.3
    }

    /// Whether the placement changed since the reading system last ran.
    pub fn placement_changed(&self) -> bool {
        self.patch.3.is_changed()
    }

    /// Its fine tuning, if on.
    pub fn tuning(&self) -> Option<&SurfaceTuning> {
        self.patch.4.0.as_ref()
    }

    /// Whether the fine tuning changed since the reading system last ran.
    pub fn tuning_changed(&self) -> bool {
        self.patch.4.is_changed()
    }

    /// The camera its scene opens with.
    pub fn view(&self) -> ViewSpec {
        self.patch.5.0
    }

    /// The reference the design was fitted to or is measured against
    /// (docs/math.md §12), if any.
    pub fn reference(&self) -> Option<&ReferenceLink> {
        self.patch.6.0.as_ref()
    }

    /// Its handle entities by cell.
    pub fn index(&self) -> &PatchIndex {
        self.patch.7
    }

    /// The kernel's design, derived from the handles.
    pub fn design(&self) -> &Design {
        &self.patch.8.design
    }

    /// The details, derived from the detail handles.
    pub fn details(&self) -> &Details {
        &self.patch.8.details
    }

    /// Whether the derived design or details changed since the reading
    /// system last ran (some handle or patch component changed).
    pub fn design_changed(&self) -> bool {
        self.patch.8.is_changed()
    }

    /// The unit direction of handle `e` (of the net or the initial curve).
    pub fn direction(&self, e: Entity) -> Option<streamline_kernel::DVec3> {
        self.handles.get(e).ok().and_then(|x| x.0).map(|d| d.0)
    }

    /// The net's control tangents, read from its handle entities (row-major).
    pub fn net(&self) -> streamline_kernel::Grid<streamline_kernel::DVec3> {
        self.index()
            .surface
            .map(|e| self.direction(e).unwrap_or(streamline_kernel::DVec3::X))
    }

    /// The scene, assembled from the patch and its handles (to save,
    /// snapshot or export; a few microseconds for a 9 × 6 net).
    pub fn scene(&self) -> Result<Scene, String> {
        let p = &self.patch;
        super::scene_io::assemble_with(
            p.1,
            &p.2,
            &p.3,
            &p.4,
            p.5,
            p.6,
            p.7,
            Some(&p.8),
            |h| self.handles.get(h).ok().and_then(|x| x.0).map(|d| d.0),
            |h| self.handles.get(h).ok().and_then(|x| x.1).map(|a| a.0),
            |h| self.handles.get(h).ok().and_then(|x| x.2).map(|d| d.0),
        )
    }
}
