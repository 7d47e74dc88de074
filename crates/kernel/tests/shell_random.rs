//! docs/math.md §10, §11.5: random two-patch shells fitted as an export
//! fits them (`nurbs::fit_shell` at the default tolerance, `1e-4` of each
//! patch's diagonal, sampled one depth deeper while a face is refused, up to
//! the deepest depth whose check grid holds at most 2²¹ points), over every
//! join (chains G0, G1, G2; side joins G0, G1 on `First` and `Last`) and
//! random Kobbelt nets (ω = 0.6, 1, 1.4) of 3–6 rows and columns, car-sized
//! (metres) and small (a fiftieth), smooth and rough (each tangent turned at
//! random by up to 0.05, 0.2 or 0.35), as `tests/cad_shell_random.rs` draws
//! them for OpenCascade.
//!
//! Every design is fitted, or its patches alone are refused too (a rough
//! net at ω = 0.6 whose own points no cubic follows within the tolerance
//! at depth 7); every face is within its tolerance of its check grid
//! (`face_deviation`); the seam is one curve of both faces (within 1e-12 of
//! the diagonal at 129 points); across every G1 and G2 seam the faces'
//! normals, by finite differences of the surfaces (not the fit's own
//! derivatives), are within 0.1° at 129 points, and the later face leaves
//! the seam away from the earlier one where its points do (no fold). A
//! side patch whose streamlines leave the seam within 10° of it is not
//! asserted there (`LEAVING_DEG`). The negative control: G0 joins whose
//! later patch leaves the seam turned out of the earlier one's tangent
//! plane read more than 1°.
//!
//! Catmull–Clark and Doo–Sabin are drawn with `STREAMLINE_SHELL_SCHEMES=3`.
//! A root patch on them stays put between depths (docs/math.md §4, "The
//! anchor"; its check grid read in its data's frame, §10), but a later
//! patch starts on the root's edge, which moves between depths by a length
//! that halves per depth, and with it the later patch: its check grid is
//! measured from where it starts (`PatchGrid::hold_start`, §11.5, "A start
//! that moves"). Seeds 1–21: all 14 such draws exported but one, a side G1
//! join 2 cm across whose later patch is refused alone too (9.5e-6 at its
//! deepest depth against 2.9e-6, halving per depth); measured as they lie,
//! only the two G2 chains and one Doo–Sabin side join exported.
//!
//! Seeded: `STREAMLINE_SHELL_SEED` is the first seed, `STREAMLINE_SHELL_CASES`
//! how many draws, and the seeds of `FIXED` are drawn too (rough ω = 0.6
//! designs the shell once refused); a failure names its seed.

use glam::{DQuat, DVec3};
use std::time::Instant;
use streamline_kernel::grid::Grid;
use streamline_kernel::joins::{Continuity, Edge, Join, JoinError, join};
use streamline_kernel::nurbs::{
    BSplineSurface, FitError, FitOptions, PatchGrid, SeamSpec, ShellError, ShellFit,
    face_deviation, fit_alone, fit_shell,
};
use streamline_kernel::streamline::initial_curve::InitialCurve;
use streamline_kernel::{BlendOrder, Design, KernelError, SurfaceScheme};

/// xorshift64 in `[-1, 1)`.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> f64 {
        let x = &mut self.0;
        *x ^= *x << 13;
        *x ^= *x >> 7;
        *x ^= *x << 17;
        (*x >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    }

    fn below(&mut self, n: usize) -> usize {
        (((self.next() + 1.0) * 0.5 * n as f64) as usize).min(n - 1)
    }
}

/// The joins drawn, in turn by seed.
const JOINS: [(Edge, Continuity); 7] = [
    (Edge::End, Continuity::G1),
    (Edge::First, Continuity::G1),
    (Edge::End, Continuity::G2),
    (Edge::Last, Continuity::G1),
    (Edge::End, Continuity::G0),
    (Edge::First, Continuity::G0),
    (Edge::Last, Continuity::G0),
];

/// One random two-patch design.
#[derive(Debug, Clone)]
struct Draw {
    seed: u64,
    join: Join,
    scheme: SurfaceScheme,
    order: BlendOrder,
    /// Metres per unit of `s` and `t`: 1 car-sized, 0.02 small.
    scale: f64,
    /// How far each tangent is turned at random.
    rough: f64,
    /// The negative control: a G0 join whose later patch leaves the seam
    /// turned out of the earlier one's tangent plane.
    turned: bool,
}

