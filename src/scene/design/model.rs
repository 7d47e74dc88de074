//! A scene in memory: the kernel's [`Design`], its details, depths and view,
//! converted from and to a [`SceneFile`] with validation across fields.

use crate::scene::files::error::{SceneError, find_key};
use crate::scene::files::format::*;
use crate::scene::files::format_v3::{
    DocumentFile, patch_name_problem, placeholder_initial, scene_file_of,
};
use crate::scene::files::patch_text::PatchText;
use crate::scene::files::reference_link::{ReferenceLink, resolve_in};
use std::path::Path;
use streamline_kernel::finetune::SurfaceTuning;
use streamline_kernel::levels::incremental::check_params;
use streamline_kernel::levels::multires::Details;
use streamline_kernel::{BlendOrder, Design, Grid, KernelError, SurfaceScheme};

/// The most tangents the finest shown level of a new design gets
/// ([`Scene::new_design`] picks the display depth by it).
pub const NEW_DESIGN_TANGENTS: usize = 20_000;

/// A validated scene.
#[derive(Debug, Clone)]
pub struct Scene {
    /// Display name.
    pub name: String,
    /// Control net, parameters, scheme, blend order, anchor, initial curve.
    pub design: Design,
    /// The initial curve as written in the file.
    pub initial: InitialSpec,
    /// Multiresolution details.
    pub details: Details,
    /// Levels shown.
    pub display_depth: u32,
    /// Level of the handles.
    pub edit_depth: u32,
    /// The camera.
    pub view: ViewSpec,
    /// Fine tuning (docs/math.md §6), if on.
    pub tuning: Option<SurfaceTuning>,
    /// Make the approximating schemes pass through the interior control
    /// tangents at the limit (progressive interpolation on the sphere, docs/math.md §7).
    pub interpolate_tangents: bool,
    /// Mirror symmetry (`docs/math.md §9`): the design is the half `t ≥ t₀`
    /// of a surface symmetric about [`Design::mirror_plane`]; both halves are
    /// shown, analysed and exported ([`Scene::mirrored_design`]).
    pub mirror: bool,
    /// The reference the design was fitted to or is measured against
    /// (docs/math.md §12): the file, resolved against the folder of the scene
    /// file it was read from, and the face; `None` when there is none.
    pub reference: Option<ReferenceLink>,
}

impl Scene {
    /// A scene around a design, with default depths and view.
    pub fn from_design(name: &str, design: Design, display_depth: u32) -> Self {
        let initial = InitialSpec::from_kernel(design.initial());
        Scene {
            name: name.to_string(),
            design,
            initial,
            details: Details::new(),
            display_depth,
            edit_depth: 0,
            view: ViewSpec::default(),
            tuning: None,
            interpolate_tangents: false,
            mirror: false,
            reference: None,
        }
    }

    /// A new, unsaved design from a template (`docs/math.md §9`) with a
    /// display depth that keeps the finest level under
    /// [`NEW_DESIGN_TANGENTS`] tangents (at most 4), edit depth 0, and the
    /// camera framing it.
    pub fn new_design(
        rows: usize,
        cols: usize,
        length: f64,
        template: streamline_kernel::authoring::Template,
        scheme: SurfaceScheme,
    ) -> Result<Self, KernelError> {
        let design =
            Design::from_template(rows, cols, length, template, scheme, BlendOrder::SFirst)?;
        let mut depth = 0;
        while depth < 4
            && scheme
                .check_depth(rows, cols, depth + 1)
                .is_ok_and(|(r, c)| r * c <= NEW_DESIGN_TANGENTS)
        {
            depth += 1;
        }
        let mut scene = Scene::from_design("untitled", design, depth);
        scene.view = scene.framing_view()?;
        Ok(scene)
    }

    /// A view of the default angles that frames the surface at the display depth.
    pub fn framing_view(&self) -> Result<ViewSpec, KernelError> {
        let built = self.design.build(self.display_depth)?;
        let [lo, hi] = streamline_kernel::streamline::surface_mesh::bounds(
            built.mesh.positions.iter().copied(),
        );
        let centre = (lo + hi) * 0.5;
        let diag = (hi - lo).length().max(1e-3);
        Ok(ViewSpec {
            distance: Finite(1.7 * diag),
            target: Point::from_vec(centre),
            ..ViewSpec::default()
        })
    }

