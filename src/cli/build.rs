//! `build SCENE.ron [--depth N] [--export OUT [--tolerance T | --relative-tolerance R] [--degree P]]`:
//! a headless build through the ECS pipeline, with JSON stats on stdout. The
//! export's format follows the extension: the mesh as `.obj`, `.stl`, `.glb`,
//! the fitted B-spline surface as `.step`/`.stp` or `.igs`/`.iges` (docs/math.md §10),
//! whose fit the report gains as `"fit"`. A version-3 scene of several
//! patches (docs/math.md §11) is built as a document: `"patches"` lists
//! each patch's streamlines and `"seams"` each join's report, read from the
//! world's patch entities; a one-patch scene reports its one patch (`main`
//! for versions 1 and 2) and no seams. An export of several patches writes
//! them all (`scene::export::document`: one STEP shell, one IGES entity 128,
//! OBJ object, glTF node or STL solid per patch), and the report gains
//! `"faces"`, each fitted face's poles and deviation. A design with a
//! reference (docs/math.md §12) is measured against it at the build depth
//! (`scene::fit::reference::measure`): `"reference"` gives the file, the face
//! and the largest and mean distance, or the error when the file cannot be
//! read (the build itself still succeeds).

use super::input::{CliError, document_arg, write_stdout};
use crate::ecs::components::{LevelData, SubdivisionLevel};
use crate::ecs::exchange::{ExportSettings, LastExport};
use crate::ecs::joined::{PatchSlot, PatchStart, PatchSurface, SeamState};
use crate::ecs::warnings::BuildWarnings;
use crate::ecs::{self, Edit, EditLog, ModelConfig, Stats, SurfaceData};
use crate::scene::files::reference_link::ReferenceLink;
use crate::scene::fit::reference;
use bevy::prelude::*;
use clap::Args;
use serde::Serialize;
use std::path::PathBuf;
use streamline_kernel::nurbs::{FitOptions, Tolerance};
use streamline_kernel::streamline::integrate::polyline_length;
use streamline_kernel::{DVec3, Grid};

/// Arguments of `build`.
#[derive(Debug, Args)]
pub struct BuildArgs {
    /// The scene: a .ron file or a built-in name.
    scene: String,
    /// Display depth (default: the scene's).
    #[arg(long)]
    depth: Option<u32>,
    /// Export the surface to this file: .obj, .stl or .glb (the mesh),
    /// .step/.stp or .igs/.iges (the fitted B-spline surface).
    #[arg(long)]
    export: Option<PathBuf>,
    /// STEP/IGES: the largest allowed deviation of the fit, in scene units
    /// (default: 1e-4 of the bounding box's diagonal).
    #[arg(
        long,
        conflicts_with = "relative_tolerance",
        allow_hyphen_values = true
    )]
    tolerance: Option<f64>,
    /// STEP/IGES: the largest allowed deviation as a fraction of the bounding
    /// box's diagonal (default 1e-4).
    #[arg(long, allow_hyphen_values = true)]
    relative_tolerance: Option<f64>,
    /// STEP/IGES: the B-spline degree in both directions, 2 to 5 (default 3),
    /// or `P,Q` for along and across the streamlines.
    #[arg(long)]
    degree: Option<String>,
}

/// The fit of a STEP or IGES export, as the report gives it.
#[derive(Serialize)]
struct FitFigures {
    /// The depth the surface was sampled at: the display depth, or deeper
    /// when the tolerance needed more points (docs/math.md §10).
    depth: u32,
    degree: [usize; 2],
    poles: [usize; 2],
    tolerance: f64,
    max_deviation: f64,
    mean_deviation: f64,
    seconds: f64,
}

/// The fit options of the arguments.
fn fit_options(a: &BuildArgs) -> Result<FitOptions, CliError> {
    let mut opts = FitOptions::DEFAULT;
    if let Some(d) = &a.degree {
        let parse = |s: &str| {
            s.trim().parse::<usize>().map_err(|_| {
                CliError::Usage(format!(
                    "--degree {d}: give a whole number from 2 to 5, or two as P,Q"
                ))
            })
        };
        opts.degree = match d.split_once(',') {
            Some((p, q)) => (parse(p)?, parse(q)?),
            None => (parse(d)?, parse(d)?),
        };
    }
    if let Some(t) = a.tolerance {
        opts.tolerance = Tolerance::Absolute(t);
    }
    if let Some(r) = a.relative_tolerance {
        opts.tolerance = Tolerance::Relative(r);
    }
    Ok(opts)
}

#[derive(Serialize)]
struct LengthError {
    max_abs: f64,
    max_rel: f64,
    total_abs: f64,
    per_streamline: Vec<f64>,
}

