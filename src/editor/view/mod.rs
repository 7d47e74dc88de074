//! The view: the main camera (`camera`), when the window draws (`pacing`),
//! multisample anti-aliasing of the 3D views (`antialias`), what our systems
//! cost per frame (`frame_timing`), and the lines over the 3D view
//! (`overlay`: axes, the ground grid; `streamlines`: every patch's).

pub mod antialias;
pub(super) mod camera;
pub(super) mod frame_timing;
pub(super) mod overlay;
pub mod pacing;
pub(super) mod streamlines;
