//! Starting from what exists (`docs/math.md §12`): a four-sided freeform
//! surface — a reference — turned into a streamline design that reproduces
//! it within a tolerance and is then edited by its tangents.
//!
//! * [`reference`]: what a reference is ([`ReferenceSurface`], implemented by
//!   [`NurbsSurface`](crate::nurbs::rational::NurbsSurface)) and the
//!   arc-length tables of its rows and of the initial curve;
//! * [`options`]: which way the streamlines run, the anchor, the tolerance,
//!   the fit depth, the scheme and the net's cap;
//! * [`initial`]: the initial curve's QI tangents fitted to the anchor curve;
//! * [`construct`]: a control net from row and column positions (tangent
//!   samples, arc lengths, phantom rows and columns of the approximating
//!   schemes);
//! * `measure`: a built mesh measured against the reference both ways, and
//!   the cells' scores that say where the net grows;
//! * [`closest`]: closest points on the reference (Newton from the nearest
//!   sample) and the distance from the reference to a design's mesh;
//! * [`mesh`]: the distance from points to a triangle mesh (a reference
//!   for display and measuring only) and [`ReferenceIndex`], which measures
//!   against a surface or a mesh alike;
//! * [`grow`]: the greedy growth of the net and the [`ReferenceFit`] it
//!   reports;
//! * [`error`]: every refusal, naming the edge and the fix.

pub mod closest;
pub mod construct;
pub mod error;
pub mod grow;
pub mod initial;
mod measure;
pub mod mesh;
pub mod options;
pub mod reference;

pub use closest::{ClosestPoints, Distances, distances_to_reference};
pub use error::ReferenceFitError;
pub use grow::{ReferenceFit, fit_reference, fit_reference_with};
pub use mesh::{MeshError, MeshIndex, ReferenceIndex, TriangleMesh};
pub use options::{Along, AnchorAt, ReferenceFitOptions, Tolerance};
pub use reference::ReferenceSurface;
