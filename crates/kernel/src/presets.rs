//! Built-in designs that reproduce the paper's examples (000, Figs. 2, 8–11),
//! used by the default scene, the benchmarks and the tests.
//!
//! Axes: `x` along the car (the streamlines' direction `s`), `y` across it (the
//! initial curve's direction `t`), `z` up.

use crate::grid::Grid;
use crate::levels::design::Design;
use crate::levels::surface::{BlendOrder, SurfaceScheme};
use crate::streamline::initial_curve::InitialCurve;
use glam::DVec3;

fn dir(pitch_deg: f64, yaw_deg: f64) -> DVec3 {
    let (p, y) = (pitch_deg.to_radians(), yaw_deg.to_radians());
    DVec3::new(p.cos() * y.cos(), p.cos() * y.sin(), p.sin())
}

/// A car-like net: `pitch` is the side profile along each streamline (degrees
/// above horizontal, front to back); rows further from the centre line are
/// flatter and splay out at the front and in at the back.
fn car(pitch: [f64; 9], yaw_front: f64, yaw_back: f64, length: f64) -> Design {
    let (rows, cols) = (6, 9);
    let mut net = Vec::with_capacity(rows * cols);
    let mut s = Vec::with_capacity(rows * cols);
    for r in 0..rows {
        let f = (r as f64 - 2.5) / 2.5; // −1 … 1 across the car
        let row_len = length * (1.0 - 0.06 * f * f);
        for (c, &p) in pitch.iter().enumerate() {
            let along = c as f64 / (cols - 1) as f64;
            let yaw = f * (yaw_front * (1.0 - along) - yaw_back * along);
            net.push(dir(
                p * (1.0 - 0.35 * f * f),
                yaw * (1.0 - 2.0 * along).abs(),
            ));
            s.push(row_len * along);
        }
    }
    let net = Grid::new(rows, cols, net).expect("6x9");
    let s = Grid::new(rows, cols, s).expect("6x9");
    let width = 2.0;
    let t = (0..rows)
        .map(|r| width * r as f64 / (rows - 1) as f64)
        .collect();
    let initial = InitialCurve::new(
        &[
            DVec3::new(0.0, 1.0, 0.55),
            DVec3::new(0.0, 1.0, 0.12),
            DVec3::new(0.0, 1.0, -0.12),
            DVec3::new(0.0, 1.0, -0.55),
        ],
        3,
        width,
        DVec3::new(0.0, -0.95, 0.25),
    )
    .expect("valid initial curve");
    Design::new(
        &net,
        s,
        t,
        0,
        SurfaceScheme::default(),
        BlendOrder::SFirst,
        initial,
    )
    .expect("valid car design")
}

/// The paper's car model no. 1 (Figs. 8–10): a 9×6 Kobbelt net, a long
/// car-roof-like surface (bumper, hood, windshield, roof, rear window, trunk, tail).
pub fn car1() -> Design {
    car(
        [55.0, 12.0, 6.0, 34.0, 3.0, -3.0, -24.0, -6.0, -58.0],
        14.0,
        10.0,
        4.4,
    )
}

/// The reshaped car model no. 2 (Fig. 11): a sportier fastback from the same net shape.
pub fn car2() -> Design {
    car(
        [45.0, 8.0, 3.0, 26.0, 9.0, -9.0, -17.0, -13.0, -50.0],
        18.0,
        14.0,
        4.6,
    )
}

/// The QI-surface examples of Fig. 2: a 3×3 net of `+x` tangents whose centre
/// tangent points down (`which = 0`), to the side (1) or up (2).
pub fn qi_demo(which: u8) -> Design {
    let centre = match which {
        0 => dir(-45.0, 0.0),
        1 => dir(0.0, 45.0),
        _ => dir(45.0, 0.0),
    };
    let mut net = Grid::filled(3, 3, DVec3::X);
    net.set(1, 1, centre);
    let s = Grid::new(3, 3, (0..9).map(|i| (i % 3) as f64).collect()).expect("3x3");
    let initial =
        InitialCurve::new(&[DVec3::Y, DVec3::Y], 2, 2.0, DVec3::new(0.0, -1.0, 0.0)).expect("line");
    Design::new(
        &net,
        s,
        vec![0.0, 1.0, 2.0],
        0,
        SurfaceScheme::default(),
        BlendOrder::SFirst,
        initial,
    )
    .expect("valid")
}

/// The smallest design: 2×2 tangents along `+x`, a flat unit square.
pub fn minimal() -> Design {
    let net = Grid::filled(2, 2, DVec3::X);
    let s = Grid::new(2, 2, vec![0.0, 1.0, 0.0, 1.0]).expect("2x2");
    let initial = InitialCurve::new(&[DVec3::Y, DVec3::Y], 2, 1.0, DVec3::ZERO).expect("line");
    Design::new(
        &net,
        s,
        vec![0.0, 1.0],
        0,
        SurfaceScheme::default(),
        BlendOrder::SFirst,
        initial,
    )
    .expect("valid")
}

/// A gently wavy `rows × cols` Kobbelt net with unit intervals, for tests and
/// benchmarks of larger nets (the 20×20 net of the incremental-rebuild figures).
pub fn wavy(rows: usize, cols: usize) -> Design {
    let net = (0..rows * cols)
        .map(|i| {
            let (r, c) = ((i / cols) as f64, (i % cols) as f64);
            DVec3::new(1.0, 0.25 * (0.7 * r).sin(), 0.35 * (0.9 * c).cos()).normalize()
        })
        .collect();
    let s = (0..rows * cols).map(|i| (i % cols) as f64 * 0.5).collect();
    let t = (0..rows).map(|r| r as f64 * 0.3).collect();
    let initial = InitialCurve::new(
        &[DVec3::Y, DVec3::Y],
        2,
        0.3 * (rows - 1).max(1) as f64,
        DVec3::ZERO,
    )
    .expect("line");
    Design::new(
        &Grid::new(rows, cols, net).expect("sizes"),
        Grid::new(rows, cols, s).expect("sizes"),
        t,
        0,
        SurfaceScheme::default(),
        BlendOrder::SFirst,
        initial,
    )
    .expect("valid wavy design")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn presets_build() {
        for (name, d, depth) in [
            ("car1", car1(), 5),
            ("car2", car2(), 3),
            ("qi-down", qi_demo(0), 3),
            ("minimal", minimal(), 3),
        ] {
            let b = d.build(depth).unwrap();
            assert!(
                b.mesh.positions.iter().all(|p| p.is_finite()),
                "{name}: finite"
            );
            assert!(
                b.mesh
                    .normals
                    .iter()
                    .all(|n| (n.length() - 1.0).abs() < 1e-9),
                "{name}: unit normals"
            );
        }
        let b = car1().build(5).unwrap();
        assert_eq!(
            (b.level.tangents.rows(), b.level.tangents.cols()),
            (161, 257)
        );
    }
}
