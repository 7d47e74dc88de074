//! Bench rows of designs of several patches (issue 28 item 7, docs/math.md
//! §11): a tangent edit in the first of three chained cars at depth 5
//! (`ecs/patches/car-x3/d5/edit-first`: the first patch's incremental
//! pipeline, then the joined patches rebuilt through the kernel's joins)
//! beside the same edit with the car alone (`ecs/patches/car-x1/d5/edit-first`).

use super::workloads::Workload;
use crate::scene::document::{Document, PatchScene, Start};
use crate::scene::{Scene, document::MAIN_PATCH};
use streamline_kernel::joins::{Continuity, Edge, Join};
use streamline_kernel::levels::presets;
use streamline_kernel::{DVec3, Design};

/// The car, and `n - 1` copies chained on its `End` edge one after the
/// other with G1 (each copy's first column the previous one's last, its
/// rows the car's, anchor 0), at display depth `depth`.
pub fn chained_cars(n: usize, depth: u32) -> Document {
    let car = presets::car1();
    let mut doc = Document::from_scene(Scene::from_design("cars", car.clone(), depth));
    let last = car.net().cols() - 1;
    let mut net = car.net().clone();
    for r in 0..net.rows() {
        net.set(r, 0, car.net().get(r, last));
    }
    let copy = Design::new(
        &net,
        car.params().s.clone(),
        car.params().t.clone(),
        0,
        car.scheme(),
        car.order(),
        car.initial().clone(),
    )
    .expect("the car's net with its last column first is a design");
    for k in 1..n {
        let parent = doc.patches[k - 1].name.clone();
        doc.patches.push(PatchScene {
            name: format!("car{k}"),
            start: Start::Edge {
                patch: if k == 1 { MAIN_PATCH.into() } else { parent },
                join: Join {
                    edge: Edge::End,
                    continuity: Continuity::G1,
                },
            },
            design: copy.clone(),
            details: Default::default(),
            tuning: None,
            interpolate_tangents: false,
        });
    }
    doc
}

/// The rows (module documentation).
pub fn rows() -> Vec<Workload> {
    use crate::ecs::{self, Edit, ModelConfig, SurfaceData};
    let depth = 5;
    let mut out = Vec::new();
    for n in [1usize, 3] {
        let doc = chained_cars(n, depth);
        let mut app = ecs::headless_document_app(&doc, None, ModelConfig::default());
        let mut sign = 1.0;
        out.push(Workload {
            name: format!("ecs/patches/car-x{n}/d{depth}/edit-first"),
            run: Box::new(move || {
                sign = -sign;
                let edit = Edit::Rotate {
                    row: 2,
                    col: 4,
                    axis: DVec3::Y,
                    radians: 0.01 * sign,
                };
                ecs::send(&mut app, edit);
                app.update();
                app.world().resource::<SurfaceData>().points.data()[0].x
            }),
        });
    }
    out
}
