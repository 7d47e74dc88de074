//! docs/math.md §11, a local edit: after `A` changes while `B`'s design does
//! not, `joins::rejoin` keeps `B`'s levels and places its points again, and
//! its result is bit for bit what the whole join (`chain`, `side`) builds
//! on the new `A`. It must also take that path for the edits it can (an
//! edit of `A` away from what `B` reads), and refuse the others: a negative
//! control shows that keeping the levels after an edit of `A`'s seam column
//! (G1) would be wrong.

mod common;

use common::joins::{Field, bits, pair_spec, side_pair};
use glam::{DQuat, DVec3};
use proptest::prelude::*;
use streamline_kernel::joins::chain::chain;
use streamline_kernel::joins::edges::Edges;
use streamline_kernel::joins::rejoin::{Rejoin, rejoin};
use streamline_kernel::joins::side::side;
use streamline_kernel::joins::{Continuity, Edge, Stack};
use streamline_kernel::{BlendOrder, Design, KernelError};

const DEPTH: u32 = 3;

/// Bit for bit the same stack.
fn same(x: &Stack, y: &Stack) -> bool {
    x.levels.len() == y.levels.len()
        && x.levels.iter().zip(&y.levels).all(|(a, b)| {
            a.tangents
                .data()
                .iter()
                .zip(b.tangents.data())
                .all(|(u, v)| bits(*u) == bits(*v))
                && a.params
                    .s
                    .data()
                    .iter()
                    .zip(b.params.s.data())
                    .all(|(u, v)| u.to_bits() == v.to_bits())
                && a.params
                    .t
                    .iter()
                    .zip(&b.params.t)
                    .all(|(u, v)| u.to_bits() == v.to_bits())
                && a.params
                    .sigma
                    .iter()
                    .zip(&b.params.sigma)
                    .all(|(u, v)| u.to_bits() == v.to_bits())
        })
        && x.points.len() == y.points.len()
        && x.points.iter().zip(&y.points).all(|(a, b)| {
            a.rows() == b.rows()
                && a.data()
                    .iter()
                    .zip(b.data())
                    .all(|(u, v)| bits(*u) == bits(*v))
        })
}

/// `a` with tangent `(row, col)` turned by `angle` about `axis`.
fn turned(a: &Design, row: usize, col: usize, axis: DVec3, angle: f64) -> Design {
    let mut out = a.clone();
    let v = DQuat::from_axis_angle(axis, angle) * a.net().get(row, col);
    out.set_tangent(row, col, v).unwrap();
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

fn stack(d: &Design) -> Option<Stack> {
    match Stack::build(d, DEPTH) {
        Ok(s) => Some(s),
        Err(KernelError::ParamsNotIncreasing { .. }) => None,
        Err(e) => panic!("{e}"),
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, ..ProptestConfig::default() })]

    /// Chains: `rejoin` equals `chain` on the new `A` bit for bit; G0 always
    /// rejoins (its levels read only `A`'s `t`), and so does G1 for an edit
    /// off the seam column with Kobbelt (the 4-point scheme refines a
    /// boundary column by itself); an edit of the seam column under G1 is
    /// refused.
    #[test]
    fn a_chain_rejoins_bit_for_bit(
        spec in pair_spec(),
        g1 in any::<bool>(),
        cell in (0usize..8, 0usize..8),
        axis in common::unit(),
        angle in 0.01f64..0.5,
    ) {
        let c = if g1 { Continuity::G1 } else { Continuity::G0 };
        let a = spec.a(Field::Bent);
        let b = spec.b_chain(&a, Field::Bent, g1, spec.order_a);
        let (row, col) = (cell.0 % a.net().rows(), cell.1 % a.net().cols());
        let a2 = turned(&a, row, col, axis, angle);
        let (Some(sa), Some(sa2)) = (stack(&a), stack(&a2)) else { return Ok(()) };
        let Ok(sb) = chain(&a, &sa, &b, c) else { return Ok(()) };
        let b2 = if g1 { shared(&a2, &b) } else { b.clone() };
        let whole = chain(&a2, &sa2, &b2, c).unwrap();
        let last = a.net().cols() - 1;
        match rejoin(&a2, &Edges::of(&sa, true), &Edges::of(&sa2, true), &b2, sb.clone(), Edge::End, c) {
            Rejoin::Moved { stack: s, .. } => prop_assert!(same(&s, &whole)),
            Rejoin::Unchanged(s) => prop_assert!(same(&s, &whole) && same(&sb, &whole)),
            Rejoin::Rebuild(s) => {
                prop_assert!(same(&s, &sb), "the old stack handed back");
                prop_assert!(g1, "G0 always rejoins");
                prop_assert!(col == last || !spec.scheme.is_interpolatory(),
                    "an edit off the seam column of a Kobbelt net rejoins");
            }
        }
        if g1 && col == last {
            let again = rejoin(&a2, &Edges::of(&sa, true), &Edges::of(&sa2, true), &b2, sb, Edge::End, c);
            prop_assert!(matches!(again, Rejoin::Rebuild(_)));
        }
    }

    /// Side joins: `rejoin` equals `side` on the new `A` bit for bit; G0
    /// always rejoins; G1 rejoins too when `B` is an s-first Kobbelt net
    /// (its first column projected again where `A`'s edge moved, and what
    /// reads it re-blended, `joins::reproject`), and is refused otherwise,
    /// or where the whole join is refused.
    #[test]
    fn a_side_join_rejoins_bit_for_bit(
        spec in pair_spec(),
        g1 in any::<bool>(),
        last in any::<bool>(),
        cell in (0usize..8, 0usize..8),
        axis in common::unit(),
        angle in 0.01f64..0.3,
    ) {
        let c = if g1 { Continuity::G1 } else { Continuity::G0 };
        let edge = if last { Edge::Last } else { Edge::First };
        let Some((a, sa, b)) = side_pair(&spec, Field::Bent, edge, DEPTH) else { return Ok(()) };
        let (row, col) = (cell.0 % a.net().rows(), cell.1 % a.net().cols());
        let a2 = turned(&a, row, col, axis, angle);
        let Some(sa2) = stack(&a2) else { return Ok(()) };
        let Ok(sb) = side(&sa, &b, edge, c) else { return Ok(()) };
        let whole = side(&sa2, &b, edge, c);
        let kept = b.scheme().is_interpolatory() && b.order() == BlendOrder::SFirst;
        match rejoin(&a2, &Edges::of(&sa, true), &Edges::of(&sa2, true), &b, sb.clone(), edge, c) {
            Rejoin::Moved { stack: s, .. } => prop_assert!(same(&s, &whole.unwrap())),
            Rejoin::Unchanged(s) => prop_assert!(same(&s, &whole.unwrap())),
            Rejoin::Rebuild(s) => {
                prop_assert!(whole.is_err() || (g1 && !kept),
                    "G0, and G1 on an s-first Kobbelt net, rejoin unless the join is refused");
                prop_assert!(whole.is_err() || same(&s, &sb), "the old stack handed back");
            }
        }
    }
}

