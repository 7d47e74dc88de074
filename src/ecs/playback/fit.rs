//! A script's `Fit` step (docs/math.md §12): the face of a STEP or IGES
//! file, relative to the script, fitted as the `fit` command fits it; the
//! design, within the tolerance, is the scene that replaces the current one
//! (`Edit::Replace`, as `Load` replaces it: the history cleared), shown at
//! the fit depth and keeping the file and face as its reference. Anything
//! short of that is the step's error, and the current design stays.

use crate::ecs::messages::Edit;
use crate::scene::edits::script::fit_step::FitStep;
use crate::scene::files::reference_link::{ReferenceLink, normalised};
use crate::scene::fit::reference::fit_file;
use std::path::Path;

/// The edit of a `Fit` step run from the script folder `dir`, and what its
/// line says: the net, the fit depth, the deviation both ways and the
/// tolerance. Refused when the file cannot be read, the face is not there
/// or not a B-spline surface, the fit refuses the face, or the design is
/// not within the tolerance (a script wants the design it names).
pub(super) fn fitted(step: &FitStep, dir: &Path) -> Result<(Edit, String), String> {
    let FitStep::Fit { path, face, .. } = step;
    let link = ReferenceLink {
        path: normalised(&dir.join(path)),
        face: *face,
    };
    // the reader's advice names the command line's option
    let (scene, fit) = fit_file(&link, &step.options())
        .map_err(|e| e.replace("with --face", "with the step's `face`"))?;
    if !fit.within {
        return Err(format!(
            "{}: face {}: the fitted design is not within the tolerance {:.3e}: {}",
            link.path.display(),
            link.face,
            fit.tolerance,
            fit.why
                .as_deref()
                .unwrap_or("the net reached its cap; raise the cap or loosen the tolerance")
        ));
    }
    let note = format!(
        "fitted {} face {}: a {} × {} net at depth {}, to the face {:.2e}, from it {:.2e}, tolerance {:.2e}, {} nets in {:.2} s",
        link.path.display(),
        link.face,
        fit.net.0,
        fit.net.1,
        fit.depth,
        fit.to_reference.max,
        fit.from_reference.max,
        fit.tolerance,
        fit.steps,
        fit.seconds
    );
    Ok((Edit::Replace(Box::new(scene)), note))
}
