//! The scene's surface as a B-spline surface (docs/math.md §10):
//! the points of the scene at a depth, as the editor shows them (details,
//! fine tuning, interpolated tangents included, both halves of a mirrored
//! design as one surface, docs/math.md §9), with the parameters the kernel's
//! fit gives them, and the fit checked one depth finer: the one face of a
//! design of one patch, fitted as [`super::document`] fits every face.

use super::document::{DocumentFitError, FaceFit, fit_document};
use crate::scene::design::document::Document;
use crate::scene::design::document_build::BuiltDocument;
use crate::scene::design::model::Scene;
use streamline_kernel::KernelError;
use streamline_kernel::grid::Grid;
use streamline_kernel::joins::Stack;
use streamline_kernel::levels::incremental::{reference_levels, tuned_points};
use streamline_kernel::nurbs::{Fit, FitError, FitOptions, Samples, ShellError, deviation_field};

/// The scene's streamline points at `depth` with their fit parameters; a
/// mirrored scene's are the doubled design's (one surface over both halves).
pub fn samples(scene: &Scene, depth: u32) -> Result<Samples, FitError> {
    let design = scene.shown_design()?;
    let levels = reference_levels(&design, &scene.details, depth)?;
    let level = levels.last().expect("level 0 at least");
    let points = tuned_points(
        design.initial(),
        &level.tangents,
        &level.params,
        scene.tuning.as_ref(),
    );
    Samples::from_level(level, points)
}

/// A fit of a scene with its time.
#[derive(Debug, Clone)]
pub struct SceneFit {
    /// The surface and its figures.
    pub fit: Fit,
    /// Seconds the fit took (the builds at `depth` and `depth + 1` not counted).
    pub seconds: f64,
    /// The depth it was fitted at: the first from the requested one whose
    /// points were enough for the tolerance.
    pub depth: u32,
}

/// The scene as a design of one patch whose design is the one shown: its
/// [`Scene::shown_design`] (tangents interpolated, both halves of a mirror
/// as one net, docs/math.md §7, §9), the mirror then off. Its patch builds
/// the points of [`samples`].
pub fn shown_document(scene: &Scene) -> Result<Document, KernelError> {
    let mut shown = scene.clone();
    shown.design = scene.shown_design()?;
    shown.interpolate_tangents = false;
    shown.mirror = false;
    Ok(Document::from_scene(shown))
}

/// Fits the scene's surface within the options' tolerance, sampled at
/// `depth` (checked at `depth + 1`) or as much deeper as it needs: the
/// surface shown ([`shown_document`]) as a design of one patch, fitted by
/// [`fit_document`] as one face (module docs of [`super::document`];
/// the depth used is in [`SceneFit::depth`]). Only when even the deepest
/// grid is not enough is the fit refused ([`FitError::TooFewPointsAtDeepest`],
/// whose message says to loosen the tolerance).
pub fn fit_scene(scene: &Scene, depth: u32, opts: &FitOptions) -> Result<SceneFit, FitError> {
    let doc = shown_document(scene)?;
    // built here first, so that a refused build keeps the kernel's error
    let stack = Stack::build_parts(doc.patches[0].parts(&doc.patches[0].design), depth + 1)?;
    let built = BuiltDocument {
        depth: depth + 1,
        patches: vec![stack],
        seams: Vec::new(),
    };
    let mut f = fit_document(&doc, &built, depth, opts, FaceFit::Alone).map_err(|e| match e {
        DocumentFitError::Shell(ShellError::Fit { error, .. }) => error,
        e => FitError::BadSamples {
            problem: e.to_string(),
        },
    })?;
    let (face, report) = (f.faces.remove(0), f.reports.remove(0));
    Ok(SceneFit {
        fit: Fit {
            surface: face.surface,
            report,
        },
        seconds: f.seconds,
        depth: f.depth,
    })
}

/// The scene's fit at its display depth ([`fit_scene`], the face a
/// one-patch export writes) and the distance of each shown point to it
/// (the one-patch deviation map, docs/cad.md).
pub fn fit_shown(scene: &Scene, opts: &FitOptions) -> Result<(SceneFit, Grid<f64>), FitError> {
    let depth = scene.display_depth;
    let f = fit_scene(scene, depth, opts)?;
    let shown = samples(scene, depth)?;
    let field = deviation_field(&f.fit.surface, &shown);
    Ok((f, field))
}
