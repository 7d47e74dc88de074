//! A design of several patches (docs/math.md §11): the validated form of a
//! version-3 file, and of a version-1 or -2 file as one patch named `main`.
//! A document of one patch is today's [`Scene`] ([`Document::from_scene`],
//! [`Document::one_scene`]), so the rest of the program keeps working on
//! scenes; saving writes version 2 when there is one patch (byte for byte
//! what [`super::document_io::save_scene`] writes) and version 3 otherwise, atomically and verified.
//!
//! Reading, checking and saving are in [`super::document_io`] (checks
//! across patches in [`super::document_check`]); building the patches
//! through the kernel's joins is in [`super::document_build`].

use super::model::Scene;
use crate::scene::files::format::{InitialSpec, ViewSpec};
use crate::scene::files::format_v3::{
    DocumentFile, StartSpec, VERSION_PATCHES, Version3, patch_file_of, placeholder_initial,
};
use crate::scene::files::reference_link::ReferenceLink;
use std::path::Path;
use streamline_kernel::Design;
use streamline_kernel::finetune::SurfaceTuning;
use streamline_kernel::joins::Join;
use streamline_kernel::levels::multires::Details;

/// The name of the one patch of a version-1 or -2 design.
pub const MAIN_PATCH: &str = "main";

/// A validated design of one or more patches.
#[derive(Debug, Clone)]
pub struct Document {
    /// Display name.
    pub name: String,
    /// Levels shown.
    pub display_depth: u32,
    /// Level of the handles.
    pub edit_depth: u32,
    /// Mirror symmetry in the first patch's plane (docs/math.md §9, §11).
    pub mirror: bool,
    /// The camera.
    pub view: ViewSpec,
    /// The reference the whole design was fitted to or is measured against
    /// (docs/math.md §12), resolved against the folder of the file it was
    /// read from; `None` when there is none.
    pub reference: Option<ReferenceLink>,
    /// The patches; one that starts on an edge starts on an earlier one.
    pub patches: Vec<PatchScene>,
}

/// One patch: its name, where it starts, and what a [`Scene`] holds per surface.
#[derive(Debug, Clone)]
pub struct PatchScene {
    /// Unique in the document, `[A-Za-z0-9_-]{1,32}`.
    pub name: String,
    /// Its own initial curve, or an edge of an earlier patch.
    pub start: Start,
    /// Control net, parameters, scheme, blend order, anchor; for a patch
    /// that starts on an edge, a placeholder initial curve (never used to
    /// place it: the join gives its start points).
    pub design: Design,
    /// Multiresolution details.
    pub details: Details,
    /// Fine tuning, if on.
    pub tuning: Option<SurfaceTuning>,
    /// Progressive interpolation of the control tangents.
    pub interpolate_tangents: bool,
}

/// Where a patch starts (docs/math.md §11).
#[derive(Debug, Clone, PartialEq)]
pub enum Start {
    /// On its own initial curve, as written in the file.
    Curve(InitialSpec),
    /// On an edge of the earlier patch named `patch`.
    Edge {
        /// The patch it starts on.
        patch: String,
        /// The edge and the continuity across it.
        join: Join,
    },
}

impl Start {
    /// The file form.
    pub fn to_spec(&self) -> StartSpec {
        use crate::scene::files::format_v3::{ContinuitySpec, EdgeSpec};
        match self {
            Start::Curve(c) => StartSpec::curve(c),
            Start::Edge { patch, join } => StartSpec::Edge {
                patch: patch.clone(),
                edge: EdgeSpec::from_kernel(join.edge),
                continuity: ContinuitySpec::from_kernel(join.continuity),
            },
        }
    }

    /// From the file form.
    pub fn from_spec(s: &StartSpec) -> Self {
        match s {
            StartSpec::Curve { .. } => {
                Start::Curve(s.initial().expect("a curve start has a curve"))
            }
            StartSpec::Edge {
                patch,
                edge,
                continuity,
            } => Start::Edge {
                patch: patch.clone(),
                join: Join {
                    edge: edge.to_kernel(),
                    continuity: continuity.to_kernel(),
                },
            },
        }
    }
}

