//! The bench rows that run the ECS pipeline, from an edit's message to the
//! updated mesh: a drag's frame on the car, one edit against a full rebuild,
//! authoring, fine tuning.

use super::workloads::{Workload, surface_row_named};
use streamline_kernel::DVec3;
use streamline_kernel::levels::presets;

/// An edit of a drag: tangent (`row`, `col`) turned 0.01 rad about `y`,
/// the other way each time (`sign` flips), so that a row alternates
/// between two states.
pub(super) fn wiggle(row: usize, col: usize, sign: &mut f64) -> crate::ecs::Edit {
    *sign = -*sign;
    crate::ecs::Edit::Rotate {
        row,
        col,
        axis: DVec3::Y,
        radians: 0.01 * *sign,
    }
}

/// A drag's frame on the car at `depth` as the editor runs it: control
/// tangent (2, 4) turned back and forth, with the mesh stage's `f32` staging
/// pair ([`crate::ecs::vertex_mirror::VertexMirror`]) that the editor's
/// renderer swaps in (`ecs/car/d6/drag`: the editor's drag frame at depth 6, less
/// the panels and the renderer); the same with the surface's `f64` normals left
/// behind as the editor leaves them while a handle is dragged
/// (`…/drag-deferred`, [`crate::ecs::DeferNormals`]); and the frame after
/// the drag, which makes them (`…/release`: the window of a drag's frame);
/// and `…/drag-deferred`'s frame with cold caches (`…/drag-cold`,
/// [`Workload::cold`]), as the editor runs it after a software-rendered
/// frame: the figure that tracks the editor's drag report headless.
pub fn car_drag(depth: u32) -> Vec<Workload> {
    use crate::ecs::{self, DeferNormals, SurfaceData, vertex_mirror::VertexMirror};
    use crate::scene::Scene;
    use streamline_kernel::parallel;
    let app = move |defer: bool| {
        let mut app = ecs::headless_app(Scene::from_design("car", presets::car1(), depth));
        app.init_resource::<VertexMirror>();
        app.insert_resource(DeferNormals(defer));
        app.update();
        app
    };
    // one thread, as the editor runs on a machine of fewer than four cores
    // (`editor::kernel_helper_wanted`)
    let frame = |app: &mut bevy::app::App, edit: Option<ecs::Edit>| {
        parallel::set_enabled(false);
        if let Some(edit) = edit {
            ecs::send(app, edit);
        }
        app.update();
        parallel::set_enabled(true);
        app.world().resource::<SurfaceData>().points.data()[0].x
    };
    let drag = move |name: &str, defer: bool| {
        Workload::lazy(format!("ecs/car/d{depth}/{name}"), move || {
            let mut app = app(defer);
            let mut sign = 1.0;
            Box::new(move || frame(&mut app, Some(wiggle(2, 4, &mut sign))))
        })
    };
    let release = Workload::lazy(format!("ecs/car/d{depth}/release"), move || {
        let mut app = app(true);
        let mut sign = 1.0;
        frame(&mut app, Some(wiggle(2, 4, &mut sign)));
        frame(&mut app, Some(wiggle(2, 4, &mut sign)));
        let behind = app.world().resource::<SurfaceData>().normals_behind();
        assert!(behind.is_some(), "a drag's frame leaves its normals behind");
        app.insert_resource(DeferNormals(false));
        Box::new(move || {
            app.world_mut().resource_mut::<SurfaceData>().normals_behind = behind;
            frame(&mut app, None)
        })
    });
    // the editor's frame after a software-rendered one (`bench` only)
    let mut cold = drag("drag-cold", true);
    cold.cold = true;
    vec![
        drag("drag", false),
        drag("drag-deferred", true),
        cold,
        release,
    ]
}

/// Authoring on the car at depth 5 (`docs/math.md §9`), each
/// from message to updated mesh: a row inserted and deleted in turn
/// (`ecs/car/d5/insert-row`, a full rebuild each), an initial-curve tangent
/// turned back and forth (`ecs/car/d5/initial-curve`: every streamline
/// placed again, no tangent re-blended; compare `ecs/car/d5/edit-interior`),
/// and the mirrored car (11 doubled rows): its full build beside the plain
/// one's (`surface/kobbelt/9x6-mirrored/d5/full`) and a tangent edit
/// (`ecs/car-mirrored/d5/edit-interior`: both copies of the cell re-blended).
pub fn authoring() -> Vec<Workload> {
    use crate::ecs::{self, Edit, SurfaceData, authoring::AuthorEdit};
    use crate::scene::Scene;
    use streamline_kernel::authoring::Axis;
    let depth = 5;
    let app_of = move |mirror: bool| {
        let mut scene = Scene::from_design("car", presets::car1(), depth);
        scene.mirror = mirror;
        ecs::headless_app(scene)
    };
    let point = |app: &bevy::prelude::App| app.world().resource::<SurfaceData>().points.data()[0].x;
    let mut out = Vec::new();
    out.push(Workload::lazy(
        format!("ecs/car/d{depth}/insert-row"),
        move || {
            let mut app = app_of(false);
            let mut inserted = false;
            Box::new(move || {
                let axis = Axis::Row;
                inserted = !inserted;
                let edit = if inserted {
                    AuthorEdit::insert(axis, 3)
                } else {
                    AuthorEdit::delete(axis, 3)
                };
                ecs::send(&mut app, Edit::Author(edit));
                app.update();
                point(&app)
            })
        },
    ));
    out.push(Workload::lazy(
        format!("ecs/car/d{depth}/initial-curve"),
        move || {
            let mut app = app_of(false);
            let mut sign = 1.0;
            Box::new(move || {
                sign = -sign;
                let edit = AuthorEdit::RotateInitial {
                    index: 1,
                    axis: DVec3::X,
                    radians: 0.01 * sign,
                };
                ecs::send(&mut app, Edit::Author(edit));
                app.update();
                point(&app)
            })
        },
    ));
    let mirrored = presets::car1().mirrored().expect("the car mirrors");
    out.push(surface_row_named(
        mirrored,
        format!("surface/kobbelt/9x6-mirrored/d{depth}/full"),
        depth,
    ));
    out.push(Workload::lazy(
        format!("ecs/car-mirrored/d{depth}/edit-interior"),
        move || {
            let mut app = app_of(true);
            let mut sign = 1.0;
            Box::new(move || {
                let edit = wiggle(2, 4, &mut sign);
                ecs::send(&mut app, edit);
                app.update();
                point(&app)
            })
        },
    ));
    out
}

