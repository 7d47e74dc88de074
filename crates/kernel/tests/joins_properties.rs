//! docs/math.md §11: joins hold by construction at every depth. Chains
//! (`edge: End`): G0 shares the seam's points, G1 also its normals, G2 is the
//! merged net cut at the seam; side joins (`edge: First | Last`): G0 starts on
//! `A`'s streamline, G1's normal angle shrinks with depth. Each with a
//! negative control; the refusals name the fix.

mod common;

use common::joins::{Field, PairSpec, bits, pair_spec, side_pair};
use glam::{DQuat, DVec3};
use proptest::prelude::*;
use streamline_kernel::grid::Grid;
use streamline_kernel::joins::edge_curve::EdgeCurve;
use streamline_kernel::joins::{Continuity, Edge, Join, JoinError, Stack, join, seam_at};
use streamline_kernel::{Design, KernelError, SurfaceScheme};

const DEPTH: u32 = 4;

fn field(nasty: bool) -> Field {
    if nasty { Field::Nasty } else { Field::Bent }
}

/// The built pair, or `None` where a patch's own build is refused for its
/// uneven intervals (docs/math.md §8); any other refusal fails the test.
fn built(r: Result<(Stack, Stack), JoinError>) -> Option<(Stack, Stack)> {
    match r {
        Ok(p) => Some(p),
        Err(JoinError::Kernel(KernelError::ParamsNotIncreasing { .. })) => None,
        Err(e) => panic!("refused: {e}"),
    }
}

fn end(continuity: Continuity) -> Join {
    Join {
        edge: Edge::End,
        continuity,
    }
}

/// The largest normal angle (degrees) and curvature deviation of a seam at every depth.
fn measures(a: &Stack, b: &Stack, edge: Edge) -> Vec<(f64, f64)> {
    (0..=a.depth())
        .map(|d| {
            let r = seam_at(a, b, edge, d).unwrap();
            (r.angle_deg, r.curvature_dev.abs())
        })
        .collect()
}

/// `B`'s design with each first-column tangent turned by `angle` about `A`'s
/// `∂S/∂t` at that row's seam point: out of `A`'s tangent plane.
fn turned_seam(b: &Design, a: &Stack, angle: f64) -> Design {
    let (pts, mut net) = (&a.points[0], b.net().clone());
    let last = pts.cols() - 1;
    for r in 0..net.rows() {
        let (lo, hi) = (r.saturating_sub(1), (r + 1).min(net.rows() - 1));
        let axis = (pts.get(hi, last) - pts.get(lo, last)).normalize();
        net.set(r, 0, DQuat::from_axis_angle(axis, angle) * net.get(r, 0));
    }
    let mut out = b.clone();
    out.set_net(&net).unwrap();
    out
}

/// The merged design of a G2 chain, from the definition (docs/math.md §11.1,
/// Eq. 68), independently of `joins::merged`.
fn merged_by_hand(a: &Design, b: &Design) -> Design {
    let rows = a.net().rows();
    let (mut net, mut s) = (Vec::new(), Vec::new());
    for r in 0..rows {
        let (sa, sb) = (a.params().s.row(r), b.params().s.row(r));
        let offset = sa[sa.len() - 1] - sb[0];
        let mut row_net = a.net().row(r).to_vec();
        row_net.extend_from_slice(&b.net().row(r)[1..]);
        let mut row_s = sa.to_vec();
        row_s.extend(sb[1..].iter().map(|v| v + offset));
        net.push(row_net);
        s.push(row_s);
    }
    Design::new(
        &Grid::from_rows(&net).unwrap(),
        Grid::from_rows(&s).unwrap(),
        a.params().t.clone(),
        a.anchor(),
        a.scheme(),
        a.order(),
        a.initial().clone(),
    )
    .unwrap()
}

/// Where the seam at control column `col` of the merged net sits at `depth`.
fn seam_col(spec: &PairSpec, col: usize, depth: u32) -> usize {
    if spec.scheme.is_interpolatory() {
        col * (1 << depth)
    } else {
        (col - 1) * (1 << depth) + 1
    }
}

