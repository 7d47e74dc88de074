//! Several patches as B-spline faces whose seams are shared exactly
//! (docs/math.md §10, §11): one face per patch, each seam's boundary curve
//! fitted **once** and used by both faces.
//!
//! - **Chain** (`edge: End`, docs/math.md §11.1): `B`'s first column of
//!   points is `A`'s last and its rows are `A`'s rows (same `t`), so `B` is
//!   given `A`'s row parameters `v`. Every patch of a chain shares one `v`
//!   knot vector: `A` is fitted on the knots it needs alone, `B` on those
//!   and its own (each kept a row spacing from `A`'s) and any its rounds add
//!   (below), and `A` is then refined onto `B`'s by knot insertion (the same
//!   surface). `A`'s last column of poles (the seam curve, fitted once by
//!   `A`'s column pass), refined the same way, is `B`'s first column,
//!   copied. (The union of both patches' knots fitted at `A` left spans of
//!   one or two rows where the two patches' knots interleave, and `A`'s
//!   column pass swung between its rows, 100 tolerances off on a rough
//!   random chain.) For G1 and G2 `B`'s second column of poles is
//!   projected onto the lines through `A`'s last two columns, so the poles
//!   next to the seam are collinear across it, then moved along `A`'s
//!   normal as on a side seam (`hold_side`, docs/math.md §11.5): collinear
//!   poles whose spacing ratio differs row by row leave the cross
//!   derivatives apart by up to 0.41° on rough random chains.
//! - **Side** (`edge: First | Last`, §11.2): `B`'s start points lie on `A`'s
//!   first or last streamline. Each is given the parameter `u` of `A` where it
//!   lies on that streamline's polyline, and `B`'s row parameter is the
//!   normalised `w = (u − u₀)/(u₁ − u₀)` between its first and last row's
//!   (`u₀`, `u₁`). The seam curve is the piece over `[u₀, u₁]` of `A`'s
//!   boundary curve (its poles row), cut by knot insertion, refined onto `B`'s
//!   `v` knots (which hold the piece's knots) and used as `B`'s first column
//!   of poles: `B`'s start edge is exactly that part of `A`'s edge, and a
//!   writer splits `A`'s edge at `u₀` and `u₁` (see [`ShellSeam::range`]).
//!   For G1 `B`'s second column is moved along `A`'s normal (`hold_side`,
//!   a least squares), and `B`'s `v` spans where the faces' normals are
//!   then over `SEAM_ANGLE_DEG` apart are halved and `B` fitted again.
//!
//! Each face's other poles are the separable least-squares fit of its points
//! with both ends of every row interpolated (`fit_knots`), so the interior is
//! fitted with the boundary held; every face is then measured against its
//! check grid (one depth finer) and must be within the tolerance. While it
//! is not, its `u` spans over the tolerance are halved (the held boundary
//! costs those), and its `v` spans over the tolerance whose column-pass
//! residual is at least half the tolerance are split at the rows'
//! quantiles as the fit alone splits them (docs/math.md §10): a row the
//! shared `v` knots miss is brought within the tolerance by no `u` knot.

use super::curve::Curve;
use super::deviation::Deviation;
use super::error::FitError;
use super::fit::{FitOptions, Tolerance, check_options, fit, fit_pass, pieces_for, split_points};
use super::knots::KnotVector;
use super::samples::Samples;
use super::seam_hold::{hold, hold_side, seam_angles, side_cross};
use super::seam_params::{ParentMap, check_params, measure_face, merge_knots, side_params};
use super::surface::BSplineSurface;
use crate::grid::Grid;
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
    /// Whether a side G1 or G2 seam's slope is held (`b`'s second column of
    /// poles in `a`'s tangent plane, docs/math.md §11.5): false where
    /// holding it kept `b`'s face beyond its tolerance, and the face was
    /// fitted with the seam curve alone held (G0 in the file); true for
    /// every other seam.
    pub slope_held: bool,
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

