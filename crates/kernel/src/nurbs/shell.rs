//! Several patches as B-spline faces whose seams are shared exactly
//! (docs/math.md §10, §11): one face per patch, each seam's boundary curve
//! fitted **once** and used by both faces.
//!
//! - **Chain** (`edge: End`, docs/math.md §11.1): `B`'s first column of
//!   points is `A`'s last and its rows are `A`'s rows (same `t`), so `B` is
//!   given `A`'s row parameters `v`. Every patch of a chain shares one `v`
//!   knot vector (the union of the knots each needs alone); `A`'s last
//!   column of poles (the seam curve, fitted once by `A`'s column pass) is
//!   `B`'s first column, copied. For G1 and G2 `B`'s second column of poles
//!   is projected onto the lines through `A`'s last two columns, so the poles
//!   next to the seam are collinear across it.
//! - **Side** (`edge: First | Last`, §11.2): `B`'s start points lie on `A`'s
//!   first or last streamline. Each is given the parameter `u` of `A` where it
//!   lies on that streamline's polyline, and `B`'s row parameter is the
//!   normalised `w = (u − u₀)/(u₁ − u₀)` between its first and last row's
//!   (`u₀`, `u₁`). The seam curve is the piece over `[u₀, u₁]` of `A`'s
//!   boundary curve (its poles row), cut by knot insertion, refined onto `B`'s
//!   `v` knots (which hold the piece's knots) and used as `B`'s first column
//!   of poles: `B`'s start edge is exactly that part of `A`'s edge, and a
//!   writer splits `A`'s edge at `u₀` and `u₁` (see [`ShellSeam::range`]).
//!
//! Each face's other poles are the separable least-squares fit of its points
//! with both ends of every row interpolated (`fit_knots`), so the interior is
//! fitted with the boundary held; every face is then measured against its
//! check grid (one depth finer) and must be within the tolerance.

use super::curve::Curve;
use super::deviation::{Deviation, deviation};
use super::error::FitError;
use super::fit::{FitOptions, Tolerance, check_options, fit, fit_knots};
use super::knots::KnotVector;
use super::samples::Samples;
use super::surface::BSplineSurface;
use crate::joins::{Continuity, Edge, Join, Stack};
use glam::DVec3;
use std::fmt;

/// One patch's points: fitted at `data`, checked at `check` (one depth finer).
#[derive(Debug, Clone)]
pub struct PatchGrid {
    /// The patch's name (the face's name in a CAD file).
    pub name: String,
    /// The points fitted.
    pub data: Samples,
    /// The points the fit is measured at.
    pub check: Samples,
}

impl PatchGrid {
    /// Levels `depth` and `depth + 1` of a built patch (`stack.depth() > depth`).
    pub fn from_stack(name: &str, stack: &Stack, depth: u32) -> Result<Self, FitError> {
        let d = depth as usize;
        let at = |d: usize| Samples::from_level(&stack.levels[d], stack.points[d].clone());
        Ok(PatchGrid {
            name: name.to_string(),
            data: at(d)?,
            check: at(d + 1)?,
        })
    }
}

/// Patch `b` starts on patch `a`'s edge (`a < b`; a patch starts on at most one edge).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SeamSpec {
    /// The earlier patch.
    pub a: usize,
    /// The later patch, which starts on `a`'s edge.
    pub b: usize,
    /// Which edge of `a`, and the continuity.
    pub join: Join,
}

/// A seam as fitted.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShellSeam {
    /// The spec.
    pub spec: SeamSpec,
    /// The part of `a`'s edge that is `b`'s start edge, in `a`'s parameter
    /// along that edge: `v` for `End` (always `(0, 1)`), `u` for `First` and
    /// `Last`, `(u₀, u₁)` at `b`'s first and last row (`u₀ > u₁` when `b`'s
    /// rows run against `a`'s `u`).
    pub range: (f64, f64),
}

/// One fitted face.
#[derive(Debug, Clone)]
pub struct ShellFace {
    /// The patch's name.
    pub name: String,
    /// The surface.
    pub surface: BSplineSurface,
    /// Its distance to the patch's check grid.
    pub deviation: Deviation,
    /// The absolute tolerance it meets.
    pub tolerance: f64,
    /// The row parameters it was fitted and checked at (`a`'s for a chained
    /// patch, `w` for a side-joined one).
    pub v: (Vec<f64>, Vec<f64>),
}

