//! The deviation map of a design of several patches (docs/cad.md): each
//! patch's points at the display depth against its face of the STEP shell
//! that the export writes (`FaceFit::Shell`, seams held, docs/math.md §10,
//! §11), each point compared with its face at its parameters on that face
//! (`nurbs::face_rows`: a joined patch's rows are placed on its parent's
//! edge, as the shell's own), with `nurbs::deviation_field`. A one-patch
//! design keeps its own map (`super::surface::fit_scene`, the one face it
//! exports).

use super::document::{DocumentFitError, FaceFit, fit_document};
use crate::scene::design::document::Document;
use std::time::Instant;
use streamline_kernel::grid::Grid;
use streamline_kernel::nurbs::{Deviation, FitOptions, Samples, deviation_field, face_rows};

/// One patch's face and the distance of each of its shown points to it.
#[derive(Debug, Clone, PartialEq)]
pub struct PatchDeviation {
    /// The patch's name.
    pub name: String,
    /// The distance at every point of the patch at the display depth
    /// (rows × points, as its mesh).
    pub field: Grid<f64>,
    /// The face's largest and mean deviation, checked one depth finer than
    /// it was sampled at (as the export reports it).
    pub deviation: Deviation,
    /// The absolute tolerance the face meets.
    pub tolerance: f64,
    /// The face's poles along and across the streamlines.
    pub poles: (usize, usize),
}

/// The deviation map of every patch of a document.
#[derive(Debug, Clone, PartialEq)]
pub struct DocumentDeviation {
    /// The depth the shell was sampled at: the display depth, or deeper when
    /// the tolerance needed more points (the map still measures the points
    /// shown, as the one-patch map does).
    pub depth: u32,
    /// One per patch, in the document's order.
    pub patches: Vec<PatchDeviation>,
    /// Seconds the builds, the fit and the fields took.
    pub seconds: f64,
}