impl Draw {
    fn new(seed: u64, turned: bool) -> Draw {
        let mut r = Rng(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1);
        let (edge, mut continuity) = JOINS[(seed % JOINS.len() as u64) as usize];
        if turned {
            continuity = Continuity::G0;
        }
        // Kobbelt only, unless STREAMLINE_SHELL_SCHEMES is 3 (Catmull–Clark
        // and Doo–Sabin too, every join): their points drift between depths
        // (module docs), which no fit at one depth removes
        let all = env_u64("STREAMLINE_SHELL_SCHEMES", 1) >= 3;
        let scheme = match (seed / JOINS.len() as u64) % 3 {
            1 if all => SurfaceScheme::CatmullClark,
            2 if all => SurfaceScheme::DooSabin,
            _ => SurfaceScheme::Kobbelt {
                omega: [1.0, 0.6, 1.4][r.below(3)],
            },
        };
        let order = if r.next() > 0.0 {
            BlendOrder::SFirst
        } else {
            BlendOrder::TFirst
        };
        Draw {
            seed,
            join: Join { edge, continuity },
            scheme,
            order,
            scale: if r.next() > 0.0 { 1.0 } else { 0.02 },
            rough: [0.05, 0.2, 0.35][r.below(3)],
            turned,
        }
    }

    fn tag(&self) -> String {
        let scheme = match self.scheme {
            SurfaceScheme::Kobbelt { omega } => format!("Kobbelt {omega}"),
            s => format!("{s:?}"),
        };
        format!(
            "seed {} ({:?} {:?}, {scheme}, scale {}, rough {}{})",
            self.seed,
            self.join.edge,
            self.join.continuity,
            self.scale,
            self.rough,
            if self.turned { ", turned" } else { "" }
        )
    }

    /// The two designs: `A`, and `B` on its edge.
    fn designs(&self) -> Option<(Design, Design)> {
        let mut r = Rng(self.seed | 1);
        let net = |r: &mut Rng, rows: usize, cols: usize, lean: DVec3, rough: f64| {
            let data = (0..rows * cols)
                .map(|i| {
                    let c = i % cols;
                    let bend = DVec3::Z * (-0.08 * c as f64);
                    let noise = DVec3::new(r.next(), r.next(), r.next()) * rough;
                    (lean + bend + noise).normalize()
                })
                .collect();
            Grid::new(rows, cols, data).unwrap()
        };
        let s_grid = |r: &mut Rng, rows: usize, cols: usize, scale: f64| {
            let step = 0.5 + 0.1 * r.next();
            let mut data = Vec::with_capacity(rows * cols);
            for _ in 0..rows {
                let mut acc = 0.0;
                for _ in 0..cols {
                    data.push(acc);
                    acc += scale * step * (1.0 + 0.25 * r.next());
                }
            }
            Grid::new(rows, cols, data).unwrap()
        };
        // an approximating scheme contracts a net of 3 rows (columns) onto
        // its middle at every depth, and shortens the boundary streamlines a
        // side patch starts on: 4 or more rows and columns, 5 or more
        // columns under a side patch
        let approx = !matches!(self.scheme, SurfaceScheme::Kobbelt { .. });
        let side = self.join.edge != Edge::End;
        let least = if approx { 4 } else { 3 };
        let rows = least + r.below(7 - least);
        let cols = if approx && side {
            5 + r.below(2)
        } else {
            least + r.below(7 - least)
        };
        let mut acc = 0.0;
        let t: Vec<f64> = (0..rows)
            .map(|j| {
                if j > 0 {
                    acc += self.scale * 0.4 * (1.0 + 0.3 * r.next());
                }
                acc
            })
            .collect();
        let up = DVec3::new(0.0, 1.0, 0.1).normalize();
        let turn = DQuat::from_axis_angle(DVec3::X, -0.1);
        let initial = InitialCurve::new(
            &[up, turn * up, turn * turn * up],
            3,
            t[rows - 1],
            DVec3::ZERO,
        )
        .unwrap();
        let s = s_grid(&mut r, rows, cols, self.scale);
        let a = Design::new(
            &net(&mut r, rows, cols, DVec3::X, self.rough),
            s.clone(),
            t.clone(),
            0,
            self.scheme,
            self.order,
            initial.clone(),
        )
        .ok()?;
        let bcols = least + r.below(7 - least);
        let b = match self.join.edge {
            Edge::End => {
                let mut tangents = net(&mut r, rows, bcols, DVec3::X, self.rough);
                for j in 0..rows {
                    let seam = a.net().get(j, cols - 1);
                    if self.join.continuity != Continuity::G0 {
                        tangents.set(j, 0, seam);
                    } else if self.turned {
                        // the seam column turned 25° up out of A's surface
                        tangents.set(j, 0, (seam + DVec3::Z * 0.47).normalize());
                    }
                }
                Design::new(
                    &tangents,
                    s_grid(&mut r, rows, bcols, self.scale),
                    t,
                    0,
                    self.scheme,
                    self.order,
                    initial,
                )
            }
            edge => {
                let row = if edge == Edge::First { 0 } else { rows - 1 };
                let len = s.get(row, cols - 1) - s.get(row, 0);
                let brows = least + r.below(3);
                let out = if edge == Edge::First {
                    -DVec3::Y
                } else {
                    DVec3::Y
                };
                let down = if self.turned { 1.2 } else { 0.3 };
                let (lo, hi) = if approx { (0.35, 0.65) } else { (0.15, 0.85) };
                let bt = (0..brows)
                    .map(|j| len * (lo + (hi - lo) * j as f64 / (brows - 1) as f64))
                    .collect();
                Design::new(
                    &net(&mut r, brows, bcols, out - down * DVec3::Z, self.rough),
                    s_grid(&mut r, brows, bcols, self.scale),
                    bt,
                    0,
                    self.scheme,
                    self.order,
                    initial,
                )
            }
        };
        Some((a, b.ok()?))
    }
}