/// The faces and seams of a shell.
#[derive(Debug, Clone)]
pub struct ShellFit {
    /// One per patch, in order.
    pub faces: Vec<ShellFace>,
    /// One per seam spec, in order.
    pub seams: Vec<ShellSeam>,
}

/// Why a shell was not fitted.
#[derive(Debug, Clone, PartialEq)]
pub enum ShellError {
    /// A patch's fit failed.
    Fit {
        /// The patch.
        patch: String,
        /// Why.
        error: FitError,
    },
    /// A seam cannot be built as given.
    Seam {
        /// Index of the seam spec.
        seam: usize,
        /// What is wrong and what to do.
        problem: String,
    },
    /// A face with its seams held is farther from its points than the tolerance.
    OverTolerance {
        /// The patch.
        patch: String,
        /// The largest distance.
        reached: f64,
        /// The tolerance.
        tolerance: f64,
    },
}

impl fmt::Display for ShellError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ShellError::Fit { patch, error } => write!(f, "patch \"{patch}\": {error}"),
            ShellError::Seam { seam, problem } => write!(f, "seam {seam}: {problem}"),
            ShellError::OverTolerance {
                patch,
                reached,
                tolerance,
            } => write!(
                f,
                "patch \"{patch}\": with its seams shared the face is {reached:.3e} from its points, over the tolerance {tolerance:.3e}; loosen the tolerance or fit at a finer depth"
            ),
        }
    }
}

impl std::error::Error for ShellError {}