impl Document {
    /// A scene as a design of one patch named [`MAIN_PATCH`].
    pub fn from_scene(scene: Scene) -> Self {
        Document {
            name: scene.name,
            display_depth: scene.display_depth,
            edit_depth: scene.edit_depth,
            mirror: scene.mirror,
            view: scene.view,
            reference: scene.reference,
            patches: vec![PatchScene {
                name: MAIN_PATCH.to_string(),
                start: Start::Curve(scene.initial),
                design: scene.design,
                details: scene.details,
                tuning: scene.tuning,
                interpolate_tangents: scene.interpolate_tangents,
            }],
        }
    }

    /// The design as one scene, when it has exactly one patch (which then
    /// starts on its own curve).
    pub fn one_scene(&self) -> Option<Scene> {
        match self.patches.as_slice() {
            [p] if matches!(p.start, Start::Curve(_)) => Some(self.patch_scene(0)),
            _ => None,
        }
    }

    /// Patch `i` as a scene of its own (the design's depths, view and
    /// reference; the mirror for the first patch only; a placeholder initial
    /// curve for a patch that starts on an edge).
    pub fn patch_scene(&self, i: usize) -> Scene {
        let p = &self.patches[i];
        Scene {
            name: self.name.clone(),
            design: p.design.clone(),
            initial: match &p.start {
                Start::Curve(c) => c.clone(),
                Start::Edge { .. } => placeholder_initial(),
            },
            details: p.details.clone(),
            display_depth: self.display_depth,
            edit_depth: self.edit_depth,
            view: self.view,
            tuning: p.tuning.clone(),
            interpolate_tangents: p.interpolate_tangents,
            mirror: i == 0 && self.mirror,
            reference: self.reference.clone(),
        }
    }

    /// The index of the patch named `name`.
    pub fn index(&self, name: &str) -> Option<usize> {
        self.patches.iter().position(|p| p.name == name)
    }

    /// The patch that patch `i` starts on and the join, if it starts on an edge.
    pub fn parent(&self, i: usize) -> Option<(usize, Join)> {
        match &self.patches[i].start {
            Start::Curve(_) => None,
            Start::Edge { patch, join } => self.index(patch).map(|p| (p, *join)),
        }
    }

    /// The version-3 file form (whatever the number of patches), the
    /// reference's path as held ([`ReferenceLink::to_spec`]); a file saved
    /// elsewhere holds [`Document::to_file_at`].
    pub fn to_file(&self) -> DocumentFile {
        DocumentFile {
            version: Version3(VERSION_PATCHES),
            name: self.name.clone(),
            display_depth: self.display_depth,
            edit_depth: self.edit_depth,
            mirror: self.mirror,
            view: self.view,
            reference: self.reference.as_ref().map(ReferenceLink::to_spec),
            patches: (0..self.patches.len())
                .map(|i| {
                    let p = &self.patches[i];
                    patch_file_of(self.patch_scene(i).to_file(), &p.name, p.start.to_spec())
                })
                .collect(),
        }
    }

    /// The version-3 file form as saved to `file`: [`Document::to_file`]
    /// with the reference's path relative to `file`'s folder (docs/math.md
    /// §12, [`ReferenceLink::to_spec_for`]).
    pub fn to_file_at(&self, file: &Path) -> DocumentFile {
        DocumentFile {
            reference: (self.reference.as_ref()).map(|r| r.to_spec_for(file)),
            ..self.to_file()
        }
    }

    /// The text saved: version 2 for one patch (what [`Scene::to_ron`]
    /// writes), version 3 for several.
    pub fn to_ron(&self) -> String {
        match self.one_scene() {
            Some(scene) => scene.to_ron(),
            None => ron_text(&self.to_file()),
        }
    }

    /// The text saved to `file` ([`Document::to_ron`] with the reference's
    /// path relative to `file`'s folder, docs/math.md §12).
    pub fn to_ron_at(&self, file: &Path) -> String {
        match self.one_scene() {
            Some(scene) => scene.to_ron_at(file),
            None => ron_text(&self.to_file_at(file)),
        }
    }
}

/// The text of a version-3 file.
fn ron_text(f: &DocumentFile) -> String {
    let cfg = ron::ser::PrettyConfig::new()
        .depth_limit(4)
        .indentor("    ".to_string());
    ron::ser::to_string_pretty(f, cfg).expect("a document serialises")
}
