//! The whole document as values (docs/architecture.md, "Undo of
//! documents"): the first patch's [`Scene`] and, for each later patch, its
//! name, where it starts (by the index of the patch it starts on, since
//! entity ids change when a patch is spawned again), its design, details,
//! fine tuning and tangent interpolation, and whether it is hidden. The edit stage assembles it from the world, applies a
//! frame's edits to it, and writes back only what differs
//! ([`super::joined::world_io`]); undo stores it ([`super::History`]). A
//! one-patch design's state is its scene and nothing else. (It imports
//! nothing of the ECS, so the resources and the patches may both use it.)

use crate::scene::Scene;
use crate::scene::design::document::{Document, MAIN_PATCH, PatchScene, Start};
use crate::scene::files::format::InitialSpec;
use streamline_kernel::Design;
use streamline_kernel::finetune::SurfaceTuning;
use streamline_kernel::joins::{Continuity, Edge, Join};
use streamline_kernel::levels::multires::Details;

/// Where a later patch starts, by document index.
#[derive(Debug, Clone, PartialEq)]
pub enum StartState {
    /// On its own initial curve (its file form).
    Curve(InitialSpec),
    /// On an edge of the earlier patch at this index.
    Edge {
        /// The document index of the patch it starts on (`A`).
        parent: usize,
        /// The edge of `A`.
        edge: Edge,
        /// The continuity across it.
        continuity: Continuity,
    },
}

/// A patch after the first.
#[derive(Debug, Clone)]
pub struct JoinedState {
    /// Unique in the document.
    pub name: String,
    /// Where it starts.
    pub start: StartState,
    /// Its control net, parameters, scheme.
    pub design: Design,
    /// Its multiresolution details (docs/math.md §5).
    pub details: Details,
    /// Its fine tuning, if on (docs/math.md §6).
    pub tuning: Option<SurfaceTuning>,
    /// Progressive interpolation of its control tangents (docs/math.md §7).
    pub interpolate_tangents: bool,
    /// Hidden by the designer (`PatchHidden`).
    pub hidden: bool,
}

/// The document: what undo stores and the edit stage edits.
#[derive(Debug, Clone)]
pub struct DocState {
    /// The first patch as a scene (also the document's name, depths, view, mirror).
    pub first: Scene,
    /// The first patch's name ([`MAIN_PATCH`] until renamed).
    pub first_name: String,
    /// Whether the first patch is hidden.
    pub first_hidden: bool,
    /// The later patches, in the document's order (each starts on an earlier one).
    pub joined: Vec<JoinedState>,
}

impl DocState {
    /// A one-patch design: `scene`, named [`MAIN_PATCH`], shown.
    pub fn of_scene(scene: Scene) -> Self {
        DocState {
            first: scene,
            first_name: MAIN_PATCH.to_string(),
            first_hidden: false,
            joined: Vec::new(),
        }
    }

    /// A document's state, every patch shown.
    pub fn of_document(doc: &Document) -> Self {
        let joined = (1..doc.patches.len())
            .map(|i| {
                let p = &doc.patches[i];
                JoinedState {
                    name: p.name.clone(),
                    start: match (&p.start, doc.parent(i)) {
                        (_, Some((a, join))) => StartState::Edge {
                            parent: a,
                            edge: join.edge,
                            continuity: join.continuity,
                        },
                        (Start::Curve(c), None) => StartState::Curve(c.clone()),
                        (Start::Edge { .. }, None) => {
                            StartState::Curve(crate::scene::files::format_v3::placeholder_initial())
                        }
                    },
                    design: p.design.clone(),
                    details: p.details.clone(),
                    tuning: p.tuning.clone(),
                    interpolate_tangents: p.interpolate_tangents,
                    hidden: false,
                }
            })
            .collect();
        DocState {
            first: doc.patch_scene(0),
            first_name: doc.patches[0].name.clone(),
            first_hidden: false,
            joined,
        }
    }

    /// The number of patches.
    pub fn len(&self) -> usize {
        1 + self.joined.len()
    }

    /// Always at least the first patch.
    pub fn is_empty(&self) -> bool {
        false
    }

    /// Patch `i`'s name.
    pub fn name(&self, i: usize) -> &str {
        match i {
            0 => &self.first_name,
            _ => &self.joined[i - 1].name,
        }
    }

    /// The index of the patch named `name`.
    pub fn index(&self, name: &str) -> Option<usize> {
        (0..self.len()).find(|&i| self.name(i) == name)
    }

    /// Patch `i`'s design.
    pub fn design(&self, i: usize) -> &Design {
        match i {
            0 => &self.first.design,
            _ => &self.joined[i - 1].design,
        }
    }

    /// Whether patch `i` is hidden.
    pub fn hidden(&self, i: usize) -> bool {
        match i {
            0 => self.first_hidden,
            _ => self.joined[i - 1].hidden,
        }
    }

