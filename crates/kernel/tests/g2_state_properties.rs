//! docs/math.md §11.1 (Eqs. 68–70) and §5, a G2 run kept between edits
//! (`joins::g2_state`): after any edit of a patch's tangents, `s` or the
//! first patch's initial curve, `G2State::update` gives bit for bit the
//! stacks that `joins::merged::g2_run` builds whole on the edited patches,
//! says which patches changed (every one that did), and re-blends no more
//! than the whole build; on three chained cars an edit in the first re-blends a small part
//! of the merged net (the window), and a change of depth builds whole.

mod common;

use common::joins::{Field, PairSpec, bits, pair_spec};
use glam::{DQuat, DVec3};
use proptest::prelude::*;
use streamline_kernel::joins::g2_state::G2State;
use streamline_kernel::joins::merged::g2_run;
use streamline_kernel::joins::{JoinError, Stack};
use streamline_kernel::levels::presets;
use streamline_kernel::streamline::initial_curve::InitialCurve;
use streamline_kernel::{Design, KernelError};

const DEPTH: u32 = 3;

/// Bit for bit the same stack: levels (tangents, `s`, `t`, `σ`) and points.
fn same(x: &Stack, y: &Stack) -> bool {
    let f = |a: &[f64], b: &[f64]| {
        a.len() == b.len() && a.iter().zip(b).all(|(u, v)| u.to_bits() == v.to_bits())
    };
    let v = |a: &[DVec3], b: &[DVec3]| {
        a.len() == b.len() && a.iter().zip(b).all(|(u, v)| bits(*u) == bits(*v))
    };
    x.levels.len() == y.levels.len()
        && x.levels.iter().zip(&y.levels).all(|(a, b)| {
            a.tangents.cols() == b.tangents.cols()
                && v(a.tangents.data(), b.tangents.data())
                && f(a.params.s.data(), b.params.s.data())
                && f(&a.params.t, &b.params.t)
                && f(&a.params.sigma, &b.params.sigma)
        })
        && x.points.len() == y.points.len()
        && x.points
            .iter()
            .zip(&y.points)
            .all(|(a, b)| a.cols() == b.cols() && v(a.data(), b.data()))
}

/// A run of two or three G2-chained patches (each one's first column the
/// previous one's last), bent or with nasty tangents (`common::nasty`).
fn run(spec: &PairSpec, three: bool, nasty: bool) -> Vec<Design> {
    let f = if nasty { Field::Nasty } else { Field::Bent };
    let a = spec.a(f);
    let b = spec.b_chain(&a, f, true, spec.order_a);
    let mut out = vec![a, b];
    if three {
        let c = spec.b_chain(&out[1], f, true, spec.order_a);
        out.push(c);
    }
    out
}

/// The whole build, or `None` when the random parameters stop increasing.
fn whole(patches: &[Design], depth: u32) -> Option<Vec<Stack>> {
    let refs: Vec<&Design> = patches.iter().collect();
    match g2_run(&refs, depth) {
        Ok(s) => Some(s),
        Err(JoinError::Kernel(KernelError::ParamsNotIncreasing { .. })) => None,
        Err(e) => panic!("{e}"),
    }
}

/// Tangent `(row, col)` of patch `p` turned; the seam column is one handle
/// of the two patches it joins, so both turn.
fn turn(patches: &mut [Design], p: usize, row: usize, col: usize, q: DQuat) {
    let v = q * patches[p].net().get(row, col);
    patches[p].set_tangent(row, col, v).unwrap();
    let last = patches[p].net().cols() - 1;
    if col == last && p + 1 < patches.len() {
        patches[p + 1].set_tangent(row, 0, v).unwrap();
    }
    if col == 0 && p > 0 {
        let prev = patches[p - 1].net().cols() - 1;
        patches[p - 1].set_tangent(row, prev, v).unwrap();
    }
}

/// Row `row` of patch `p`'s `s` lengthened by `by` from column `col` on.
fn stretch(patches: &mut [Design], p: usize, row: usize, col: usize, by: f64) {
    let mut s = patches[p].params().s.row(row).to_vec();
    for v in &mut s[col..] {
        *v += by;
    }
    patches[p].set_s_row(row, &s).unwrap();
}