/// One fine-tuning control-value edit on the car at depth 3 (3×3 quadratic
/// function, paper 003's surfaces), from message to updated mesh (docs/math.md §6),
/// free and with every streamline's ends kept, beside the same app's tangent
/// edit. Rows: `tune/car/d3/<free|keep-ends>`.
pub fn fine_tuning() -> Vec<Workload> {
    use crate::ecs::{self, Edit, SurfaceData};
    use crate::scene::Scene;
    use streamline_kernel::finetune::{Constraint, SurfaceTuning};
    [
        ("free", Constraint::Free),
        ("keep-ends", Constraint::KeepEnds),
    ]
    .into_iter()
    .map(|(what, constraint)| {
        Workload::lazy(format!("tune/car/d3/{what}"), move || {
            let mut scene = Scene::from_design("car", presets::car1(), 3);
            scene.tuning = Some(SurfaceTuning {
                constraint,
                ..SurfaceTuning::identity()
            });
            let mut app = ecs::headless_app(scene);
            let mut flip = false;
            Box::new(move || {
                flip = !flip;
                let value = if flip { 1.3 } else { 0.8 };
                ecs::send(
                    &mut app,
                    Edit::SetTuningValue {
                        row: 1,
                        col: 1,
                        value,
                    },
                );
                app.update();
                app.world().resource::<SurfaceData>().points.data()[0].x
            })
        })
    })
    .collect()
}

/// Marks the patch's [`PatchStructure`](crate::ecs::patch::PatchStructure)
/// changed, so that the next update builds every level and streamline afresh.
fn force_full_build(app: &mut bevy::prelude::App) {
    use crate::ecs::patch::{PatchStructure, patch_entity};
    use bevy::prelude::DetectChangesMut;
    let w = app.world_mut();
    if let Some(mut st) = patch_entity(w).and_then(|p| w.get_mut::<PatchStructure>(p)) {
        st.set_changed();
    }
}

/// One edit through the ECS pipeline (message → blend → integrate → mesh) vs a
/// full rebuild, on the car and on a 20×20 net, at depths 3 and 5 (docs/math.md §5).
/// Rows: `ecs/<net>/d<depth>/<edit-interior|edit-corner|full>`; `full` sends
/// the blend order the design has and builds everything afresh.
pub fn incremental() -> Vec<Workload> {
    use crate::ecs::{self, Edit, SurfaceData};
    use crate::scene::Scene;
    let mut out = Vec::new();
    for (net, design, interior) in [
        ("car", presets::car1(), (2usize, 4usize)),
        ("grid20", presets::wavy(20, 20), (10, 9)),
    ] {
        for depth in [3u32, 5] {
            let cases = [
                ("edit-interior", Some(interior)),
                ("edit-corner", Some((0, 0))),
                ("full", None),
            ];
            for (what, cell) in cases {
                let design = design.clone();
                out.push(Workload::lazy(
                    format!("ecs/{net}/d{depth}/{what}"),
                    move || {
                        let order = design.order();
                        let mut app = ecs::headless_app(Scene::from_design(net, design, depth));
                        let mut sign = 1.0;
                        Box::new(move || {
                            let edit = match cell {
                                Some((row, col)) => {
                                    sign = -sign;
                                    Edit::Rotate {
                                        row,
                                        col,
                                        axis: DVec3::Y,
                                        radians: 0.01 * sign,
                                    }
                                }
                                None => Edit::SetBlendOrder(order),
                            };
                            ecs::send(&mut app, edit);
                            if cell.is_none() {
                                // the order it has changes no component, so asks
                                // for no build: mark the patch's
                                // structure changed, as a structural edit does
                                force_full_build(&mut app);
                            }
                            app.update();
                            app.world().resource::<SurfaceData>().points.data()[0].x
                        })
                    },
                ));
            }
        }
    }
    out
}
