//! # streamline-kernel
//!
//! The geometry kernel of Streamline Studio: streamline modeling with subdivision
//! on the Gaussian sphere (Miura, Wang, Cheng, *CAD* 33, 2001 — "paper 000").
//!
//! A *tangent* is a unit vector, a point of the Gaussian sphere S² ([`sphere`]).
//! Tangents are refined as curves ([`curve`]) and as tensor-product surfaces
//! ([`levels`], which also keeps the subdivision levels between edits); each row
//! of a refined net is integrated into an arc-length streamline placed on an
//! initial curve, and the rows together make a triangle mesh ([`streamline`]).
//! [`finetune`] reshapes streamlines and surfaces by B-spline functions of arc
//! length (paper 003), [`loop_subdiv`] subdivides and interpolates triangle meshes
//! (paper 002), and [`analysis`] measures curvature. [`grid`], [`error`],
//! [`limits`], [`parallel`] and [`simd`] are shared by all of them.
//!
//! Conventions (see `docs/math.md`): all math is `f64` ([`glam::DVec3`]); inputs are
//! normalised at the kernel's boundary ([`Tangent::new`], [`sphere::tangent::normalize_all`]);
//! degenerate geometry is a documented branch, never a NaN; invalid input is a
//! [`KernelError`] that names the place and the fix. This crate never imports Bevy.
//!
//! The public API is what the application, its command line and its fuzz
//! targets use, plus the documented rules a geometer looks up (the Loop masks,
//! the caps in [`limits`]); the rest is crate-internal. [`Design`] keeps its
//! invariants: its fields are read through getters and changed through setters
//! that check (docs/architecture.md, "The kernel's modules and public API").

pub mod aesthetic;
pub mod analysis;
pub mod authoring;
pub(crate) mod bits;
pub mod curve;
pub mod error;
pub mod finetune;
pub mod fit;
pub mod grid;
pub mod joins;
pub mod levels;
pub mod limits;
pub mod loop_subdiv;
pub mod nurbs;
pub mod parallel;
pub mod plane;
pub mod simd;
pub mod sphere;
pub mod streamline;

pub use curve::scheme::CurveScheme;
pub use error::{KernelError, Place};
pub use glam::{DQuat, DVec3};
pub use grid::Grid;
pub use levels::builder::Builder;
pub use levels::design::{Built, Design, Level};
pub use levels::surface::{BlendOrder, SurfaceScheme};
pub use sphere::tangent::Tangent;
