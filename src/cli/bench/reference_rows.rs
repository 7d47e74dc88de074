//! Starting from what exists (docs/math.md §12, docs/fit.md): a design fitted
//! to a face of a STEP or IGES file, and its deviation measured against it.
//!
//! - `reference-fit/{hood,duct,roof}/d5`: the whole fit of the shipped face
//!   (`scenes/references/`) at the default options (within 1e-4 of the face's
//!   diagonal, measured at depth 5), as `streamline-studio fit` runs it (the
//!   kernel's helper thread on); the file is read once, outside the timing;
//! - `reference-fit/{hood,duct,roof}/d5/1t`: the same on one thread, as
//!   OpenCascade's fitter runs (`scripts/reference_peers.py`);
//! - `reference-deviation/hood/d5`: every point of the shipped fitted design
//!   `scenes/references/hood.ron` at depth 5 (257 × 226 points) to its face, by
//!   a [`ClosestPoints`] of the face made once outside the timing, as a
//!   deviation map of the edited design would keep it (the design's build
//!   outside too);
//! - `reference-deviation/car/d5`: the car at depth 5 (161 × 258 points)
//!   against its own depth-4 B-spline export (docs/math.md §10), a
//!   car-sized face, likewise;
//! - `reference-deviation/car/index`: that [`ClosestPoints`] made: the dense
//!   sample of the face and its k-d tree, paid once a reference.
//!
//! The rows of a shipped file are left out when the checkout's file is
//! missing (an installed binary).

use super::workloads::Workload;
use crate::scene::io;
use std::path::{Path, PathBuf};
use streamline_kernel::fit::{ClosestPoints, ReferenceFitOptions, fit_reference};
use streamline_kernel::levels::presets;
use streamline_kernel::nurbs::rational::NurbsSurface;
use streamline_kernel::nurbs::{FitOptions, fit_design};
use streamline_kernel::parallel;

/// The fit depth of the rows (the default).
const DEPTH: u32 = 5;

fn shipped(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("scenes/references")
        .join(name)
}

/// Face 0 of a shipped reference file, kept for the rest of the run (a
/// [`ClosestPoints`] borrows its face; a row's setup runs once).
fn face_of(path: &Path) -> &'static NurbsSurface {
    let file = streamline_reference::read(path).expect("the shipped reference reads");
    let surface = file.surface(0).expect("face 0 is a B-spline").clone();
    Box::leak(Box::new(surface))
}

fn fit_row(label: &'static str, file: &'static str, one_thread: bool) -> Workload {
    let suffix = if one_thread { "/1t" } else { "" };
    Workload::lazy(
        format!("reference-fit/{label}/d{DEPTH}{suffix}"),
        move || {
            let path = shipped(file);
            let file = streamline_reference::read(&path).expect("the shipped reference reads");
            let surface = file.surface(0).expect("face 0 is a B-spline").clone();
            let opts = ReferenceFitOptions {
                depth: DEPTH,
                ..ReferenceFitOptions::default()
            };
            Box::new(move || {
                if one_thread {
                    parallel::set_enabled(false);
                }
                let f = fit_reference(&surface, &opts);
                parallel::set_enabled(true);
                let f = f.expect("the shipped face fits");
                f.to_reference.max + (f.net.0 * f.net.1) as f64
            })
        },
    )
}

/// The rows (module docs).
pub fn rows() -> Vec<Workload> {
    let faces = [
        ("hood", "hood.step"),
        ("duct", "duct.igs"),
        ("roof", "roof.step"),
    ];
    let present: Vec<_> = faces
        .into_iter()
        .filter(|(_, f)| shipped(f).exists())
        .collect();
    let mut rows: Vec<Workload> = present
        .iter()
        .map(|&(label, file)| fit_row(label, file, false))
        .collect();
    rows.extend(
        present
            .iter()
            .map(|&(label, file)| fit_row(label, file, true)),
    );
    let hood = shipped("hood.ron");
    if hood.exists() && shipped("hood.step").exists() {
        rows.push(Workload::lazy(
            format!("reference-deviation/hood/d{DEPTH}"),
            move || {
                let scene = io::load(&hood).expect("the shipped design loads");
                let link = scene.reference.as_ref().expect("it names its face");
                let face = face_of(&link.path);
                let index = ClosestPoints::new(face).expect("the face samples");
                let built = scene.design.build(DEPTH).expect("the design builds");
                let points = built.points.data().to_vec();
                Box::new(move || {
                    let d = index.distances(&points);
                    d.iter().copied().fold(0.0, f64::max)
                })
            },
        ));
    }
    rows.push(Workload::lazy(
        format!("reference-deviation/car/d{DEPTH}"),
        move || {
            let (face, points) = car_reference();
            let index = ClosestPoints::new(face).expect("the export samples");
            Box::new(move || {
                let d = index.distances(&points);
                d.iter().copied().fold(0.0, f64::max)
            })
        },
    ));
    rows.push(Workload::lazy(
        "reference-deviation/car/index".into(),
        move || {
            let (face, _) = car_reference();
            Box::new(move || {
                let index = ClosestPoints::new(face).expect("the export samples");
                index.samples() as f64
            })
        },
    ));
    rows
}

/// The car's depth-4 B-spline export as a face, and the car's points at
/// depth 5.
fn car_reference() -> (&'static NurbsSurface, Vec<streamline_kernel::DVec3>) {
    let car = presets::car1();
    let exported = fit_design(&car, 4, &FitOptions::default()).expect("the car exports");
    let face = Box::leak(Box::new(NurbsSurface::from_bspline(&exported.surface)));
    let built = car.build(DEPTH).expect("the car builds");
    (face, built.points.data().to_vec())
}
