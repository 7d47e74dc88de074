//! Every patch is a whole patch (docs/math.md §5, §6, §7, §11): details,
//! fine tuning and tangent interpolation on any patch of a design of
//! several, joined or not, kept through save and load, through the ECS
//! world and its edits, undo and redo, and built so that the joins still
//! hold: a G1 chain's seam column stays its parent's (gap 0, normals
//! equal), a side G1 join's first column lies in the parent's tangent plane
//! after the detail, and a patch on its own curve is what the one-patch
//! pipeline builds of it. Random three-patch designs, each measure with a
//! negative control.

use bevy::prelude::*;
use proptest::prelude::*;
use streamline_kernel::finetune::{Constraint, SurfaceTuning};
use streamline_kernel::joins::edge_curve::EdgeCurve;
use streamline_kernel::joins::{Continuity, Edge};
use streamline_kernel::{DVec3, Grid};
use streamline_studio::ecs::joined::{PatchSlot, PatchSurface, world_io};
use streamline_studio::ecs::patch::Patch;
use streamline_studio::ecs::{self, Edit, ModelConfig, SurfaceData};
use streamline_studio::scene::design::document::{Document, Start};
use streamline_studio::scene::design::document_io::{load, save};
use streamline_studio::scene::edits::patch_edit::PatchEdit;

fn rng(seed: u64) -> impl FnMut() -> f64 {
    let mut x = seed | 1;
    move || {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        (x >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    }
}

/// `p0` on its own curve; `p1` chained on `p0`'s End (`chain`); `p2` on
/// `p0`'s edge `side` (`side_c`); every patch `rows × cols`-ish with nets
/// leaning along x, `scheme` for all. No features yet.
fn three(seed: u64, scheme: &str, chain: &str, side: &str, side_c: &str) -> Document {
    let mut rnd = rng(seed);
    let mut dir = |lean: DVec3| {
        let v = lean + DVec3::new(0.15 * rnd(), 0.15 * rnd(), 0.15 * rnd());
        let v = v.normalize();
        format!("({}, {}, {})", v.x, v.y, v.z)
    };
    let net = |rows: usize, cols: usize, lean: DVec3, dir: &mut dyn FnMut(DVec3) -> String| {
        let rows: Vec<String> = (0..rows)
            .map(|_| {
                let r: Vec<String> = (0..cols).map(|_| dir(lean)).collect();
                format!("[{}]", r.join(", "))
            })
            .collect();
        format!("[{}]", rows.join(", "))
    };
    let s = |rows: usize, cols: usize| {
        let r: Vec<String> = (0..cols).map(|c| format!("{}", 0.3 * c as f64)).collect();
        format!("[{}]", vec![format!("[{}]", r.join(", ")); rows].join(", "))
    };
    let (rows, cols) = (4, 5);
    let a_net = net(rows, cols, DVec3::X, &mut dir);
    let b_net = net(rows, 4, DVec3::X, &mut dir);
    let out = if side == "First" { -DVec3::Y } else { DVec3::Y };
    let c_net = net(4, 4, (out - 0.3 * DVec3::Z).normalize(), &mut dir);
    let text = format!(
        r#"(
    version: 3,
    name: "three",
    display_depth: 3,
    patches: [
        (
            name: "p0",
            tangents: {a_net},
            s: {sa},
            t: [0.0, 0.4, 0.8, 1.2],
            initial: Curve(tangents: [(0.0, 1.0, 0.1), (0.0, 1.0, 0.0), (0.0, 1.0, -0.1)], order: 3, length: 1.2, origin: (0.0, 0.0, 0.0)),
            scheme: {scheme},
        ),
        (
            name: "p1",
            tangents: {b_net},
            s: {sb},
            t: [0.0, 0.4, 0.8, 1.2],
            initial: Edge(patch: "p0", edge: End, continuity: G0),
            scheme: {scheme},
        ),
        (
            name: "p2",
            tangents: {c_net},
            s: {sc},
            t: [0.15, 0.45, 0.75, 1.05],
            initial: Edge(patch: "p0", edge: {side}, continuity: {side_c}),
            scheme: {scheme},
        ),
    ],
)"#,
        sa = s(rows, cols),
        sb = s(rows, 4),
        sc = s(4, 4),
    );
    let mut doc =
        Document::parse(&text, std::path::Path::new("three.ron")).unwrap_or_else(|e| panic!("{e}"));
    // a G1 or G2 chain's first column is p0's last (one handle)
    let continuity = match chain {
        "G1" => Continuity::G1,
        "G2" => Continuity::G2,
        _ => return doc,
    };
    let a = doc.patches[0].design.net().clone();
    let mut b = doc.patches[1].design.net().clone();
    for r in 0..b.rows() {
        b.set(r, 0, a.get(r, a.cols() - 1));
    }
    doc.patches[1].design.set_net(&b).unwrap();
    if let Start::Edge { join, .. } = &mut doc.patches[1].start {
        join.continuity = continuity;
    }
    doc
}

