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
//! - `reference-deviation/hood/d5/drag-row`: what the editor's map measures
//!   again in a frame of a drag of tangent (4, 3), a handle of the hood's
//!   net (depth 0): the window of points the drag moves (189 rows × 223
//!   columns, 42,147 of the 58,082 points) measured, the other points' distances
//!   kept, the largest and mean distance of all made again
//!   ([`ReferenceField::update`]);
//! - `reference-deviation/hood/d5/drag-frame`: a whole frame of that drag
//!   headless on one thread, as the editor runs on a machine of fewer than
//!   four cores: the edit, the streamlines integrated again, the mesh and
//!   the map's measure (no panels, no renderer);
//! - `reference-deviation/car/d5`: the car at depth 5 (161 × 258 points)
//!   against its own depth-4 B-spline export (docs/math.md §10), a
//!   car-sized face, likewise;
//! - `reference-deviation/car/index`: that [`ClosestPoints`] made: the dense
//!   sample of the face and its k-d tree, paid once a reference.
//!
//! The rows of a shipped file are left out when the checkout's file is
//! missing (an installed binary).

use super::workloads::Workload;
use crate::editor::ReferenceField;
use crate::scene::design::document_io;
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
                let scene = document_io::load_scene(&hood).expect("the shipped design loads");
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
    if shipped("hood.ron").exists() && shipped("hood.step").exists() {
        rows.extend(hood_drag());
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

/// The handle of the hood's net the drag rows turn.
const HOOD_HANDLE: (usize, usize) = (4, 3);

/// The shipped hood in a windowless editor with its map to the reference
/// shown (the model, the interaction core and the map; as
/// `tests/editor_reference_map.rs`), one thread, measured once.
fn hood_editor() -> bevy::app::App {
    use crate::ecs::ModelPlugin;
    use crate::editor::ReferenceMapPlugin;
    use crate::editor::interaction::InteractionPlugin;
    use bevy::prelude::*;
    let doc = crate::scene::design::document_io::load(&shipped("hood.ron"))
        .expect("the shipped design loads");
    let mut app = App::new();
    app.add_plugins(MinimalPlugins)
        .init_resource::<ButtonInput<MouseButton>>()
        .init_resource::<ButtonInput<KeyCode>>()
        .add_plugins(ModelPlugin::new(doc.patch_scene(0)))
        .add_plugins(InteractionPlugin)
        .add_plugins(ReferenceMapPlugin);
    app.edit_schedule(Update, |s| {
        s.set_executor(bevy::ecs::schedule::SingleThreadedExecutor::new());
    });
    app.world_mut().resource_mut::<ReferenceField>().shown = true;
    app.update();
    app.update();
    app
}

/// The hood's drag rows (module docs).
fn hood_drag() -> Vec<Workload> {
    use crate::ecs::{self, SurfaceChange, SurfaceData};
    let (row, col) = HOOD_HANDLE;
    let measured = Workload::lazy(
        format!("reference-deviation/hood/d{DEPTH}/drag-row"),
        move || {
            let mut app = hood_editor();
            let mut sign = 1.0;
            ecs::send(&mut app, super::ecs_rows::wiggle(row, col, &mut sign));
            app.update();
            let points = app.world().resource::<SurfaceData>().points.clone();
            let mut field = std::mem::take(&mut *app.world_mut().resource_mut::<ReferenceField>());
            let window = field.window.expect("a tangent's drag measures its window");
            Box::new(move || {
                field.note(SurfaceChange::Window(window));
                field.update(&points, false);
                field.distances.max
            })
        },
    );
    let frame = Workload::lazy(
        format!("reference-deviation/hood/d{DEPTH}/drag-frame"),
        move || {
            let mut app = hood_editor();
            let mut sign = 1.0;
            Box::new(move || {
                parallel::set_enabled(false);
                ecs::send(&mut app, super::ecs_rows::wiggle(row, col, &mut sign));
                app.update();
                parallel::set_enabled(true);
                app.world().resource::<ReferenceField>().distances.max
            })
        },
    );
    vec![measured, frame]
}