/// How a face's poles next to its incoming seam are held for G1 and G2.
#[derive(Debug, Clone)]
enum Smooth {
    /// G0: only the seam's poles.
    None,
    /// A chain: the earlier face on the later one's `v` knots (each row of
    /// poles made collinear across the seam with its last two columns).
    Chain(BSplineSurface),
    /// A side join: `a`'s cross derivative along the piece of its edge, a
    /// curve in `b`'s `v` (the seam's own parameter), whose normal with the
    /// seam curve is `a`'s normal there.
    Side(Curve),
}

/// A seam's poles held in a face's first column, and how its second is held.
type Held = (Vec<DVec3>, Smooth);

/// The most rounds of knots added to a face whose held boundary (or shared
/// `v` knots) puts it over the tolerance.
const MAX_ROUNDS: usize = 40;

/// The share of the tolerance a direction's own pass residual must reach in
/// a span over the tolerance for a face of a shell to split that span by it
/// (as `fit` weighs its directions, docs/math.md §10).
const RESIDUAL_SHARE: f64 = 0.5;

/// The largest angle between the faces' normals along a side G1 seam that
/// the least squares of Eq. 76 may leave before the later face's `v` spans
/// there are split (a quarter of the 0.1° asked, docs/math.md §11.5).
const SEAM_ANGLE_DEG: f64 = 0.025;

/// The most times a side G1 face's `v` knots are split for its seam's angle.
const MAX_V_ROUNDS: usize = 6;

/// The margin of the fits alone (whose knots a shell starts from) under
/// the tolerance: room for what holding a seam costs. A face that cannot
/// be fitted within it alone starts from its fit within the tolerance
/// itself, else from the fit of its own points (the margin is a head start,
/// not a requirement: a margin the grid cannot reach refused every depth,
/// docs/math.md §10); the shell's own rounds then hold the tolerance.
const ALONE_MARGIN: f64 = 0.7;

/// `s` on the `v` knots `kv` (which hold its own): every column of poles
/// refined by knot insertion (Piegl & Tiller Algorithm A5.1), the same
/// surface; `None` when `kv` lacks one of `s`'s knots.
fn refined_v(s: &BSplineSurface, kv: &KnotVector) -> Option<BSplineSurface> {
    let cols = s.poles.cols();
    let columns: Vec<Vec<DVec3>> = (0..cols)
        .map(|c| {
            Some(
                Curve::new(&s.knots_v, s.poles.column(c))
                    .refined_to(kv)?
                    .poles,
            )
        })
        .collect::<Option<_>>()?;
    let rows = kv.count();
    let data = (0..rows * cols)
        .map(|n| columns[n % cols][n / cols])
        .collect();
    Some(BSplineSurface {
        knots_u: s.knots_u.clone(),
        knots_v: kv.clone(),
        poles: Grid::new(rows, cols, data).ok()?,
    })
}

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