/// A random detail of level `level` at `(row, col)`.
fn detail(rnd: &mut impl FnMut() -> f64) -> DVec3 {
    DVec3::new(0.3 * rnd(), 0.3 * rnd(), 1.0).normalize()
}

/// A random fine tuning: 3×3 quadratic values in [0.8, 1.2], a constraint.
fn tuning(rnd: &mut impl FnMut() -> f64, keep_ends: bool) -> SurfaceTuning {
    let mut t = SurfaceTuning::identity();
    for r in 0..3 {
        for c in 0..3 {
            t.function.set(r, c, 1.0 + 0.2 * rnd()).unwrap();
        }
    }
    t.constraint = if keep_ends {
        Constraint::KeepEnds
    } else {
        Constraint::Free
    };
    t
}

/// Gives every patch details (levels 1 and 2, never a G1 chain's seam
/// column), a fine tuning and, with an approximating scheme, tangent
/// interpolation.
fn with_features(mut doc: Document, seed: u64) -> Document {
    let mut rnd = rng(seed ^ 0x5eed);
    for i in 0..doc.patches.len() {
        let seam = matches!(&doc.patches[i].start, Start::Edge { join, .. }
            if join.edge == Edge::End && join.continuity != Continuity::G0);
        let p = &mut doc.patches[i];
        for level in 1..=2u32 {
            let col = if seam { 2 } else { (level as usize) % 3 };
            p.details.insert((level, 1, col), detail(&mut rnd));
        }
        p.tuning = Some(tuning(&mut rnd, seed.is_multiple_of(2)));
        p.interpolate_tangents = true;
    }
    doc
}

/// Every patch's own fields and the document's text, for comparisons.
fn fields(doc: &Document) -> Vec<String> {
    let mut out = vec![doc.to_ron()];
    for p in &doc.patches {
        let tuning = p.tuning.as_ref().map(|t| {
            let f = &t.function;
            (f.degree_s(), f.degree_t(), f.values().clone(), t.constraint)
        });
        out.push(format!(
            "{} {:?} {:?} {}",
            p.name, p.details, tuning, p.interpolate_tangents
        ));
    }
    out
}

