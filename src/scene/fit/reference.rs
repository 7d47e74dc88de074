//! A design made from its reference and measured against it (docs/math.md
//! §12): the scene a fit of a STEP or IGES face makes ([`fitted_scene`],
//! for the `fit` command and a script's `Fit` step, which reads and fits the
//! file by [`fit_file`]), and the distance from a design's streamline
//! points to the face its `reference` names ([`measure`], for a script's
//! `ExpectReferenceDeviation` and the `"reference"` of `build --json`), a
//! B-spline face or a triangle mesh (OBJ, STL: measured, never fitted).
//!
//! What is measured is the first patch's streamline points at the depth
//! shown ([`measured_points`]): the points a fit makes lie on the face, and
//! a later patch of a design of several is a surface of its own, not on it.
//! With the mirror on, only the design's own half is measured (its rows
//! from the middle on, docs/math.md §9): the reflection lies on the
//! reflected face, which the file does not hold.

use crate::scene::design::model::Scene;
use crate::scene::files::reference_link::ReferenceLink;
use std::path::Path;
use streamline_kernel::fit::{
    ClosestPoints, Distances, MeshIndex, ReferenceFit, ReferenceFitOptions, ReferenceIndex,
    fit_reference,
};
use streamline_kernel::{DVec3, Grid, KernelError};

/// The scene of a fitted design: shown at its fit depth, framed by the
/// camera, named `name`, keeping `link` as its reference.
pub fn fitted_scene(
    fit: &ReferenceFit,
    name: &str,
    link: ReferenceLink,
) -> Result<Scene, KernelError> {
    let mut scene = Scene::from_design(name, fit.design.clone(), fit.depth);
    scene.view = scene.framing_view()?;
    scene.reference = Some(link);
    Ok(scene)
}

/// The name a design fitted to `path` gets: the file's stem (`hood` for
/// `hood.step`), or `fitted`.
pub fn fitted_name(path: &Path) -> String {
    path.file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "fitted".into())
}

/// Reads the STEP or IGES file of `link` and fits its face with `opts`:
/// the fit (within the tolerance or not: [`ReferenceFit::within`] says)
/// and its scene ([`fitted_scene`], named by [`fitted_name`]). Refused,
/// with the file named, when the file cannot be read, has no such face, the
/// face is not a B-spline surface (a triangle mesh is refused at its line:
/// it is for display and measuring only) or the fit refuses it.
pub fn fit_file(
    link: &ReferenceLink,
    opts: &ReferenceFitOptions,
) -> Result<(Scene, ReferenceFit), String> {
    let file = streamline_reference::read(&link.path).map_err(|e| e.to_string())?;
    let surface = file.surface(link.face).map_err(|e| e.to_string())?;
    let fit = fit_reference(surface, opts)
        .map_err(|e| format!("{}: face {}: {e}", link.path.display(), link.face))?;
    let scene = fitted_scene(&fit, &fitted_name(&link.path), link.clone())
        .map_err(|e| format!("{}: face {}: {e}", link.path.display(), link.face))?;
    Ok((scene, fit))
}

/// The points of the first patch's surface `points` (as shown, both halves
/// when `mirror` is on) that are measured against the reference: all of
/// them, or with the mirror on the design's own half, the rows from the
/// middle on (the doubled net's row `m − 1 + r` is the half's row `r`,
/// docs/math.md §9; the middle row lies in the mirror plane).
pub fn measured_points(points: &Grid<DVec3>, mirror: bool) -> &[DVec3] {
    let first = if mirror { points.rows() / 2 } else { 0 };
    &points.data()[first * points.cols()..]
}

/// The index that measures against the face of `link`, read from its file
/// (docs/math.md §12): a surface's closest points (eq. 12.6: Gauss–Newton
/// from the nearest of a dense sample) or, for a triangle mesh (OBJ or
/// STL), the closest point of its triangles (eq. 12.8). Refused, with the
/// file named, when the file cannot be read, the face is not there or is
/// neither a B-spline surface nor a mesh.
pub fn reference_index(link: &ReferenceLink) -> Result<ReferenceIndex, String> {
    let file = streamline_reference::read(&link.path).map_err(|e| e.to_string())?;
    if let Some(mesh) = file.mesh(link.face).map_err(|e| e.to_string())? {
        return Ok(ReferenceIndex::Mesh(MeshIndex::new(mesh.clone())));
    }
    let surface = file.surface(link.face).map_err(|e| e.to_string())?;
    ClosestPoints::shared(std::sync::Arc::new(surface.clone()))
        .map(ReferenceIndex::Surface)
        .map_err(|e| format!("{}: face {}: {e}", link.path.display(), link.face))
}

/// The distance from each of `points` to the face of `link`
/// ([`reference_index`]).
pub fn distances(link: &ReferenceLink, points: &[DVec3]) -> Result<Vec<f64>, String> {
    Ok(reference_index(link)?.distances(points))
}

/// The largest and mean distance from the measured points of the first
/// patch's `points` ([`measured_points`]) to the face of `link`
/// ([`distances`]).
pub fn measure(
    link: &ReferenceLink,
    points: &Grid<DVec3>,
    mirror: bool,
) -> Result<Distances, String> {
    Ok(Distances::of(&distances(
        link,
        measured_points(points, mirror),
    )?))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_mirrored_half_is_left_out() {
        let g = Grid::new(5, 2, (0..10).map(|i| DVec3::splat(i as f64)).collect()).unwrap();
        assert_eq!(measured_points(&g, false).len(), 10);
        let half = measured_points(&g, true);
        assert_eq!(half.len(), 6, "the middle row and the two after it");
        assert_eq!(half[0], DVec3::splat(4.0));
        let even = Grid::new(4, 1, (0..4).map(|i| DVec3::splat(i as f64)).collect()).unwrap();
        assert_eq!(measured_points(&even, true), &even.data()[2..]);
    }
}