    /// The doubled design of a mirrored scene (`docs/math.md §9`), or `None`
    /// when the mirror is off; an error when a seam tangent lies along the
    /// plane's normal. Built from [`Scene::effective_design`].
    pub fn mirrored_design(&self) -> Option<Result<Design, KernelError>> {
        self.mirror.then(|| self.effective_design().mirrored())
    }

    /// Whether the control tangents are interpolated (the option is on and
    /// the scheme approximates: Catmull–Clark or Doo–Sabin).
    pub fn interpolates_tangents(&self) -> bool {
        interpolates(&self.design, self.interpolate_tangents)
    }

    /// The design the levels are built from: the designer's, or with
    /// [`Scene::interpolate_tangents`] the net whose limit passes through the
    /// designer's interior tangents (within 1e-12 rad).
    pub fn effective_design(&self) -> Design {
        effective_design(&self.design, self.interpolate_tangents)
    }

    /// The design the levels are built from: [`Scene::effective_design`],
    /// doubled when mirrored (`docs/math.md §9`).
    pub fn shown_design(&self) -> Result<Design, KernelError> {
        shown_design(&self.design, self.interpolate_tangents, self.mirror)
    }

    /// The deepest level the scene needs.
    pub fn max_depth(&self) -> u32 {
        self.display_depth.max(self.edit_depth)
    }

    /// Checks what crosses fields: depth cap, parameter increase at every
    /// level, details inside their level. `file`/`text` locate the errors.
    pub fn validate(&self, file: &Path, text: &str) -> Result<(), SceneError> {
        self.validate_at(file, &|key| find_key(text, key).unwrap_or((0, 0)))
    }

    /// [`Scene::validate`], with `place` giving the line and column of a
    /// field by its key (a version-3 file places them inside the patch).
    pub fn validate_at(
        &self,
        file: &Path,
        place: &dyn Fn(&str) -> (usize, usize),
    ) -> Result<(), SceneError> {
        let d = &self.design;
        let at = |key: &str, e: String| {
            let (line, col) = place(key);
            SceneError::at(file, line, col, e)
        };
        let depth = self.max_depth();
        if let Err(e) = d
            .scheme()
            .check_depth(d.net().rows(), d.net().cols(), depth)
        {
            let key = if self.display_depth >= self.edit_depth {
                "display_depth"
            } else {
                "edit_depth"
            };
            return Err(at(key, e.to_string()));
        }
        check_params(d, depth).map_err(|e| at("s", e.to_string()))?;
        if let Some(m) = self.mirrored_design() {
            let m = m.map_err(|e| at("mirror", e.to_string()))?;
            m.scheme()
                .check_depth(m.net().rows(), m.net().cols(), depth)
                .map_err(|e| at("mirror", format!("the mirrored surface: {e}")))?;
            check_params(&m, depth)
                .map_err(|e| at("mirror", format!("the mirrored surface: {e}")))?;
        }
        let mut shape = (d.net().rows(), d.net().cols());
        let c = d.scheme().curve();
        let mut shapes = vec![shape];
        for _ in 0..depth.max(self.details.keys().map(|k| k.0).max().unwrap_or(0)) {
            shape = (c.refined_len(shape.0), c.refined_len(shape.1));
            shapes.push(shape);
        }
        for &(level, row, col) in self.details.keys() {
            let ok = level >= 1
                && level <= depth.max(1)
                && shapes
                    .get(level as usize)
                    .is_some_and(|&(r, k)| row < r && col < k);
            if !ok {
                return Err(at(
                    "details",
                    format!(
                        "detail at level {level}, row {row}, column {col} is outside the levels 1..={} of this scene; remove it or raise the edit depth",
                        depth
                    ),
                ));
            }
        }
        Ok(())
    }

    /// From a file's contents, with every error located.
    pub fn from_file(f: SceneFile, file: &Path, text: &str) -> Result<Self, SceneError> {
        Scene::from_file_at(f, file, &|key| find_key(text, key).unwrap_or((0, 0)))
    }

