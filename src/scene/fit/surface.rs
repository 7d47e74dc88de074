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
use streamline_kernel::nurbs::{Fit, FitError, FitOptions, Samples, ShellError, deviation_field};

/// The scene's streamline points at `depth` with their fit parameters; a
/// mirrored scene's are the doubled design's (one surface over both halves).
/// Built as every patch is, by [`Stack::build_parts`] of
/// [`shown_document`]'s one patch (its details and fine tuning included),
/// so they are the points [`fit_scene`] fits, bit for bit.
pub fn samples(scene: &Scene, depth: u32) -> Result<Samples, FitError> {
    let doc = shown_document(scene)?;
    let patch = &doc.patches[0];
    let mut stack = Stack::build_parts(patch.parts(&patch.design), depth)?;
    let d = depth as usize;
    let points = std::mem::replace(&mut stack.points[d], Grid::filled(0, 0, Default::default()));
    Samples::from_level(&stack.levels[d], points)
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
    // the points shown, in the frame of the points the face was fitted to
    let doc = shown_document(scene)?;
    let patch = &doc.patches[0];
    let mut stack = Stack::build_parts(patch.parts(&patch.design), f.depth)?;
    let d = depth as usize;
    let points = std::mem::replace(&mut stack.points[d], Grid::filled(0, 0, Default::default()));
    let curve = patch.design.scheme().curve();
    let shown = Samples::in_frame_of(
        (&stack.levels[d], points),
        &stack.levels[f.depth as usize],
        curve,
    );
    let field = deviation_field(&f.fit.surface, &shown);
    Ok((f, field))
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;
    use std::path::Path;
    use streamline_kernel::levels::incremental::{reference_levels, tuned_points};

    /// The points the one-patch pipeline shows, made independently of the
    /// stack: the kernel's reference levels and tuned points of the shown
    /// design (docs/math.md §5, §6).
    fn pipeline_points(scene: &Scene, depth: u32) -> Grid<DVec3> {
        let design = scene.shown_design().unwrap();
        let levels = reference_levels(&design, &scene.details, depth).unwrap();
        let level = levels.last().unwrap();
        let tuning = scene.tuning.as_ref();
        tuned_points(design.initial(), &level.tangents, &level.params, tuning)
    }

    /// The samples are the pipeline's points bit for bit, with details,
    /// fine tuning, interpolated tangents and a mirror, at depths 0–4;
    /// negative control: without the detail they differ.
    #[test]
    fn the_samples_are_the_pipeline_s_points() {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/car1-tuned.ron");
        let text = std::fs::read_to_string(&path).unwrap();
        let mut scene = Scene::parse(&text, &path).unwrap();
        assert!(scene.tuning.is_some());
        scene
            .details
            .insert((1, 2, 3), DVec3::new(0.2, -0.1, 1.0).normalize());
        for (mirror, interpolate) in [(false, false), (true, false), (false, true), (true, true)] {
            scene.mirror = mirror;
            scene.interpolate_tangents = interpolate;
            for depth in 0..=4 {
                let got = samples(&scene, depth).unwrap().points;
                let want = pipeline_points(&scene, depth);
                assert_eq!((got.rows(), got.cols()), (want.rows(), want.cols()));
                let same = (got.data().iter().zip(want.data()))
                    .all(|(a, b)| a.to_array().map(f64::to_bits) == b.to_array().map(f64::to_bits));
                assert!(
                    same,
                    "mirror {mirror}, interpolated {interpolate}, depth {depth}"
                );
            }
        }
        let mut plain = scene.clone();
        plain.details = Default::default();
        let (a, b) = (
            samples(&plain, 2).unwrap().points,
            pipeline_points(&scene, 2),
        );
        assert!(a.data().iter().zip(b.data()).any(|(p, q)| p != q));
    }
}
