//! docs/math.md §5 and §11: one patch kept between edits
//! (`joins::patch_state`) — on its own initial curve, chained on `A`'s end
//! or side-joined on `A`'s first or last streamline, G0 or G1, with or
//! without details and fine tuning — equals the whole build (`Stack::build_parts`,
//! `chain`, `side`) bit for bit after every edit of a random sequence: a
//! tangent of its own turned, a row of its `s` stretched, a tangent of `A`
//! turned (its edge moves). The update must also stay local: a one-cell edit
//! of a larger net re-blends fewer tangents than a whole build (a negative
//! control: a state built whole counts every one), and places again only
//! the rows of its window.

mod common;

use common::joins::{Field, PairSpec, bits, pair_spec, side_pair};
use glam::{DQuat, DVec3};
use proptest::prelude::*;
use streamline_kernel::finetune::{Constraint, SurfaceTuning};
use streamline_kernel::grid::Grid;
use streamline_kernel::joins::chain::chain;
use streamline_kernel::joins::patch_state::{PatchState, Start};
use streamline_kernel::joins::side::side;
use streamline_kernel::joins::{Continuity, Edge, PatchParts, Stack};
use streamline_kernel::levels::multires::Details;
use streamline_kernel::{Design, KernelError};

const DEPTH: u32 = 3;

/// Where two stacks differ (levels, parameters and points), `None` when
/// they are bit for bit the same.
fn differ(x: &Stack, y: &Stack) -> Option<String> {
    let f = |a: &[f64], b: &[f64]| {
        a.len() == b.len() && a.iter().zip(b).all(|(u, v)| u.to_bits() == v.to_bits())
    };
    let v = |a: &[DVec3], b: &[DVec3]| {
        (a.len() != b.len())
            .then_some(usize::MAX)
            .or_else(|| a.iter().zip(b).position(|(u, v)| bits(*u) != bits(*v)))
    };
    if x.levels.len() != y.levels.len() || x.points.len() != y.points.len() {
        return Some("depths".into());
    }
    for (d, (a, b)) in x.levels.iter().zip(&y.levels).enumerate() {
        if let Some(i) = v(a.tangents.data(), b.tangents.data()) {
            let c = a.tangents.cols();
            return Some(format!(
                "level {d} tangent ({}, {})",
                i / c.max(1),
                i % c.max(1)
            ));
        }
        if !f(a.params.s.data(), b.params.s.data()) {
            return Some(format!("level {d} s"));
        }
        if !f(&a.params.t, &b.params.t) {
            return Some(format!("level {d} t"));
        }
        if !f(&a.params.sigma, &b.params.sigma) {
            return Some(format!("level {d} sigma"));
        }
    }
    for (d, (a, b)) in x.points.iter().zip(&y.points).enumerate() {
        if let Some(i) = v(a.data(), b.data()) {
            let c = a.cols();
            return Some(format!("points {d} ({}, {})", i / c.max(1), i % c.max(1)));
        }
    }
    None
}

/// Bit for bit the same stack.
fn same(x: &Stack, y: &Stack) -> bool {
    differ(x, y).is_none()
}

/// One edit of a random sequence.
#[derive(Debug, Clone)]
enum Step {
    /// `B`'s tangent `(row, col)` (taken modulo its net) turned.
    TurnB(usize, usize, DVec3, f64),
    /// `B`'s row `row` of `s` stretched by a factor.
    StretchB(usize, f64),
    /// `A`'s tangent `(row, col)` turned (its stack built again).
    TurnA(usize, usize, DVec3, f64),
}

fn step() -> impl Strategy<Value = Step> {
    prop_oneof![
        3 => (0usize..8, 0usize..8, common::unit(), 0.01f64..0.4)
            .prop_map(|(r, c, a, x)| Step::TurnB(r, c, a, x)),
        1 => (0usize..8, 0.9f64..1.1).prop_map(|(r, k)| Step::StretchB(r, k)),
        1 => (0usize..8, 0usize..8, common::unit(), 0.01f64..0.3)
            .prop_map(|(r, c, a, x)| Step::TurnA(r, c, a, x)),
    ]
}

fn turned(d: &Design, row: usize, col: usize, axis: DVec3, angle: f64) -> Design {
    let (row, col) = (row % d.net().rows(), col % d.net().cols());
    let mut out = d.clone();
    let v = DQuat::from_axis_angle(axis, angle) * d.net().get(row, col);
    out.set_tangent(row, col, v).unwrap();
    out
}

fn stretched(d: &Design, row: usize, k: f64) -> Design {
    let row = row % d.net().rows();
    let s: Vec<f64> = d.params().s.row(row).iter().map(|x| x * k).collect();
    let mut out = d.clone();
    out.set_s_row(row, &s).unwrap();
    out
}