    /// [`Scene::from_file`], with `place` giving the line and column of a
    /// field by its key.
    pub fn from_file_at(
        f: SceneFile,
        file: &Path,
        place: &dyn Fn(&str) -> (usize, usize),
    ) -> Result<Self, SceneError> {
        let at = |key: &str, e: String| {
            let (line, col) = place(key);
            SceneError::at(file, line, col, e)
        };
        let rows = f.tangents.len();
        if rows < 2 {
            return Err(at(
                "tangents",
                format!(
                    "the control net has {rows} rows; a surface needs at least 2 rows of at least 2 tangents"
                ),
            ));
        }
        let cols = f.tangents[0].len();
        for (r, row) in f.tangents.iter().enumerate() {
            if row.len() != cols || cols < 2 {
                return Err(at(
                    "tangents",
                    format!(
                        "row {r} of tangents has {} entries but row 0 has {cols}; every row needs the same number, at least 2",
                        row.len()
                    ),
                ));
            }
        }
        if f.s.len() != rows || f.s.iter().any(|r| r.0.len() != cols) {
            let bad =
                f.s.iter()
                    .position(|r| r.0.len() != cols)
                    .unwrap_or(f.s.len());
            return Err(at(
                "s",
                format!(
                    "s must have the shape of tangents ({rows} rows of {cols}); row {bad} differs or is missing"
                ),
            ));
        }
        if f.t.len() != rows {
            return Err(at(
                "t",
                format!(
                    "t has {} entries but there are {rows} rows; give one t per row",
                    f.t.len()
                ),
            ));
        }
        if f.anchor >= cols {
            return Err(at(
                "anchor",
                format!(
                    "anchor column {} is out of range; use 0 to {}",
                    f.anchor,
                    cols - 1
                ),
            ));
        }
        let initial = f
            .initial
            .to_kernel()
            .map_err(|e| at("initial", e.to_string()))?;
        let net = Grid::new(
            rows,
            cols,
            f.tangents.iter().flatten().map(|d| d.vec()).collect(),
        )
        .map_err(|e| at("tangents", e.to_string()))?;
        let s = Grid::new(
            rows,
            cols,
            f.s.iter().flat_map(|r| r.0.iter().copied()).collect(),
        )
        .map_err(|e| at("s", e.to_string()))?;
        let design = Design::new(
            &net,
            s,
            f.t.iter().map(|t| t.0).collect(),
            f.anchor,
            f.scheme.to_kernel(),
            f.blend_order.to_kernel(),
            initial,
        )
        .map_err(|e| at("tangents", e.to_string()))?;
        let mut details = Details::new();
        for d in &f.details {
            let v = streamline_kernel::Tangent::new(d.local.vec())
                .map_err(|_| {
                    at(
                        "details",
                        "a detail's local direction is zero; remove the detail".into(),
                    )
                })?
                .get();
            if details.insert((d.level, d.row, d.col), v).is_some() {
                return Err(at(
                    "details",
                    format!(
                        "two details at level {}, row {}, column {}; keep one",
                        d.level, d.row, d.col
                    ),
                ));
            }
        }
        let tuning = match &f.tuning {
            None => None,
            Some(t) => Some(t.to_kernel().map_err(|e| at("tuning", e))?),
        };
        if f.version.0 < 2 && f.mirror {
            return Err(at(
                "mirror",
                "mirror symmetry is a version 2 field; write `version: 2`".into(),
            ));
        }
        let reference = resolve_in(f.reference.as_ref(), file, || place("reference"))?;
        let scene = Scene {
            name: f.name,
            design,
            initial: f.initial,
            details,
            display_depth: f.display_depth,
            edit_depth: f.edit_depth,
            view: f.view,
            tuning,
            interpolate_tangents: f.interpolate_tangents,
            mirror: f.mirror,
            reference,
        };
        scene.validate_at(file, place)?;
        Ok(scene)
    }

