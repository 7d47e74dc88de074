//! The streamline surface as drawn: every patch's shaded mesh, kept up to
//! date by one sync (`patches`: from the patch's stack, or the first
//! patch's incremental surface; `patch_mesh`: the rows written in place;
//! `shaded`: the material, the lights, the first patch's mesh entity), the
//! analysis displays over it (`analysis_display`: the display mode, its
//! settings and the maps' materials; `maps`: the curvature maps, zebra
//! stripes, deviation map and map to the reference on every patch's mesh,
//! by one path, with `colour_maps`, their ramps and coordinates;
//! `deviation`: the one deviation map of every patch against the CAD
//! export's fit; `reference_map`: the distance to the design's reference;
//! `combs`: the curvature comb), and the reference drawn as a ghost
//! (`reference_ghost`).

pub(super) mod analysis_display;
pub(super) mod colour_maps;
pub(super) mod combs;
pub(super) mod deviation;
pub(super) mod maps;
mod patch_mesh;
pub(super) mod patches;
pub mod reference_ghost;
pub mod reference_map;
pub(super) mod shaded;