/// The deepest depth an export samples both patches at: the last whose
/// check grids (one depth finer) hold at most 2²¹ points.
fn deepest(a: &Design, b: &Design) -> u32 {
    [a, b]
        .iter()
        .map(|d| {
            let (rows, cols) = (d.net().rows(), d.net().cols());
            let mut depth = 0;
            while let Ok((r, c)) = d.scheme().check_depth(rows, cols, depth + 2) {
                if r.saturating_mul(c + 1) > 1 << 21 {
                    break;
                }
                depth += 1;
            }
            depth
        })
        .min()
        .unwrap()
}

/// The shell fitted from depth 3 down as deep as it needs, and the grids;
/// refused, why and the deepest grids.
type Exported = (u32, ShellFit, Vec<PatchGrid>);

fn export(a: &Design, b: &Design, jn: Join) -> Result<Exported, (String, Vec<PatchGrid>)> {
    let last = deepest(a, b).max(3);
    let seam = SeamSpec {
        a: 0,
        b: 1,
        join: jn,
    };
    for depth in 3..=last {
        let (sa, sb) = match join(a, b, jn, depth + 1) {
            Ok(p) => p,
            Err(JoinError::Kernel(KernelError::ParamsNotIncreasing { .. })) => {
                return Err(("not a design".into(), vec![]));
            }
            Err(e) => return Err((format!("not built: {e}"), vec![])),
        };
        let grid = |n: &str, s, d: &Design| {
            PatchGrid::from_stack(n, s, depth, d.scheme().curve()).map_err(|e| e.to_string())
        };
        // a later patch on an edge that moves between depths is measured
        // from where it starts (PatchGrid::hold_start, docs/math.md §11.5)
        let g2 = jn.edge == Edge::End && jn.continuity == Continuity::G2;
        let moving = !g2 && [a, b].iter().any(|d| !d.scheme().is_interpolatory());
        let grids = match (grid("A", &sa, a), grid("B", &sb, b)) {
            (Ok(a), Ok(mut b)) => {
                if moving {
                    b.hold_start();
                }
                vec![a, b]
            }
            (Err(e), _) | (_, Err(e)) => return Err((format!("not built: {e}"), vec![])),
        };
        match fit_shell(&grids, &[seam], &FitOptions::DEFAULT) {
            Ok(shell) => return Ok((depth, shell, grids)),
            Err(
                e @ (ShellError::OverTolerance { .. }
                | ShellError::Fit {
                    error: FitError::TooFewPoints { .. },
                    ..
                }),
            ) => {
                if std::env::var("DBG").is_ok() {
                    eprintln!("depth {depth}: {e}");
                }
                if depth == last {
                    return Err((format!("refused at the deepest depth {depth}: {e}"), grids));
                }
            }
            Err(e) => return Err((format!("refused at depth {depth}: {e}"), grids)),
        }
    }
    unreachable!("the loop returns")
}