fn tmp(tag: &str) -> std::path::PathBuf {
    let d = std::env::temp_dir().join(format!("ss-features-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn scheme_of(seed: u64) -> &'static str {
    ["CatmullClark", "DooSabin", "Kobbelt(omega: 1.0)"][(seed % 3) as usize]
}

fn app(doc: &Document) -> App {
    ecs::headless_document_app(doc, None, ModelConfig::default())
}

fn entities(app: &mut App) -> Vec<Entity> {
    let w = app.world_mut();
    let mut q = w.query_filtered::<(Entity, &PatchSlot), With<Patch>>();
    let mut v: Vec<_> = q.iter(w).map(|(e, s)| (s.index, e)).collect();
    v.sort();
    v.into_iter().map(|(_, e)| e).collect()
}

fn finest(app: &App, e: Entity) -> Grid<DVec3> {
    match &app.world().get::<PatchSurface>(e).unwrap().built {
        Some(Ok(s)) => s.finest_points().clone(),
        other => panic!("not built: {other:?}"),
    }
}

fn bits(g: &Grid<DVec3>) -> Vec<[u64; 3]> {
    g.data()
        .iter()
        .map(|p| p.to_array().map(f64::to_bits))
        .collect()
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 12, ..ProptestConfig::default() })]

    /// Each field on each patch of a random three-patch design is saved
    /// and read back as it was, and so is it after the ECS world holds the
    /// design (what the editor and the command line save). Negative
    /// control: the design without one patch's details compares unequal.
    #[test]
    fn every_field_on_every_patch_survives_save_load_and_the_world(seed in any::<u64>()) {
        let doc = with_features(three(seed, scheme_of(seed), "G1", "Last", "G1"), seed);
        let dir = tmp(&format!("rt-{seed}"));
        let path = dir.join("three.ron");
        save(&doc, &path).unwrap();
        let back = load(&path).unwrap();
        for (x, y) in fields(&back).iter().zip(fields(&doc)) {
            if *x != y {
                let at = x.chars().zip(y.chars()).take_while(|(a, b)| a == b).count();
                panic!("differ at {at}: {:?} vs {:?}", &x[at.saturating_sub(80)..(at + 80).min(x.len())], &y[at.saturating_sub(80)..(at + 80).min(y.len())]);
            }
        }
        let mut app = app(&doc);
        let world = world_io::document(app.world()).unwrap();
        prop_assert_eq!(fields(&world), fields(&doc));
        // each patch's surface is the document's build, bit for bit
        let built = doc.build(doc.display_depth).unwrap();
        for (i, e) in entities(&mut app).into_iter().enumerate() {
            prop_assert_eq!(bits(&finest(&app, e)), bits(built.patches[i].finest_points()), "patch {}", i);
        }
        let mut less = doc.clone();
        less.patches[2].details.clear();
        prop_assert_ne!(fields(&less), fields(&doc));
        let _ = std::fs::remove_dir_all(dir);
    }

    /// A G1 chain with details and fine tuning on both patches: at every
    /// depth the seam's gap is 0 and its normals agree (the seam column is
    /// the parent's, details and all; tuning scales speed, not direction).
    /// Negative control: the same design chained G0 with its seam column
    /// turned has a normal angle of degrees.
    #[test]
    fn a_g1_chain_holds_with_details_and_tuning_on_both_sides(seed in any::<u64>()) {
        let doc = with_features(three(seed, scheme_of(seed), "G1", "First", "G0"), seed);
        for d in 1..=3u32 {
            let b = doc.build(d).unwrap();
            let s = b.seams.iter().find(|s| s.b == 1).unwrap();
            prop_assert!(s.report.gap <= 1e-12, "depth {}: gap {}", d, s.report.gap);
            prop_assert!(s.report.angle_deg <= 1e-6, "depth {}: angle {}°", d, s.report.angle_deg);
        }
        let mut g0 = three(seed, scheme_of(seed), "G0", "First", "G0");
        let mut net = g0.patches[1].design.net().clone();
        for r in 0..net.rows() {
            let v = net.get(r, 0);
            net.set(r, 0, (v + 0.4 * DVec3::Z).normalize());
        }
        g0.patches[1].design.set_net(&net).unwrap();
        let g0 = with_features(g0, seed);
        let s = g0.build(3).unwrap().seams.into_iter().find(|s| s.b == 1).unwrap();
        prop_assert!(s.report.angle_deg > 1.0, "G0 control: {}°", s.report.angle_deg);
    }

    /// A side G1 join with a detail on its first column: after every step
    /// the detail applies first and the projection (Eq. 73) after it, so at
    /// every depth each first-column tangent is perpendicular to the
    /// parent's normal there. Negative control: the same join G0 keeps the
    /// detail's direction, off the plane.
    #[test]
    fn a_side_g1_projection_applies_after_the_detail(seed in any::<u64>(), last in any::<bool>()) {
        let side = if last { "Last" } else { "First" };
        let edge = if last { Edge::Last } else { Edge::First };
        let worst = |c: &str| {
            let mut doc = with_features(three(seed, scheme_of(seed), "G1", side, c), seed);
            let mut rnd = rng(seed ^ 7);
            for level in 1..=3u32 {
                doc.patches[2].details.insert((level, 1, 0), detail(&mut rnd));
            }
            let b = doc.build(3).unwrap();
            let mut worst = 0.0f64;
            for d in 0..=3u32 {
                let curve = EdgeCurve::of(&b.patches[0], d, edge).unwrap();
                let level = &b.patches[2].levels[d as usize];
                for r in 0..level.tangents.rows() {
                    if let Some(n) = curve.normal(level.params.t[r]) {
                        worst = worst.max(level.tangents.get(r, 0).dot(n).abs());
                    }
                }
            }
            worst
        };
        let g1 = worst("G1");
        prop_assert!(g1 <= 1e-12, "G1: |T·n| = {}", g1);
        let g0 = worst("G0");
        prop_assert!(g0 > 1e-3, "G0 control: |T·n| = {}", g0);
    }
}