/// A G1 side join on an s-first Kobbelt `B` after an edit of `A` near its
/// edge: `rejoin` projects `B`'s first column again and re-blends only what
/// reads it, bit for bit the whole join; at the finest depth that leaves
/// most columns of `B` untouched (the re-blended window is the first few
/// columns, while every point moves with its start). Controls: the edit
/// moved `A`'s edge normals at every depth from 2 on (so the levels did
/// need re-blending), and `B`'s finest tangents differ from the old ones in
/// the first column but not in the last.
#[test]
fn a_side_g1_join_reblends_only_its_first_columns() {
    let spec = common::joins::PairSpec::kobbelt_s_first(7, 9);
    let edge = Edge::First;
    let depth = 4;
    let (a, sa, b) = side_pair(&spec, Field::Bent, edge, depth).expect("a side pair");
    let a2 = turned(&a, 1, 4, DVec3::new(0.2, 0.9, 0.3).normalize(), 0.2);
    let sa2 = Stack::build(&a2, depth).unwrap();
    let sb = side(&sa, &b, edge, Continuity::G1).unwrap();
    let whole = side(&sa2, &b, edge, Continuity::G1).unwrap();
    let (old_a, new_a) = (Edges::of(&sa, true), Edges::of(&sa2, true));
    for d in 2..=depth as usize {
        let (o, n) = (
            old_a.levels[d].curve(edge).unwrap(),
            new_a.levels[d].curve(edge).unwrap(),
        );
        assert!(!o.same_bits(n), "control: the edge moved at depth {d}");
    }
    let Rejoin::Moved { stack, rows } =
        rejoin(&a2, &old_a, &new_a, &b, sb.clone(), edge, Continuity::G1)
    else {
        panic!("a G1 side join on an s-first Kobbelt net rejoins");
    };
    assert!(same(&stack, &whole));
    let (fine, old) = (stack.finest(), sb.finest());
    let cols = fine.tangents.cols();
    let differs = |c: usize| {
        (0..fine.tangents.rows())
            .any(|r| bits(fine.tangents.get(r, c)) != bits(old.tangents.get(r, c)))
    };
    assert!(differs(0), "control: the first column was projected again");
    let untouched = (0..cols).rev().take_while(|&c| !differs(c)).count();
    assert!(
        untouched * 2 > cols,
        "only the first columns re-blended: {untouched} of {cols} columns untouched"
    );
    assert!(
        rows.last().copied().flatten().is_some(),
        "the moved rows are reported"
    );
}
/// The rows of `new` whose first point is not bit for bit `old`'s.
fn moved_rows(
    old: &streamline_kernel::Grid<DVec3>,
    new: &streamline_kernel::Grid<DVec3>,
) -> Vec<usize> {
    (0..new.rows())
        .filter(|&r| bits(old.get(r, 0)) != bits(new.get(r, 0)))
        .collect()
}

