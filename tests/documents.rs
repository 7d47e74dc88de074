//! Designs of several patches (docs/math.md §11): version-3 files,
//! versions 1 and 2 as one patch, saving (version 2 for one patch, byte for
//! byte; version 3 bit for bit), building through the kernel's joins with a
//! seam report per join, and the shipped three-patch scene.

use std::path::Path;
use streamline_studio::kernel::DVec3;
use streamline_studio::scene::design::document::{Document, MAIN_PATCH, Start};
use streamline_studio::scene::design::document_io::{load, save};
use streamline_studio::scene::{
    Scene,
    design::{builtin, document_io},
};

mod common;
use common::documents::{bits, shipped, tmpdir};

#[test]
fn versions_1_and_2_open_as_one_patch_and_save_the_same_bytes() {
    let dir = tmpdir("v12");
    for (name, _) in builtin::SCENES {
        let path = shipped(name);
        let doc = load(&path).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(doc.patches.len(), 1);
        assert_eq!(doc.patches[0].name, MAIN_PATCH);
        let scene = document_io::load_scene(&path).unwrap();
        let (a, b) = (dir.join("doc.ron"), dir.join("scene.ron"));
        save(&doc, &a).unwrap();
        document_io::save_scene(&scene, &b).unwrap();
        let (ba, bb) = (std::fs::read(&a).unwrap(), std::fs::read(&b).unwrap());
        assert_eq!(
            ba, bb,
            "{name}: a one-patch document saves as the scene does"
        );
        assert!(String::from_utf8(ba).unwrap().contains("version: 2"));
        // and the document's one scene is the scene
        assert_eq!(doc.one_scene().unwrap().to_file(), scene.to_file());
    }
    // a version-2 file with the mirror on
    let mut scene = builtin::scene("minimal").unwrap();
    scene.mirror = true;
    let v2 = dir.join("mirror.ron");
    document_io::save_scene(&scene, &v2).unwrap();
    let doc = load(&v2).unwrap();
    assert!(doc.mirror);
    let again = dir.join("mirror-again.ron");
    save(&doc, &again).unwrap();
    assert_eq!(std::fs::read(&v2).unwrap(), std::fs::read(&again).unwrap());
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_three_patch_document_saves_as_version_3_and_reads_back_bit_for_bit() {
    let doc = load(&shipped("hood-screen-wing")).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(doc.patches.len(), 3);
    let dir = tmpdir("v3");
    let path = dir.join("hsw.ron");
    save(&doc, &path).unwrap();
    let text = std::fs::read_to_string(&path).unwrap();
    assert!(text.contains("version: 3"), "{text}");
    let back = load(&path).unwrap();
    assert_eq!(back.to_file(), doc.to_file());
    assert_eq!(bits(&back), bits(&doc));
    assert_eq!(back.to_ron(), text);
    // no temporary file is left behind
    let left: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .filter_map(|e| e.ok())
        .filter(|e| e.file_name().to_string_lossy().contains(".tmp-"))
        .collect();
    assert!(left.is_empty(), "{left:?}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The shipped file is what saving writes (so a save of the unchanged
/// design changes nothing); `REGENERATE_SCENES=1` rewrites it.
#[test]
fn the_shipped_three_patch_scene_is_in_saved_form() {
    let path = shipped("hood-screen-wing");
    let doc = load(&path).unwrap();
    if std::env::var("REGENERATE_SCENES").is_ok_and(|v| v == "1") {
        std::fs::write(&path, doc.to_ron()).unwrap();
        return;
    }
    assert_eq!(std::fs::read_to_string(&path).unwrap(), doc.to_ron());
}

#[test]
fn the_one_surface_loader_says_the_file_has_several_patches() {
    let path = shipped("hood-screen-wing");
    let e = document_io::load_scene(&path).unwrap_err();
    assert!(
        e.message.contains("3 patches (`hood`, `screen`, `wing`)")
            && e.message.contains("this reader takes one surface only"),
        "{e}"
    );
    assert!(e.line > 0, "located: {e}");
}

#[test]
fn a_version_3_file_of_one_patch_opens_as_a_scene() {
    let doc = load(&shipped("hood-screen-wing")).unwrap();
    let one = Document {
        patches: vec![doc.patches[0].clone()],
        ..doc.clone()
    };
    let text = ron::ser::to_string_pretty(&one.to_file(), ron::ser::PrettyConfig::new()).unwrap();
    let scene = Scene::parse(&text, Path::new("one.ron")).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(scene.to_file(), one.one_scene().unwrap().to_file());
    // the same through the document: saved as version 2
    let read = Document::parse(&text, Path::new("one.ron")).unwrap();
    assert_eq!(read.patches[0].name, "hood");
    assert!(read.to_ron().contains("version: 2"));
}

/// A design with every kind of join this build makes: `b` G2-chained on
/// `a`'s End, `c` G1-chained on `b`'s End, `d` on `a`'s First side with G1.
fn four_patches() -> Document {
    let text = r#"(
    version: 3,
    name: "four",
    display_depth: 4,
    patches: [
        (
            name: "a",
            tangents: [
                [(1.0, 0.0, -0.1), (1.0, 0.05, 0.0), (1.0, 0.0, 0.15), (1.0, -0.05, 0.3)],
                [(1.0, 0.0, -0.05), (1.0, 0.0, 0.05), (1.0, 0.0, 0.2), (1.0, 0.0, 0.35)],
                [(1.0, 0.0, 0.0), (1.0, -0.05, 0.1), (1.0, 0.0, 0.25), (1.0, 0.05, 0.4)],
                [(1.0, 0.0, 0.05), (1.0, 0.0, 0.15), (1.0, 0.0, 0.3), (1.0, 0.0, 0.45)],
            ],
            s: [[0.0, 0.4, 0.8, 1.2], [0.0, 0.4, 0.8, 1.2], [0.0, 0.4, 0.8, 1.2], [0.0, 0.4, 0.8, 1.2]],
            t: [0.0, 0.5, 1.0, 1.5],
            initial: Curve(tangents: [(0.0, 1.0, 0.2), (0.0, 1.0, 0.0), (0.0, 1.0, -0.2)], order: 3, length: 1.5, origin: (0.0, 0.0, 0.0)),
            scheme: Kobbelt(omega: 1.0),
        ),
        (
            name: "b",
            tangents: [
                [(1.0, -0.05, 0.3), (1.0, 0.0, 0.6), (1.0, 0.0, 0.9)],
                [(1.0, 0.0, 0.35), (1.0, 0.0, 0.7), (1.0, 0.0, 1.0)],
                [(1.0, 0.05, 0.4), (1.0, 0.0, 0.8), (1.0, 0.0, 1.1)],
                [(1.0, 0.0, 0.45), (1.0, 0.0, 0.9), (1.0, 0.0, 1.2)],
            ],
            s: [[0.0, 0.3, 0.6], [0.0, 0.3, 0.6], [0.0, 0.3, 0.6], [0.0, 0.3, 0.6]],
            t: [0.0, 0.5, 1.0, 1.5],
            initial: Edge(patch: "a", edge: End, continuity: G2),
            scheme: Kobbelt(omega: 1.0),
        ),
        (
            name: "c",
            tangents: [
                [(1.0, 0.0, 0.9), (1.0, 0.0, 0.5), (1.0, 0.0, 0.2)],
                [(1.0, 0.0, 1.0), (1.0, 0.0, 0.6), (1.0, 0.0, 0.3)],
                [(1.0, 0.0, 1.1), (1.0, 0.0, 0.7), (1.0, 0.0, 0.4)],
                [(1.0, 0.0, 1.2), (1.0, 0.0, 0.8), (1.0, 0.0, 0.5)],
            ],
            s: [[0.0, 0.3, 0.6], [0.0, 0.3, 0.6], [0.0, 0.3, 0.6], [0.0, 0.3, 0.6]],
            t: [0.0, 0.5, 1.0, 1.5],
            initial: Edge(patch: "b", edge: End, continuity: G1),
            scheme: Kobbelt(omega: 1.0),
        ),
        (
            name: "d",
            tangents: [
                [(0.0, -1.0, 0.0), (0.0, -0.8, -0.5), (0.0, -0.3, -1.0)],
                [(0.0, -1.0, 0.05), (0.0, -0.8, -0.45), (0.0, -0.3, -1.0)],
                [(0.0, -1.0, 0.1), (0.0, -0.8, -0.4), (0.0, -0.3, -1.0)],
            ],
            s: [[0.0, 0.2, 0.4], [0.0, 0.2, 0.4], [0.0, 0.2, 0.4]],
            t: [0.1, 0.6, 1.1],
            initial: Edge(patch: "a", edge: First, continuity: G1),
            scheme: Kobbelt(omega: 1.0),
        ),
    ],
)
"#;
    Document::parse(text, Path::new("four.ron")).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn a_version_3_design_builds_through_its_joins_with_seam_reports() {
    let doc = four_patches();
    let mut side_angles = Vec::new();
    for depth in 2..=4 {
        let built = doc.build(depth).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(built.patches.len(), 4);
        assert_eq!(built.seams.len(), 3);
        for stack in &built.patches {
            assert_eq!(stack.depth(), depth);
            assert!(stack.finest_points().data().iter().all(|p| p.is_finite()));
        }
        let (ab, bc, ad) = (&built.seams[0], &built.seams[1], &built.seams[2]);
        assert_eq!((ab.a, ab.b, bc.a, bc.b, ad.a, ad.b), (0, 1, 1, 2, 0, 3));
        // chains share their seam points exactly, and their normals
        assert_eq!(ab.report.gap, 0.0, "G2 gap at depth {depth}");
        assert_eq!(bc.report.gap, 0.0, "G1 gap at depth {depth}");
        assert!(
            ab.report.angle_deg < 1e-9,
            "G2 angle {} at depth {depth}",
            ab.report.angle_deg
        );
        assert!(
            bc.report.angle_deg < 1e-9,
            "G1 angle {} at depth {depth}",
            bc.report.angle_deg
        );
        // the side seam starts on a's streamline polyline
        assert!(
            ad.report.gap < 1e-12,
            "side gap {} at depth {depth}",
            ad.report.gap
        );
        side_angles.push(ad.report.angle_deg);
    }
    eprintln!("side G1 normal angle at depths 2-4: {side_angles:?}");
    assert!(
        side_angles[2] < side_angles[1] && side_angles[1] < side_angles[0],
        "the side G1 angle shrinks with depth: {side_angles:?}"
    );
    // negative control: the same side patch joined with G0 keeps its angle
    let mut g0 = doc.clone();
    if let Start::Edge { join, .. } = &mut g0.patches[3].start {
        join.continuity = streamline_studio::kernel::joins::Continuity::G0;
    }
    let g0_angle = g0.build(4).unwrap().seams[2].report.angle_deg;
    assert!(
        g0_angle > 10.0 * side_angles[2],
        "G0 {g0_angle} against G1 {side_angles:?}"
    );
}

/// The G2 chain's two patches are the merged net cut at the seam: `a` built
/// with `b` has other points than `a` built alone (it is one net); the G1
/// chain `c` on `b` starts exactly on `b`'s merged end points.
#[test]
fn a_g2_chain_is_one_net_and_the_next_chain_starts_on_its_points() {
    let doc = four_patches();
    let built = doc.build(3).unwrap();
    let alone = streamline_studio::kernel::joins::Stack::build(&doc.patches[0].design, 3).unwrap();
    assert_ne!(built.patches[0].finest_points(), alone.finest_points());
    let (b, c) = (&built.patches[1], &built.patches[2]);
    let last = b.finest_points().cols() - 1;
    for j in 0..c.finest_points().rows() {
        assert_eq!(
            c.finest_points().get(j, 0).to_array().map(f64::to_bits),
            b.finest_points().get(j, last).to_array().map(f64::to_bits)
        );
    }
}

// ---- the shipped scene -------------------------------------------------

#[test]
fn the_shipped_three_patch_scene_joins_as_it_says_at_its_depth() {
    let doc = load(&shipped("hood-screen-wing")).unwrap_or_else(|e| panic!("{e}"));
    let names: Vec<&str> = doc.patches.iter().map(|p| p.name.as_str()).collect();
    assert_eq!(names, ["hood", "screen", "wing"]);
    let depth = doc.display_depth;
    assert!(depth >= 3, "shown at depth {depth}");
    let built = doc.build(depth).unwrap_or_else(|e| panic!("{e}"));
    let (screen, wing) = (&built.seams[0], &built.seams[1]);
    assert_eq!((screen.a, screen.b, wing.a, wing.b), (0, 1, 0, 2));
    assert_eq!(screen.report.gap, 0.0);
    assert!(
        screen.report.angle_deg < 1e-9,
        "{:?}",
        screen.report.angle_deg
    );
    assert!(wing.report.gap < 1e-12, "{}", wing.report.gap);
    assert!(
        wing.report.angle_deg < 0.5,
        "side G1 angle {}",
        wing.report.angle_deg
    );
    let angles: Vec<f64> = (1..=depth)
        .map(|d| doc.build(d).unwrap().seams[1].report.angle_deg)
        .collect();
    eprintln!("hood-screen-wing: wing seam angle at depths 1..={depth}: {angles:?}");
    assert!(angles.windows(2).all(|w| w[1] < w[0]), "{angles:?}");

    // a plausible product: sizes, and the patches apart but at their seams
    let pts = |i: usize| built.patches[i].finest_points().data().to_vec();
    let (hood, scr, wng) = (pts(0), pts(1), pts(2));
    let bounds = |p: &[DVec3]| {
        p.iter().fold(
            [DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)],
            |[lo, hi], q| [lo.min(*q), hi.max(*q)],
        )
    };
    let [hl, hh] = bounds(&hood);
    let [sl, sh] = bounds(&scr);
    let [wl, wh] = bounds(&wng);
    eprintln!("hood {hl:?}..{hh:?}\nscreen {sl:?}..{sh:?}\nwing {wl:?}..{wh:?}");
    let size = |lo: DVec3, hi: DVec3| hi - lo;
    assert!((1.2..2.0).contains(&size(hl, hh).x) && (1.3..1.8).contains(&size(hl, hh).y));
    assert!(
        size(sl, sh).z > 0.3 && sh.z > hh.z,
        "the screen rises above the hood"
    );
    assert!(wl.z < hl.z - 0.2, "the wing falls below the hood's side");
    // separating planes: the screen beyond the hood's end, the wing beyond its side
    let first_col = |i: usize| {
        let g = built.patches[i].finest_points();
        (0..g.rows()).map(|j| g.get(j, 0)).collect::<Vec<_>>()
    };
    let inner = |i: usize| {
        let g = built.patches[i].finest_points();
        (0..g.rows())
            .flat_map(|j| g.row(j)[1..].to_vec())
            .collect::<Vec<_>>()
    };
    assert!(
        inner(1).iter().all(|p| p.x > hh.x - 1e-9 || p.z > hh.z),
        "screen clear of the hood"
    );
    // the wing leaves the hood's last streamline outwards: beyond it at the same x
    let edge = {
        let g = built.patches[0].finest_points();
        g.row(g.rows() - 1).to_vec()
    };
    let edge_y = |x: f64| {
        let k = edge.partition_point(|p| p.x <= x).clamp(1, edge.len() - 1);
        let (p, q) = (edge[k - 1], edge[k]);
        p.y + (q.y - p.y) * (x - p.x) / (q.x - p.x)
    };
    assert!(
        inner(2).iter().all(|p| p.y > edge_y(p.x)),
        "wing clear of the hood"
    );
    assert!(
        first_col(2)
            .iter()
            .all(|p| (p.y - edge_y(p.x)).abs() < 1e-9)
    );
    // no fold inside a patch: each streamline advances, rows keep their order
    let g = built.patches[0].finest_points();
    for j in 0..g.rows() {
        assert!(g.row(j).windows(2).all(|w| w[1].x > w[0].x), "hood row {j}");
    }
    for k in 0..g.cols() {
        assert!(
            (1..g.rows()).all(|j| g.get(j, k).y > g.get(j - 1, k).y),
            "hood column {k}"
        );
    }
    let g = built.patches[1].finest_points();
    for j in 0..g.rows() {
        assert!(
            g.row(j).windows(2).all(|w| w[1].z > w[0].z),
            "screen row {j}"
        );
    }
    let g = built.patches[2].finest_points();
    for j in 0..g.rows() {
        assert!(
            g.row(j)
                .windows(2)
                .all(|w| w[1].z < w[0].z || w[1].y > w[0].y),
            "wing row {j}"
        );
    }
    for k in 0..g.cols() {
        assert!(
            (1..g.rows()).all(|j| g.get(j, k).x > g.get(j - 1, k).x),
            "wing column {k}"
        );
    }
}