#[derive(Serialize)]
struct BuildReport {
    scene: String,
    depth: u32,
    scheme: &'static str,
    blend_order: &'static str,
    levels: Vec<(usize, usize)>,
    streamlines: usize,
    points_per_streamline: usize,
    triangles: usize,
    total_length: f64,
    length_error: LengthError,
    timings_us: ecs::EditStats,
    export: Option<PathBuf>,
    /// A STEP or IGES export of one patch: its face's fit.
    #[serde(skip_serializing_if = "Option::is_none")]
    fit: Option<FitFigures>,
    /// A STEP or IGES export: each face written (one per patch).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    faces: Vec<FaceFigures>,
    /// What the build blended about a fixed axis (antipodal neighbours,
    /// docs/math.md §1), one sentence each; empty when nothing.
    warnings: Vec<String>,
    /// The world after the build, counted by queries over it.
    entities: ecs::census::Census,
    /// Every patch, in the document's order.
    patches: Vec<PatchFigures>,
    /// Every join's seam at the display depth (docs/math.md §11, "Seam report").
    seams: Vec<SeamFigures>,
    /// The design's reference and the first patch's distance to it; absent
    /// when the design has none.
    #[serde(skip_serializing_if = "Option::is_none")]
    reference: Option<ReferenceFigures>,
}

/// The design's reference as the report gives it: the file (resolved, as
/// the build read it), the face, and the distance of the first patch's
/// streamline points at the build depth to it, or why it was not measured.
#[derive(Serialize)]
struct ReferenceFigures {
    path: String,
    face: usize,
    #[serde(skip_serializing_if = "Option::is_none")]
    deviation: Option<MaxMean>,
    #[serde(skip_serializing_if = "Option::is_none")]
    error: Option<String>,
}

/// A largest and a mean distance.
#[derive(Serialize)]
struct MaxMean {
    max: f64,
    mean: f64,
}

/// The report's `"reference"` of a design whose first patch shows `points`.
fn reference_figures(link: &ReferenceLink, points: &Grid<DVec3>, mirror: bool) -> ReferenceFigures {
    let measured = reference::measure(link, points, mirror);
    ReferenceFigures {
        path: link.path.display().to_string(),
        face: link.face,
        deviation: measured.as_ref().ok().map(|d| MaxMean {
            max: d.max,
            mean: d.mean,
        }),
        error: measured.err(),
    }
}

/// A patch as the report lists it.
#[derive(Serialize)]
struct PatchFigures {
    name: String,
    streamlines: usize,
    points_per_streamline: usize,
}

/// A join's seam as the report lists it.
#[derive(Serialize)]
struct SeamFigures {
    a: String,
    b: String,
    edge: &'static str,
    continuity: &'static str,
    gap: f64,
    angle_deg: f64,
    curvature_dev: f64,
}

/// The patches and seams of the world: the first patch's streamlines are
/// the incremental pipeline's ([`SurfaceData`]); a joined patch's its
/// [`PatchSurface`]'s at the display depth. A join that failed is the
/// error, naming both patches.
fn patches_and_seams(
    w: &mut World,
    depth: u32,
    first_name: &str,
) -> Result<(Vec<PatchFigures>, Vec<SeamFigures>), CliError> {
    let surface = &w.resource::<SurfaceData>().points;
    let first = PatchFigures {
        name: first_name.to_string(),
        streamlines: surface.rows(),
        points_per_streamline: surface.cols(),
    };
    let mut q = w.query::<(&PatchSlot, &PatchStart, &PatchSurface, Option<&SeamState>)>();
    let mut rows: Vec<_> = q.iter(w).collect();
    if rows.is_empty() {
        return Ok((vec![first], Vec::new()));
    }
    rows.sort_by_key(|r| r.0.index);
    let name_of = |e: Entity| {
        w.get::<PatchSlot>(e)
            .map_or_else(String::new, |s| s.name.clone())
    };
    let (mut patches, mut seams) = (Vec::new(), Vec::new());
    for (slot, start, surf, seam) in rows {
        if slot.index == 0 {
            patches.push(PatchFigures {
                name: slot.name.clone(),
                ..first
            });
            continue;
        }
        let points = match &surf.built {
            Some(Ok(s)) => &s.points[depth as usize],
            Some(Err(e)) => return Err(CliError::Usage(e.clone())),
            None => {
                return Err(CliError::Usage(format!(
                    "patch `{}` was not built",
                    slot.name
                )));
            }
        };
        patches.push(PatchFigures {
            name: slot.name.clone(),
            streamlines: points.rows(),
            points_per_streamline: points.cols(),
        });
        if let (
            PatchStart::Edge {
                parent,
                edge,
                continuity,
            },
            Some(r),
        ) = (start, seam.and_then(|s| s.report.as_ref()))
        {
            seams.push(SeamFigures {
                a: name_of(*parent),
                b: slot.name.clone(),
                edge: edge.name(),
                continuity: continuity.name(),
                gap: r.gap,
                angle_deg: r.angle_deg,
                curvature_dev: r.curvature_dev,
            });
        }
    }
    Ok((patches, seams))
}

