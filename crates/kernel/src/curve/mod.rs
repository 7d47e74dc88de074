//! Curves of tangents on the Gaussian sphere (paper 000, §3.5–3.7; docs/math.md §2).
//!
//! - [`scheme`]: one subdivision step of Chaikin, the cubic B-spline and the
//!   4-point scheme on the sphere (Eqs. 49–61).
//! - `scalar`: the same schemes in the plane, for the parameter grids
//!   `s`, `t`, `σ` (docs/math.md §4).
//! - [`qi`]: the QI curve of Kim–Kim–Shin, the smooth reference of Table 1
//!   and the initial curve's default shape (Eqs. 22–26).

pub mod qi;
pub(crate) mod scalar;
pub mod scheme;
