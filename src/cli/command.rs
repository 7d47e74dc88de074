//! The command line's parser and dispatch (with the editor: feature `app`).

use super::input::CliError;
use super::{bench, build, editor, faces, fit, geometry, interpolate, play};
use clap::{Parser, Subcommand};

/// Streamline Studio: design fair free-form surfaces by streamline modeling.
///
/// With no subcommand the editor opens; the subcommands run headless.
#[derive(Debug, Parser)]
#[command(name = "streamline-studio", version, about, long_about = None)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Option<Command>,
    /// With no subcommand: the scene to open, a .ron file or a built-in scene
    /// (car1, car2, qi-down, qi-side, qi-up, minimal, car1-tuned).
    #[arg(value_name = "SCENE")]
    pub file: Option<String>,
    /// The same as SCENE, as an option.
    #[arg(long)]
    pub scene: Option<String>,
    /// With no subcommand: multisample anti-aliasing of the 3D views, 1 (off),
    /// 2, 4 or 8, or the nearest the graphics adapter offers [default: off on
    /// a software renderer such as llvmpipe, which then draws about four times
    /// as many frames; 4 on a GPU].
    #[arg(long, value_parser = crate::editor::view::antialias::parse_samples)]
    pub msaa: Option<u32>,
}

/// Headless subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Subdivide a curve of tangents (stdin: [[x,y,z],…]) or sample a QI curve.
    Curve(geometry::CurveArgs),
    /// Subdivide a net of tangents (stdin: rows [[[x,y,z],…],…], one row per streamline).
    Surface(geometry::SurfaceArgs),
    /// Integrate one streamline by Eq. 65 (stdin: {"tangents", "s", "anchor", "origin"}).
    Integrate(geometry::IntegrateArgs),
    /// Time the built-in benchmark rows on this machine.
    Bench(bench::BenchArgs),
    /// Run a script of edits and expectations headless; exit 0 only if all hold.
    Play(play::PlayArgs),
    /// Build a scene headless and print JSON stats; optionally export it (OBJ, STL, glTF, STEP, IGES).
    Build(build::BuildArgs),
    /// Open the editor, render, save a PNG of the window and exit.
    Screenshot(editor::ScreenshotArgs),
    /// Make a Loop surface interpolate a triangle mesh's vertices (paper 002); one JSON line.
    Interpolate(interpolate::InterpolateArgs),
    /// List the faces of a STEP or IGES file that a design can be fitted to.
    Faces(faces::FacesArgs),
    /// Fit a streamline design to a face of a STEP or IGES file within a tolerance.
    Fit(fit::FitArgs),
}

/// Runs the binary; returns the process exit code.
pub fn main() -> i32 {
    let cli = match Cli::try_parse() {
        Ok(c) => c,
        Err(e) => {
            let _ = e.print();
            return if e.use_stderr() { 2 } else { 0 };
        }
    };
    match run(cli) {
        Ok(()) => 0,
        Err(e) => {
            eprintln!("streamline-studio: {e}");
            e.exit_code()
        }
    }
}

/// Runs a parsed command line.
pub fn run(cli: Cli) -> Result<(), CliError> {
    match cli.command {
        None => editor::open(
            cli.file
                .as_deref()
                .or(cli.scene.as_deref())
                .unwrap_or(crate::scene::design::builtin::DEFAULT),
            cli.msaa,
        ),
        Some(Command::Curve(a)) => geometry::curve(a),
        Some(Command::Surface(a)) => geometry::surface(a),
        Some(Command::Integrate(a)) => geometry::integrate(a),
        Some(Command::Bench(a)) => bench::bench(a),
        Some(Command::Screenshot(a)) => editor::screenshot(a),
        Some(Command::Play(a)) => play::play(a),
        Some(Command::Build(a)) => build::build(a),
        Some(Command::Interpolate(a)) => interpolate::run(a),
        Some(Command::Faces(a)) => faces::run(a),
        Some(Command::Fit(a)) => fit::run(a),
    }
}
