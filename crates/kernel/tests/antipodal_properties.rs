//! docs/math.md §1: a build names the neighbours it blends about the fixed
//! axis (`sphere::antipodal`), from its own levels, for the designer's warning.

mod common;

use common::authoring::design;
use proptest::prelude::*;
use streamline_kernel::levels::antipodal::{AntipodalPair, antipodal_pairs};
use streamline_kernel::sphere::antipodal::is_antipodal;
use streamline_kernel::sphere::blend::blend;

/// The pairs of every level of `d` up to `depth` but the finest (the ones a
/// step blends).
fn scanned(d: &streamline_kernel::Design, depth: u32) -> Vec<AntipodalPair> {
    let levels = d.levels(depth).unwrap();
    let mut out = Vec::new();
    for (k, l) in levels[..levels.len() - 1].iter().enumerate() {
        antipodal_pairs(k as u32, &l.tangents, &mut out);
    }
    out
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(96))]

    /// A gentle random design has no antipodal neighbours at any level; the
    /// same design with one tangent turned to face its right or lower
    /// neighbour is reported at level 0 with exactly those cells (and no
    /// pair without the planted cell), the blend of that pair turns about an
    /// axis perpendicular to it, and the build stays finite and unit.
    #[test]
    fn a_planted_antipode_is_named_by_its_cells(
        d in design(),
        at in (0usize..64, 0usize..64),
        down in any::<bool>(),
    ) {
        prop_assert!(scanned(&d, 2).is_empty(), "a gentle net has none");
        let (rows, cols) = (d.net().rows(), d.net().cols());
        let (r, c) = (at.0 % rows, at.1 % cols);
        let (r1, c1) = match down {
            true if r + 1 < rows => (r + 1, c),
            _ if c + 1 < cols => (r, c + 1),
            _ => (r + 1, c),
        };
        prop_assume!(r1 < rows && c1 < cols);
        let mut planted = d.clone();
        let a = d.net().get(r, c);
        planted.set_tangent(r1, c1, -a).unwrap();
        prop_assert!(is_antipodal(a, planted.net().get(r1, c1)));
        let found = scanned(&planted, 2);
        let level0: Vec<_> = found.iter().filter(|p| p.level == 0).collect();
        prop_assert!(
            level0.iter().any(|p| p.a == (r, c) && p.b == (r1, c1)),
            "({r}, {c})-({r1}, {c1}) not in {level0:?}"
        );
        // every level-0 pair found really is antipodal, and involves the planted cell
        for p in &level0 {
            prop_assert!(p.a == (r1, c1) || p.b == (r1, c1), "{p:?}");
        }
        let fixed = blend(a, -a, 0.5);
        prop_assert!((fixed.length() - 1.0).abs() < 1e-12);
        prop_assert!(fixed.dot(a).abs() < 1e-12, "a quarter turn about the fixed axis");
        if let Ok(levels) = planted.levels(2) {
            for l in &levels {
                for t in l.tangents.data() {
                    prop_assert!(t.is_finite() && (t.length() - 1.0).abs() < 1e-9);
                }
            }
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    /// A window's scan (which rules a row out by its smallest dot product
    /// first) lists exactly the pairs that the predicate, applied to every
    /// row and column neighbour with a first cell in the window, finds: on
    /// grids of random unit tangents with antipodes planted anywhere
    /// (first and last rows and columns included), in any window.
    #[test]
    fn a_window_scan_lists_every_antipodal_pair_and_no_other(
        rows in 1usize..9,
        cols in 1usize..13,
        seed in any::<u64>(),
        plants in prop::collection::vec((0usize..64, 0usize..64, any::<bool>()), 0..6),
        win in (0usize..10, 0usize..10, 0usize..14, 0usize..14),
    ) {
        use streamline_kernel::Grid;
        use streamline_kernel::DVec3;
        use streamline_kernel::levels::antipodal::antipodal_pairs_from;
        let mut x = seed | 1;
        let mut next = || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            (x >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        };
        let mut g = Grid::filled(rows, cols, DVec3::X);
        for r in 0..rows {
            for c in 0..cols {
                let v = DVec3::new(next(), next(), next()) + DVec3::new(2.0, 0.0, 0.0);
                g.set(r, c, v.normalize());
            }
        }
        for (r, c, down) in plants {
            let (r, c) = (r % rows, c % cols);
            let (r1, c1) = if down { ((r + 1).min(rows - 1), c) } else { (r, (c + 1).min(cols - 1)) };
            let a = g.get(r, c);
            g.set(r1, c1, -a);
        }
        let (r0, r1) = (win.0.min(win.1), win.0.max(win.1));
        let (c0, c1) = (win.2.min(win.3), win.2.max(win.3));
        let mut found = Vec::new();
        antipodal_pairs_from(3, &g, r0..=r1, c0..=c1, &mut found);
        let mut expected = Vec::new();
        for r in r0..=r1.min(rows - 1) {
            for c in c0..=c1.min(cols - 1) {
                if c + 1 < cols && is_antipodal(g.get(r, c), g.get(r, c + 1)) {
                    expected.push(((r, c), (r, c + 1)));
                }
                if r + 1 < rows && is_antipodal(g.get(r, c), g.get(r + 1, c)) {
                    expected.push(((r, c), (r + 1, c)));
                }
            }
        }
        let got: Vec<_> = found.iter().map(|p| (p.a, p.b)).collect();
        prop_assert_eq!(got, expected);
    }
}
