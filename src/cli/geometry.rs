//! `curve`, `surface` and `integrate`: the kernel over JSON.

use super::input::{CliError, parse, read_stdin_text, write_stdout};
use clap::{Args, ValueEnum};
use serde::Deserialize;
use streamline_kernel::curve::qi::QiCurve;
use streamline_kernel::curve::scheme::{self as curve, CurveScheme, OMEGA_DEFAULT};
use streamline_kernel::levels::surface::{self, BlendOrder, SurfaceScheme};
use streamline_kernel::streamline::integrate::streamline;
use streamline_kernel::{DVec3, Grid};

/// A curve scheme on the command line.
#[derive(Debug, Clone, Copy, ValueEnum)]
pub enum CurveName {
    /// Chaikin's corner cutting (Eqs. 51–53).
    Chaikin,
    /// Cubic B-spline refinement (Eqs. 57–58).
    CubicBspline,
    /// The 4-point interpolatory scheme (Eqs. 59–61).
    FourPoint,
    /// The B-spline unit quaternion (QI) curve (Eqs. 22–26).
    Qi,
}

/// Arguments of `curve`.
#[derive(Debug, Args)]
#[command(
    after_help = "Input on stdin: [[x,y,z],…] (non-unit vectors are normalised).\n\
Output: the subdivided tangents [[x,y,z],…], or for --scheme qi the curve's tangent at M evenly spaced u in [0,1].\n\
Example: echo '[[1,0,0],[0,1,0],[0,0,1]]' | streamline-studio curve --scheme four-point --depth 2"
)]
pub struct CurveArgs {
    /// Subdivision scheme, or `qi` for the QI curve.
    #[arg(long)]
    pub scheme: CurveName,
    /// Subdivision steps (subdivision schemes).
    #[arg(long, default_value_t = 1)]
    pub depth: u32,
    /// 4-point tension ω, 0 ≤ ω < 2(√5−1).
    #[arg(long, default_value_t = OMEGA_DEFAULT)]
    pub omega: f64,
    /// QI curve order k (degree k−1), 2 ≤ k ≤ number of tangents.
    #[arg(long, default_value_t = 4)]
    pub order: usize,
    /// QI curve samples M ≥ 2.
    #[arg(long, default_value_t = 257)]
    pub samples: usize,
}

/// A surface scheme on the command line.
#[derive(Debug, Clone, Copy, ValueEnum)]
pub enum SurfaceName {
    /// 4-point ⊗ 4-point (interpolatory).
    Kobbelt,
    /// Cubic B-spline ⊗ cubic B-spline.
    CatmullClark,
    /// Chaikin ⊗ Chaikin.
    DooSabin,
}

/// The blend order on the command line.
#[derive(Debug, Clone, Copy, ValueEnum)]
pub enum OrderName {
    /// Rows (along s) first, then columns.
    SFirst,
    /// Columns (along t) first, then rows.
    TFirst,
}

/// Arguments of `surface`.
#[derive(Debug, Args)]
#[command(
    after_help = "Input on stdin: rows [[[x,y,z],…],…], one row per streamline, all rows the same length.\n\
Output: the refined rows.\n\
Example: echo '[[[1,0,0],[1,1,0]],[[1,0,1],[0,1,0]]]' | streamline-studio surface --scheme kobbelt --depth 1 --order s-first"
)]
pub struct SurfaceArgs {
    /// Surface scheme.
    #[arg(long)]
    pub scheme: SurfaceName,
    /// Subdivision steps.
    #[arg(long, default_value_t = 1)]
    pub depth: u32,
    /// Which direction is blended first in each step.
    #[arg(long, default_value = "s-first")]
    pub order: OrderName,
    /// Kobbelt tension ω, 0 ≤ ω < 2(√5−1).
    #[arg(long, default_value_t = OMEGA_DEFAULT)]
    pub omega: f64,
}

/// Arguments of `integrate`.
#[derive(Debug, Args)]
#[command(
    after_help = "Input on stdin: {\"tangents\": [[x,y,z],…], \"s\": [s0,…], \"anchor\": a, \"origin\": [x,y,z]}\n\
(anchor defaults to 0, origin to [0,0,0]).\n\
Output: the n+2 streamline points of Eq. 65 for n+1 tangents, placed so the point at arc length s[anchor] is origin."
)]
pub struct IntegrateArgs {}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct IntegrateInput {
    tangents: Vec<[f64; 3]>,
    s: Vec<f64>,
    #[serde(default)]
    anchor: usize,
    #[serde(default)]
    origin: [f64; 3],
}

fn to_vecs(v: &[[f64; 3]]) -> Vec<DVec3> {
    v.iter().map(|&a| DVec3::from_array(a)).collect()
}

fn to_arrays(v: &[DVec3]) -> Vec<[f64; 3]> {
    v.iter().map(|p| p.to_array()).collect()
}

/// `curve` on JSON text: the output tangents.
pub fn curve_json(a: &CurveArgs, text: &str) -> Result<Vec<[f64; 3]>, CliError> {
    let input: Vec<[f64; 3]> = parse(text)?;
    let t = to_vecs(&input);
    let out = match a.scheme {
        CurveName::Qi => QiCurve::new(&t, a.order)?.sample(a.samples)?,
        CurveName::Chaikin => curve::subdivide(CurveScheme::Chaikin, &t, a.depth)?,
        CurveName::CubicBspline => curve::subdivide(CurveScheme::CubicBSpline, &t, a.depth)?,
        CurveName::FourPoint => {
            curve::subdivide(CurveScheme::FourPoint { omega: a.omega }, &t, a.depth)?
        }
    };
    Ok(to_arrays(&out))
}

/// `surface` on JSON text: the refined rows.
pub fn surface_json(a: &SurfaceArgs, text: &str) -> Result<Vec<Vec<[f64; 3]>>, CliError> {
    let rows: Vec<Vec<[f64; 3]>> = parse(text)?;
    let rows: Vec<Vec<DVec3>> = rows.iter().map(|r| to_vecs(r)).collect();
    let grid = Grid::from_rows(&rows)?;
    let scheme = match a.scheme {
        SurfaceName::Kobbelt => SurfaceScheme::Kobbelt { omega: a.omega },
        SurfaceName::CatmullClark => SurfaceScheme::CatmullClark,
        SurfaceName::DooSabin => SurfaceScheme::DooSabin,
    };
    let order = match a.order {
        OrderName::SFirst => BlendOrder::SFirst,
        OrderName::TFirst => BlendOrder::TFirst,
    };
    let out = surface::subdivide(scheme, order, &grid, a.depth)?;
    Ok((0..out.rows()).map(|r| to_arrays(out.row(r))).collect())
}

/// `integrate` on JSON text: the streamline's points.
pub fn integrate_json(text: &str) -> Result<Vec<[f64; 3]>, CliError> {
    let input: IntegrateInput = parse(text)?;
    let p = streamline(
        &to_vecs(&input.tangents),
        &input.s,
        input.anchor,
        DVec3::from_array(input.origin),
    )?;
    Ok(to_arrays(&p))
}

/// `curve`.
pub fn curve(a: CurveArgs) -> Result<(), CliError> {
    write_stdout(&curve_json(&a, &read_stdin_text()?)?)
}

/// `surface`.
pub fn surface(a: SurfaceArgs) -> Result<(), CliError> {
    write_stdout(&surface_json(&a, &read_stdin_text()?)?)
}

/// `integrate`.
pub fn integrate(_: IntegrateArgs) -> Result<(), CliError> {
    write_stdout(&integrate_json(&read_stdin_text()?)?)
}
