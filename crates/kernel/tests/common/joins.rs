//! Strategies and helpers shared by the joins' property tests
//! (`joins_properties.rs`, docs/math.md §11).

use super::{nasty, unit};
use glam::{DQuat, DVec3};
use proptest::prelude::*;
use streamline_kernel::KernelError;
use streamline_kernel::grid::Grid;
use streamline_kernel::joins::edge_curve::EdgeCurve;
use streamline_kernel::joins::{Edge, Stack};
use streamline_kernel::streamline::initial_curve::InitialCurve;
use streamline_kernel::{BlendOrder, Design, SurfaceScheme};

/// The tangent field of a net.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Field {
    /// Streamlines that bend steadily (about `y`, the direction across them)
    /// with small random turns: clear normal curvature everywhere.
    Bent,
    /// Any direction: exact antipodes, repeats, nearly parallel pairs and
    /// magnitudes from subnormal to near `f64::MAX` (`common::nasty`).
    Nasty,
}

/// Everything a random pair of patches is made from.
#[derive(Debug, Clone)]
pub struct PairSpec {
    pub scheme: SurfaceScheme,
    pub order_a: BlendOrder,
    pub order_b: BlendOrder,
    pub rows: usize,
    pub cols_a: usize,
    pub cols_b: usize,
    /// Radians per column of A's bend and of B's.
    pub rate_a: f64,
    pub rate_b: f64,
    /// Small random turns of every tangent.
    pub noise: Vec<DVec3>,
    /// `s` intervals and row spacings.
    pub steps: Vec<f64>,
    /// Nasty tangents (used by `Field::Nasty`).
    pub wild: Vec<DVec3>,
}

pub const SCHEMES: [SurfaceScheme; 3] = [
    SurfaceScheme::Kobbelt { omega: 1.0 },
    SurfaceScheme::CatmullClark,
    SurfaceScheme::DooSabin,
];

/// A random pair specification (up to 6 rows, 3–6 columns each).
pub fn pair_spec() -> impl Strategy<Value = PairSpec> {
    (
        (0usize..3, 0.25f64..1.6, any::<bool>(), any::<bool>()),
        (3usize..7, 3usize..7, 3usize..7),
        (0.05f64..0.3, -0.3f64..0.3),
        prop::collection::vec(unit(), 72),
        prop::collection::vec(0.45f64..1.0, 72),
        nasty(72..=72),
    )
        .prop_map(
            |(
                (which, omega, oa, ob),
                (rows, cols_a, cols_b),
                (rate_a, rate_b),
                noise,
                steps,
                wild,
            )| {
                let scheme = match SCHEMES[which] {
                    SurfaceScheme::Kobbelt { .. } => SurfaceScheme::Kobbelt { omega },
                    s => s,
                };
                let order = |b: bool| {
                    if b {
                        BlendOrder::TFirst
                    } else {
                        BlendOrder::SFirst
                    }
                };
                PairSpec {
                    scheme,
                    order_a: order(oa),
                    order_b: order(ob),
                    rows,
                    cols_a,
                    cols_b,
                    rate_a,
                    rate_b,
                    noise,
                    steps,
                    wild,
                }
            },
        )
}

fn initial() -> InitialCurve {
    let y = DVec3::new(0.0, 1.0, 0.1).normalize();
    let turn = DQuat::from_axis_angle(DVec3::X, 0.3);
    InitialCurve::new(
        &[y, turn * y, turn * turn * y],
        3,
        2.0,
        DVec3::new(0.1, -0.2, 0.3),
    )
    .unwrap()
}

/// A bent tangent: `x` pitched by `angle` about `y`, turned a little by `noise`.
fn bent(angle: f64, noise: DVec3) -> DVec3 {
    (DQuat::from_rotation_y(-angle) * DVec3::X + noise * 0.02).normalize()
}

impl PairSpec {
    /// A fixed pair of s-first Kobbelt nets (ω = 1): `A` with `rows × cols`
    /// tangents, `B` (on a side) with `rows` columns and 6 rows; the
    /// noise, spacings and bends are fixed numbers, not drawn.
    pub fn kobbelt_s_first(rows: usize, cols: usize) -> PairSpec {
        let unit = |i: usize| {
            let (a, b) = (i as f64 * 0.7, i as f64 * 1.3);
            DVec3::new(a.sin(), b.cos(), (a + b).sin()).normalize()
        };
        PairSpec {
            scheme: SurfaceScheme::Kobbelt { omega: 1.0 },
            order_a: BlendOrder::SFirst,
            order_b: BlendOrder::SFirst,
            rows,
            cols_a: cols,
            cols_b: 6,
            rate_a: 0.12,
            rate_b: 0.1,
            noise: (0..72).map(unit).collect(),
            steps: (0..72)
                .map(|i| 0.6 + 0.3 * (i as f64 * 0.9).sin().abs())
                .collect(),
            wild: (0..72).map(unit).collect(),
        }
    }

    /// A's row parameters: uneven spacings.
    pub fn t(&self) -> Vec<f64> {
        let mut acc = 0.0;
        (0..self.rows)
            .map(|r| {
                if r > 0 {
                    acc += self.steps[(r * 11) % 72];
                }
                acc
            })
            .collect()
    }