/// Updates `state` and `stacks` to `patches` and checks them against the
/// whole build: the same bits, `changed` every stack that differs, `rows`
/// every finest row that moved and `levels` every row of a level whose
/// tangents or parameters changed.
fn check_update(
    state: &mut G2State,
    stacks: &mut Vec<Stack>,
    patches: &[Design],
    depth: u32,
) -> Result<(), TestCaseError> {
    let Some(expect) = whole(patches, depth) else {
        return Ok(());
    };
    let before = stacks.clone();
    let refs: Vec<&Design> = patches.iter().collect();
    let u = state.update(&refs, depth, stacks).unwrap();
    for (p, (got, want)) in stacks.iter().zip(&expect).enumerate() {
        prop_assert!(same(got, want), "patch {} differs from the whole build", p);
        // every stack that changed says so (one left of the edit may say so too)
        prop_assert!(
            u.changed[p] || same(&before[p], want),
            "patch {} changed unsaid",
            p
        );
        // the finest points outside the rows it names kept their bits
        let (old, new) = (before[p].finest_points(), got.finest_points());
        if old.rows() == new.rows() && old.cols() == new.cols() {
            for r in 0..new.rows() {
                let named = u.rows[p].is_some_and(|s| s.lo <= r && r <= s.hi);
                let kept = old
                    .row(r)
                    .iter()
                    .zip(new.row(r))
                    .all(|(a, b)| bits(*a) == bits(*b));
                prop_assert!(named || kept, "patch {} row {} moved unnamed", p, r);
            }
        }
        // each level's tangents and parameters outside the rows `levels`
        // names kept their bits
        for (d, (lo, ln)) in before[p].levels.iter().zip(&got.levels).enumerate() {
            let (t0, t1) = (&lo.tangents, &ln.tangents);
            if (t0.rows(), t0.cols()) != (t1.rows(), t1.cols()) {
                continue;
            }
            for r in 0..t1.rows() {
                let named = u.levels[d].is_some_and(|s| s.lo <= r && r <= s.hi);
                let kept = (t0.row(r).iter().zip(t1.row(r))).all(|(a, b)| bits(*a) == bits(*b))
                    && (lo.params.s.row(r).iter().zip(ln.params.s.row(r)))
                        .all(|(a, b)| a.to_bits() == b.to_bits())
                    && lo.params.t[r].to_bits() == ln.params.t[r].to_bits()
                    && lo.params.sigma[r].to_bits() == ln.params.sigma[r].to_bits();
                prop_assert!(
                    named || kept,
                    "patch {} level {} row {} changed unnamed",
                    p,
                    d,
                    r
                );
            }
        }
    }
    let total: usize = expect
        .iter()
        .flat_map(|s| s.levels.iter().skip(1))
        .map(|l| l.tangents.rows() * l.tangents.cols())
        .sum();
    // the merged levels share each seam column, so the parts add up to more
    prop_assert!(u.reblended <= total);
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, ..ProptestConfig::default() })]

    /// Built whole, the state's stacks are `g2_run`'s.
    #[test]
    fn a_state_built_whole_is_g2_run(spec in pair_spec(), three in any::<bool>(), nasty in any::<bool>()) {
        let patches = run(&spec, three, nasty);
        let Some(expect) = whole(&patches, DEPTH) else { return Ok(()) };
        let refs: Vec<&Design> = patches.iter().collect();
        let (_, stacks) = G2State::build(&refs, DEPTH).unwrap();
        for (got, want) in stacks.iter().zip(&expect) {
            prop_assert!(same(got, want));
        }
    }

    /// Edits of tangents (seam columns too), of `s`, and of the first
    /// patch's initial curve, one after the other, each updated in place:
    /// bit for bit the whole build after every one. Turning a tangent back
    /// to what it was restores the first stacks.
    #[test]
    fn an_updated_run_is_the_whole_build_bit_for_bit(
        spec in pair_spec(),
        three in any::<bool>(),
        nasty in any::<bool>(),
        cells in prop::collection::vec((0usize..3, 0usize..8, 0usize..8), 1..4),
        axis in common::unit(),
        angle in 0.01f64..0.5,
        by in 0.01f64..0.4,
    ) {
        let mut patches = run(&spec, three, nasty);
        let refs: Vec<&Design> = patches.iter().collect();
        let Ok((mut state, mut stacks)) = G2State::build(&refs, DEPTH) else { return Ok(()) };
        let first = stacks.clone();
        let q = DQuat::from_axis_angle(axis, angle);
        for &(p, r, c) in &cells {
            let p = p % patches.len();
            let (r, c) = (r % patches[p].net().rows(), c % patches[p].net().cols());
            turn(&mut patches, p, r, c, q);
            check_update(&mut state, &mut stacks, &patches, DEPTH)?;
        }
        // and back, in the opposite order
        for &(p, r, c) in cells.iter().rev() {
            let p = p % patches.len();
            let (r, c) = (r % patches[p].net().rows(), c % patches[p].net().cols());
            turn(&mut patches, p, r, c, q.inverse());
        }
        check_update(&mut state, &mut stacks, &patches, DEPTH)?;
        // a turn and its inverse may differ in the last bit: when every net
        // came back exactly, so did every stack
        let refs: Vec<&Design> = patches.iter().collect();
        let (_, again) = G2State::build(&refs, DEPTH).unwrap();
        let nets_back = again.iter().zip(&first).all(|(s, f)| {
            s.levels[0].tangents.data().iter().zip(f.levels[0].tangents.data()).all(|(a, b)| bits(*a) == bits(*b))
        });
        if nets_back {
            for (s, f) in stacks.iter().zip(&first) {
                prop_assert!(same(s, f));
            }
        }
        let (p, r, c) = cells[0];
        let p = p % patches.len();
        let (r, c) = (r % patches[p].net().rows(), c % patches[p].net().cols());
        stretch(&mut patches, p, r, c, by);
        check_update(&mut state, &mut stacks, &patches, DEPTH)?;
        // another initial curve: only the points move
        let curve = patches[0].initial();
        let moved = InitialCurve::new(
            curve.qi().tangents(),
            curve.qi().order(),
            curve.length() * 1.1,
            curve.origin() + DVec3::new(0.0, 0.1, 0.0),
        ).unwrap();
        patches[0].set_initial(moved);
        let refs: Vec<&Design> = patches.iter().collect();
        let before = stacks.clone();
        let u = state.update(&refs, DEPTH, &mut stacks).unwrap();
        prop_assert_eq!(u.reblended, 0, "a new initial curve re-blends nothing");
        let expect = whole(&patches, DEPTH).unwrap();
        for (p, (got, want)) in stacks.iter().zip(&expect).enumerate() {
            prop_assert!(same(got, want));
            prop_assert!(u.changed[p] && !same(&before[p], want));
        }
    }

    /// Negative control: the stacks before an edit that moves something are
    /// not the whole build after it (so the comparisons above can fail), and
    /// an update that is told nothing changed changes nothing.
    #[test]
    fn stale_stacks_are_not_the_new_build(spec in pair_spec(), cell in (0usize..8, 0usize..8), axis in common::unit()) {
        let mut patches = run(&spec, false, false);
        let refs: Vec<&Design> = patches.iter().collect();
        let Ok((mut state, mut stacks)) = G2State::build(&refs, DEPTH) else { return Ok(()) };
        let u = state.update(&refs, DEPTH, &mut stacks).unwrap();
        prop_assert!(!u.whole && u.reblended == 0 && !u.changed.contains(&true));
        let (r, c) = (cell.0 % patches[0].net().rows(), cell.1 % patches[0].net().cols());
        turn(&mut patches, 0, r, c, DQuat::from_axis_angle(axis, 0.3));
        let Some(expect) = whole(&patches, DEPTH) else { return Ok(()) };
        prop_assert!(!same(&stacks[0], &expect[0]), "the edited patch's old stack is not its new one");
    }
}