/// `b` with its first column `a`'s last (a G1 chain's one handle).
fn shared(a: &Design, b: &Design) -> Design {
    let mut out = b.clone();
    let last = a.net().cols() - 1;
    for r in 0..b.net().rows() {
        out.set_tangent(r, 0, a.net().get(r, last)).unwrap();
    }
    out
}

/// A few details on levels 1 and 2 of `b` (small turns in the local frame).
fn details_of(b: &Design, on: bool) -> Details {
    let mut d = Details::new();
    if on {
        let (rows, cols) = (b.net().rows(), b.net().cols());
        d.insert(
            (1, 1 % (2 * rows - 1), 2 % cols),
            DVec3::new(0.1, -0.05, 1.0).normalize(),
        );
        d.insert(
            (2, 3 % (2 * rows - 1), 1),
            DVec3::new(-0.08, 0.1, 1.0).normalize(),
        );
    }
    d
}

/// A fine tuning with values near 1, or none.
fn tuning_of(values: &[f64], constraint: u8) -> Option<SurfaceTuning> {
    let c = match constraint {
        0 => return None,
        1 => Constraint::Free,
        _ => Constraint::KeepEnds,
    };
    let mut t = SurfaceTuning::identity();
    t.function = streamline_kernel::finetune::bspline::TensorBSpline::new(
        2,
        2,
        Grid::new(3, 3, values.to_vec()).unwrap(),
    )
    .unwrap();
    t.constraint = c;
    Some(t)
}

/// The kind of start a case tests.
#[derive(Debug, Clone, Copy)]
enum Kind {
    Curve,
    Chain(Continuity),
    Side(Edge, Continuity),
}

fn kind() -> impl Strategy<Value = Kind> {
    prop_oneof![
        Just(Kind::Curve),
        Just(Kind::Chain(Continuity::G0)),
        Just(Kind::Chain(Continuity::G1)),
        Just(Kind::Side(Edge::First, Continuity::G0)),
        Just(Kind::Side(Edge::Last, Continuity::G1)),
        Just(Kind::Side(Edge::First, Continuity::G1)),
    ]
}

fn stack(d: &Design) -> Option<Stack> {
    match Stack::build(d, DEPTH) {
        Ok(s) => Some(s),
        Err(KernelError::ParamsNotIncreasing { .. }) => None,
        Err(e) => panic!("{e}"),
    }
}

/// The whole build of `b` on the case's start.
fn whole(kind: Kind, a: &Design, sa: &Stack, parts: PatchParts) -> Result<Stack, String> {
    match kind {
        Kind::Curve => Stack::build_parts(parts, DEPTH).map_err(|e| e.to_string()),
        Kind::Chain(c) => chain(a, sa, parts, c).map_err(|e| e.to_string()),
        Kind::Side(e, c) => side(sa, parts, e, c).map_err(|e| e.to_string()),
    }
}

fn start<'a>(kind: Kind, a: &'a Design, sa: &'a Stack) -> Start<'a> {
    match kind {
        Kind::Curve => Start::Curve,
        Kind::Chain(continuity) => Start::Edge {
            a_design: a,
            a: sa,
            edge: Edge::End,
            continuity,
        },
        Kind::Side(edge, continuity) => Start::Edge {
            a_design: a,
            a: sa,
            edge,
            continuity,
        },
    }
}