/// The pair with Kobbelt's ω at its default 1: the curvature claims are for
/// it (with a smaller ω the 4-point rule is only just C¹ and its curvature
/// jumps at every control column, across a seam or not).
fn default_omega(mut spec: PairSpec) -> PairSpec {
    if spec.scheme.is_interpolatory() {
        spec.scheme = SurfaceScheme::Kobbelt { omega: 1.0 };
    }
    spec
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 32, max_global_rejects: 8192, ..ProptestConfig::default() })]

    /// Chain G0: at every depth B's streamline j starts at A's streamline j's
    /// last point, bit for bit (gap exactly 0), and B's rows are A's.
    #[test]
    fn chain_g0_shares_the_seam_points_at_every_depth(spec in pair_spec(), nasty in any::<bool>()) {
        let a = spec.a(field(nasty));
        let b = spec.b_chain(&a, field(nasty), false, spec.order_b);
        let Some((sa, sb)) = built(join(&a, &b, end(Continuity::G0), DEPTH)) else { return Ok(()) };
        for d in 0..=DEPTH as usize {
            let (pa, pb) = (&sa.points[d], &sb.points[d]);
            prop_assert_eq!(pa.rows(), pb.rows());
            prop_assert_eq!(&sa.levels[d].params.t, &sb.levels[d].params.t);
            for j in 0..pa.rows() {
                prop_assert_eq!(bits(pa.get(j, pa.cols() - 1)), bits(pb.get(j, 0)), "depth {} row {}", d, j);
            }
            prop_assert_eq!(seam_at(&sa, &sb, Edge::End, d as u32).unwrap().gap, 0.0);
        }
    }

    /// Negative control: a G0 chain whose seam column is turned out of A's
    /// tangent plane shows the turn as a normal angle: on the control net,
    /// and for Kobbelt (which keeps the column) at every depth. The
    /// approximating schemes move the boundary, so deeper the turn mixes with
    /// the bend of the next columns: a crease of some size (at least 1e-3°;
    /// G1 is below 1e-11°), never rounding.
    #[test]
    fn chain_g0_with_a_turned_seam_column_shows_the_angle(spec in pair_spec(), deg in 10.0f64..40.0) {
        let a = spec.a(Field::Bent);
        let shared = spec.b_chain(&a, Field::Bent, true, spec.order_b);
        let Some((sa, _)) = built(join(&a, &shared, end(Continuity::G1), DEPTH)) else { return Ok(()) };
        let b = turned_seam(&shared, &sa, deg.to_radians());
        let Some((sa, sb)) = built(join(&a, &b, end(Continuity::G0), DEPTH)) else { return Ok(()) };
        for (d, (angle, _)) in measures(&sa, &sb, Edge::End).into_iter().enumerate() {
            let least = if d == 0 || spec.scheme.is_interpolatory() { deg / 3.0 } else { 1e-3 };
            prop_assert!(angle > least, "depth {}: {} degrees for a {} degree turn", d, angle, deg);
        }
    }

    /// Chain G1: B's first column is A's last at every depth, so the seam's
    /// normals agree within rounding; for Kobbelt B's own subdivision already
    /// gives that column, bit for bit.
    #[test]
    fn chain_g1_seam_normals_agree_at_every_depth(spec in pair_spec(), nasty in any::<bool>()) {
        let a = spec.a(field(nasty));
        let b = spec.b_chain(&a, field(nasty), true, spec.order_b);
        let Some((sa, sb)) = built(join(&a, &b, end(Continuity::G1), DEPTH)) else { return Ok(()) };
        let own = spec.scheme.is_interpolatory().then(|| b.levels(DEPTH).unwrap());
        for d in 0..=DEPTH as usize {
            let (la, lb) = (&sa.levels[d].tangents, &sb.levels[d].tangents);
            for j in 0..la.rows() {
                let seam = bits(la.get(j, la.cols() - 1));
                prop_assert_eq!(seam, bits(lb.get(j, 0)));
                if let Some(own) = &own {
                    prop_assert_eq!(seam, bits(own[d].tangents.get(j, 0)), "kobbelt keeps the column");
                }
            }
            let r = seam_at(&sa, &sb, Edge::End, d as u32).unwrap();
            prop_assert_eq!(r.gap, 0.0);
            if !nasty {
                prop_assert!(r.angle_deg < 1e-9, "depth {}: {} degrees", d, r.angle_deg);
            } else {
                // nasty nets may fold a seam point flat (a carried normal); elsewhere exact
                let flat = r.samples.iter().filter(|s| s.angle_deg >= 1e-9).count();
                prop_assert!(flat * 4 <= r.samples.len(), "depth {}: {:?}", d, r);
            }
        }
    }

    /// Negative control: a G1 chain of two patches that bend at different
    /// rates keeps its curvature jump at depth 5, where the G2 join of the
    /// same pair has shrunk it (measured over 2 000 pairs: G1's deviation at
    /// least 0.039 for Kobbelt, whose 4-point rule smooths it somewhat, 0.66
    /// and 0.88 for Doo–Sabin and Catmull–Clark; at least 3.1 times G2's);
    /// and its `B` is not the merged net's surface.
    #[test]
    fn chain_g1_does_not_pass_as_g2(spec in pair_spec()) {
        let spec = default_omega(spec);
        prop_assume!(spec.rate_b > 0.05 && (spec.rate_a - spec.rate_b).abs() > 0.4 * spec.rate_a.max(spec.rate_b));
        let a = spec.a(Field::Bent);
        let b = spec.b_chain(&a, Field::Bent, true, spec.order_a);
        let Some((g1a, g1b)) = built(join(&a, &b, end(Continuity::G1), 5)) else { return Ok(()) };
        let Some((g2a, g2b)) = built(join(&a, &b, end(Continuity::G2), 5)) else { return Ok(()) };
        let g1 = measures(&g1a, &g1b, Edge::End)[5].1;
        let g2 = measures(&g2a, &g2b, Edge::End)[5].1;
        prop_assert!(g1 > 0.02 && g1 > 2.0 * g2, "G1 deviation {} against G2's {}", g1, g2);
        // nor is it the merged net's surface: B's points next to the seam
        // (which the G2 test finds bit for bit in the merged net) are elsewhere
        let (p1, p2) = (&g1b.points[1], &g2b.points[1]);
        let apart = (0..p1.rows()).map(|j| (p1.get(j, 1) - p2.get(j, 1)).length()).fold(0.0f64, f64::max);
        prop_assert!(apart > 1e-6, "G1's B at depth 1 is the merged net's to {}", apart);
    }

    /// Chain G2: the two patches are the merged net's surface cut at the seam
    /// column, bit for bit against an independent build of the merged design
    /// (Design::build); the seam point lies on the merged segment through it.
    #[test]
    fn chain_g2_is_the_merged_net_cut_at_the_seam(spec in pair_spec(), nasty in any::<bool>()) {
        let a = spec.a(field(nasty));
        let b = spec.b_chain(&a, field(nasty), true, spec.order_a);
        let Some((sa, sb)) = built(join(&a, &b, end(Continuity::G2), DEPTH)) else { return Ok(()) };
        let merged = merged_by_hand(&a, &b);
        for d in 0..=DEPTH {
            let whole = merged.build(d).unwrap();
            let k = seam_col(&spec, a.net().cols() - 1, d);
            let (pa, pb, pm) = (&sa.points[d as usize], &sb.points[d as usize], &whole.points);
            prop_assert_eq!(pa.cols(), k + 2);
            prop_assert_eq!(pa.cols() + pb.cols(), pm.cols() + 2);
            for j in 0..pm.rows() {
                for c in 0..=k {
                    prop_assert_eq!(bits(pa.get(j, c)), bits(pm.get(j, c)));
                    prop_assert_eq!(bits(sa.levels[d as usize].tangents.get(j, c)), bits(whole.level.tangents.get(j, c)));
                }
                for c in 1..pb.cols() {
                    prop_assert_eq!(bits(pb.get(j, c)), bits(pm.get(j, k + c)));
                }
                let seam = pa.get(j, k + 1);
                prop_assert_eq!(bits(seam), bits(pb.get(j, 0)));
                // on the merged segment k → k + 1
                let (p, q) = (pm.get(j, k), pm.get(j, k + 1));
                let along = (seam - p).dot(q - p) / (q - p).length_squared();
                let off = (p + (q - p) * along - seam).length();
                let scale = 1.0 + p.length() + q.length();
                prop_assert!(off <= 1e-12 * scale && (-1e-12..=1.0 + 1e-12).contains(&along), "row {} depth {}: {} off, at {}", j, d, off, along);
            }
        }
    }

    /// Chain G2: the normal-curvature jump across the seam shrinks with depth.
    #[test]
    fn chain_g2_curvature_jump_shrinks_with_depth(spec in pair_spec()) {
        let spec = default_omega(spec);
        prop_assume!(spec.rate_b > 0.05);
        let a = spec.a(Field::Bent);
        let b = spec.b_chain(&a, Field::Bent, true, spec.order_a);
        let Some((sa, sb)) = built(join(&a, &b, end(Continuity::G2), 5)) else { return Ok(()) };
        let dev: Vec<f64> = measures(&sa, &sb, Edge::End).iter().map(|m| m.1).collect();
        let early = dev[..=2].iter().fold(0.0f64, |m, v| m.max(*v));
        prop_assert!(dev[5] <= 0.5 * early, "{:?}", dev);
    }

    /// Side G0: B's streamline j starts at the point of A's streamline at arc
    /// length t_j, on A's polyline, at every depth (where A's streamline
    /// reaches: an approximating scheme's boundary streamline shortens).
    #[test]
    fn side_g0_starts_on_the_streamline(spec in pair_spec(), nasty in any::<bool>(), last in any::<bool>()) {
        let edge = if last { Edge::Last } else { Edge::First };
        let Some((_, sa, b)) = side_pair(&spec, field(nasty), edge, DEPTH) else { return Ok(()) };
        let sb = streamline_kernel::joins::side::side(&sa, &b, edge, Continuity::G0).unwrap();
        for d in 0..=DEPTH {
            let curve = EdgeCurve::of(&sa, d, edge).unwrap();
            let r = seam_at(&sa, &sb, edge, d).unwrap();
            let scale = 1.0 + curve.points().iter().fold(0.0f64, |m, p| m.max(p.length()));
            for (j, sample) in r.samples.iter().enumerate() {
                let t = sb.levels[d as usize].params.t[j];
                prop_assert_eq!(bits(sb.points[d as usize].get(j, 0)), bits(curve.point(t)));
                if (curve.start()..=curve.length()).contains(&t) {
                    prop_assert!(sample.gap <= 1e-12 * scale, "depth {} row {}: gap {}", d, j, sample.gap);
                }
            }
            if spec.scheme.is_interpolatory() {
                prop_assert!(r.gap <= 1e-12 * scale, "depth {}: gap {}", d, r.gap);
            }
        }
    }

    /// Side G1: projecting B's first column into A's tangent planes after
    /// every step makes the seam's normal angle shrink with depth: at depth 5
    /// at most half the largest of depths 1–3 (the measure's constant depends
    /// on where B's rows fall in A's segments, docs/math.md §11.2, so one
    /// level may rise; the envelope halves). B's first column is in A's
    /// tangent planes at every depth. Negative control: the control column
    /// projected once drifts out of A's planes as it is refined, the drift
    /// does not shrink from depth 4 to 5, and the seam's angle at depth 5 is
    /// that drift (and above G1's).
    #[test]
    fn side_g1_angle_shrinks_and_control_only_does_not(spec in pair_spec(), last in any::<bool>()) {
        let spec = refining(default_omega(spec));
        let edge = if last { Edge::Last } else { Edge::First };
        let Some((_, sa, b)) = side_pair(&spec, Field::Bent, edge, 5) else { return Ok(()) };
        let g1 = streamline_kernel::joins::side::side(&sa, &b, edge, Continuity::G1).unwrap();
        let angle: Vec<f64> = measures(&sa, &g1, edge).iter().map(|m| m.0).collect();
        let early = angle[1].max(angle[2]).max(angle[3]);
        prop_assert!(angle[5] <= 0.5 * early, "G1: {:?}", angle);
        prop_assert!(drift(&sa, &g1, edge).iter().all(|&v| v < 1e-9), "G1 leaves A's planes");
        // the control column projected once, with A's level-0 normals, then free
        let curve = EdgeCurve::of(&sa, 0, edge).unwrap();
        let mut net = b.net().clone();
        for r in 0..net.rows() {
            let n = curve.normal(b.params().t[r]).unwrap();
            let v = net.get(r, 0);
            net.set(r, 0, (v - n * v.dot(n)).normalize());
        }
        let mut once = b.clone();
        once.set_net(&net).unwrap();
        let g0 = streamline_kernel::joins::side::side(&sa, &once, edge, Continuity::G0).unwrap();
        let ctl: Vec<f64> = measures(&sa, &g0, edge).iter().map(|m| m.0).collect();
        let off = drift(&sa, &g0, edge);
        prop_assert!(off[0] < 1e-9 && off[5] > 0.05 && off[5] >= 0.6 * off[4], "control drift: {:?}", off);
        prop_assert!(ctl[5] >= 0.7 * off[5] && ctl[5] > angle[5], "control only: {:?}, drift {:?}, G1 {:?}", ctl, off, angle);
    }
}

