//! Bench rows of designs of several patches (docs/math.md §11): a tangent edit
//! in the first, the middle and the last of three G1-chained cars at depth 5
//! (`ecs/patches/car-x3/d5/edit-first`: the first patch's incremental
//! pipeline, then the cars on it placed again on its moved end;
//! `…/edit-middle`, `…/edit-last`: that car's kept levels re-blended in the
//! edit's window, `joins::patch_state`) beside the same edit with the car
//! alone (`ecs/patches/car-x1/d5/edit-first`);
//! the same three cars G2-chained, edited in the first car and in the last
//! (`ecs/patches/car-g2x3/d5/edit-first`, `…/edit-last`: the run kept
//! between edits, `joins::g2_state`), and the kernel's G2 run after an edit
//! of the first car updated in place beside built whole
//! (`joins/car-g2x3/d5/update`, `joins/car-g2x3/d5/whole`); and the shipped
//! `scenes/hood-screen-wing.ron` at depth 6, its hood's tangent (2, 4) (the
//! seam column of its G2 run with the screen, the wing side-joined on the
//! hood) turned back and forth (`ecs/patches/hood-screen-wing/d6/edit-hood`).

use super::workloads::Workload;
use crate::scene::design::document::{Document, PatchScene, Start};
use crate::scene::edits::patch_edit::PatchEdit;
use crate::scene::{Scene, design::document::MAIN_PATCH};
use streamline_kernel::joins::g2_state::G2State;
use streamline_kernel::joins::merged::g2_run;
use streamline_kernel::joins::{Continuity, Edge, Join};
use streamline_kernel::levels::presets;
use streamline_kernel::{DQuat, Design};

/// The car, and `n - 1` copies chained on its `End` edge one after the
/// other with G1 (each copy's first column the previous one's last, its
/// rows the car's, anchor 0), at display depth `depth`.
pub fn chained_cars(n: usize, depth: u32) -> Document {
    chained_cars_with(n, depth, Continuity::G1)
}

/// [`chained_cars`] with the given continuity at every seam.
pub fn chained_cars_with(n: usize, depth: u32, continuity: Continuity) -> Document {
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
                    continuity,
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
    use crate::ecs::{self, Edit, ModelConfig};
    let depth = 5;
    let mut out = Vec::new();
    let rows = [
        ("car-x1", 1, Continuity::G1, 0),
        ("car-x3", 3, Continuity::G1, 0),
        ("car-x3", 3, Continuity::G1, 1),
        ("car-x3", 3, Continuity::G1, 2),
        ("car-g2x3", 3, Continuity::G2, 0),
        ("car-g2x3", 3, Continuity::G2, 2),
    ];
    for (name, n, continuity, patch) in rows {
        let which = match patch {
            0 => "first",
            p if p + 1 == n => "last",
            _ => "middle",
        };
        let row = format!("ecs/patches/{name}/d{depth}/edit-{which}");
        out.push(Workload::lazy(row, move || {
            let doc = chained_cars_with(n, depth, continuity);
            let mut app = ecs::headless_document_app(&doc, None, ModelConfig::default());
            if patch > 0 {
                let target = doc.patches[patch].name.clone();
                ecs::apply(&mut app, Edit::Patch(PatchEdit::SetPatch(target)))
                    .expect("the patch exists");
            }
            wiggling(app)
        }));
    }
    out.push(Workload::lazy(
        "ecs/patches/hood-screen-wing/d6/edit-hood".into(),
        || {
            let text = include_str!("../../../scenes/hood-screen-wing.ron");
            let mut doc = Document::parse(text, std::path::Path::new("hood-screen-wing.ron"))
                .expect("the shipped scene reads");
            doc.display_depth = 6;
            wiggling(ecs::headless_document_app(
                &doc,
                None,
                ModelConfig::default(),
            ))
        },
    ));
    out.extend(kernel_rows(depth));
    out
}

/// One run of a row: the active patch's tangent (2, 4) turned one way or
/// back ([`super::ecs_rows::wiggle`]), then one update of `app`.
fn wiggling(mut app: bevy::app::App) -> Box<dyn FnMut() -> f64> {
    use crate::ecs::{self, SurfaceData};
    let mut sign = 1.0;
    Box::new(move || {
        let edit = super::ecs_rows::wiggle(2, 4, &mut sign);
        ecs::send(&mut app, edit);
        app.update();
        app.world().resource::<SurfaceData>().points.data()[0].x
    })
}

/// The kernel's G2 run of three cars: an edit of the first car's tangent
/// (2, 4) updated in place (`G2State::update`) beside built whole
/// (`g2_run`), each turning it back and forth.
fn kernel_rows(depth: u32) -> Vec<Workload> {
    let doc = chained_cars_with(3, depth, Continuity::G2);
    let designs: Vec<Design> = doc.patches.iter().map(|p| p.design.clone()).collect();
    let turned = |sign: f64, designs: &mut [Design]| {
        let v = DQuat::from_rotation_y(0.01 * sign) * designs[0].net().get(2, 4);
        designs[0].set_tangent(2, 4, v).expect("a unit tangent");
    };
    let mut out = Vec::new();
    let mut mine = designs.clone();
    out.push(Workload::lazy(
        format!("joins/car-g2x3/d{depth}/update"),
        move || {
            let (mut state, mut stacks) = {
                let refs: Vec<&Design> = mine.iter().collect();
                G2State::build(&refs, depth).expect("the cars are a G2 run")
            };
            let mut sign = 1.0;
            Box::new(move || {
                sign = -sign;
                turned(sign, &mut mine);
                let refs: Vec<&Design> = mine.iter().collect();
                let u = state.update(&refs, depth, &mut stacks).expect("updated");
                u.reblended as f64 + stacks[2].finest_points().data()[0].x
            })
        },
    ));
    let mut mine = designs;
    let mut sign = 1.0;
    out.push(Workload {
        name: format!("joins/car-g2x3/d{depth}/whole"),
        cold: false,
        run: Box::new(move || {
            sign = -sign;
            turned(sign, &mut mine);
            let refs: Vec<&Design> = mine.iter().collect();
            let stacks = g2_run(&refs, depth).expect("built");
            stacks[2].finest_points().data()[0].x
        }),
    });
    out
}
