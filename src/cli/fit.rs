//! `fit FILE --out design.ron`: a streamline design fitted to a face of a
//! STEP or IGES file within a tolerance (`docs/math.md §12`), saved as a
//! scene, with the deviation measured both ways.
//!
//! The design is written whether or not it came within the tolerance (the
//! best net reached, when the cap stopped the growth); the command then
//! exits 1 and says why.

use super::faces::read_reference;
use super::input::{CliError, write_stdout};
use crate::scene::files::reference_link::ReferenceLink;
use crate::scene::fit::reference::{fitted_name, fitted_scene};
use crate::scene::{Scene, design::document_io};
use clap::{Args, ValueEnum};
use serde::Serialize;
use std::path::PathBuf;
use streamline_kernel::SurfaceScheme;
use streamline_kernel::fit::{
    Along, AnchorAt, Distances, ReferenceFit, ReferenceFitOptions, Tolerance, fit_reference,
};

/// Which parameter of the face the streamlines follow.
#[derive(Debug, Clone, Copy, ValueEnum)]
pub enum AlongArg {
    /// Rows are the face's iso-curves `v = const`.
    U,
    /// Rows are the face's iso-curves `u = const`.
    V,
}

/// Where the streamlines start.
#[derive(Debug, Clone, Copy, ValueEnum)]
pub enum AnchorArg {
    /// On the face's first edge across the streamlines.
    First,
    /// Through the middle of every row; streamlines run both ways.
    Middle,
}

/// The design's subdivision scheme.
#[derive(Debug, Clone, Copy, ValueEnum)]
pub enum SchemeArg {
    /// Kobbelt's interpolating 4-point scheme (ω = 1).
    Kobbelt,
    /// Catmull–Clark (cubic B-spline), approximating.
    CatmullClark,
    /// Doo–Sabin (Chaikin), approximating.
    DooSabin,
}

/// Arguments of `fit`.
#[derive(Debug, Args)]
pub struct FitArgs {
    /// A STEP (.step, .stp) or IGES (.igs, .iges) file, or an OBJ grid of
    /// points (a triangle mesh, OBJ or STL, is refused: it is measured
    /// against, never fitted).
    file: PathBuf,
    /// Which face (`faces FILE` lists them).
    #[arg(long, default_value_t = 0)]
    face: usize,
    /// The face's parameter the streamlines follow.
    #[arg(long, value_enum, default_value = "u")]
    along: AlongArg,
    /// Where each streamline meets the initial curve.
    #[arg(long, value_enum, default_value = "first")]
    anchor: AnchorArg,
    /// The largest allowed deviation, in metres.
    #[arg(long, conflicts_with = "relative", allow_hyphen_values = true)]
    tolerance: Option<f64>,
    /// The largest allowed deviation as a fraction of the face's bounding
    /// box's diagonal [default: 1e-4].
    #[arg(long, allow_hyphen_values = true)]
    relative: Option<f64>,
    /// The fit depth: where the design is measured, shown and exported (1–7).
    #[arg(long, default_value_t = 5)]
    depth: u32,
    /// The design's subdivision scheme.
    #[arg(long, value_enum, default_value = "kobbelt")]
    scheme: SchemeArg,
    /// The largest net, ROWSxCOLS control tangents [default: the authoring cap].
    #[arg(long, value_name = "RxC")]
    max_net: Option<String>,
    /// The design file to write (a version-2 scene).
    #[arg(long)]
    out: PathBuf,
    /// Print one JSON object instead of a summary.
    #[arg(long)]
    json: bool,
}

#[derive(Serialize)]
struct NetSize {
    rows: usize,
    cols: usize,
}

#[derive(Serialize)]
struct MaxMean {
    max: f64,
    mean: f64,
}

impl From<Distances> for MaxMean {
    fn from(d: Distances) -> Self {
        MaxMean {
            max: d.max,
            mean: d.mean,
        }
    }
}

#[derive(Serialize)]
struct Deviation {
    to_reference: MaxMean,
    from_reference: MaxMean,
}

#[derive(Serialize)]
struct InitialCurveFigures {
    tangents: usize,
    deviation: f64,
}

#[derive(Serialize)]
struct FitReport {
    file: String,
    face: usize,
    along: &'static str,
    scheme: &'static str,
    out: String,
    net: NetSize,
    depth: u32,
    tolerance: f64,
    deviation: Deviation,
    within: bool,
    #[serde(skip_serializing_if = "Option::is_none")]
    why: Option<String>,
    initial_curve: InitialCurveFigures,
    nets_tried: usize,
    seconds: f64,
}