    /// The patches that start on patch `i`, by index.
    pub fn children(&self, i: usize) -> Vec<usize> {
        (1..self.len())
            .filter(|&k| matches!(self.joined[k - 1].start, StartState::Edge { parent, .. } if parent == i))
            .collect()
    }

    /// Makes every G1 or G2 chain's seam column its parent's last column
    /// (one handle of both, docs/math.md §11.1: the build reads it from the
    /// parent, and the file must say so to be read back). Only the cells
    /// that differ are written.
    pub fn sync_seams(&mut self) {
        for k in 0..self.joined.len() {
            let StartState::Edge {
                parent,
                edge: Edge::End,
                continuity,
            } = self.joined[k].start
            else {
                continue;
            };
            if continuity == Continuity::G0 || parent > k {
                continue;
            }
            let a = self.design(parent);
            let last = a.net().cols() - 1;
            let col: Vec<_> = (0..a.net().rows()).map(|r| a.net().get(r, last)).collect();
            let b = &mut self.joined[k].design;
            for (r, v) in col.into_iter().enumerate().take(b.net().rows()) {
                if b.net().get(r, 0) != v {
                    let _ = b.set_tangent(r, 0, v);
                }
            }
        }
    }

    /// `` `a`, `b`, … `` for messages.
    pub fn listed(&self) -> String {
        (0..self.len())
            .map(|i| format!("`{}`", self.name(i)))
            .collect::<Vec<_>>()
            .join(", ")
    }

    /// The document (what is saved, exported, built): the first patch's
    /// scene as patch 0 (a one-patch state gives exactly
    /// [`Document::from_scene`] of it, named as the state names it).
    pub fn to_document(&self) -> Document {
        let mut doc = Document::from_scene(self.first.clone());
        doc.patches[0].name.clone_from(&self.first_name);
        for j in &self.joined {
            let start = match &j.start {
                StartState::Curve(c) => Start::Curve(c.clone()),
                StartState::Edge {
                    parent,
                    edge,
                    continuity,
                } => Start::Edge {
                    patch: self.name(*parent).to_string(),
                    join: Join {
                        edge: *edge,
                        continuity: *continuity,
                    },
                },
            };
            doc.patches.push(PatchScene {
                name: j.name.clone(),
                start,
                design: j.design.clone(),
                details: j.details.clone(),
                tuning: j.tuning.clone(),
                interpolate_tangents: j.interpolate_tangents,
            });
        }
        doc
    }

    /// Bit for bit the same document (scenes compared in their file form,
    /// designs bit for bit), names, starts and hidden flags included.
    pub fn same(&self, other: &DocState) -> bool {
        self.first.to_file() == other.first.to_file()
            && same_design(&self.first.design, &other.first.design)
            && same_details(&self.first.details, &other.first.details)
            && self.first_name == other.first_name
            && self.first_hidden == other.first_hidden
            && self.joined.len() == other.joined.len()
            && (self.joined.iter().zip(&other.joined)).all(|(a, b)| {
                a.name == b.name
                    && a.start == b.start
                    && a.hidden == b.hidden
                    && same_design(&a.design, &b.design)
                    && same_details(&a.details, &b.details)
                    && a.tuning == b.tuning
                    && a.interpolate_tangents == b.interpolate_tangents
            })
    }
}

/// The same details, bit for bit.
fn same_details(a: &Details, b: &Details) -> bool {
    a.len() == b.len()
        && (a.iter().zip(b)).all(|((ka, va), (kb, vb))| ka == kb && bits(*va) == bits(*vb))
}

fn bits(v: streamline_kernel::DVec3) -> [u64; 3] {
    v.to_array().map(f64::to_bits)
}

/// Two designs equal bit for bit: net, parameters, scheme, blend order,
/// anchor and initial curve.
pub fn same_design(a: &Design, b: &Design) -> bool {
    let f = |x: &[f64], y: &[f64]| {
        x.len() == y.len() && x.iter().zip(y).all(|(p, q)| p.to_bits() == q.to_bits())
    };
    let (ca, cb) = (a.initial(), b.initial());
    a.net().rows() == b.net().rows()
        && a.net().cols() == b.net().cols()
        && (a.net().data().iter().zip(b.net().data())).all(|(p, q)| bits(*p) == bits(*q))
        && f(a.params().s.data(), b.params().s.data())
        && f(&a.params().t, &b.params().t)
        && a.scheme() == b.scheme()
        && a.order() == b.order()
        && a.anchor() == b.anchor()
        && ca.qi().order() == cb.qi().order()
        && ca.length().to_bits() == cb.length().to_bits()
        && bits(ca.origin()) == bits(cb.origin())
        && ca.qi().tangents().len() == cb.qi().tangents().len()
        && (ca.qi().tangents().iter().zip(cb.qi().tangents())).all(|(p, q)| bits(*p) == bits(*q))
}
