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
//!
//! The steps, beside this file: `prepare` (the seams checked, the row
//! parameters, the fits alone), `chain` (a chain's shared `v` knots),
//! `side` (a side seam's piece of the parent's boundary curve, and its
//! normals' angle), `hold` (the seam's poles and slope held) and `rounds`
//! (a face's fitting rounds).

mod chain;
mod hold;
mod prepare;
mod rounds;
mod side;
mod start;

use super::deviation::Deviation;
use super::error::FitError;
use super::fit::{FitOptions, fit};
use super::knots::KnotVector;
use super::samples::Samples;
use super::seam_params::{ParentMap, check_params, measure_face};
use super::surface::BSplineSurface;
use crate::curve::scheme::CurveScheme;
use crate::joins::{Edge, Join, Stack};
use hold::Incoming;
use prepare::Prepared;
use rounds::Face;
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
    /// Levels `depth` and `depth + 1` of a patch built with `curve` along
    /// its rows (`stack.depth() > depth`), in one frame ([`Samples::pair`]).
    pub fn from_stack(
        name: &str,
        stack: &Stack,
        depth: u32,
        curve: CurveScheme,
    ) -> Result<Self, FitError> {
        let d = depth as usize;
        let at = |d: usize| (&stack.levels[d], stack.points[d].clone());
        let (data, check) = Samples::pair(at(d), at(d + 1), curve)?;
        Ok(PatchGrid {
            name: name.to_string(),
            data,
            check,
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

/// A patch's fit failed: the error as a shell names it.
fn fit_error(patch: &str, error: FitError) -> ShellError {
    ShellError::Fit {
        patch: patch.to_string(),
        error,
    }
}

/// Where a face's points near its start edge lie on the earlier face, the
/// seam being that face's `edge` over `range` (`measure_face`).
fn parent_map(edge: Edge, range: (f64, f64)) -> ParentMap {
    match edge {
        Edge::End => ParentMap::Chain,
        e => ParentMap::Side(if e == Edge::First { 0.0 } else { 1.0 }, range),
    }
}

/// Face `i` of a fitted shell measured at `check` (its points, with the
/// face's own row parameters) as [`fit_shell`] measures it: foot points for
/// the points over the face's tolerance, on the face and on the earlier face
/// across its start edge.
pub fn face_deviation(shell: &ShellFit, i: usize, check: &Samples) -> Deviation {
    let face = &shell.faces[i];
    let parent = shell.seams.iter().find(|s| s.spec.b == i).map(|s| {
        (
            &shell.faces[s.spec.a].surface,
            parent_map(s.spec.join.edge, s.range),
        )
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
    let mut shell = Prepared::new(patches, seams, opts)?;
    // the faces, in order: a parent's boundary is final before its
    // children's, and a chain group's v knots are made at its first patch
    let mut group_kv: Vec<Option<KnotVector>> = vec![None; n];
    let mut faces: Vec<ShellFace> = Vec::with_capacity(n);
    let mut slope_held = vec![true; seams.len()];
    for (i, patch) in patches.iter().enumerate() {
        let root = shell.root[i];
        let (surface, dev, held) = fit_face(&shell, i, &faces, group_kv[root].as_ref())?;
        if !held && let Some(k) = shell.incoming[i] {
            slope_held[k] = false;
        }
        let tol = shell.tols[i];
        if dev.max.partial_cmp(&tol) != Some(std::cmp::Ordering::Less) && dev.max != tol {
            if let Some(e) = shell.too_few[i].take() {
                return Err(fit_error(&patch.name, e));
            }
            return Err(ShellError::OverTolerance {
                patch: patch.name.clone(),
                reached: dev.max,
                tolerance: tol,
            });
        }
        // the chain's faces share the face's v knots: the earlier ones are
        // refined onto them (`chain::refine_group`)
        let kv = surface.knots_v.clone();
        let seam = shell.incoming[i].unwrap_or(0);
        chain::refine_group(&mut faces, &shell.root, i, &kv, seam)?;
        group_kv[root] = Some(kv);
        faces.push(ShellFace {
            name: patch.name.clone(),
            surface,
            deviation: dev,
            tolerance: tol,
            v: shell.v[i].clone(),
        });
    }
    let seams = seams
        .iter()
        .zip(shell.ranges)
        .zip(slope_held)
        .map(|((spec, range), slope_held)| ShellSeam {
            spec: *spec,
            range,
            slope_held,
        })
        .collect();
    Ok(ShellFit { faces, seams })
}

/// Face `i` of the shell fitted on the faces before it (`faces`) and its
/// chain group's `v` knots so far (`group`): its incoming seam's piece of
/// the parent's edge and that edge's cross derivative, the `v` knots it
/// starts from, then its rounds (`rounds::fit_face`). Returns the surface,
/// its deviation and whether a side G1 seam's slope is held.
fn fit_face(
    shell: &Prepared,
    i: usize,
    faces: &[ShellFace],
    group: Option<&KnotVector>,
) -> Result<(BSplineSurface, Deviation, bool), ShellError> {
    let opts = shell.opts;
    let seam = shell.incoming[i].map(|k| (k, shell.seams[k]));
    let (piece, cross) = match seam {
        Some((k, s)) if s.join.edge != Edge::End => {
            side::piece_and_cross(&faces[s.a].surface, s, shell.ranges[k], opts, k)?
        }
        _ => (None, None),
    };
    let is_root = shell.root[i] == i;
    let required = chain::required_v_knots(is_root, piece.as_ref(), group);
    let kv = chain::start_v_knots(
        &shell.data[i].v,
        &shell.alone[i].knots_v,
        &required,
        opts.degree.1,
        shell.incoming[i].unwrap_or(0),
    )?;
    let face = Face {
        name: &shell.patches[i].name,
        data: &shell.data[i],
        check: &shell.check[i],
        tol: shell.tols[i],
        ku: &shell.alone[i].knots_u,
        q: opts.degree.1,
        parent: seam.map(|(k, s)| {
            (
                &faces[s.a].surface,
                parent_map(s.join.edge, shell.ranges[k]),
            )
        }),
        seam: seam.map(|(k, spec)| Incoming {
            k,
            spec,
            a: &faces[spec.a].surface,
            piece: piece.as_ref(),
            cross: cross.as_ref(),
        }),
        is_root,
    };
    rounds::fit_face(&face, kv)
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
