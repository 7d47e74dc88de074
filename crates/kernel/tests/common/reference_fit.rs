//! The reference faces and the helpers shared by the tests of the fit to a
//! reference (`reference_fit_*.rs`, docs/math.md §12).

use glam::DVec3;
use streamline_kernel::fit::{ReferenceFit, ReferenceSurface, distances_to_reference};
use streamline_kernel::nurbs::rational::NurbsSurface;
use streamline_kernel::{Design, Grid};

/// The flat rectangle `[0, w] × [0, h]` in `z = 0`, bilinear.
pub fn flat(w: f64, h: f64) -> NurbsSurface {
    NurbsSurface::new(
        1,
        1,
        vec![0.0, 0.0, 1.0, 1.0],
        vec![0.0, 0.0, 1.0, 1.0],
        Grid::new(
            2,
            2,
            vec![
                DVec3::ZERO,
                DVec3::new(w, 0.0, 0.0),
                DVec3::new(0.0, h, 0.0),
                DVec3::new(w, h, 0.0),
            ],
        )
        .unwrap(),
        None,
    )
    .unwrap()
}

/// A quarter cylinder of radius `r` about the `z` axis: `u` the arc (rational
/// quadratic, exact), `v` the height `0..h` (linear).
pub fn cylinder(r: f64, h: f64) -> NurbsSurface {
    let w = std::f64::consts::FRAC_1_SQRT_2;
    let arc = [
        DVec3::new(r, 0.0, 0.0),
        DVec3::new(r, r, 0.0),
        DVec3::new(0.0, r, 0.0),
    ];
    let mut poles = Vec::new();
    let mut weights = Vec::new();
    for z in [0.0, h] {
        for p in arc {
            poles.push(p + DVec3::new(0.0, 0.0, z));
        }
        weights.extend([1.0, w, 1.0]);
    }
    NurbsSurface::new(
        2,
        1,
        vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
        vec![0.0, 0.0, 1.0, 1.0],
        Grid::new(2, 3, poles).unwrap(),
        Some(Grid::new(2, 3, weights).unwrap()),
    )
    .unwrap()
}

/// A wavy bicubic face with interior knots (a typical freeform face).
pub fn wavy(seed: f64, amp: f64) -> NurbsSurface {
    let ku = vec![0.0, 0.0, 0.0, 0.0, 0.3, 0.6, 1.0, 1.0, 1.0, 1.0];
    let kv = vec![0.0, 0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0, 1.0];
    let (nu, nv) = (ku.len() - 4, kv.len() - 4);
    let mut poles = Vec::new();
    for j in 0..nv {
        for i in 0..nu {
            let (x, y) = (i as f64 / (nu - 1) as f64, j as f64 / (nv - 1) as f64);
            let z = amp * ((3.0 * x + seed).sin() * (2.0 * y - seed).cos());
            poles.push(DVec3::new(2.0 * x + 0.1 * y * y, 1.5 * y, z));
        }
    }
    NurbsSurface::new(3, 3, ku, kv, Grid::new(nv, nu, poles).unwrap(), None).unwrap()
}

pub fn show(name: &str, f: &ReferenceFit) {
    eprintln!(
        "{name}: net {:?}, to reference max {:.3e} mean {:.3e}, from reference max {:.3e} mean {:.3e}, tolerance {:.3e}, within {}, {} nets, initial curve {:.1e} ({} tangents), {:.3} s",
        f.net,
        f.to_reference.max,
        f.to_reference.mean,
        f.from_reference.max,
        f.from_reference.mean,
        f.tolerance,
        f.within,
        f.steps,
        f.initial_deviation,
        f.initial_tangents,
        f.seconds
    );
}

/// The largest distance from the design's mesh at `depth` to `reference`,
/// measured from outside the fit (nearest sample, then Newton).
pub fn outside_deviation(design: &Design, depth: u32, reference: &dyn ReferenceSurface) -> f64 {
    let b = design.build(depth).unwrap();
    distances_to_reference(reference, b.points.data())
        .unwrap()
        .into_iter()
        .fold(0.0, f64::max)
}
