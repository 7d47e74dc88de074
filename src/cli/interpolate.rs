//! `interpolate IN.obj`: progressive interpolation with Loop surfaces (paper
//! 002): writes the control mesh whose Loop limit surface passes through the
//! input's vertices (same vertex order and faces) and prints one JSON line.

use super::input::{CliError, write_stdout};
use crate::scene::loop_mesh::{obj, usd};
use clap::{Args, ValueEnum};
use serde::Serialize;
use std::path::PathBuf;
use std::time::Instant;
use streamline_kernel::loop_subdiv::mesh_interpolation::{Method, Options, interpolate};
use streamline_kernel::loop_subdiv::subdivide::{BoundaryRule, subdivide_levels};

/// Which iteration.
#[derive(Debug, Clone, Copy, ValueEnum)]
pub enum MethodArg {
    /// 002's progressive iteration.
    Plain,
    /// Conjugate gradients / BiCGSTAB on the same system (fewer iterations).
    Fast,
}

/// Which boundary rules (`docs/loop.md`).
#[derive(Debug, Clone, Copy, ValueEnum)]
pub enum BoundaryArg {
    /// 002's rules (valence-4 regular boundary vertices, ⅝–⅜ edge points); USD cannot say it.
    Paper,
    /// OpenSubdiv's VTX_BOUNDARY_EDGE_ONLY (USD edgeOnly): cubic B-spline boundaries.
    EdgeOnly,
    /// OpenSubdiv's VTX_BOUNDARY_EDGE_AND_CORNER, USD's default: single-face corners stay put.
    EdgeAndCorner,
}

impl From<BoundaryArg> for BoundaryRule {
    fn from(b: BoundaryArg) -> Self {
        match b {
            BoundaryArg::Paper => BoundaryRule::Paper,
            BoundaryArg::EdgeOnly => BoundaryRule::EdgeOnly,
            BoundaryArg::EdgeAndCorner => BoundaryRule::EdgeAndCorner,
        }
    }
}

/// Arguments of `interpolate`.
#[derive(Debug, Args)]
pub struct InterpolateArgs {
    /// The triangle mesh (OBJ; polygons are fan-triangulated).
    input: PathBuf,
    /// Stop when every vertex is this close to its limit point (bounding box's largest side = 1).
    #[arg(long, default_value_t = 1e-3)]
    tolerance: f64,
    /// Give up after this many iterations per phase (boundary, interior).
    #[arg(long, default_value_t = 10_000)]
    max_iterations: usize,
    /// plain (002) or fast.
    #[arg(long, value_enum, default_value = "plain")]
    method: MethodArg,
    /// Boundary rules of the Loop surface: paper (002), edge-only or
    /// edge-and-corner (OpenSubdiv's; USD's default).
    #[arg(long, value_enum, default_value = "edge-and-corner")]
    boundary: BoundaryArg,
    /// Write the control mesh here: OBJ (same vertex order and faces) or, named
    /// `.usda`, a USD mesh with `subdivisionScheme = "loop"` and the boundary rule.
    #[arg(long)]
    out: Option<PathBuf>,
    /// Subdivide the control mesh this many times (for --surface).
    #[arg(long, default_value_t = 0)]
    subdivide: u32,
    /// Write the subdivided control mesh (the interpolating surface) here.
    #[arg(long)]
    surface: Option<PathBuf>,
}

#[derive(Serialize)]
struct Report {
    input: String,
    vertices: usize,
    faces: usize,
    boundary_loops: usize,
    method: &'static str,
    boundary: &'static str,
    tolerance: f64,
    iterations: usize,
    boundary_iterations: usize,
    interior_iterations: usize,
    converged: bool,
    max_error: f64,
    avg_error: f64,
    seconds: f64,
}

/// Runs `interpolate`.
pub fn run(a: InterpolateArgs) -> Result<(), CliError> {
    if !(a.tolerance.is_finite() && a.tolerance > 0.0) {
        return Err(CliError::Usage(format!(
            "--tolerance {} must be a positive number, e.g. 1e-3",
            a.tolerance
        )));
    }
    if a.surface.is_some() != (a.subdivide > 0) {
        return Err(CliError::Usage(
            "--subdivide N and --surface SURF.obj go together".into(),
        ));
    }
    if a.subdivide > 6 {
        return Err(CliError::Usage(format!(
            "--subdivide {} would multiply the faces by 4^{}; use at most 6",
            a.subdivide, a.subdivide
        )));
    }
    let boundary: BoundaryRule = a.boundary.into();
    if let Some(out) = a.out.as_ref().filter(|o| usd::is_usd(o))
        && let Some(why) = usd::refusal(boundary)
    {
        return Err(CliError::Usage(format!("--out {}: {why}", out.display())));
    }
    let (mesh, topo) = obj::read(&a.input).map_err(CliError::Scene)?;
    let method = match a.method {
        MethodArg::Plain => Method::Plain,
        MethodArg::Fast => Method::Fast,
    };
    let opts = Options {
        tolerance: a.tolerance,
        max_iterations: a.max_iterations,
        method,
        boundary,
    };
    let t0 = Instant::now();
    let (ctrl, rep) = interpolate(&mesh, &topo, &opts);
    let seconds = t0.elapsed().as_secs_f64();
    let comment = format!(
        "control mesh of a Loop surface interpolating {} ({} iterations, {}, boundary {}, max error {:e})",
        a.input.display(),
        rep.iterations(),
        method.name(),
        boundary.name(),
        rep.max_error
    );
    if let Some(out) = &a.out {
        if usd::is_usd(out) {
            usd::write(out, &ctrl, &mesh.faces, boundary, &comment)
        } else {
            obj::write(out, &ctrl, &mesh.faces, &comment)
        }
        .map_err(CliError::Scene)?;
    }
    if let Some(surf) = &a.surface {
        let c = streamline_kernel::loop_subdiv::trimesh::TriMesh {
            positions: ctrl.clone(),
            faces: mesh.faces.clone(),
        };
        // the control mesh has the input's faces, so its topology
        let m = subdivide_levels(&c, &topo, boundary, a.subdivide)
            .map_err(|e| CliError::Usage(format!("--subdivide: {e}")))?;
        obj::write(
            surf,
            &m.positions,
            &m.faces,
            "Loop surface of the control mesh",
        )
        .map_err(CliError::Scene)?;
    }
    write_stdout(&Report {
        input: a.input.display().to_string(),
        vertices: mesh.positions.len(),
        faces: mesh.faces.len(),
        boundary_loops: topo.loops.len(),
        method: method.name(),
        boundary: opts.boundary.name(),
        tolerance: a.tolerance,
        iterations: rep.iterations(),
        boundary_iterations: rep.boundary_iterations,
        interior_iterations: rep.interior_iterations,
        converged: rep.converged,
        max_error: rep.max_error,
        avg_error: rep.avg_error,
        seconds,
    })
}