/// A patch on its own initial curve, with details, fine tuning and
/// tangent interpolation, is built as the one-patch pipeline (the
/// incremental ECS layer of a scene) builds it on its own; without them it
/// differs (the fields have effect).
#[test]
fn a_later_patch_on_its_own_curve_is_what_one_patch_builds() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/features");
    for file in ["two-details.ron", "two-tuning.ron", "two-interpolate.ron"] {
        let mut doc = load(&dir.join(file)).unwrap();
        if file == "two-interpolate.ron" {
            // interpolation applies to an approximating scheme
            for p in &mut doc.patches {
                p.design
                    .set_scheme(streamline_kernel::levels::surface::SurfaceScheme::CatmullClark)
                    .unwrap();
            }
        }
        let depth = doc.display_depth;
        let built = doc.build(depth).unwrap();
        let one = ecs::headless_app(doc.patch_scene(1));
        let points = &one.world().resource::<SurfaceData>().points;
        assert_eq!(
            bits(points),
            bits(built.patches[1].finest_points()),
            "{file}"
        );
        let mut plain = doc.clone();
        plain.patches[1].details.clear();
        plain.patches[1].tuning = None;
        plain.patches[1].interpolate_tangents = false;
        let bare = plain.build(depth).unwrap();
        assert_ne!(
            bits(bare.patches[1].finest_points()),
            bits(built.patches[1].finest_points()),
            "{file}: the field changes nothing"
        );
    }
}