/// A fitted face of an export, as the report gives it.
#[derive(Serialize)]
struct FaceFigures {
    name: String,
    depth: u32,
    /// In `u` (along the streamlines) and in `v`, as the fit's.
    poles: [usize; 2],
    tolerance: f64,
    max_deviation: f64,
}

/// Builds and prints the stats.
pub fn build(a: BuildArgs) -> Result<(), CliError> {
    let doc = document_arg(&a.scene)?;
    let mut scene = doc.patch_scene(0);
    if let Some(d) = a.depth {
        // mirrored: the doubled net is what is built (docs/math.md §9)
        let design = &scene
            .shown_design()
            .map_err(|e| CliError::Usage(format!("mirror: {e}")))?;
        design
            .scheme()
            .check_depth(
                design.net().rows(),
                design.net().cols(),
                d.max(scene.edit_depth),
            )
            .map_err(|e| CliError::Usage(format!("--depth {d}: {e}")))?;
        streamline_kernel::levels::incremental::check_params(design, d)
            .map_err(|e| CliError::Usage(format!("--depth {d}: {e}")))?;
        scene.display_depth = d;
    }
    let fit = fit_options(&a)?;
    let mut app =
        ecs::headless_document_app(&doc, Some(scene.display_depth), ModelConfig::default());
    let build_stats = app.world().resource::<Stats>().last.clone();
    app.world_mut().resource_mut::<ExportSettings>().fit = fit;
    // every patch, through the editor's own export (`Edit::Export`)
    if let Some(out) = &a.export {
        ecs::send(&mut app, Edit::Export(out.clone()));
        app.update();
        if let Some(Err(e)) = app.world().resource::<EditLog>().entries.first() {
            return Err(CliError::Usage(e.to_string()));
        }
    }
    let w = app.world_mut();
    let entities = ecs::census::census(w);
    let scene = ecs::patch::try_scene(w).map_err(CliError::Usage)?;
    let (patches, seams) = patches_and_seams(w, scene.display_depth, &doc.patches[0].name)?;
    let mut per = Vec::new();
    let mut total = 0.0;
    let depth = scene.display_depth;
    let mut levels = w.query::<(&SubdivisionLevel, &LevelData)>();
    let mut q = w.query::<&ecs::components::Streamline>();
    let w = &*w;
    let points = &w.resource::<ecs::SurfaceData>().points;
    let Some((_, level)) = levels.iter(w).find(|(l, _)| l.0 == depth) else {
        return Err(CliError::Usage(format!("no level {depth} was built")));
    };
    let mut rows: Vec<_> = q
        .iter(w)
        .map(|l| {
            let (_, s) = level.row(l.row);
            (
                l.row,
                polyline_length(points.row(l.row)),
                s[s.len() - 1] - s[0],
            )
        })
        .collect();
    rows.sort_by_key(|r| r.0);
    let (mut max_abs, mut max_rel) = (0.0f64, 0.0f64);
    for (_, len, want) in &rows {
        let e = (len - want).abs();
        per.push(e);
        total += len;
        max_abs = max_abs.max(e);
        max_rel = max_rel.max(e / want.abs().max(f64::MIN_POSITIVE));
    }
    let stats = w.resource::<Stats>();
    let surface = w.resource::<SurfaceData>();
    let reference =
        (doc.reference.as_ref()).map(|link| reference_figures(link, &surface.points, scene.mirror));
    let report = BuildReport {
        scene: scene.name.clone(),
        depth: scene.display_depth,
        scheme: scene.design.scheme().name(),
        blend_order: scene.design.order().name(),
        entities,
        patches,
        seams,
        reference,
        levels: stats.levels.clone(),
        streamlines: surface.points.rows(),
        points_per_streamline: surface.points.cols(),
        triangles: surface.triangle_count(),
        total_length: total,
        length_error: LengthError {
            max_abs,
            max_rel,
            total_abs: per.iter().sum(),
            per_streamline: per,
        },
        timings_us: build_stats,
        warnings: w.resource::<BuildWarnings>().lines.clone(),
        export: a.export.clone(),
        faces: w
            .resource::<LastExport>()
            .written
            .iter()
            .flat_map(|(_, out)| {
                out.faces.iter().map(|f| FaceFigures {
                    name: f.name.clone(),
                    depth: out.depth,
                    poles: f.surface.pole_counts().into(),
                    tolerance: f.tolerance,
                    max_deviation: f.deviation.max,
                })
            })
            .collect(),
        fit: w
            .resource::<LastExport>()
            .written
            .as_ref()
            .and_then(|(_, out)| match out.faces.as_slice() {
                [f] => Some(FitFigures {
                    depth: out.depth,
                    degree: f.surface.degree().into(),
                    poles: f.surface.pole_counts().into(),
                    tolerance: f.tolerance,
                    max_deviation: f.deviation.max,
                    mean_deviation: f.deviation.mean,
                    seconds: out.seconds,
                }),
                _ => None,
            }),
    };
    write_stdout(&report)
}
