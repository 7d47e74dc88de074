//! Incremental rebuild (docs/architecture.md): random edit sequences applied through dirty
//! windows give the same levels as an independent full rebuild, for every
//! scheme and both blend orders; and single edits stay local.

mod common;

use proptest::prelude::*;
use streamline_kernel::levels::dirty_window::DirtyWindow;
use streamline_kernel::levels::incremental::{
    LevelState, build_levels, propagate, reference_levels,
};
use streamline_kernel::levels::multires::{self, Details};
use streamline_kernel::{BlendOrder, DVec3, Design, Grid, SurfaceScheme, levels::presets};

#[derive(Debug, Clone)]
enum Edit {
    Control {
        r: usize,
        c: usize,
        v: DVec3,
    },
    Detail {
        level: u32,
        r: usize,
        c: usize,
        v: DVec3,
    },
    Length {
        r: usize,
        c: usize,
        k: f64,
    },
}

fn design(scheme: SurfaceScheme, order: BlendOrder, rows: usize, cols: usize) -> Design {
    let base = presets::minimal();
    let net = Grid::new(
        rows,
        cols,
        (0..rows * cols)
            .map(|i| {
                let (r, c) = ((i / cols) as f64, (i % cols) as f64);
                DVec3::new(1.0, 0.2 * (0.7 * r).sin(), 0.3 * (0.9 * c).cos()).normalize()
            })
            .collect(),
    )
    .unwrap();
    let s = Grid::new(
        rows,
        cols,
        (0..rows * cols).map(|i| (i % cols) as f64 * 0.5).collect(),
    )
    .unwrap();
    let t = (0..rows).map(|r| r as f64 * 0.3).collect();
    Design::new(&net, s, t, cols / 2, scheme, order, base.initial().clone()).unwrap()
}

fn edit_strategy(rows: usize, cols: usize, depth: u32) -> impl Strategy<Value = Edit> {
    prop_oneof![
        (0..rows, 0..cols, common::unit()).prop_map(|(r, c, v)| Edit::Control { r, c, v }),
        (1..=depth, 0usize..1000, 0usize..1000, common::unit())
            .prop_map(|(level, r, c, v)| Edit::Detail { level, r, c, v }),
        (0..rows, 1..cols, 0.8f64..1.25).prop_map(|(r, c, k)| Edit::Length { r, c, k }),
    ]
}

fn scheme_strategy() -> impl Strategy<Value = (SurfaceScheme, BlendOrder)> {
    (
        prop_oneof![
            (0.0f64..2.0).prop_map(|omega| SurfaceScheme::Kobbelt { omega }),
            Just(SurfaceScheme::CatmullClark),
            Just(SurfaceScheme::DooSabin),
        ],
        prop_oneof![Just(BlendOrder::SFirst), Just(BlendOrder::TFirst)],
    )
}