/// Edits of a later patch's own fields through the ECS layer (a script's
/// `SetPatch`, then a detail at edit depth 1, a fine-tuning value, tangent
/// interpolation): each lands on that patch, a save writes it, undo takes
/// it back exactly and redo brings it again.
#[test]
fn a_later_patchs_fields_are_edited_undone_and_redone() {
    let doc = three(11, "CatmullClark", "G1", "Last", "G1");
    let mut app = app(&doc);
    let before = fields(&world_io::document(app.world()).unwrap());
    ecs::apply(&mut app, Edit::Patch(PatchEdit::SetPatch("p2".into()))).unwrap();
    ecs::apply(&mut app, Edit::SetEditDepth(1)).unwrap();
    let said = ecs::apply(
        &mut app,
        Edit::SetDirection {
            row: 2,
            col: 3,
            dir: DVec3::new(0.2, 1.0, -0.4),
        },
    )
    .unwrap();
    assert!(
        said.contains("detail (2, 3) at level 1") && said.contains("`p2`"),
        "{said}"
    );
    // the built surface has the detail: the detailed tangent is the one set
    let built = world_io::document(app.world()).unwrap().build(1).unwrap();
    let t = built.patches[2].levels[1].tangents.get(2, 3);
    let want = DVec3::new(0.2, 1.0, -0.4).normalize();
    assert!(t.angle_between(want) < 1e-9, "{t} vs {want}");
    ecs::apply(
        &mut app,
        Edit::SetTuningValue {
            row: 1,
            col: 1,
            value: 1.3,
        },
    )
    .unwrap();
    ecs::apply(&mut app, Edit::SetInterpolateTangents(true)).unwrap();
    let edited = world_io::document(app.world()).unwrap();
    let p2 = &edited.patches[2];
    assert_eq!(p2.details.len(), 1);
    assert!(p2.details.contains_key(&(1, 2, 3)));
    assert_eq!(p2.tuning.as_ref().unwrap().function.values().get(1, 1), 1.3);
    assert!(p2.interpolate_tangents);
    assert!(edited.patches[0].details.is_empty() && edited.patches[0].tuning.is_none());
    // the world's surface is the document's
    let ids = entities(&mut app);
    let whole = edited.build(edited.display_depth).unwrap();
    assert_eq!(
        bits(&finest(&app, ids[2])),
        bits(whole.patches[2].finest_points())
    );
    // saved and read back
    let dir = tmp("edits");
    save(&edited, &dir.join("e.ron")).unwrap();
    assert_eq!(fields(&load(&dir.join("e.ron")).unwrap()), fields(&edited));
    // four undo steps: the edit depth, the detail, the tuning, the interpolation
    for _ in 0..4 {
        ecs::apply(&mut app, Edit::Undo).unwrap();
    }
    assert_eq!(fields(&world_io::document(app.world()).unwrap()), before);
    for _ in 0..4 {
        ecs::apply(&mut app, Edit::Redo).unwrap();
    }
    assert_eq!(
        fields(&world_io::document(app.world()).unwrap()),
        fields(&edited)
    );
    // a detail on a G1 chain's seam column is refused, naming the handle to turn
    ecs::apply(&mut app, Edit::Patch(PatchEdit::SetPatch("p1".into()))).unwrap();
    let err = ecs::apply(
        &mut app,
        Edit::SetDirection {
            row: 1,
            col: 0,
            dir: DVec3::X,
        },
    )
    .unwrap_err()
    .to_string();
    assert!(err.contains("seam with `p0`"), "{err}");
    // fine tuning on a G2 chain is refused, and the design is as it was
    let g2 = three(12, "Kobbelt(omega: 1.0)", "G2", "Last", "G1");
    let mut app = ecs::headless_document_app(&g2, None, ModelConfig::default());
    ecs::apply(&mut app, Edit::Patch(PatchEdit::SetPatch("p1".into()))).unwrap();
    let was = fields(&world_io::document(app.world()).unwrap());
    let err = ecs::apply(&mut app, Edit::SetTuning(Some(SurfaceTuning::identity())))
        .unwrap_err()
        .to_string();
    assert!(err.contains("G2 chain") && err.contains("κ/α"), "{err}");
    assert_eq!(fields(&world_io::document(app.world()).unwrap()), was);
    let _ = std::fs::remove_dir_all(dir);
}