/// A net that is refined along the side edge: Catmull–Clark keeps a net of 3
/// columns (or rows) at 3 at every depth (`2n − 3`), contracting it onto its
/// middle column instead of refining it, so `A` needs 4 columns and `B` 4
/// rows there (docs/math.md §11.2). The other schemes refine any net.
fn refining(mut spec: PairSpec) -> PairSpec {
    if spec.scheme == SurfaceScheme::CatmullClark {
        spec.cols_a = spec.cols_a.max(4);
        spec.cols_b = spec.cols_b.max(4);
    }
    spec
}

/// How far (degrees) `B`'s first-column tangents lie out of `A`'s tangent
/// planes at their rows' starts (Eq. 72's normal), the largest at each depth.
fn drift(a: &Stack, b: &Stack, edge: Edge) -> Vec<f64> {
    (0..=a.depth())
        .map(|d| {
            let curve = EdgeCurve::of(a, d, edge).unwrap();
            let level = &b.levels[d as usize];
            (0..level.tangents.rows())
                .map(|r| {
                    let n = curve.normal(level.params.t[r]).unwrap();
                    level.tangents.get(r, 0).dot(n).abs().asin().to_degrees()
                })
                .fold(0.0, f64::max)
        })
        .collect()
}

/// Every refusal of docs/math.md §11 ("Bad input") is an error that says
/// what to do, and nothing is built.
#[test]
fn refusals_name_the_fix() {
    use proptest::strategy::ValueTree;
    let mut runner = proptest::test_runner::TestRunner::deterministic();
    let spec = default_omega(pair_spec().new_tree(&mut runner).unwrap().current());
    let a = spec.a(Field::Bent);
    let shared = spec.b_chain(&a, Field::Bent, true, spec.order_a);
    let free = spec.b_chain(&a, Field::Bent, false, spec.order_a);
    let message = |r: Result<(Stack, Stack), JoinError>| r.expect_err("refused").to_string();
    let side = |c| Join {
        edge: Edge::First,
        continuity: c,
    };
    // G2 on a side edge: future work
    let m = message(join(&a, &shared, side(Continuity::G2), 1));
    assert!(m.contains("future work") && m.contains("use G1"), "{m}");
    // G1/G2 seam column not A's last
    for c in [Continuity::G1, Continuity::G2] {
        let m = message(join(&a, &free, end(c), 1));
        assert!(m.contains("copy A's last column into B's first"), "{m}");
    }
    // G2 across schemes, and across blend orders
    let mut other = shared.clone();
    other
        .set_scheme(if spec.scheme.is_interpolatory() {
            SurfaceScheme::CatmullClark
        } else {
            SurfaceScheme::Kobbelt { omega: 1.0 }
        })
        .unwrap();
    let m = message(join(&a, &other, end(Continuity::G2), 1));
    assert!(m.contains("give B A's"), "{m}");
    let m = message(join(&a, &other, end(Continuity::G0), 1));
    assert!(m.contains("give B A's scheme"), "{m}");
    let mut flipped = shared.clone();
    flipped.set_order(match spec.order_a {
        streamline_kernel::BlendOrder::SFirst => streamline_kernel::BlendOrder::TFirst,
        _ => streamline_kernel::BlendOrder::SFirst,
    });
    assert!(message(join(&a, &flipped, end(Continuity::G2), 1)).contains("blend order"));
    assert!(
        join(&a, &flipped, end(Continuity::G1), 1).is_ok(),
        "G1 allows another blend order"
    );
    // rows that differ: count, then t
    let rows = |b: &Design, t: Vec<f64>, keep: usize| {
        let net = Grid::from_rows(
            &(0..keep)
                .map(|r| b.net().row(r).to_vec())
                .collect::<Vec<_>>(),
        )
        .unwrap();
        let s = Grid::from_rows(
            &(0..keep)
                .map(|r| b.params().s.row(r).to_vec())
                .collect::<Vec<_>>(),
        )
        .unwrap();
        Design::new(&net, s, t, 0, b.scheme(), b.order(), b.initial().clone()).unwrap()
    };
    let n = a.params().t.len();
    let fewer = rows(&shared, a.params().t[..n - 1].to_vec(), n - 1);
    assert!(
        message(join(&a, &fewer, end(Continuity::G0), 1)).contains(&format!("give B {n} rows"))
    );
    let mut t = a.params().t.clone();
    t[1] += 1e-9;
    let moved = rows(&shared, t, n);
    assert!(message(join(&a, &moved, end(Continuity::G1), 1)).contains("set B's t to A's"));
    // anchor not 0
    let anchored = Design::new(
        shared.net(),
        shared.params().s.clone(),
        shared.params().t.clone(),
        1,
        shared.scheme(),
        shared.order(),
        shared.initial().clone(),
    )
    .unwrap();
    assert!(
        message(join(&a, &anchored, end(Continuity::G0), 1)).contains("set its anchor to column 0")
    );
    // a G2 chain is not built as B alone
    let sa = Stack::build(&a, 1).unwrap();
    let m = streamline_kernel::joins::chain::chain(&a, &sa, &shared, Continuity::G2).unwrap_err();
    assert_eq!(m, JoinError::G2IsOneNet);
    // side rows outside the streamline, or not increasing
    let curve = EdgeCurve::of(&sa, 0, Edge::First).unwrap();
    let b = spec.b_side(Field::Bent, (0.1, curve.length() + 0.5), -DVec3::Y);
    assert!(message(join(&a, &b, side(Continuity::G0), 1)).contains("outside A's streamline"));
    let b = spec.b_side(
        Field::Bent,
        (0.6 * curve.length(), 0.2 * curve.length()),
        -DVec3::Y,
    );
    assert!(message(join(&a, &b, side(Continuity::G0), 1)).contains("order the rows"));
    // a side G1 boundary tangent along A's normal
    let b = spec.b_side(
        Field::Bent,
        (0.2 * curve.length(), 0.8 * curve.length()),
        -DVec3::Y,
    );
    let mut net = b.net().clone();
    net.set(1, 0, curve.normal(b.params().t[1]).unwrap());
    let mut along = b.clone();
    along.set_net(&net).unwrap();
    let m = message(join(&a, &along, side(Continuity::G1), 1));
    assert!(
        m.contains("row 1 (level 0)") && m.contains("turn it towards A's surface"),
        "{m}"
    );
    assert!(
        join(&a, &along, side(Continuity::G0), 1).is_ok(),
        "G0 keeps any tangent"
    );
}