/// Face `i` of a fitted shell measured at `check` (its points, with the
/// face's own row parameters) as [`fit_shell`] measures it: foot points for
/// the points over the face's tolerance, on the face and on the earlier face
/// across its start edge.
pub fn face_deviation(shell: &ShellFit, i: usize, check: &Samples) -> Deviation {
    let face = &shell.faces[i];
    let parent = shell.seams.iter().find(|s| s.spec.b == i).map(|s| {
        let to = match s.spec.join.edge {
            Edge::End => ParentMap::Chain,
            e => ParentMap::Side(if e == Edge::First { 0.0 } else { 1.0 }, s.range),
        };
        (&shell.faces[s.spec.a].surface, to)
    });
    measure_face(&face.surface, check, face.tolerance, parent).0
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
    let mut too_few: Vec<Option<FitError>> = Vec::with_capacity(n);
    let mut alone = Vec::with_capacity(n);
    for i in 0..n {
        let tol = check_options(opts, &data[i]).map_err(fit_err(i))?;
        let within = |t: f64| FitOptions {
            degree: opts.degree,
            tolerance: Tolerance::Absolute(t),
        };
        // a later face's check grid may start beyond its data's seam (see
        // `measure_face`): measured alone it cannot come closer than that
        // strip
        // then, for a later face, the knots its own points need (no strip
        // there), the shell's rounds measuring the rest
        // (and for a root whose check grid slides against its data: the
        // parametric measure of the fit alone, docs/math.md §10)
        let ladder: &[(f64, bool)] = &[
            (ALONE_MARGIN, true),
            (1.0, true),
            (ALONE_MARGIN, false),
            (1.0, false),
        ];
        let mut found = None;
        let mut short = None;
        for (n, &(m, on_check)) in ladder.iter().enumerate() {
            let against = if on_check { &check[i] } else { &data[i] };
            match fit(&data[i], against, &within(m * tol)) {
                Ok(f) => {
                    found = Some(f);
                    break;
                }
                Err(e @ FitError::TooFewPoints { .. }) if n + 1 < ladder.len() => {
                    if on_check {
                        short = Some(e);
                    }
                }
                Err(e) => return Err(fit_err(i)(e)),
            }
        }
        let f = found.expect("the ladder returns or finds one");
        // a face started from its own points that the shell's rounds cannot
        // bring within the tolerance is refused as its fit alone was
        too_few.push(short);
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
    let mut slope_held = vec![true; seams.len()];
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
        let cross = match incoming[i] {
            Some(k)
                if seams[k].join.edge != Edge::End
                    && seams[k].join.continuity >= Continuity::G1 =>
            {
                Some(side_cross(
                    &faces[seams[k].a].surface,
                    seams[k].join.edge,
                    ranges[k],
                ))
            }
            _ => None,
        };
        // the face's v knots: a root's own (and the knots of the piece of
        // its parent's edge it starts on), a chain's later patch the
        // group's so far (they carry its seam curve) and its own, kept a
        // row spacing apart
        let gap = data[i]
            .v
            .windows(2)
            .map(|w| w[1] - w[0])
            .fold(0.0, f64::max);
        let required: Vec<f64> = if root[i] == i {
            piece
                .as_ref()
                .map(|c| c.knots[c.degree + 1..c.knots.len() - c.degree - 1].to_vec())
                .unwrap_or_default()
        } else {
            group_kv[root[i]]
                .as_ref()
                .expect("made at the group's first patch")
                .interior()
                .to_vec()
        };
        let knots = merge_knots(&required, alone[i].knots_v.interior(), gap);
        let mut kv =
            KnotVector::with_interior(opts.degree.1, &knots).ok_or_else(|| ShellError::Seam {
                seam: incoming[i].unwrap_or(0),
                problem: "the shared v knots are not increasing inside (0, 1)".into(),
            })?;
        // the seam's poles on the knots `kv`, fitted once: a's last column
        // (a refined onto `kv`, the same surface), or the piece of a's edge
        let held_on = |kv: &KnotVector| -> Result<Option<Held>, ShellError> {
            let Some(k) = incoming[i] else {
                return Ok(None);
            };
            let s = seams[k];
            let unfit = |what: &str| ShellError::Seam {
                seam: k,
                problem: format!("the {what} does not fit on the shared knots"),
            };
            if s.join.edge == Edge::End {
                let a = refined_v(&faces[s.a].surface, kv).ok_or_else(|| unfit("seam curve"))?;
                let seam = a.poles.column(a.poles.cols() - 1);
                let g1 = if s.join.continuity >= Continuity::G1 {
                    Smooth::Chain(a)
                } else {
                    Smooth::None
                };
                Ok(Some((seam, g1)))
            } else {
                let c = piece.as_ref().expect("a side seam's piece");
                let refined = c.refined_to(kv).ok_or_else(|| unfit("seam piece"))?;
                let g1 = match &cross {
                    Some(d) => Smooth::Side(d.clone()),
                    None => Smooth::None,
                };
                Ok(Some((refined.poles, g1)))
            }
        };
        let parent = incoming[i].map(|k| {
            let s = seams[k];
            let to: ParentMap = match s.join.edge {
                Edge::End => ParentMap::Chain,
                e => ParentMap::Side(if e == Edge::First { 0.0 } else { 1.0 }, ranges[k]),
            };
            (&faces[s.a].surface, to)
        });
        let q = opts.degree.1;
        let mut v_rounds = 0;
        let (surface, dev) = loop {
            // refine where the held boundary costs the tolerance; a side G1
            // seam whose held slope keeps the face off its points beyond the
            // tolerance is fitted again with the seam curve alone held (the
            // faces then meet G0 in the file, within the tolerance)
            let is_side = cross.is_some();
            let mut side_hold = true;
            let (surface, dev) = loop {
                let mut ku = alone[i].knots_u.clone();
                let mut rounds = 0;
                let mut held: Option<(KnotVector, Option<Held>)> = None;
                let mut best: Option<(BSplineSurface, Deviation)> = None;
                let (surface, dev) = loop {
                    if held.as_ref().is_none_or(|(k, _)| *k != kv) {
                        held = Some((kv.clone(), held_on(&kv)?));
                    }
                    let pass = match (fit_pass(&data[i], &ku, &kv), best.take()) {
                        (Ok(s), before) => {
                            best = before;
                            s
                        }
                        // a split left a span without data: keep the best round
                        (Err(_), Some(before)) => break before,
                        (Err(e), None) => return Err(fit_err(i)(e)),
                    };
                    let mut surface = pass.surface.clone();
                    if let Some((_, Some((poles, smooth)))) = &held {
                        match smooth {
                            Smooth::None => hold(&mut surface, poles, None),
                            Smooth::Chain(a) => {
                                let col = a.poles.cols() - 2;
                                hold(&mut surface, poles, Some((a, col)));
                                // the projection leaves each row's poles collinear;
                                // the cross derivatives' weights still differ row by
                                // row, so the normal is then held as on a side seam
                                let last = col + 1;
                                let cross: Vec<DVec3> = (0..a.poles.rows())
                                    .map(|l| a.poles.get(l, last) - a.poles.get(l, col))
                                    .collect();
                                let seam = Curve::new(&kv, poles.clone());
                                hold_side(&mut surface, &seam, &Curve::new(&kv, cross));
                            }
                            Smooth::Side(d) => {
                                hold(&mut surface, poles, None);
                                let seam = Curve::new(&kv, poles.clone());
                                if side_hold {
                                    hold_side(&mut surface, &seam, d);
                                }
                            }
                        }
                    }
                    let (mut dev, mut span_u, mut span_v) =
                        measure_face(&surface, &check[i], tols[i], parent);
                    if dev.max <= tols[i] {
                        // and the fitted points themselves (foot points one depth
                        // finer promise nothing for them)
                        let at_data = measure_face(&surface, &data[i], tols[i], parent);
                        if at_data.0.max > tols[i] {
                            (dev, span_u, span_v) = at_data;
                        }
                    }
                    if best.as_ref().is_none_or(|(_, b)| dev.max < b.max) {
                        best = Some((surface, dev));
                    }
                    if dev.max <= tols[i] || rounds >= MAX_ROUNDS || ku.count() >= data[i].u.len() {
                        break best.take().expect("this round's at least");
                    }
                    rounds += 1;
                    // v spans over the tolerance that the column pass' own
                    // residual explains are split at the rows' quantiles, as
                    // the fit alone splits them (docs/math.md §10): held
                    // boundaries cost `u` spans, and splitting those cannot
                    // bring a row the v knots miss within the tolerance
                    let res_v = pass.residuals_v(&data[i]);
                    let mut new_v = Vec::new();
                    for j in (0..span_v.len()).filter(|&j| span_v[j] > tols[i]) {
                        if res_v[j] >= RESIDUAL_SHARE * tols[i] {
                            let pieces = pieces_for(res_v[j], tols[i], q);
                            split_points(&kv, &data[i].v, j, pieces, &mut new_v);
                        }
                    }
                    // u spans over the tolerance are halved (at most as many
                    // knots as the grid has room for); while v spans are
                    // split, only those the row pass' residual explains
                    let room = data[i].u.len() - ku.count();
                    let res_u = if new_v.is_empty() {
                        Vec::new()
                    } else {
                        pass.residuals_u(&data[i])
                    };
                    let mids: Vec<f64> = (0..span_u.len())
                        .filter(|&j| span_u[j] > tols[i])
                        .filter(|&j| new_v.is_empty() || res_u[j] >= RESIDUAL_SHARE * tols[i])
                        .map(|j| {
                            let (lo, hi) = ku.span_range(j);
                            0.5 * (lo + hi)
                        })
                        .take(room)
                        .collect();
                    let mut grew = false;
                    for u in mids {
                        grew |= ku.insert(u);
                    }
                    for v in new_v {
                        grew |= kv.insert(v);
                    }
                    if !grew {
                        break best.take().expect("kept above");
                    }
                };
                // the knots of the round kept
                kv = surface.knots_v.clone();
                if dev.max > tols[i] && is_side && side_hold {
                    side_hold = false;
                    if let Some(k) = incoming[i] {
                        slope_held[k] = false;
                    }
                    continue;
                }
                break (surface, dev);
            };
            // Eq. 76 is a least squares: where the face's v knots are too few
            // for the turning of the earlier face's normal it leaves a residual
            // angle; those v spans are split and the face fitted again (a side
            // patch of its own v knots: its chain, if any, is fitted after it)
            if let (Some(c), Some(d)) = (&piece, &cross)
                && side_hold
                && root[i] == i
                && v_rounds < MAX_V_ROUNDS
            {
                let seam = c.refined_to(&kv).ok_or_else(|| ShellError::Seam {
                    seam: incoming[i].unwrap_or(0),
                    problem: "the seam piece does not fit on the shared knots".into(),
                })?;
                let spans = seam_angles(&surface, &seam, d);
                let rows = &data[i].v;
                let holds = |lo: f64, hi: f64| rows.iter().any(|x| *x > lo && *x < hi);
                let mids: Vec<f64> = (0..spans.len())
                    .filter(|&j| spans[j] > SEAM_ANGLE_DEG)
                    .map(|j| kv.span_range(j))
                    .filter(|&(lo, hi)| holds(lo, 0.5 * (lo + hi)) && holds(0.5 * (lo + hi), hi))
                    .map(|(lo, hi)| 0.5 * (lo + hi))
                    .collect();
                let mut grew = false;
                for m in mids {
                    grew |= kv.insert(m);
                }
                if grew {
                    v_rounds += 1;
                    continue;
                }
            }
            break (surface, dev);
        };
        if dev.max.partial_cmp(&tols[i]) != Some(std::cmp::Ordering::Less) && dev.max != tols[i] {
            if let Some(e) = too_few[i].take() {
                return Err(fit_err(i)(e));
            }
            return Err(ShellError::OverTolerance {
                patch: patches[i].name.clone(),
                reached: dev.max,
                tolerance: tols[i],
            });
        }
        // the chain's faces share the face's v knots: the earlier ones are
        // refined onto them (knots inserted, the same surfaces), each seam
        // curve by the same insertions as the later face's copy of it
        let kv = surface.knots_v.clone();
        for m in (0..i).filter(|&m| root[m] == root[i]) {
            if faces[m].surface.knots_v != kv {
                faces[m].surface =
                    refined_v(&faces[m].surface, &kv).ok_or_else(|| ShellError::Seam {
                        seam: incoming[i].unwrap_or(0),
                        problem: "the shared v knots do not hold an earlier face's".into(),
                    })?;
            }
        }
        group_kv[root[i]] = Some(kv);
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
        .zip(slope_held)
        .map(|((spec, range), slope_held)| ShellSeam {
            spec: *spec,
            range,
            slope_held,
        })
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