/// `ROWSxCOLS`.
fn parse_net(s: &str) -> Result<(usize, usize), CliError> {
    let bad = || {
        CliError::Usage(format!(
            "--max-net {s}: give rows and columns of control tangents as RxC, e.g. 16x32"
        ))
    };
    let (r, c) = s.split_once(['x', 'X', '×']).ok_or_else(bad)?;
    Ok((
        r.trim().parse().map_err(|_| bad())?,
        c.trim().parse().map_err(|_| bad())?,
    ))
}

/// The kernel's options of the arguments.
fn options(a: &FitArgs) -> Result<ReferenceFitOptions, CliError> {
    let mut o = ReferenceFitOptions {
        along: match a.along {
            AlongArg::U => Along::U,
            AlongArg::V => Along::V,
        },
        anchor: match a.anchor {
            AnchorArg::First => AnchorAt::First,
            AnchorArg::Middle => AnchorAt::Middle,
        },
        depth: a.depth,
        scheme: match a.scheme {
            SchemeArg::Kobbelt => SurfaceScheme::default(),
            SchemeArg::CatmullClark => SurfaceScheme::CatmullClark,
            SchemeArg::DooSabin => SurfaceScheme::DooSabin,
        },
        ..ReferenceFitOptions::default()
    };
    if let Some(t) = a.tolerance {
        o.tolerance = Tolerance::Absolute(t);
    }
    if let Some(r) = a.relative {
        o.tolerance = Tolerance::Relative(r);
    }
    if let Some(n) = &a.max_net {
        o.max_net = parse_net(n)?;
    }
    Ok(o)
}

/// The scene of a fitted design: shown at its fit depth, framed by the
/// camera, naming the face it was fitted to (written relative to the scene).
fn scene_of(fit: &ReferenceFit, name: &str, a: &FitArgs) -> Result<Scene, CliError> {
    let link = ReferenceLink {
        path: a.file.clone(),
        face: a.face,
    };
    Ok(fitted_scene(fit, name, link)?)
}

/// Runs `fit`.
pub fn run(a: FitArgs) -> Result<(), CliError> {
    if a.out.extension().is_none_or(|e| e != "ron") {
        return Err(CliError::Usage(format!(
            "--out {}: the design is a scene; name it with .ron",
            a.out.display()
        )));
    }
    let opts = options(&a)?;
    let file = read_reference(&a.file)?;
    let surface = file
        .surface(a.face)
        .map_err(|e| CliError::Usage(e.to_string()))?;
    let fit = fit_reference(surface, &opts)
        .map_err(|e| CliError::Usage(format!("{}: face {}: {e}", a.file.display(), a.face)))?;
    let name = fitted_name(&a.file);
    let scene = scene_of(&fit, &name, &a)?;
    document_io::save_scene(&scene, &a.out)?;
    let report = FitReport {
        file: a.file.display().to_string(),
        face: a.face,
        along: match a.along {
            AlongArg::U => "u",
            AlongArg::V => "v",
        },
        scheme: opts.scheme.name(),
        out: a.out.display().to_string(),
        net: NetSize {
            rows: fit.net.0,
            cols: fit.net.1,
        },
        depth: fit.depth,
        tolerance: fit.tolerance,
        deviation: Deviation {
            to_reference: fit.to_reference.into(),
            from_reference: fit.from_reference.into(),
        },
        within: fit.within,
        why: fit.why.clone(),
        initial_curve: InitialCurveFigures {
            tangents: fit.initial_tangents,
            deviation: fit.initial_deviation,
        },
        nets_tried: fit.steps,
        seconds: fit.seconds,
    };
    if a.json {
        write_stdout(&report)?;
    } else {
        println!(
            "{} face {}: a {} × {} net ({}), depth {}: to the face max {:.3e} mean {:.3e}, from the face max {:.3e} mean {:.3e}, tolerance {:.3e}; {:.2} s; wrote {}",
            report.file,
            report.face,
            report.net.rows,
            report.net.cols,
            report.scheme,
            report.depth,
            fit.to_reference.max,
            fit.to_reference.mean,
            fit.from_reference.max,
            fit.from_reference.mean,
            fit.tolerance,
            fit.seconds,
            report.out
        );
    }
    if fit.within {
        Ok(())
    } else {
        Err(CliError::Failed(format!(
            "{} face {}: not within the tolerance {:.3e}: {}; the best design reached was written to {}",
            report.file,
            report.face,
            fit.tolerance,
            fit.why.as_deref().unwrap_or("the net reached its cap"),
            report.out
        )))
    }
}