/// `∂F/∂u` and `∂F/∂v` at `(u, v)` by differences (one-sided at the boundary).
fn partials(s: &BSplineSurface, u: f64, v: f64) -> (DVec3, DVec3) {
    let h = 1e-6;
    let d = |x: f64| {
        let (lo, hi) = ((x - h).max(0.0), (x + h).min(1.0));
        (lo, hi)
    };
    let (u0, u1) = d(u);
    let (v0, v1) = d(v);
    (
        (s.eval(u1, v) - s.eval(u0, v)) / (u1 - u0),
        (s.eval(u, v1) - s.eval(u, v0)) / (v1 - v0),
    )
}

fn angle_deg(a: DVec3, b: DVec3) -> f64 {
    a.normalize()
        .dot(b.normalize())
        .clamp(-1.0, 1.0)
        .acos()
        .to_degrees()
}

/// Across the seam at 129 points: the largest angle between the faces'
/// normal lines, whether the later face folds back over the earlier one,
/// and the largest gap between the two faces' edge curves.
fn seam_figures(shell: &ShellFit, jn: Join) -> (f64, bool, f64) {
    let (fa, fb) = (&shell.faces[0].surface, &shell.faces[1].surface);
    let (u0, u1) = shell.seams[0].range;
    let (mut worst, mut fold, mut gap) = (0.0f64, false, 0.0f64);
    for k in 0..=128 {
        let w = k as f64 / 128.0;
        let (ua, va) = match jn.edge {
            Edge::End => (1.0, w),
            Edge::First => (u0 + w * (u1 - u0), 0.0),
            Edge::Last => (u0 + w * (u1 - u0), 1.0),
        };
        let (au, av) = partials(fa, ua, va);
        let (bu, bw) = partials(fb, 0.0, w);
        gap = gap.max((fa.eval(ua, va) - fb.eval(0.0, w)).length());
        let theta = angle_deg(au.cross(av), bu.cross(bw));
        worst = worst.max(theta.min(180.0 - theta));
        // the later face leaves the seam on the far side of the earlier one
        let away = match jn.edge {
            Edge::End => au.dot(bu),
            Edge::First => -av.dot(bu),
            Edge::Last => av.dot(bu),
        };
        fold |= away <= 0.0;
    }
    (worst, fold, gap)
}

/// The smallest angle (degrees) between the later patch's first segment of
/// a row and the seam there, on its points: how far from tangent to the seam
/// its streamlines leave it (the faces' normals there are the cross products
/// of the two, so a small angle leaves them ill-determined).
fn leaving_angle(grids: &[PatchGrid]) -> f64 {
    let b = &grids[1].data.points;
    (1..b.rows() - 1)
        .map(|j| {
            let a = angle_deg(b.get(j, 1) - b.get(j, 0), b.get(j + 1, 0) - b.get(j - 1, 0));
            a.min(180.0 - a)
        })
        .fold(f64::INFINITY, f64::min)
}

/// Whether the later patch's points leave the seam back over the earlier
/// patch somewhere (a design whose streamlines start into the earlier
/// surface, not a fault of the fit): its first segment of a row against the
/// earlier patch's inward segment next to the seam point.
fn data_folds(grids: &[PatchGrid], jn: Join) -> bool {
    let (a, b) = (&grids[0].data.points, &grids[1].data.points);
    (0..b.rows()).any(|j| {
        let out = b.get(j, 1) - b.get(j, 0);
        let inward = match jn.edge {
            Edge::End => {
                let c = a.cols() - 1;
                a.get(j, c - 1) - a.get(j, c)
            }
            Edge::First | Edge::Last => {
                let (r, n) = if jn.edge == Edge::First {
                    (0, 1)
                } else {
                    (a.rows() - 1, a.rows() - 2)
                };
                let p = b.get(j, 0);
                let i = (0..a.cols())
                    .min_by(|x, y| {
                        (a.get(r, *x) - p)
                            .length()
                            .total_cmp(&(a.get(r, *y) - p).length())
                    })
                    .unwrap();
                a.get(n, i) - a.get(r, i)
            }
        };
        out.dot(inward) >= 0.0
    })
}

/// Below this angle between a later patch's streamlines and its seam the
/// seam's normals are not asserted: `∂B/∂u × ∂B/∂w` there is the cross
/// product of nearly parallel vectors, and a distance within the tolerance
/// turns it by degrees (rough side patches leaving 0.2° and 1.3° off their
/// seams: 0.12° and 0.61°).
const LEAVING_DEG: f64 = 10.0;