/// Fits `doc`'s shell as the STEP export does, sampled at `depth` (or
/// deeper, when the tolerance needs it), and measures every patch's points
/// at `depth` against its face.
pub fn document_deviation(
    doc: &Document,
    depth: u32,
    opts: &FitOptions,
) -> Result<DocumentDeviation, DocumentFitError> {
    let t0 = Instant::now();
    // the fit checks one depth finer: build that far once
    let built = doc.build(depth + 1).map_err(DocumentFitError::Build)?;
    let fit = fit_document(doc, &built, depth, opts, FaceFit::Shell)?;
    // every patch's points as shown, each with its own parameters first, in
    // the frame of the points its face was fitted to (nurbs::Samples::pair)
    let deeper;
    let at_fit = if fit.depth > depth + 1 {
        deeper = doc.build(fit.depth).map_err(DocumentFitError::Build)?;
        &deeper
    } else {
        &built
    };
    let shown: Vec<Samples> = (built.patches.iter().zip(&at_fit.patches).zip(&doc.patches))
        .map(|((stack, fitted), p)| {
            let d = depth as usize;
            let data = &fitted.levels[fit.depth as usize];
            let curve = p.design.scheme().curve();
            Samples::in_frame_of((&stack.levels[d], stack.points[d].clone()), data, curve)
        })
        .collect();
    let rows = face_rows(&shown, &fit.seams);
    let patches = (fit.faces.iter().zip(shown).zip(rows))
        .map(|((face, s), v)| PatchDeviation {
            name: face.name.clone(),
            field: deviation_field(&face.surface, &Samples { v, ..s }),
            deviation: face.deviation,
            tolerance: face.tolerance,
            poles: face.surface.pole_counts(),
        })
        .collect();
    Ok(DocumentDeviation {
        depth: fit.depth,
        patches,
        seconds: t0.elapsed().as_secs_f64(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::design::document_io::load;
    use std::path::Path;
    use streamline_kernel::nurbs::deviation;

    fn hood_screen_wing() -> Document {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/hood-screen-wing.ron");
        load(&path).unwrap()
    }

    /// Every patch gets a field shaped like its points at the display depth;
    /// at the depth the shell was fitted at, the rows it measures at are the
    /// faces' own (`face_rows` places them as `fit_shell` did, bit for bit),
    /// and each distance is the one between the point and its face at the
    /// point's parameters, evaluated here point by point (not through the
    /// field's table of basis functions).
    #[test]
    fn every_patch_is_measured_against_its_shell_face() {
        let doc = hood_screen_wing();
        let depth = 4;
        let built = doc.build(depth).unwrap();
        let d = document_deviation(&doc, depth, &FitOptions::default()).unwrap();
        assert_eq!(d.depth, depth);
        assert_eq!(d.patches.len(), doc.patches.len());
        let fit = fit_document(
            &doc,
            &doc.build(depth + 1).unwrap(),
            depth,
            &FitOptions::default(),
            FaceFit::Shell,
        )
        .unwrap();
        let grids: Vec<Samples> = fit.grids.iter().map(|g| g.data.clone()).collect();
        let rows = face_rows(&grids, &fit.seams);
        for (i, ((p, stack), face)) in d
            .patches
            .iter()
            .zip(&built.patches)
            .zip(&fit.faces)
            .enumerate()
        {
            let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            assert_eq!(bits(&rows[i]), bits(&face.v.0), "{}", p.name);
            let field = &p.field;
            let points = &stack.points[depth as usize];
            assert_eq!((field.rows(), field.cols()), (points.rows(), points.cols()));
            let u = &fit.grids[i].data.u;
            for (j, &v) in face.v.0.iter().enumerate() {
                for (k, &uk) in u.iter().enumerate() {
                    let want = (face.surface.eval(uk, v) - points.row(j)[k]).length();
                    let got = field.row(j)[k];
                    assert!((got - want).abs() <= 1e-12 * (1.0 + want), "{got} {want}");
                }
            }
            // (the tolerance holds at the check points one depth finer; a
            // shown point may lie a little beyond it, and the map says so)
            let largest = field.data().iter().copied().fold(0.0, f64::max);
            assert!(
                largest.is_finite() && largest < 10.0 * p.tolerance,
                "{largest}"
            );
            assert_eq!(p.deviation, face.deviation);
            assert!(p.poles.0 >= 4 && p.poles.1 >= 4, "{:?}", p.poles);
            // the field's points are the patch's own: measured alone they are the same
            let alone = deviation(
                &face.surface,
                &Samples {
                    points: points.clone(),
                    u: u.clone(),
                    v: face.v.0.clone(),
                },
            );
            assert_eq!(alone.max.to_bits(), largest.to_bits());
        }
    }

    /// A depth whose points cannot carry the tolerance is sampled deeper
    /// (hood-screen-wing at depth 1 needs depth 4); the map still measures
    /// the points shown, each patch's rows placed on its face at that depth.
    #[test]
    fn a_deeper_sampling_still_measures_the_points_shown() {
        let doc = hood_screen_wing();
        let shown = doc.build(1).unwrap();
        let d = document_deviation(&doc, 1, &FitOptions::default()).unwrap();
        assert_eq!(d.depth, 4);
        assert_eq!(d.patches.len(), 3);
        for (p, stack) in d.patches.iter().zip(&shown.patches) {
            let points = &stack.points[1];
            assert_eq!(
                (p.field.rows(), p.field.cols()),
                (points.rows(), points.cols())
            );
            assert!(p.field.data().iter().all(|d| d.is_finite() && *d >= 0.0));
            // the faces meet the tolerance at depth 4's points; depth 1's
            // coarse streamlines lie well off them (1.6e-3 to 2.6e-3, about
            // ten tolerances), which is what the map is for
            let largest = p.field.data().iter().copied().fold(0.0, f64::max);
            assert!(p.deviation.max <= p.tolerance);
            assert!(largest > 2.0 * p.tolerance, "{} {largest}", p.name);
        }
    }
}