/// Applies `edits` through dirty windows and compares every level with an
/// independent full rebuild. An edit the parameters refuse (as the editor
/// refuses it) is undone and skipped, and the edits after it are still
/// checked; returns `(edits applied, edits refused)`.
fn check_sequence(
    scheme: SurfaceScheme,
    order: BlendOrder,
    edits: &[Edit],
) -> Result<(usize, usize), TestCaseError> {
    let depth = 3;
    let mut d = design(scheme, order, 5, 6);
    let mut details = Details::new();
    let mut levels = build_levels(&d, &details, depth).unwrap();
    let (mut applied, mut refused) = (0, 0);
    for e in edits {
        let before = d.clone();
        let mut seeds = vec![None; depth as usize + 1];
        match *e {
            Edit::Control { r, c, v } => {
                d.set_tangent(r, c, v).unwrap();
                seeds[0] = Some(DirtyWindow::cell(r, c));
            }
            Edit::Detail { level, r, c, v } => {
                let lv = &levels[level as usize];
                let (r, c) = (r % lv.base().rows(), c % lv.base().cols());
                details.insert((level, r, c), multires::to_local(lv.base(), r, c, v));
                seeds[level as usize] = Some(DirtyWindow::cell(r, c));
            }
            Edit::Length { r, c, k } => {
                let mut s = d.params().s.row(r).to_vec();
                let (a, b) = (s[c] - s[c - 1], s.get(c + 1).map(|x| x - s[c]));
                let shift_c = (k - 1.0) * a;
                let shift_next = shift_c + b.map_or(0.0, |b| (k - 1.0) * b);
                s[c] += shift_c;
                for x in &mut s[c + 1..] {
                    *x += shift_next;
                }
                if d.set_s_row(r, &s).is_err() {
                    refused += 1;
                    continue;
                }
                seeds[0] = Some(DirtyWindow {
                    rows: streamline_kernel::levels::dirty_window::Span::single(r),
                    cols: streamline_kernel::levels::dirty_window::Span::new(
                        c,
                        d.params().s.cols() - 1,
                    ),
                });
            }
        }
        if streamline_kernel::levels::incremental::check_params(&d, depth).is_err() {
            // only new lengths can be refused; the design stays as it was
            prop_assert!(matches!(e, Edit::Length { .. }), "refused {e:?}");
            d = before;
            refused += 1;
            continue;
        }
        let mut refs: Vec<&mut LevelState> = levels.iter_mut().collect();
        propagate(&d, &details, &mut refs, &seeds).unwrap();
        applied += 1;
    }
    let reference = reference_levels(&d, &details, depth).unwrap();
    for (l, (a, b)) in levels.iter().zip(&reference).enumerate() {
        for (x, y) in a.tangents.data().iter().zip(b.tangents.data()) {
            prop_assert!((*x - *y).length() <= 1e-12, "level {l}: {x} vs {y}");
        }
        for (x, y) in a.params.s.data().iter().zip(b.params.s.data()) {
            prop_assert!(
                (x - y).abs() <= 1e-12 * (1.0 + y.abs()),
                "level {l} s: {x} vs {y}"
            );
        }
        prop_assert_eq!(&a.params.t, &b.params.t);
        for (x, y) in a.params.sigma.iter().zip(&b.params.sigma) {
            prop_assert!((x - y).abs() <= 1e-12 * (1.0 + y.abs()));
        }
    }
    Ok((applied, refused))
}

/// docs/architecture.md ("Incremental rebuild, exactly"): random edit sequences through dirty windows equal a full rebuild.
/// Refused edits are skipped, not the rest of the sequence, and the test
/// counts what it checked: every edit is either applied and compared or
/// refused, and nearly all are applied.
#[test]
fn incremental_equals_full_rebuild() {
    use proptest::test_runner::{Config, TestRunner};
    let mut runner = TestRunner::new(Config::with_cases(48));
    let strategy = (
        scheme_strategy(),
        proptest::collection::vec(edit_strategy(5, 6, 3), 1..8),
    );
    let counts = std::cell::Cell::new((0usize, 0usize, 0usize));
    runner
        .run(&strategy, |((scheme, order), edits)| {
            let (applied, refused) = check_sequence(scheme, order, &edits)?;
            prop_assert_eq!(applied + refused, edits.len());
            let (a, r, n) = counts.get();
            counts.set((a + applied, r + refused, n + edits.len()));
            Ok(())
        })
        .unwrap();
    let (applied, refused, edits) = counts.get();
    assert_eq!(applied + refused, edits);
    assert!(
        edits >= 48 && applied * 10 >= edits * 9,
        "{applied} of {edits} edits applied and checked, {refused} refused"
    );
}

#[test]
fn single_edit_is_local_on_20x20_depth_3() {
    let mut d = design(SurfaceScheme::default(), BlendOrder::SFirst, 20, 20);
    let details = Details::new();
    let mut levels = build_levels(&d, &details, 3).unwrap();
    d.set_tangent(10, 10, DVec3::new(0.3, 0.9, 0.1)).unwrap();
    let mut refs: Vec<&mut LevelState> = levels.iter_mut().collect();
    let seeds = [Some(DirtyWindow::cell(10, 10)), None, None, None];
    let p = propagate(&d, &details, &mut refs, &seeds).unwrap();
    let total: usize = levels[1..].iter().map(|l| l.shape().0 * l.shape().1).sum();
    let fine = p.dirty[3].unwrap();
    let rows = levels[3].shape().0;
    let frac = p.reblended as f64 / total as f64;
    let row_frac = fine.rows.len() as f64 / rows as f64;
    assert!(
        frac <= 0.20,
        "re-blended {} of {total} = {frac:.3}",
        p.reblended
    );
    assert!(
        row_frac <= 0.30,
        "dirty rows {} of {rows} = {row_frac:.3}",
        fine.rows.len()
    );
}