/// `A`, its stack and `B` for a case (`B` is `A` itself on its own curve).
fn pair(spec: &PairSpec, kind: Kind) -> Option<(Design, Stack, Design)> {
    match kind {
        Kind::Curve => {
            let a = spec.a(Field::Bent);
            let sa = stack(&a)?;
            Some((a.clone(), sa, a))
        }
        Kind::Chain(c) => {
            let a = spec.a(Field::Bent);
            let sa = stack(&a)?;
            let b = spec.b_chain(&a, Field::Bent, c == Continuity::G1, spec.order_b);
            Some((a, sa, b))
        }
        Kind::Side(edge, _) => side_pair(spec, Field::Bent, edge, DEPTH),
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, ..ProptestConfig::default() })]

    /// After every edit of a random sequence the kept patch equals the
    /// whole build bit for bit, or both refuse it with the same message.
    #[test]
    fn a_kept_patch_is_the_whole_build_after_every_edit(
        spec in pair_spec(),
        kind in kind(),
        with_details in any::<bool>(),
        values in prop::collection::vec(0.85f64..1.15, 9),
        constraint in 0u8..3,
        steps in prop::collection::vec(step(), 1..6),
    ) {
        let Some((mut a, mut sa, mut b)) = pair(&spec, kind) else { return Ok(()) };
        let details = details_of(&b, with_details);
        let tuning = tuning_of(&values, constraint);
        let parts = PatchParts::new(&b, Some(&details), tuning.as_ref());
        let built = PatchState::build(parts, start(kind, &a, &sa), DEPTH);
        let reference = whole(kind, &a, &sa, parts);
        let (mut state, mut kept) = match (built, reference) {
            (Ok(x), Ok(w)) => {
                prop_assert!(same(&x.1, &w), "{kind:?} built: {:?}", differ(&x.1, &w));
                x
            }
            (Err(e), Err(w)) => {
                prop_assert_eq!(e.to_string(), w);
                return Ok(());
            }
            (x, w) => {
                return Err(TestCaseError::fail(format!(
                    "built {:?} but the whole build {:?}",
                    x.map(|_| ()).map_err(|e| e.to_string()),
                    w.map(|_| ())
                )));
            }
        };
        for s in steps {
            match s {
                Step::TurnB(r, c, axis, x) => b = turned(&b, r, c, axis, x),
                Step::StretchB(r, k) => b = stretched(&b, r, k),
                Step::TurnA(r, c, axis, x) => {
                    if matches!(kind, Kind::Curve) {
                        continue;
                    }
                    let a2 = turned(&a, r, c, axis, x);
                    let Some(sa2) = stack(&a2) else { continue };
                    a = a2;
                    sa = sa2;
                }
            }
            if let Kind::Chain(Continuity::G1) = kind {
                b = shared(&a, &b);
            }
            let parts = PatchParts::new(&b, Some(&details), tuning.as_ref());
            let reference = whole(kind, &a, &sa, parts);
            let before = kept.clone();
            match (state.update(parts, start(kind, &a, &sa), DEPTH, &mut kept), reference) {
                (Ok(u), Ok(w)) => {
                    prop_assert!(
                        same(&kept, &w),
                        "{kind:?}, details {with_details}, tuning {constraint}, after {s:?}: {:?}",
                        differ(&kept, &w)
                    );
                    // the rows it does not name kept their bits
                    for (d, (old, new)) in before.points.iter().zip(&kept.points).enumerate() {
                        if old.rows() != new.rows() || old.cols() != new.cols() {
                            continue;
                        }
                        for r in 0..new.rows() {
                            let named = u.rows[d].is_some_and(|x| x.lo <= r && r <= x.hi);
                            let same_row = old.row(r).iter().zip(new.row(r)).all(|(x, y)| bits(*x) == bits(*y));
                            prop_assert!(named || same_row, "after {s:?}: depth {d} row {r} moved unnamed");
                        }
                    }
                }
                (Err(e), Err(w)) => {
                    prop_assert_eq!(e.to_string(), w);
                    return Ok(());
                }
                (x, w) => {
                    return Err(TestCaseError::fail(format!(
                        "after {s:?}: updated {:?} but the whole build {:?}",
                        x.map(|_| ()).map_err(|e| e.to_string()),
                        w.map(|_| ())
                    )));
                }
            }
        }
    }
}

/// A one-cell edit of a larger chained net at depth 4 re-blends a small
/// part of what a whole build does, and places again only the rows of its
/// window; the rows outside keep their points bit for bit. Control: a
/// change of shape builds whole and counts every tangent.
#[test]
fn a_one_cell_edit_stays_local() {
    let spec = PairSpec {
        cols_b: 16,
        ..PairSpec::kobbelt_s_first(24, 9)
    };
    let depth = 4;
    let a = spec.a(Field::Bent);
    let sa = Stack::build(&a, depth).unwrap();
    let mut b = spec.b_chain(&a, Field::Bent, true, spec.order_b);
    let start = Start::Edge {
        a_design: &a,
        a: &sa,
        edge: Edge::End,
        continuity: Continuity::G1,
    };
    let (mut state, mut kept) = PatchState::build((&b).into(), start, depth).unwrap();
    let before = kept.clone();
    b = turned(&b, 12, 8, DVec3::Z, 0.2);
    let u = state.update((&b).into(), start, depth, &mut kept).unwrap();
    let w = chain(&a, &sa, &b, Continuity::G1).unwrap();
    assert!(same(&kept, &w));
    let fine = kept.finest();
    let all = (1..=depth as usize)
        .map(|d| kept.levels[d].tangents.data().len())
        .sum::<usize>();
    assert!(!u.whole);
    assert!(
        u.reblended * 4 < all,
        "re-blended {} of {all} tangents",
        u.reblended
    );
    let rows = u.rows[depth as usize].expect("some rows moved");
    assert!(rows.hi - rows.lo + 1 < fine.tangents.rows() / 2, "{rows:?}");
    let p = kept.finest_points();
    for r in (0..p.rows()).filter(|&r| r < rows.lo || r > rows.hi) {
        assert_eq!(p.row(r), before.finest_points().row(r), "row {r} kept");
    }
    // control: another net shape is built whole
    let c = PairSpec {
        cols_b: spec.cols_b + 1,
        ..spec.clone()
    };
    let wider = c.b_chain(&a, Field::Bent, true, spec.order_b);
    let u = state
        .update((&wider).into(), start, depth, &mut kept)
        .unwrap();
    assert!(
        u.whole
            && u.reblended
                == (1..=depth as usize)
                    .map(|d| kept.levels[d].tangents.data().len())
                    .sum::<usize>()
    );
}
