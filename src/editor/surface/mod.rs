//! The streamline surface as drawn: the shaded mesh that mirrors the model's
//! surface (`shaded`), and the analysis displays over it (`analysis`: the
//! curvature comb, Gaussian and mean curvature maps, zebra stripes; and
//! `deviation`: the deviation map against the CAD export's fit;
//! `reference_map`: the distance to the design's reference), the
//! reference drawn as a ghost (`reference_ghost`), and the
//! shaded surfaces of a document's other patches (`patches`) with the same
//! maps on them (`patch_maps`).

pub(super) mod analysis;
pub(super) mod deviation;
pub(super) mod patch_maps;
mod patch_mesh;
pub(super) mod patches;
pub mod reference_ghost;
pub mod reference_map;
pub(super) mod shaded;