/// Three G2-chained cars at depth 5: an edit of the first car's interior
/// re-blends a window of the merged net, not all of it; the result is the
/// whole build's; a change of depth builds whole.
#[test]
fn three_chained_cars_reblend_the_window_only() {
    let car = presets::car1();
    let last = car.net().cols() - 1;
    let mut copy = car.clone();
    for r in 0..car.net().rows() {
        copy.set_tangent(r, 0, car.net().get(r, last)).unwrap();
    }
    let mut patches = vec![car, copy.clone(), copy];
    for p in 1..3 {
        // each copy's first column the previous one's last (one handle)
        for r in 0..patches[p].net().rows() {
            let v = patches[p - 1].net().get(r, patches[p - 1].net().cols() - 1);
            patches[p].set_tangent(r, 0, v).unwrap();
        }
    }
    let refs: Vec<&Design> = patches.iter().collect();
    let (mut state, mut stacks) = G2State::build(&refs, 5).unwrap();
    turn(&mut patches, 0, 2, 4, DQuat::from_rotation_y(0.01));
    let refs: Vec<&Design> = patches.iter().collect();
    let u = state.update(&refs, 5, &mut stacks).unwrap();
    let expect = g2_run(&refs, 5).unwrap();
    assert!(stacks.iter().zip(&expect).all(|(a, b)| same(a, b)));
    let total: usize = (1..=5)
        .map(|d| {
            let l = &state.design().level(d).unwrap().tangents;
            l.rows() * l.cols()
        })
        .sum();
    assert!(!u.whole);
    assert!(
        u.reblended * 3 < total,
        "re-blended {} of {} merged tangents",
        u.reblended,
        total
    );
    // the third car's levels are untouched; its points moved with the seam
    assert_eq!(u.changed, vec![true, true, true]);
    // an edit of the last car leaves the first two as they are
    let before = stacks.clone();
    turn(&mut patches, 2, 2, 4, DQuat::from_rotation_y(0.01));
    let refs: Vec<&Design> = patches.iter().collect();
    let u = state.update(&refs, 5, &mut stacks).unwrap();
    assert_eq!(u.changed, vec![false, false, true]);
    assert!(same(&stacks[0], &before[0]) && same(&stacks[1], &before[1]));
    let expect = g2_run(&refs, 5).unwrap();
    assert!(stacks.iter().zip(&expect).all(|(a, b)| same(a, b)));
    // a new depth is a whole build
    let u = state.update(&refs, 4, &mut stacks).unwrap();
    assert!(u.whole);
    let expect = g2_run(&refs, 4).unwrap();
    assert!(stacks.iter().zip(&expect).all(|(a, b)| same(a, b)));
}
