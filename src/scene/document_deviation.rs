//! The deviation map of a design of several patches (docs/cad.md): each
//! patch's points at the display depth against its face of the STEP shell
//! that the export writes (`FaceFit::Shell`, seams held, docs/math.md §10,
//! §11), each point compared with its face at the parameters the face was
//! fitted with (`nurbs::deviation_field`). A one-patch design keeps its own
//! map (`super::cad::fit_scene`, the one face it exports).

use super::document::Document;
use super::document_fit::{DocumentFitError, FaceFit, fit_document};
use std::time::Instant;
use streamline_kernel::grid::Grid;
use streamline_kernel::nurbs::{Deviation, FitOptions, Samples, deviation_field};

/// One patch's face and the distance of each of its shown points to it.
#[derive(Debug, Clone, PartialEq)]
pub struct PatchDeviation {
    /// The patch's name.
    pub name: String,
    /// The distance at every point of the patch at the display depth
    /// (rows × points, as its mesh), or `None` when the shell had to be
    /// sampled deeper than that ([`DocumentDeviation::depth`]): the face's
    /// parameters are then those of the deeper points.
    pub field: Option<Grid<f64>>,
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
    /// the tolerance needed more points (then no patch has a field).
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
    let patches = (fit.faces.iter().zip(&fit.grids))
        .map(|(face, grid)| {
            // the face's own parameters: a joined patch's rows are its parent's
            let shown = Samples {
                points: grid.data.points.clone(),
                u: grid.data.u.clone(),
                v: face.v.0.clone(),
            };
            PatchDeviation {
                name: face.name.clone(),
                field: (fit.depth == depth).then(|| deviation_field(&face.surface, &shown)),
                deviation: face.deviation,
                tolerance: face.tolerance,
                poles: face.surface.pole_counts(),
            }
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
    use crate::scene::document_io::load;
    use std::path::Path;
    use streamline_kernel::nurbs::deviation;

    fn hood_screen_wing() -> Document {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/hood-screen-wing.ron");
        load(&path).unwrap()
    }

    /// Every patch gets a field shaped like its points at the display depth;
    /// each distance is the one between the point and its face at the
    /// point's parameters, evaluated here point by point (not through the
    /// field's table of basis functions).
    #[test]
    fn every_patch_is_measured_against_its_shell_face() {
        let doc = hood_screen_wing();
        let depth = 3;
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
        for ((p, stack), face) in d.patches.iter().zip(&built.patches).zip(&fit.faces) {
            let field = p.field.as_ref().expect("sampled at the display depth");
            let points = &stack.points[depth as usize];
            assert_eq!((field.rows(), field.cols()), (points.rows(), points.cols()));
            let u = &fit.grids[d.patches.iter().position(|q| q.name == p.name).unwrap()]
                .data
                .u;
            for (j, &v) in face.v.0.iter().enumerate() {
                for (i, &ui) in u.iter().enumerate() {
                    let want = (face.surface.eval(ui, v) - points.row(j)[i]).length();
                    let got = field.row(j)[i];
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
    /// (hood-screen-wing at depth 0 needs depth 3): the figures are the
    /// deeper fit's and no patch has a field (its parameters are the deeper
    /// points').
    #[test]
    fn a_deeper_sampling_leaves_the_fields_out() {
        let doc = hood_screen_wing();
        let d = document_deviation(&doc, 0, &FitOptions::default()).unwrap();
        assert_eq!(d.depth, 3);
        assert_eq!(d.patches.len(), 3);
        assert!(d.patches.iter().all(|p| p.field.is_none()));
        assert!(d.patches.iter().all(|p| p.deviation.max <= p.tolerance));
    }
}