/// A G0 chain's rejoin after an edit of `A` (`cell`): the row span of each
/// depth is exactly that of the rows whose start moved, the rows outside it
/// are `B`'s old rows bit for bit, and the span's first and last rows
/// differ from the old ones (negative control: a rejoin that copied them,
/// or placed no row again, would not be the join). Returns the finest
/// depth's span length and row count, `None` when the case does not apply.
fn check_row_spans(
    spec: &common::joins::PairSpec,
    cell: (usize, usize),
    angle: f64,
) -> Option<(usize, usize)> {
    let a = spec.a(Field::Bent);
    let b = spec.b_chain(&a, Field::Bent, false, spec.order_a);
    let (row, col) = (cell.0 % a.net().rows(), cell.1 % a.net().cols());
    let a2 = turned(&a, row, col, DVec3::new(0.3, 0.9, 0.2).normalize(), angle);
    let (sa, sa2) = (stack(&a)?, stack(&a2)?);
    let sb = chain(&a, &sa, &b, Continuity::G0).ok()?;
    let whole = chain(&a2, &sa2, &b, Continuity::G0).unwrap();
    let (old_a, new_a) = (Edges::of(&sa, true), Edges::of(&sa2, true));
    let (s, rows) = match rejoin(
        &a2,
        &old_a,
        &new_a,
        &b,
        sb.clone(),
        Edge::End,
        Continuity::G0,
    ) {
        Rejoin::Moved { stack, rows } => (stack, rows),
        Rejoin::Unchanged(s) => {
            assert!(same(&s, &whole));
            return None;
        }
        Rejoin::Rebuild(_) => panic!("a G0 chain always rejoins"),
    };
    assert!(same(&s, &whole), "bit for bit the whole chain");
    assert_eq!(rows.len(), whole.points.len());
    let mut finest = None;
    for (d, span) in rows.iter().enumerate() {
        let (old, new) = (&sb.points[d], &whole.points[d]);
        let moved = moved_rows(old, new);
        match span {
            None => {
                assert!(
                    moved.is_empty(),
                    "depth {d}: rows {moved:?} moved unreported"
                );
            }
            Some(span) => {
                assert_eq!(
                    (span.lo, span.hi),
                    (moved[0], *moved.last().unwrap()),
                    "depth {d}"
                );
                for r in 0..new.rows() {
                    let same_row = old
                        .row(r)
                        .iter()
                        .zip(new.row(r))
                        .all(|(x, y)| bits(*x) == bits(*y));
                    assert_eq!(same_row, !moved.contains(&r), "depth {d} row {r}");
                }
                // negative control: copying the span's ends would be wrong
                for r in [span.lo, span.hi] {
                    assert!(
                        old.row(r)
                            .iter()
                            .zip(new.row(r))
                            .any(|(x, y)| bits(*x) != bits(*y))
                    );
                }
                if d + 1 == rows.len() {
                    finest = Some((span.hi - span.lo + 1, new.rows()));
                    check_normals_window(old, new, span.lo, span.hi);
                }
            }
        }
    }
    finest
}

/// What `build_joined` does with a rejoin's span (docs/math.md §4): the
/// old mesh normals with the moved rows ± 1 recomputed by `normals_window`
/// are the new points' whole mesh normals bit for bit; recomputing the
/// moved rows alone is not (negative control, when a row borders them).
fn check_normals_window(
    old: &streamline_kernel::Grid<DVec3>,
    new: &streamline_kernel::Grid<DVec3>,
    lo: usize,
    hi: usize,
) {
    use streamline_kernel::streamline::surface_mesh::{SurfaceMesh, normals_window};
    let whole = SurfaceMesh::from_points(new).normals;
    let window = |lo: usize, hi: usize| {
        let mut out = SurfaceMesh::from_points(old).normals;
        normals_window(new.data(), new.cols(), lo, hi, 0, &mut out);
        out
    };
    let last = new.rows() - 1;
    let local = window(lo.saturating_sub(1), (hi + 1).min(last));
    assert!(local.iter().zip(&whole).all(|(x, y)| bits(*x) == bits(*y)));
    if lo > 0 || hi < last {
        let short = window(lo, hi);
        assert!(short.iter().zip(&whole).any(|(x, y)| bits(*x) != bits(*y)));
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, ..ProptestConfig::default() })]

    /// A rejoin places again only the rows whose start moved, and says
    /// which (see [`check_row_spans`]).
    #[test]
    fn a_rejoin_places_only_the_moved_rows(
        spec in pair_spec(),
        cell in (0usize..8, 0usize..8),
        angle in 0.01f64..0.5,
    ) {
        check_row_spans(&spec, cell, angle);
    }
}

