//! docs/math.md §1: a build names the neighbours it blends about the fixed
//! axis (`sphere::antipodal`), from its own levels, for the designer's warning.

mod common;

use common::authoring::design;
use proptest::prelude::*;
use streamline_kernel::sphere::antipodal::{AntipodalPair, antipodal_pairs, is_antipodal};
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
