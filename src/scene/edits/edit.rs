//! Edits: the only way the model changes. The editor, scripts and the
//! command line make the same [`Edit`]s; the ECS applies them
//! (`src/ecs/edit.rs`, wrapped in its `EditMessage`). A script step that edits
//! is an `Edit` written in RON by its variant's name, with the values in
//! their file form ([`crate::scene::files::format`]: directions, finite numbers, angles in
//! degrees, schemes), checked while they are read:
//!
//! ```ron
//! Rotate(row: 2, col: 4, axis: (0.0, 0.0, 1.0), degrees: 15.0)
//! ```
//!
//! Edits that only a running editor makes (cancelling a drag, replacing or
//! recovering a scene, files by absolute path) have no script form; a
//! script's `Load`, `Save` and `Export` name files relative to the script,
//! and its `SetTuning` gives a function checked when the step runs
//! ([`super::script::step::Step`]).

use super::patch_edit::PatchEdit;
use crate::scene::design::document::Document;
use crate::scene::design::model::Scene;
use crate::scene::files::format::{
    ConstraintSpec, Dir, Finite, OrderSpec, Point, SchemeSpec, TemplateSpec,
};
use serde::{Deserialize, Deserializer, Serialize, Serializer};
use std::path::PathBuf;
use streamline_kernel::authoring::{Axis, Template};
use streamline_kernel::finetune::{Constraint, SurfaceTuning};
use streamline_kernel::{BlendOrder, DVec3, SurfaceScheme};