    /// The file form, the reference's path as held (relative to the working
    /// folder, or absolute: [`ReferenceLink::to_spec`]); a file saved
    /// elsewhere holds [`Scene::to_file_at`].
    pub fn to_file(&self) -> SceneFile {
        let d = &self.design;
        SceneFile {
            version: Version(VERSION),
            name: self.name.clone(),
            tangents: (0..d.net().rows())
                .map(|r| d.net().row(r).iter().map(|&v| Dir::from_vec(v)).collect())
                .collect(),
            s: (0..d.params().s.rows())
                .map(|r| SRow(d.params().s.row(r).to_vec()))
                .collect(),
            t: d.params().t.iter().map(|&t| Finite(t)).collect(),
            anchor: d.anchor(),
            initial: self.initial.clone(),
            scheme: SchemeSpec::from_kernel(d.scheme()),
            blend_order: OrderSpec::from_kernel(d.order()),
            display_depth: self.display_depth,
            edit_depth: self.edit_depth,
            details: self
                .details
                .iter()
                .map(|(&(level, row, col), &v)| DetailSpec {
                    level,
                    row,
                    col,
                    local: Dir::from_vec(v),
                })
                .collect(),
            view: self.view,
            tuning: self.tuning.as_ref().map(TuningSpec::from_kernel),
            interpolate_tangents: self.interpolate_tangents,
            mirror: self.mirror,
            reference: self.reference.as_ref().map(ReferenceLink::to_spec),
        }
    }

    /// The file form as saved to `file`: [`Scene::to_file`] with the
    /// reference's path relative to `file`'s folder (docs/math.md §12,
    /// [`ReferenceLink::to_spec_for`]).
    pub fn to_file_at(&self, file: &Path) -> SceneFile {
        SceneFile {
            reference: (self.reference.as_ref()).map(|r| r.to_spec_for(file)),
            ..self.to_file()
        }
    }

    /// Patch `i` of a version-3 file as a scene of its own: the design's
    /// depths and view, the mirror for the first patch only (its plane is
    /// the design's, docs/math.md §11), and for a patch that starts on an
    /// edge a placeholder initial curve ([`placeholder_initial`]: the join
    /// gives its start points). Errors are placed inside the patch and name it.
    pub fn from_patch(
        f: &DocumentFile,
        i: usize,
        file: &Path,
        place: &PatchText,
    ) -> Result<Self, SceneError> {
        let patch = &f.patches[i];
        let name_err = patch_name_problem(&patch.name);
        let named = |e: SceneError| SceneError {
            message: format!("patch `{}`: {}", patch.name, e.message),
            ..e
        };
        if let Some(m) = name_err {
            let (line, col) = place.in_patch(i, "name");
            return Err(SceneError::at(file, line, col, m));
        }
        let initial = patch.initial.initial().unwrap_or_else(placeholder_initial);
        let sf = scene_file_of(f, i, initial);
        Scene::from_file_at(sf, file, &|key| place.in_patch(i, key)).map_err(named)
    }

    /// RON text of this scene ([`Scene::to_file`]).
    pub fn to_ron(&self) -> String {
        ron_text(&self.to_file())
    }

    /// RON text of this scene as saved to `file` ([`Scene::to_file_at`]: the
    /// reference's path relative to `file`'s folder).
    pub fn to_ron_at(&self, file: &Path) -> String {
        ron_text(&self.to_file_at(file))
    }
}

/// The text of a version-2 file.
fn ron_text(f: &SceneFile) -> String {
    let cfg = ron::ser::PrettyConfig::new()
        .depth_limit(2)
        .indentor("    ".to_string());
    ron::ser::to_string_pretty(f, cfg).expect("scene serialises")
}

/// Whether `design`'s control tangents are interpolated: `interpolate` is on
/// and the scheme approximates (Catmull–Clark or Doo–Sabin, docs/math.md §7).
pub fn interpolates(design: &Design, interpolate: bool) -> bool {
    interpolate && streamline_kernel::levels::tangent_interpolation::applies(design.scheme())
}

/// The design the levels are built from: `design`, or when it
/// [`interpolates`] the net whose limit passes through its interior tangents
/// (within 1e-12 rad, docs/math.md §7).
pub fn effective_design(design: &Design, interpolate: bool) -> Design {
    let mut d = design.clone();
    if interpolates(design, interpolate) {
        let net = streamline_kernel::levels::tangent_interpolation::interpolate_net(
            d.scheme(),
            d.order(),
            design.net(),
            1e-12,
            2000,
        )
        .net;
        d.set_net(&net)
            .expect("the interpolated net has the design's shape, and unit tangents");
    }
    d
}

/// [`effective_design`], doubled when `mirror` is on (`docs/math.md §9`).
pub fn shown_design(
    design: &Design,
    interpolate: bool,
    mirror: bool,
) -> Result<Design, KernelError> {
    let d = effective_design(design, interpolate);
    if mirror { d.mirrored() } else { Ok(d) }
}