/// A G2 chain with details on both patches is its merged net subdivided
/// with the details at their merged places: the one-patch pipeline (the
/// incremental ECS layer) of a scene whose net is the merged net and whose
/// details are the members' moved by Eq. 69's seam column (computed here
/// by hand) gives, row by row, the two patches' points. Negative control:
/// the details moved one column off do not.
#[test]
fn a_g2_chain_subdivides_its_merged_net_with_its_members_details() {
    for (k, scheme) in ["Kobbelt(omega: 1.0)", "CatmullClark", "DooSabin"]
        .into_iter()
        .enumerate()
    {
        let mut doc = three(40 + k as u64, scheme, "G2", "Last", "G0");
        let mut rnd = rng(77 + k as u64);
        doc.patches[0].details.insert((1, 1, 3), detail(&mut rnd));
        doc.patches[0].details.insert((2, 2, 7), detail(&mut rnd));
        doc.patches[1].details.insert((1, 2, 1), detail(&mut rnd));
        doc.patches[1].details.insert((2, 1, 2), detail(&mut rnd));
        let depth = 2;
        doc.display_depth = depth;
        let built = doc.build(depth).unwrap();
        // the merged net (Eq. 68) and its details (Eq. 69)
        let a = &doc.patches[0];
        let b = &doc.patches[1];
        let seam = a.design.net().cols() - 1;
        let merged_col = |d: u32| {
            if scheme.starts_with("Kobbelt") {
                seam << d
            } else {
                ((seam - 1) << d) + 1
            }
        };
        let merged = |shift: usize| {
            let mut scene = doc.patch_scene(0);
            let rows = a.design.net().rows();
            let mut net = Vec::new();
            let mut s = Vec::new();
            for r in 0..rows {
                let mut row = a.design.net().row(r).to_vec();
                row.extend_from_slice(&b.design.net().row(r)[1..]);
                net.push(row);
                let mut sr = a.design.params().s.row(r).to_vec();
                let off = sr[seam] - b.design.params().s.get(r, 0);
                sr.extend(b.design.params().s.row(r)[1..].iter().map(|v| v + off));
                s.push(sr);
            }
            let design = streamline_kernel::Design::new(
                &Grid::from_rows(&net).unwrap(),
                Grid::from_rows(&s).unwrap(),
                a.design.params().t.clone(),
                0,
                a.design.scheme(),
                a.design.order(),
                a.design.initial().clone(),
            )
            .unwrap();
            scene.design = design;
            scene.details = a.details.clone();
            for (&(l, r, c), &v) in &b.details {
                scene.details.insert((l, r, merged_col(l) + c + shift), v);
            }
            let app = ecs::headless_app(scene);
            app.world().resource::<SurfaceData>().points.clone()
        };
        let whole = merged(0);
        let (pa, pb) = (
            built.patches[0].finest_points(),
            built.patches[1].finest_points(),
        );
        let cut = merged_col(depth);
        for r in 0..whole.rows() {
            let w = whole.row(r);
            // A's points but its last, B's points but its first (Eq. 70)
            assert_eq!(
                bits_of(&pa.row(r)[..=cut]),
                bits_of(&w[..=cut]),
                "{scheme} row {r}: A"
            );
            let nb = pb.cols();
            assert_eq!(
                bits_of(&pb.row(r)[1..]),
                bits_of(&w[cut + 1..cut + nb]),
                "{scheme} row {r}: B"
            );
        }
        let off = merged(1);
        assert!(
            (0..off.rows()).any(|r| bits_of(&pb.row(r)[1..]) != bits_of(&off.row(r)[cut + 1..cut + pb.cols()])),
            "{scheme}: moved details built the same"
        );
    }
}

fn bits_of(p: &[DVec3]) -> Vec<[u64; 3]> {
    p.iter().map(|v| v.to_array().map(f64::to_bits)).collect()
}

/// A detail set on a patch of a G2 chain (its first patch or the one
/// chained on it) is, once built, the very direction set: its frame is the
/// chain's merged level, the one drawn (docs/math.md §5, §11.1).
#[test]
fn a_detail_on_a_g2_chain_is_the_direction_set() {
    for scheme in ["Kobbelt(omega: 1.0)", "CatmullClark"] {
        let doc = three(21, scheme, "G2", "Last", "G1");
        let mut app = app(&doc);
        ecs::apply(&mut app, Edit::SetEditDepth(1)).unwrap();
        for (patch, row, col) in [("p1", 2, 1), ("p0", 1, 6), ("p0", 2, 5), ("p1", 1, 3)] {
            ecs::apply(&mut app, Edit::Patch(PatchEdit::SetPatch(patch.into()))).unwrap();
            let want = DVec3::new(1.0, 0.3, -0.2).normalize();
            let said = ecs::apply(
                &mut app,
                Edit::SetDirection {
                    row,
                    col,
                    dir: want,
                },
            )
            .unwrap();
            assert!(
                said.contains(&format!("detail ({row}, {col}) at level 1")),
                "{said}"
            );
            let now = world_io::document(app.world()).unwrap();
            let i = now.index(patch).unwrap();
            let t = now.build(1).unwrap().patches[i].levels[1]
                .tangents
                .get(row, col);
            assert!(
                t.angle_between(want) < 1e-9,
                "{scheme} {patch} ({row}, {col}): {t} vs {want}"
            );
            // and the world's surface is the document's
            let ids = entities(&mut app);
            let whole = now.build(now.display_depth).unwrap();
            assert_eq!(
                bits(&finest(&app, ids[i])),
                bits(whole.patches[i].finest_points())
            );
        }
    }
}