/// One edit.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum Edit {
    /// Points handle `(row, col)` of the edit depth in `dir` (normalised).
    SetDirection {
        row: usize,
        col: usize,
        #[serde(with = "form::dir")]
        dir: DVec3,
    },
    /// Rotates handle `(row, col)` of the edit depth about `axis` by `radians`
    /// (`degrees` in a script).
    Rotate {
        row: usize,
        col: usize,
        #[serde(with = "form::dir")]
        axis: DVec3,
        #[serde(rename = "degrees", with = "form::degrees")]
        radians: f64,
    },
    /// Scales the `s` intervals on both sides of control tangent `(row, col)`.
    SetLength {
        row: usize,
        col: usize,
        #[serde(with = "form::finite")]
        coefficient: f64,
    },
    /// Removes the detail of handle `(row, col)` at the edit depth.
    ClearDetail { row: usize, col: usize },
    /// Scheme and ω.
    SetScheme(#[serde(with = "form::scheme")] SurfaceScheme),
    /// Blend order.
    SetBlendOrder(#[serde(with = "form::order")] BlendOrder),
    /// Levels shown.
    SetDisplayDepth(u32),
    /// Level of the handles.
    SetEditDepth(u32),
    /// Turns fine tuning on with this function and constraint, or off (docs/math.md §6).
    /// (A script's `SetTuning` step gives the function in its file form,
    /// checked when the step runs: [`super::script::step::Step::SetTuning`].)
    #[serde(skip)]
    SetTuning(Option<SurfaceTuning>),
    /// Sets fine-tuning control value `(row, col)` (row across the
    /// streamlines, column along them); turns fine tuning on (3×3 quadratic) if off.
    SetTuningValue {
        row: usize,
        col: usize,
        #[serde(with = "form::finite")]
        value: f64,
    },
    /// What fine-tuned streamlines keep; turns fine tuning on if off.
    SetTuningConstraint(#[serde(with = "form::constraint")] Constraint),
    /// Interpolate the control tangents (Catmull–Clark, Doo–Sabin) or not.
    SetInterpolateTangents(bool),
    /// Cancel a drag: restore the scene from before the first edit of `group`
    /// and forget that undo step (no redo). Esc during a drag sends it.
    #[serde(skip)]
    CancelGroup(u64),
    /// Undo the last edit.
    Undo,
    /// Redo the last undone edit.
    Redo,
    /// Open a scene file of any version (every patch of a version-3 file);
    /// on failure the current design stays.
    #[serde(skip)]
    Load(PathBuf),
    /// Replace the scene (new, built-in, recovered).
    #[serde(skip)]
    Replace(Box<Scene>),
    /// Reopen autosaved work: replace the design (every patch), remember
    /// the file it belongs to, and keep it marked unsaved.
    #[serde(skip)]
    Recover {
        /// The autosaved design.
        document: Box<Document>,
        /// The file it was edited from.
        origin: Option<PathBuf>,
    },
    /// Save the design to a file (atomic, verified): version 2 for one
    /// patch, version 3 for several.
    #[serde(skip)]
    Save(PathBuf),
    /// Export the surface: the mesh (`.obj`, `.stl`, `.glb`) or its fitted
    /// B-spline surface (`.step`/`.stp`, `.igs`/`.iges`), by the extension.
    #[serde(skip)]
    Export(PathBuf),
    /// Turns handles `(row, col)` of the edit depth by one rotation about
    /// `axis` (one undo step; refused whole if one handle is out of range).
    RotateMany {
        handles: Vec<(usize, usize)>,
        #[serde(with = "form::dir")]
        axis: DVec3,
        #[serde(rename = "degrees", with = "form::degrees")]
        radians: f64,
    },
    /// An authoring edit (`docs/math.md §9`): new design, structure, initial
    /// curve, anchor, streamline length, mirror. A script names its variant
    /// directly (`SetAnchor(3)`, not `Author(SetAnchor(3))`).
    #[serde(skip)]
    Author(AuthorEdit),
    /// An edit of the design's patches (docs/math.md §11): add, choose the
    /// one handle edits act on, remove, rename, hide. A script names its
    /// variant directly (`SetPatch("tail")`).
    #[serde(skip)]
    Patch(PatchEdit),
    /// File ▸ Import surface…: a design fitted to a reference, one undo
    /// step. `as_patch: false` makes `scene` the design (every patch
    /// replaced, its reference the imported face; the design has no file
    /// until saved); `true` adds its surface as a new patch of the current
    /// design on its own initial curve (joined to none), named after the
    /// scene, and keeps the design's reference (the imported face when it
    /// has none).
    #[serde(skip)]
    Import {
        /// The fitted scene (`scene::fit::reference::fitted_scene`).
        scene: Box<Scene>,
        /// Add it as a new patch instead of replacing the design.
        as_patch: bool,
    },
    /// Attaches a reference (File ▸ Reference…) or, with `None`, detaches
    /// it (one undo step).
    #[serde(skip)]
    SetReference(Option<crate::scene::files::reference_link::ReferenceLink>),
}

impl Edit {
    /// A short description for logs and stats.
    pub fn label(&self) -> String {
        match self {
            Edit::SetDirection { row, col, .. } => format!("set direction ({row}, {col})"),
            Edit::Rotate {
                row, col, radians, ..
            } => {
                format!("rotate ({row}, {col}) by {:.3}°", radians.to_degrees())
            }
            Edit::SetLength {
                row,
                col,
                coefficient,
            } => {
                format!("length coefficient {coefficient} at ({row}, {col})")
            }
            Edit::ClearDetail { row, col } => format!("clear detail ({row}, {col})"),
            Edit::SetScheme(s) => format!("scheme {}", s.name()),
            Edit::SetBlendOrder(o) => format!("blend order {}", o.name()),
            Edit::SetDisplayDepth(d) => format!("display depth {d}"),
            Edit::SetEditDepth(d) => format!("edit depth {d}"),
            Edit::SetTuning(Some(_)) => "fine tuning on".into(),
            Edit::SetTuning(None) => "fine tuning off".into(),
            Edit::SetTuningValue { row, col, value } => {
                format!("fine-tuning value ({row}, {col}) = {value}")
            }
            Edit::SetTuningConstraint(c) => format!("fine-tuning constraint {}", c.name()),
            Edit::SetInterpolateTangents(on) => format!("interpolate control tangents {on}"),
            Edit::CancelGroup(_) => "cancel drag".into(),
            Edit::Undo => "undo".into(),
            Edit::Redo => "redo".into(),
            Edit::Load(p) => format!("load {}", p.display()),
            Edit::Replace(s) => format!("open {}", s.name),
            Edit::Recover { document, .. } => format!("recover {}", document.name),
            Edit::Save(p) => format!("save {}", p.display()),
            Edit::Export(p) => format!("export {}", p.display()),
            Edit::RotateMany {
                handles, radians, ..
            } => format!(
                "rotate {} handles by {:.3}°",
                handles.len(),
                radians.to_degrees()
            ),
            Edit::Author(a) => a.label(),
            Edit::Patch(p) => p.label(),
            Edit::Import {
                scene,
                as_patch: false,
            } => format!("import {} as a new design", scene.name),
            Edit::Import {
                scene,
                as_patch: true,
            } => format!("import {} as a new patch", scene.name),
            Edit::SetReference(Some(r)) => {
                format!("reference {} face {}", r.path.display(), r.face)
            }
            Edit::SetReference(None) => "detach the reference".into(),
        }
    }

    /// Whether the edit changes the model (and so gets an undo step).
    pub fn is_undoable(&self) -> bool {
        if let Edit::Author(a) = self {
            return a.is_undoable();
        }
        if let Edit::Patch(p) = self {
            return p.is_undoable();
        }
        !matches!(
            self,
            Edit::Undo
                | Edit::CancelGroup(_)
                | Edit::Redo
                | Edit::Load(_)
                | Edit::Replace(_)
                | Edit::Recover { .. }
                | Edit::Save(_)
                | Edit::Export(_)
        )
    }
}

/// One authoring edit (the [`Edit::Author`] payload; applied by
/// `src/ecs/authoring.rs`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum AuthorEdit {
    /// A new, unsaved design from a template (the scheme defaults to Kobbelt).
    NewDesign {
        /// Control rows (2–64).
        rows: usize,
        /// Control columns (2–64).
        cols: usize,
        /// Streamline length.
        #[serde(with = "form::finite")]
        length: f64,
        /// Flat or Cylinder.
        #[serde(with = "form::template")]
        template: Template,
        /// The scheme.
        #[serde(default, with = "form::new_scheme")]
        scheme: SurfaceScheme,
    },
    /// A new control row (a streamline) that gets index `at` (0 ..= rows).
    InsertRow { at: usize },
    /// A new control column that gets index `at` (0 ..= columns).
    InsertColumn { at: usize },
    /// Deletes control row `i` (the net keeps at least 2).
    DeleteRow(usize),
    /// Deletes control column `j` (the net keeps at least 2).
    DeleteColumn(usize),
    /// Points the initial curve's control tangent `index` in `dir`.
    SetInitialDirection {
        index: usize,
        #[serde(with = "form::dir")]
        dir: DVec3,
    },
    /// Rotates the initial curve's control tangent `index` (`degrees` in a script).
    RotateInitial {
        index: usize,
        #[serde(with = "form::dir")]
        axis: DVec3,
        #[serde(rename = "degrees", with = "form::degrees")]
        radians: f64,
    },
    /// The initial curve's length.
    SetInitialLength(#[serde(with = "form::finite")] f64),
    /// The initial curve's start point.
    SetInitialOrigin(#[serde(with = "form::point")] DVec3),
    /// The initial curve's QI order.
    SetInitialOrder(usize),
    /// The anchor column.
    SetAnchor(usize),
    /// Control row `row`'s streamline length.
    SetStreamlineLength {
        row: usize,
        #[serde(with = "form::finite")]
        length: f64,
    },
    /// Mirror symmetry on or off.
    SetMirror(bool),
}

impl AuthorEdit {
    /// Inserts a row or column that gets index `at`.
    pub fn insert(axis: Axis, at: usize) -> Self {
        match axis {
            Axis::Row => AuthorEdit::InsertRow { at },
            Axis::Column => AuthorEdit::InsertColumn { at },
        }
    }

    /// Deletes row or column `at`.
    pub fn delete(axis: Axis, at: usize) -> Self {
        match axis {
            Axis::Row => AuthorEdit::DeleteRow(at),
            Axis::Column => AuthorEdit::DeleteColumn(at),
        }
    }

    /// For an insert or a delete: the axis and the index.
    pub fn structure(&self) -> Option<(Axis, usize)> {
        match *self {
            AuthorEdit::InsertRow { at } | AuthorEdit::DeleteRow(at) => Some((Axis::Row, at)),
            AuthorEdit::InsertColumn { at } | AuthorEdit::DeleteColumn(at) => {
                Some((Axis::Column, at))
            }
            _ => None,
        }
    }

    /// A short description.
    pub fn label(&self) -> String {
        match self {
            AuthorEdit::NewDesign {
                rows,
                cols,
                template,
                ..
            } => format!("new {rows} × {cols} design ({template:?})"),
            AuthorEdit::InsertRow { at } | AuthorEdit::InsertColumn { at } => {
                format!("insert {} {at}", self.axis_name())
            }
            AuthorEdit::DeleteRow(at) | AuthorEdit::DeleteColumn(at) => {
                format!("delete {} {at}", self.axis_name())
            }
            AuthorEdit::SetInitialDirection { index, .. } => {
                format!("initial tangent {index} direction")
            }
            AuthorEdit::RotateInitial { index, radians, .. } => {
                format!(
                    "rotate initial tangent {index} by {:.3}°",
                    radians.to_degrees()
                )
            }
            AuthorEdit::SetInitialLength(l) => format!("initial curve length {l}"),
            AuthorEdit::SetInitialOrigin(o) => {
                format!("initial curve origin ({}, {}, {})", o.x, o.y, o.z)
            }
            AuthorEdit::SetInitialOrder(k) => format!("initial curve order {k}"),
            AuthorEdit::SetAnchor(c) => format!("anchor column {c}"),
            AuthorEdit::SetStreamlineLength { row, length } => {
                format!("streamline {row} length {length}")
            }
            AuthorEdit::SetMirror(on) => format!("mirror {}", if *on { "on" } else { "off" }),
        }
    }

    /// `row` or `column` for a structure edit.
    fn axis_name(&self) -> &'static str {
        self.structure().map_or("", |(axis, _)| axis.name())
    }

    /// Whether it gets an undo step (a new design replaces the scene and its history).
    pub fn is_undoable(&self) -> bool {
        !matches!(self, AuthorEdit::NewDesign { .. })
    }
}

/// The file form of an edit's kernel values: each is read and written as a
/// type of [`crate::scene::files::format`], which checks it while it is read.
mod form {
    use super::*;

    /// `#[serde(with = "form::NAME")]` for a kernel type `K` written as the
    /// file-form type `F`, with `read: F → K` and `write: K → F`.
    macro_rules! form {
        ($name:ident: $k:ty as $f:ty, $read:expr, $write:expr) => {
            pub(super) mod $name {
                use super::*;
                pub fn serialize<S: Serializer>(k: &$k, s: S) -> Result<S::Ok, S::Error> {
                    let write: fn($k) -> $f = $write;
                    write(*k).serialize(s)
                }
                pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<$k, D::Error> {
                    let read: fn($f) -> $k = $read;
                    Ok(read(<$f>::deserialize(d)?))
                }
            }
        };
    }

    form!(dir: DVec3 as Dir, Dir::vec, Dir::from_vec);
    form!(point: DVec3 as Point, Point::vec, Point::from_vec);
    form!(finite: f64 as Finite, |f| f.0, Finite);
    form!(degrees: f64 as Finite, |d| d.0.to_radians(), degrees_of);
    form!(scheme: SurfaceScheme as SchemeSpec, SchemeSpec::to_kernel, SchemeSpec::from_kernel);
    // `None` is the default scheme (Kobbelt)
    form!(
        new_scheme: SurfaceScheme as Option<SchemeSpec>,
        |s| s.map_or_else(SurfaceScheme::default, SchemeSpec::to_kernel),
        |k| Some(SchemeSpec::from_kernel(k))
    );
    form!(order: BlendOrder as OrderSpec, OrderSpec::to_kernel, OrderSpec::from_kernel);
    form!(
        constraint: Constraint as ConstraintSpec,
        ConstraintSpec::to_kernel,
        ConstraintSpec::from_kernel
    );
    form!(template: Template as TemplateSpec, TemplateSpec::to_kernel, TemplateSpec::from_kernel);

    /// The degrees that read back as exactly `radians`: `to_degrees` or one
    /// of its nearest neighbours (one rounding each way may miss).
    fn degrees_of(radians: f64) -> Finite {
        let d = radians.to_degrees();
        let (mut lo, mut hi) = (d, d);
        for _ in 0..8 {
            for x in [lo, hi] {
                if x.is_finite() && x.to_radians() == radians {
                    return Finite(x);
                }
            }
            (lo, hi) = (lo.next_down(), hi.next_up());
        }
        Finite(d)
    }
}