/// The parameter `u` at which `p` lies on the polyline `row` (points at
/// parameters `u`), and its distance to it.
fn on_polyline(row: &[DVec3], u: &[f64], p: DVec3) -> (f64, f64) {
    let mut best = (f64::INFINITY, 0.0);
    for k in 0..row.len() - 1 {
        let (a, b) = (row[k], row[k + 1]);
        let ab = b - a;
        let t = if ab.length_squared() > 0.0 {
            ((p - a).dot(ab) / ab.length_squared()).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let d = (a + ab * t - p).length();
        if d < best.0 {
            best = (d, u[k] + t * (u[k + 1] - u[k]));
        }
    }
    (best.1, best.0)
}

/// `b`'s start column's parameters on `a`'s edge row: `(w, u₀, u₁)`, or why not.
fn side_params(a: &Samples, b: &Samples, edge: Edge) -> Result<(Vec<f64>, f64, f64), String> {
    let r = if edge == Edge::First {
        0
    } else {
        a.points.rows() - 1
    };
    let row = a.points.row(r);
    let scale = a.diagonal().max(f64::MIN_POSITIVE);
    let mut us = Vec::with_capacity(b.points.rows());
    for j in 0..b.points.rows() {
        let (u, d) = on_polyline(row, &a.u, b.points.get(j, 0));
        if d > 1e-9 * scale {
            return Err(format!(
                "the later patch's row {j} starts {d:.3e} away from the earlier patch's {} streamline; build both with joins::join",
                edge.name()
            ));
        }
        us.push(u);
    }
    let (u0, u1) = (us[0], us[us.len() - 1]);
    let w: Vec<f64> = us.iter().map(|u| (u - u0) / (u1 - u0)).collect();
    if !w.windows(2).all(|x| x[1] > x[0]) || !(u1 - u0).is_finite() || u0 == u1 {
        return Err(format!(
            "the later patch's start points do not run one way along the earlier patch's {} streamline",
            edge.name()
        ));
    }
    Ok((w, u0, u1))
}

/// `b`'s check grid's `w`: its start points placed on `a`'s check edge row,
/// normalised by the data's `(u₀, u₁)` (clamped into `[0, 1]`).
fn check_params(a: &Samples, b: &Samples, edge: Edge, u0: f64, u1: f64) -> Vec<f64> {
    let r = if edge == Edge::First {
        0
    } else {
        a.points.rows() - 1
    };
    let row = a.points.row(r);
    let mut w: Vec<f64> = (0..b.points.rows())
        .map(|j| ((on_polyline(row, &a.u, b.points.get(j, 0)).0 - u0) / (u1 - u0)).clamp(0.0, 1.0))
        .collect();
    let n = w.len();
    (w[0], w[n - 1]) = (0.0, 1.0);
    w
}

/// The union of the required knots (kept exactly) and the optional ones
/// farther than `gap` from every kept knot.
fn merge_knots(required: &[f64], optional: &[f64], gap: f64) -> Vec<f64> {
    let mut kept: Vec<f64> = required.to_vec();
    kept.sort_by(f64::total_cmp);
    kept.dedup();
    let mut opt = optional.to_vec();
    opt.sort_by(f64::total_cmp);
    for k in opt {
        if kept.iter().all(|x| (x - k).abs() > gap) && k > gap && k < 1.0 - gap {
            let at = kept.partition_point(|x| *x < k);
            kept.insert(at, k);
        }
    }
    kept
}

/// A seam's poles held in a face's first column, and for G1 the earlier
/// face and its column next to the seam.
type Held = (Vec<DVec3>, Option<(usize, usize)>);

/// The most `u` knots added to a face whose held boundary puts it over the tolerance.
const MAX_ROUNDS: usize = 12;

/// The piece of `a`'s edge that seam `k` (a side seam over `range`) is.
fn side_piece(
    a: &BSplineSurface,
    s: SeamSpec,
    (u0, u1): (f64, f64),
    opts: &FitOptions,
    k: usize,
) -> Result<Curve, ShellError> {
    let r = if s.join.edge == Edge::First {
        0
    } else {
        a.poles.rows() - 1
    };
    let edge = Curve::new(&a.knots_u, a.poles.row(r).to_vec());
    if opts.degree.0 != opts.degree.1 {
        return Err(ShellError::Seam {
            seam: k,
            problem: "a side join needs the same degree in u and v (the seam is a u curve of one face and a v curve of the other)".into(),
        });
    }
    Ok(if u0 < u1 {
        edge.piece(u0, u1)
    } else {
        edge.piece(u1, u0).reversed()
    })
}

/// Puts the seam's poles into `surface`'s first column; with `g1` (`a`'s
/// face and its column next to the seam), each pole of the second column
/// is projected onto the line through `a`'s two poles before it, so the
/// poles next to the seam are collinear across it.
fn hold(surface: &mut BSplineSurface, seam: &[DVec3], g1: Option<(&BSplineSurface, usize)>) {
    for (l, p) in seam.iter().enumerate() {
        surface.poles.set(l, 0, *p);
    }
    if let Some((a, inner)) = g1 {
        for l in 0..surface.poles.rows() {
            let p0 = surface.poles.get(l, 0);
            let dir = (p0 - a.poles.get(l, inner)).normalize_or_zero();
            let p1 = surface.poles.get(l, 1);
            surface.poles.set(l, 1, p0 + dir * (p1 - p0).dot(dir));
        }
    }
}

/// Fits every patch as one face, the seams shared exactly (module docs).
pub fn fit_shell(
    patches: &[PatchGrid],
    seams: &[SeamSpec],
    opts: &FitOptions,
) -> Result<ShellFit, ShellError> {
    let n = patches.len();
    let fit_err = |i: usize| {
        let name = patches[i].name.clone();
        move |error| ShellError::Fit {
            patch: name.clone(),
            error,
        }
    };
    // the incoming seam of every patch
    let mut incoming: Vec<Option<usize>> = vec![None; n];
    for (k, s) in seams.iter().enumerate() {
        let bad = |problem: &str| ShellError::Seam {
            seam: k,
            problem: problem.to_string(),
        };
        if !(s.a < s.b && s.b < n) {
            return Err(bad(
                "a seam joins an earlier patch to a later one; give indices a < b within the patches",
            ));
        }
        if incoming[s.b].replace(k).is_some() {
            return Err(bad(
                "the later patch already starts on another edge; a patch starts on one edge",
            ));
        }
        if s.join.edge != Edge::End && s.join.continuity == Continuity::G2 {
            return Err(bad(
                "G2 on a side edge is not built (docs/math.md §11.2); use G1",
            ));
        }
        let (ra, rb) = (
            patches[s.a].data.points.rows(),
            patches[s.b].data.points.rows(),
        );
        if s.join.edge == Edge::End && ra != rb {
            return Err(bad(
                "a chain's patches have the same rows; build both with joins::join",
            ));
        }
    }
    // row parameters: a chain's are its first patch's, a side join's are w
    let mut v: Vec<(Vec<f64>, Vec<f64>)> = patches
        .iter()
        .map(|p| (p.data.v.clone(), p.check.v.clone()))
        .collect();
    let mut ranges = vec![(0.0, 1.0); seams.len()];
    for b in 0..n {
        let Some(k) = incoming[b] else { continue };
        let s = seams[k];
        if s.join.edge == Edge::End {
            v[b] = v[s.a].clone();
            if patches[b].check.points.rows() != v[b].1.len() {
                return Err(ShellError::Seam {
                    seam: k,
                    problem:
                        "a chain's check grids have the same rows; build both with joins::join"
                            .into(),
                });
            }
        } else {
            let (pa, pb) = (&patches[s.a], &patches[b]);
            let (w, u0, u1) = side_params(&pa.data, &pb.data, s.join.edge)
                .map_err(|problem| ShellError::Seam { seam: k, problem })?;
            let wc = check_params(&pa.check, &pb.check, s.join.edge, u0, u1);
            v[b] = (w, wc);
            ranges[k] = (u0, u1);
        }
    }
    let with_v = |s: &Samples, v: &[f64]| Samples {
        points: s.points.clone(),
        u: s.u.clone(),
        v: v.to_vec(),
    };
    let data: Vec<Samples> = (0..n).map(|i| with_v(&patches[i].data, &v[i].0)).collect();
    let check: Vec<Samples> = (0..n).map(|i| with_v(&patches[i].check, &v[i].1)).collect();
    // each patch's knots alone, with a margin for the shared v knots
    let mut tols = Vec::with_capacity(n);
    let mut alone = Vec::with_capacity(n);
    for i in 0..n {
        let tol = check_options(opts, &data[i]).map_err(fit_err(i))?;
        let tight = FitOptions {
            degree: opts.degree,
            tolerance: Tolerance::Absolute(0.7 * tol),
        };
        let f = fit(&data[i], &check[i], &tight).map_err(fit_err(i))?;
        tols.push(tol);
        alone.push(f.surface);
    }
    // chain groups share their v knots; a side-joined root also needs the
    // knots of the piece of its parent's edge
    let mut root: Vec<usize> = (0..n).collect();
    for b in 0..n {
        if let Some(k) = incoming[b]
            && seams[k].join.edge == Edge::End
        {
            root[b] = root[seams[k].a];
        }
    }
    // the faces, in order: a parent's boundary is final before its
    // children's, and a chain group's v knots are made at its first patch
    let mut group_kv: Vec<Option<KnotVector>> = vec![None; n];
    let mut faces: Vec<ShellFace> = Vec::with_capacity(n);
    for i in 0..n {
        let piece = match incoming[i] {
            Some(k) if seams[k].join.edge != Edge::End => Some(side_piece(
                &faces[seams[k].a].surface,
                seams[k],
                ranges[k],
                opts,
                k,
            )?),
            _ => None,
        };
        if root[i] == i {
            let required: Vec<f64> = piece
                .as_ref()
                .map(|c| c.knots[c.degree + 1..c.knots.len() - c.degree - 1].to_vec())
                .unwrap_or_default();
            let optional: Vec<f64> = (0..n)
                .filter(|&m| root[m] == i)
                .flat_map(|m| alone[m].knots_v.interior().to_vec())
                .collect();
            let gap = data[i]
                .v
                .windows(2)
                .map(|w| w[1] - w[0])
                .fold(0.0, f64::max);
            let knots = merge_knots(&required, &optional, gap);
            let kv = KnotVector::with_interior(opts.degree.1, &knots).ok_or_else(|| {
                ShellError::Seam {
                    seam: incoming[i].unwrap_or(0),
                    problem: "the shared v knots are not increasing inside (0, 1)".into(),
                }
            })?;
            group_kv[i] = Some(kv);
        }
        let kv = group_kv[root[i]]
            .clone()
            .expect("made at the group's first patch");
        // the seam's poles, fitted once: a's last column, or the piece of a's edge
        let held: Option<Held> = match incoming[i] {
            None => None,
            Some(k) => {
                let s = seams[k];
                let a = &faces[s.a].surface;
                if s.join.edge == Edge::End {
                    let g1 =
                        (s.join.continuity >= Continuity::G1).then_some((s.a, a.poles.cols() - 2));
                    Some((a.poles.column(a.poles.cols() - 1), g1))
                } else {
                    let c = piece.as_ref().expect("a side seam's piece");
                    let c = c.refined_to(&kv).ok_or_else(|| ShellError::Seam {
                        seam: k,
                        problem: "the seam piece does not fit on the shared knots".into(),
                    })?;
                    Some((c.poles, None))
                }
            }
        };
        // refine u where the held boundary costs the tolerance
        let mut ku = alone[i].knots_u.clone();
        let mut rounds = 0;
        let (surface, dev) = loop {
            let mut surface = fit_knots(&data[i], &ku, &kv).map_err(fit_err(i))?;
            if let Some((poles, g1)) = &held {
                hold(
                    &mut surface,
                    poles,
                    g1.map(|(a, col)| (&faces[a].surface, col)),
                );
            }
            let dev = deviation(&surface, &check[i]);
            if dev.max <= tols[i] || rounds >= MAX_ROUNDS {
                break (surface, dev);
            }
            rounds += 1;
            let u = check[i].u[dev.at.1];
            let (lo, hi) = ku.span_range(ku.span(u));
            if !ku.insert(0.5 * (lo + hi)) {
                break (surface, dev);
            }
        };
        if dev.max.partial_cmp(&tols[i]) != Some(std::cmp::Ordering::Less) && dev.max != tols[i] {
            return Err(ShellError::OverTolerance {
                patch: patches[i].name.clone(),
                reached: dev.max,
                tolerance: tols[i],
            });
        }
        faces.push(ShellFace {
            name: patches[i].name.clone(),
            surface,
            deviation: dev,
            tolerance: tols[i],
            v: v[i].clone(),
        });
    }
    let seams = seams
        .iter()
        .zip(ranges)
        .map(|(spec, range)| ShellSeam { spec: *spec, range })
        .collect();
    Ok(ShellFit { faces, seams })
}

/// Each patch's row parameters on its face for samples of any depth
/// (`grids`, one per patch in the shell's order, each with its own `u` and
/// `v`), given the shell's seams as fitted: a chain's rows are its first
/// patch's; a side-joined patch's are its start points placed on its
/// parent's edge row of the same depth, normalised by the seam's range, as
/// [`fit_shell`] places its check grids. At the depth the shell was fitted
/// at these are the faces' own (`ShellFace::v`); at another they let a
/// face be measured at that depth's points (the deviation map). A chain
/// whose patches' rows differ at that depth keeps the later patch's own.
pub fn face_rows(grids: &[Samples], seams: &[ShellSeam]) -> Vec<Vec<f64>> {
    let mut v: Vec<Vec<f64>> = grids.iter().map(|g| g.v.clone()).collect();
    let mut by_later: Vec<&ShellSeam> = seams
        .iter()
        .filter(|s| s.spec.a < s.spec.b && s.spec.b < grids.len())
        .collect();
    // parents first: a chain takes its first patch's rows as placed
    by_later.sort_by_key(|s| s.spec.b);
    for s in by_later {
        let (a, b) = (s.spec.a, s.spec.b);
        if s.spec.join.edge == Edge::End {
            if v[a].len() == grids[b].points.rows() {
                v[b] = v[a].clone();
            }
        } else {
            let (u0, u1) = s.range;
            v[b] = check_params(&grids[a], &grids[b], s.spec.join.edge, u0, u1);
        }
    }
    v
}

/// Each face fitted alone, as one face of its own (today's export per
/// patch; no shared edge): the negative control of the shell's tests.
pub fn fit_alone(patches: &[PatchGrid], opts: &FitOptions) -> Result<Vec<ShellFace>, ShellError> {
    patches
        .iter()
        .map(|p| {
            let f = fit(&p.data, &p.check, opts).map_err(|error| ShellError::Fit {
                patch: p.name.clone(),
                error,
            })?;
            Ok(ShellFace {
                name: p.name.clone(),
                surface: f.surface,
                deviation: f.report.deviation,
                tolerance: f.report.tolerance,
                v: (p.data.v.clone(), p.check.v.clone()),
            })
        })
        .collect()
}
