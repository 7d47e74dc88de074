//! # streamline-kernel
//!
//! The geometry kernel of Streamline Studio: streamline modeling with subdivision
//! on the Gaussian sphere (Miura, Wang, Cheng, *CAD* 33, 2001 — "paper 000").
//!
//! A *tangent* is a unit vector, a point of the Gaussian sphere S². Tangents are
//! blended on the sphere ([`sphere`]), refined as curves ([`curve`], [`qi`]) and as
//! tensor-product surfaces ([`surface`]); each row of a refined net is integrated
//! into an arc-length streamline ([`streamline`]) placed on an initial curve
//! ([`initial_curve`]); the rows together make a triangle mesh ([`mesh`]).
//!
//! Conventions (see `docs/math.md`): all math is `f64` ([`glam::DVec3`]); inputs are
//! normalised at the kernel's boundary ([`Tangent::new`], [`tangent::normalize_all`]);
//! degenerate geometry is a documented branch, never a NaN; invalid input is a
//! [`KernelError`] that names the place and the fix. This crate never imports Bevy.

pub mod aesthetic;
pub mod analysis;
pub mod authoring;
pub mod bspline;
pub mod builder;
pub mod curve;
pub mod design;
pub mod error;
pub mod finetune;
pub mod grid;
pub mod incremental;
pub mod initial_curve;
pub mod interpolate;
pub mod limits;
pub mod loop_subdiv;
pub mod mesh;
pub mod multires;
pub mod nurbs;
pub mod parallel;
pub mod params;
pub mod presets;
pub mod qi;
pub mod scalar;
pub mod simd;
pub mod sphere;
pub mod sphere_pi;
pub mod streamline;
pub mod surface;
pub mod tangent;
pub mod trimesh;
pub mod window;

pub use builder::Builder;
pub use curve::CurveScheme;
pub use design::{Built, Design, Level};
pub use error::{KernelError, Place};
pub use glam::{DQuat, DVec3};
pub use grid::Grid;
pub use surface::{BlendOrder, SurfaceScheme};
pub use tangent::Tangent;
