//! A patch as the joins build it (docs/math.md §11): its control net and
//! what it adds to it, its multiresolution details (§5) and its fine tuning
//! (§6). Tangent interpolation (§7) is a change of the net, so a patch
//! that interpolates its tangents is given with the interpolated net.

use crate::finetune::SurfaceTuning;
use crate::levels::design::Design;
use crate::levels::multires::Details;

/// A patch's design with its details and fine tuning, borrowed.
#[derive(Debug, Clone, Copy)]
pub struct PatchParts<'a> {
    /// Control net, parameters, scheme, blend order, anchor, initial curve.
    pub design: &'a Design,
    /// Its details (`None`: none).
    pub details: Option<&'a Details>,
    /// Its fine tuning (`None`: off).
    pub tuning: Option<&'a SurfaceTuning>,
}

impl<'a> PatchParts<'a> {
    /// A design with its details and fine tuning.
    pub fn new(
        design: &'a Design,
        details: Option<&'a Details>,
        tuning: Option<&'a SurfaceTuning>,
    ) -> Self {
        PatchParts {
            design,
            details: details.filter(|d| !d.is_empty()),
            tuning,
        }
    }

    /// Whether it has details or fine tuning (else it is its net alone).
    pub fn adds(&self) -> bool {
        self.details.is_some() || self.tuning.is_some()
    }
}

impl<'a> From<&'a Design> for PatchParts<'a> {
    fn from(design: &'a Design) -> Self {
        PatchParts {
            design,
            details: None,
            tuning: None,
        }
    }
}