/// Drawn on every run besides the seeded range: rough ω = 0.6 designs
/// whose patches fit alone and which the shell once refused at the deepest
/// depth (docs/math.md §11.5; docs/cad.md, "Several patches"): on the union
/// of a chain's two patches' `v` knots, 116's first face was 108 tolerances
/// off and 25's later face 1.15; 106's side face lost the knots its own fit
/// placed a row apart (1.26).
const FIXED: [u64; 3] = [25, 106, 116];

fn env_u64(name: &str, default: u64) -> u64 {
    std::env::var(name)
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(default)
}

#[test]
fn random_shells_fit_within_the_tolerance_and_keep_their_seams_normals() {
    let first = env_u64("STREAMLINE_SHELL_SEED", 1);
    let count = env_u64("STREAMLINE_SHELL_CASES", 21);
    let mut draws: Vec<Draw> = (first..first + count)
        .chain(
            FIXED
                .iter()
                .copied()
                .filter(|s| !(first..first + count).contains(s)),
        )
        .map(|s| Draw::new(s, false))
        .collect();
    draws.extend((first..first + 2).map(|s| Draw::new(s, true)));
    let (mut worst, mut least_control, mut fitted) = (0.0f64, f64::INFINITY, 0);
    let mut failures = Vec::new();
    for d in &draws {
        let Some((a, b)) = d.designs() else {
            eprintln!("{}: not a design", d.tag());
            continue;
        };
        let start = Instant::now();
        let (depth, shell, grids) = match export(&a, &b, d.join) {
            Ok(x) => x,
            Err((e, _)) if e == "not a design" || e.starts_with("not built") => {
                eprintln!("{}: {e}", d.tag());
                continue;
            }
            Err((e, grids)) => {
                // a patch its own fit refuses at the deepest depth is no
                // shell's doing (a rough net at ω = 0.6: docs/cad.md)
                match fit_alone(&grids, &FitOptions::DEFAULT) {
                    Err(alone) => eprintln!("{}: refused alone too ({alone})", d.tag()),
                    Ok(_) => failures.push(format!("{}: {e}", d.tag())),
                }
                continue;
            }
        };
        let seconds = start.elapsed().as_secs_f64();
        fitted += 1;
        let (angle, fold, gap) = seam_figures(&shell, d.join);
        let fold = fold && !data_folds(&grids, d.join);
        let leaving = leaving_angle(&grids);
        let ratios: Vec<f64> = (0..2)
            .map(|i| {
                let f = &shell.faces[i];
                let check = streamline_kernel::nurbs::Samples {
                    points: grids[i].check.points.clone(),
                    u: grids[i].check.u.clone(),
                    v: f.v.1.clone(),
                };
                face_deviation(&shell, i, &check).max / f.tolerance
            })
            .collect();
        eprintln!(
            "{}: depth {depth}, poles {:?} {:?}, deviation/tolerance {:.2} {:.2}, seam {:.4}°, leaving {:.1}°, slope held {}, {:.2} s",
            d.tag(),
            shell.faces[0].surface.pole_counts(),
            shell.faces[1].surface.pole_counts(),
            ratios[0],
            ratios[1],
            angle,
            leaving,
            shell.seams[0].slope_held,
            seconds
        );
        let scale = grids[0].data.diagonal();
        if ratios.iter().any(|r| *r > 1.0) {
            failures.push(format!("{}: over the tolerance {ratios:?}", d.tag()));
        }
        if gap > 1e-12 * scale {
            failures.push(format!("{}: the edges {gap:.3e} apart", d.tag()));
        }
        if d.turned {
            least_control = least_control.min(angle);
            if angle <= 1.0 {
                failures.push(format!("{}: a turned G0 seam reads {angle}°", d.tag()));
            }
        } else if d.join.continuity != Continuity::G0
            && d.join.edge != Edge::End
            && leaving < LEAVING_DEG
        {
            eprintln!(
                "{}: leaves its seam {leaving:.1}° from tangent, normals not asserted",
                d.tag()
            );
        } else if d.join.continuity != Continuity::G0 {
            worst = worst.max(angle);
            if angle >= 0.1 || fold {
                failures.push(format!("{}: seam {angle}° (fold {fold})", d.tag()));
            }
        }
    }
    eprintln!(
        "worst G1/G2 seam {worst:.4}°, least turned G0 {least_control:.2}°, {fitted} of {} fitted",
        draws.len()
    );
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    assert!(fitted * 4 >= draws.len() * 3, "too few designs were built");
}