/// An edit of one handle of a net with several rows moves a strict part of
/// the finest depth's rows (the rejoin is local), on most nets.
#[test]
fn an_edit_of_one_row_moves_a_few_rows_only() {
    use proptest::strategy::ValueTree;
    use proptest::test_runner::TestRunner;
    let mut runner = TestRunner::deterministic();
    let (mut local, mut checked) = (0, 0);
    for _ in 0..48 {
        let spec = pair_spec().new_tree(&mut runner).unwrap().current();
        if let Some((span, rows)) = check_row_spans(&spec, (0, 0), 0.3) {
            checked += 1;
            if span < rows {
                local += 1;
            }
        }
    }
    assert!(checked >= 16, "only {checked} nets checked");
    assert!(
        local * 2 >= checked,
        "only {local} of {checked} edits were local"
    );
}

/// Negative control: under G1, keeping `B`'s levels after `A`'s seam column
/// turned (placing the old levels at the new starts, what `rejoin` refuses
/// to do) is not the join: its seam tangents are not `A`'s.
#[test]
fn keeping_the_levels_after_a_seam_column_edit_is_wrong() {
    use proptest::strategy::ValueTree;
    use proptest::test_runner::TestRunner;
    let mut runner = TestRunner::deterministic();
    let mut checked = 0;
    for _ in 0..64 {
        let spec = pair_spec().new_tree(&mut runner).unwrap().current();
        let a = spec.a(Field::Bent);
        let b = spec.b_chain(&a, Field::Bent, true, spec.order_a);
        let last = a.net().cols() - 1;
        let a2 = turned(&a, 0, last, DVec3::Y, 0.3);
        let (Some(sa), Some(sa2)) = (stack(&a), stack(&a2)) else {
            continue;
        };
        let Ok(sb) = chain(&a, &sa, &b, Continuity::G1) else {
            continue;
        };
        let b2 = shared(&a2, &b);
        let whole = chain(&a2, &sa2, &b2, Continuity::G1).unwrap();
        let again = rejoin(
            &a2,
            &Edges::of(&sa, true),
            &Edges::of(&sa2, true),
            &b2,
            sb.clone(),
            Edge::End,
            Continuity::G1,
        );
        assert!(matches!(again, Rejoin::Rebuild(_)));
        // the shortcut: old levels, new starts
        let seam = sa2.levels[DEPTH as usize]
            .tangents
            .column(sa2.levels[DEPTH as usize].tangents.cols() - 1);
        let kept = sb.levels[DEPTH as usize].tangents.column(0);
        assert!(seam.iter().zip(&kept).any(|(x, y)| bits(*x) != bits(*y)));
        assert!(!same(&sb, &whole));
        checked += 1;
    }
    assert!(checked >= 16, "only {checked} nets checked");
}

/// The drag of the two-car scene: the car and a copy
/// G1-chained on its `End` at depth 5, the car's tangent (2, 4) turned. The
/// rejoin moves most of the 161 rows at depth 5, not all, and equals the whole chain bit for bit; the rows it did
/// not place are the old ones (negative control: the span's end rows moved).
#[test]
fn the_two_car_drag_rejoins_bit_for_bit_at_depth_5() {
    use streamline_kernel::levels::presets;
    let depth = 5;
    let a = presets::car1();
    let b = shared(&a, &a);
    let a2 = turned(&a, 2, 4, DVec3::Y, 0.01);
    let (sa, sa2) = (
        Stack::build(&a, depth).unwrap(),
        Stack::build(&a2, depth).unwrap(),
    );
    let sb = chain(&a, &sa, &b, Continuity::G1).unwrap();
    let whole = chain(&a2, &sa2, &b, Continuity::G1).unwrap();
    let (s, rows) = match rejoin(
        &a2,
        &Edges::of(&sa, false),
        &Edges::of(&sa2, false),
        &b,
        sb.clone(),
        Edge::End,
        Continuity::G1,
    ) {
        Rejoin::Moved { stack, rows } => (stack, rows),
        other => panic!("a rejoin that moves rows, not {other:?}"),
    };
    assert!(same(&s, &whole), "bit for bit the whole chain");
    let span = rows[depth as usize].expect("rows moved at depth 5");
    let fine = &whole.points[depth as usize];
    assert_eq!(fine.rows(), 161);
    let old = &sb.points[depth as usize];
    let moved = moved_rows(old, fine);
    assert!(
        moved.len() > 140 && moved.len() < 161,
        "{} rows moved",
        moved.len()
    );
    for r in [span.lo, span.hi] {
        assert_ne!(bits(old.get(r, 1)), bits(fine.get(r, 1)));
    }
}