    fn s(&self, cols: usize, salt: usize) -> Grid<f64> {
        let data = (0..self.rows * cols)
            .map(|i| {
                let (r, c) = (i / cols, i % cols);
                // one spacing for every row, each row a little longer or shorter
                let row = 1.0 + 0.1 * (self.steps[(r * 7 + salt) % 72] - 0.7);
                row * (0..c).map(|k| self.steps[(k * 3 + salt) % 72]).sum::<f64>()
            })
            .collect();
        Grid::new(self.rows, cols, data).unwrap()
    }

    fn tangent(
        &self,
        field: Field,
        r: usize,
        c: usize,
        rate: f64,
        phase: f64,
        salt: usize,
    ) -> DVec3 {
        let i = (r * 13 + c * 5 + salt) % 72;
        match field {
            Field::Bent => bent(phase + rate * c as f64 + 0.02 * r as f64, self.noise[i]),
            Field::Nasty => self.wild[i],
        }
    }

    /// Patch A (anchor at its first column, on its own initial curve).
    pub fn a(&self, field: Field) -> Design {
        let net = (0..self.rows * self.cols_a)
            .map(|i| self.tangent(field, i / self.cols_a, i % self.cols_a, self.rate_a, 0.0, 0))
            .collect();
        Design::new(
            &Grid::new(self.rows, self.cols_a, net).unwrap(),
            self.s(self.cols_a, 0),
            self.t(),
            0,
            self.scheme,
            self.order_a,
            initial(),
        )
        .unwrap()
    }

    /// Patch B chained on A's edge End: A's rows, anchor 0, A's scheme; its
    /// first column A's last when `shared` (G1, G2), its own otherwise.
    pub fn b_chain(&self, a: &Design, field: Field, shared: bool, order: BlendOrder) -> Design {
        let last = a.net().cols() - 1;
        let phase = self.rate_a * last as f64;
        let net = (0..self.rows * self.cols_b)
            .map(|i| {
                let (r, c) = (i / self.cols_b, i % self.cols_b);
                if c == 0 && shared {
                    a.net().get(r, last)
                } else {
                    self.tangent(field, r, c, self.rate_b, phase, 31)
                }
            })
            .collect();
        Design::new(
            &Grid::new(self.rows, self.cols_b, net).unwrap(),
            self.s(self.cols_b, 17),
            a.params().t.clone(),
            0,
            self.scheme,
            order,
            initial(),
        )
        .unwrap()
    }

    /// Patch B on a side edge: its rows spread over `[lo, hi]` along it, its
    /// streamlines leaving across (along `−y` from `First`, `+y` from `Last`)
    /// and bending down.
    pub fn b_side(&self, field: Field, (lo, hi): (f64, f64), outward: DVec3) -> Design {
        let rows = self.cols_b.max(3);
        let cols = self.rows.max(3);
        let net = (0..rows * cols)
            .map(|i| {
                let (r, c) = (i / cols, i % cols);
                match field {
                    Field::Bent => (outward
                        + DVec3::Z * (-0.2 - self.rate_b.abs() * c as f64)
                        + self.noise[(r * 5 + c * 7) % 72] * 0.1)
                        .normalize(),
                    Field::Nasty => self.wild[(r * 5 + c * 7) % 72],
                }
            })
            .collect();
        let t = (0..rows)
            .map(|r| lo + (hi - lo) * r as f64 / (rows - 1) as f64)
            .collect();
        let s = Grid::new(
            rows,
            cols,
            (0..rows * cols)
                .map(|i| {
                    let (r, c) = (i / cols, i % cols);
                    0.6 * (0..c)
                        .map(|k| self.steps[(r * 3 + k * 5 + 7) % 72])
                        .sum::<f64>()
                })
                .collect(),
        )
        .unwrap();
        Design::new(
            &Grid::new(rows, cols, net).unwrap(),
            s,
            t,
            0,
            self.scheme,
            self.order_b,
            initial(),
        )
        .unwrap()
    }
}

/// `B` on `A`'s side edge: its rows along the edge, leaving it outwards.
pub fn side_pair(
    spec: &PairSpec,
    f: Field,
    edge: Edge,
    depth: u32,
) -> Option<(Design, Stack, Design)> {
    let a = spec.a(f);
    let sa = match Stack::build(&a, depth) {
        Ok(s) => s,
        Err(KernelError::ParamsNotIncreasing { .. }) => return None,
        Err(e) => panic!("{e}"),
    };
    // inside what A's streamline covers at the deepest depth (an
    // approximating scheme's boundary streamline shortens with depth)
    let deep = EdgeCurve::of(&sa, depth, edge).unwrap();
    let margin = 0.05 * (deep.length() - deep.start());
    let out = if edge == Edge::First {
        -DVec3::Y
    } else {
        DVec3::Y
    };
    let b = spec.b_side(f, (deep.start() + margin, deep.length() - margin), out);
    b.level(depth).ok()?;
    Some((a, sa, b))
}

/// The bits of a vector.
pub fn bits(v: DVec3) -> [u64; 3] {
    v.to_array().map(f64::to_bits)
}
