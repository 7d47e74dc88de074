//! A grid of surface points with the parameters the fit gives them
//! (docs/math.md §10): `u` per column is the average over the
//! rows of the normalised arc length `(s − s_first)/(s_last − s_first)` of
//! each point, `v` per row the normalised `(t − t_first)/(t_last − t_first)`.
//!
//! A fit's check grid, one depth finer, is measured in its data's frame
//! ([`Samples::pair`]): an approximating scheme shortens the rows and
//! moves the first and last rows inwards at every depth, so each grid
//! normalised by its own ends would give the same point of the surface
//! parameters a sample spacing apart. Both grids are first normalised by
//! the limit ends of the scheme (`(s − a)/(b − a)` with `a`, `b` from
//! [`CurveScheme::limit_ends`], the same at every depth, and so for `t`),
//! then mapped so that the data runs from 0 to 1: the check grid lies
//! inside, where its points are.

use super::error::FitError;
use crate::curve::scheme::CurveScheme;
use crate::grid::Grid;
use crate::levels::builder::Builder;
use crate::levels::design::{Design, Level};
use crate::streamline::integrate::point_arclength;
use glam::DVec3;

/// Points on a `v × u` grid of parameters: row `j`, column `i` sits at `(u[i], v[j])`.
#[derive(Debug, Clone, PartialEq)]
pub struct Samples {
    /// The points, one row per streamline.
    pub points: Grid<DVec3>,
    /// One parameter per column, rising strictly from 0 to 1.
    pub u: Vec<f64>,
    /// One parameter per row, rising strictly from 0 to 1.
    pub v: Vec<f64>,
}

fn check_params(p: &[f64], what: &str) -> Result<(), FitError> {
    check_rising(p, what)?;
    if !(p.first() == Some(&0.0) && p.last() == Some(&1.0)) {
        return Err(FitError::BadSamples {
            problem: format!("{what} parameters must run from exactly 0 to exactly 1"),
        });
    }
    Ok(())
}

/// The first index whose next value does not rise strictly above it (NaN included).
fn first_not_rising(p: &[f64]) -> Option<usize> {
    p.windows(2)
        .position(|w| w[1].partial_cmp(&w[0]) != Some(std::cmp::Ordering::Greater))
}

fn check_rising(p: &[f64], what: &str) -> Result<(), FitError> {
    if let Some(i) = first_not_rising(p) {
        return Err(FitError::BadSamples {
            problem: format!(
                "{what} parameter {} ({}) does not rise above the one before ({}); give strictly increasing parameters",
                i + 1,
                p[i + 1],
                p[i]
            ),
        });
    }
    if p.iter().any(|x| !(0.0..=1.0).contains(x)) {
        return Err(FitError::BadSamples {
            problem: format!("{what} parameters must lie between 0 and 1"),
        });
    }
    Ok(())
}

/// Per column the mean over the rows of `(s − a)/(b − a)` at each point,
/// per row `(t − a_t)/(b_t − a_t)`, with the ends `a`, `b` of each row's
/// `s` and of `t` from `ends`, or the values' own ends where those enclose
/// nothing (a net as short as its scheme's mask has a limit of one point).
fn raw_params(level: &Level, limit: impl Fn(&[f64]) -> (f64, f64)) -> (Vec<f64>, Vec<f64>) {
    let ends = |x: &[f64]| match limit(x) {
        (a, b) if b > a => (a, b),
        _ => (x[0], x[x.len() - 1]),
    };
    let s = &level.params.s;
    let (rows, n) = (s.rows(), s.cols());
    let mut u = vec![0.0; n + 1];
    for r in 0..rows {
        let row = s.row(r);
        let (a, b) = ends(row);
        let len = b - a;
        for (k, x) in u.iter_mut().enumerate() {
            *x += (point_arclength(row, k) - a) / len;
        }
    }
    for x in &mut u {
        *x /= rows as f64;
    }
    let (t0, t1) = ends(&level.params.t);
    let span = t1 - t0;
    let v = level.params.t.iter().map(|x| (x - t0) / span).collect();
    (u, v)
}

/// `x` mapped by the affine map that takes `from.0` to 0 and `from.1` to 1
/// (left as it is when that map is the identity), then clamped to `[0, 1]`.
fn mapped(x: &mut [f64], from: (f64, f64)) {
    let w = from.1 - from.0;
    for y in x.iter_mut() {
        if from != (0.0, 1.0) {
            *y = (*y - from.0) / w;
        }
        *y = y.clamp(0.0, 1.0);
    }
}

/// The error of a level whose `t` stops rising.
fn t_not_rising(v: &[f64]) -> Result<(), FitError> {
    if let Some(r) = first_not_rising(v) {
        return Err(FitError::BadSamples {
            problem: format!(
                "the row parameter t stops rising at row {} of {} at this depth (subdivision bends it back where rows are spaced very unevenly); space the rows more evenly",
                r + 1,
                v.len()
            ),
        });
    }
    Ok(())
}

impl Samples {
    /// Checks sizes, finiteness and that both parameter lists rise strictly from 0 to 1.
    pub fn new(points: Grid<DVec3>, u: Vec<f64>, v: Vec<f64>) -> Result<Self, FitError> {
        Samples::checked(points, u, v, check_params)
    }

    /// [`Samples::new`] for a grid measured against a fit, whose
    /// parameters rise strictly within `[0, 1]` without having to reach
    /// either end (a check grid inside its data, [`Samples::pair`]).
    pub fn inside(points: Grid<DVec3>, u: Vec<f64>, v: Vec<f64>) -> Result<Self, FitError> {
        Samples::checked(points, u, v, check_rising)
    }

    /// The samples once their sizes, their parameters (by `params`) and
    /// their points (finite) are checked.
    fn checked(
        points: Grid<DVec3>,
        u: Vec<f64>,
        v: Vec<f64>,
        params: fn(&[f64], &str) -> Result<(), FitError>,
    ) -> Result<Self, FitError> {
        if (points.rows(), points.cols()) != (v.len(), u.len()) {
            return Err(FitError::BadSamples {
                problem: format!(
                    "a {}×{} point grid needs {} v and {} u parameters, got {} and {}",
                    points.rows(),
                    points.cols(),
                    points.rows(),
                    points.cols(),
                    v.len(),
                    u.len()
                ),
            });
        }
        if points.rows() < 2 || points.cols() < 2 {
            return Err(FitError::BadSamples {
                problem: "the point grid needs at least 2 rows and 2 columns".into(),
            });
        }
        params(&u, "u")?;
        params(&v, "v")?;
        if let Some(i) = points.data().iter().position(|p| !p.is_finite()) {
            return Err(FitError::BadSamples {
                problem: format!(
                    "point at row {}, column {} is not finite",
                    i / points.cols(),
                    i % points.cols()
                ),
            });
        }
        Ok(Samples { points, u, v })
    }

    /// The points of a level (from [`Design::streamlines`] or a build) with
    /// their parameters, normalised by the level's own ends.
    pub fn from_level(level: &Level, points: Grid<DVec3>) -> Result<Self, FitError> {
        let (mut u, mut v) = raw_params(level, |x| (x[0], x[x.len() - 1]));
        let (width, rows) = (u.len(), v.len());
        u[0] = 0.0;
        u[width - 1] = 1.0;
        v[rows - 1] = 1.0;
        t_not_rising(&v)?;
        Samples::new(points, u, v)
    }

    /// A fit's data, level `data`, and its check grid, level `check` (one
    /// depth finer), in one frame (module docs): the data from 0 to 1, the
    /// check grid inside. With an interpolating scheme both are
    /// [`Samples::from_level`]'s, bit for bit.
    pub fn pair(
        data: (&Level, Grid<DVec3>),
        check: (&Level, Grid<DVec3>),
        curve: CurveScheme,
    ) -> Result<(Self, Self), FitError> {
        let ends = |x: &[f64]| curve.limit_ends(x);
        let (mut u, mut v) = raw_params(data.0, ends);
        let (mut cu, mut cv) = raw_params(check.0, ends);
        let fu = (u[0], u[u.len() - 1]);
        let fv = (v[0], v[v.len() - 1]);
        for (x, f) in [(&mut u, fu), (&mut cu, fu), (&mut v, fv), (&mut cv, fv)] {
            mapped(x, f);
        }
        let (width, rows) = (u.len(), v.len());
        u[0] = 0.0;
        u[width - 1] = 1.0;
        v[0] = 0.0;
        v[rows - 1] = 1.0;
        t_not_rising(&v)?;
        t_not_rising(&cv)?;
        let data = Samples::new(data.1, u, v)?;
        let check = Samples::inside(check.1, cu, cv)?;
        Ok((data, check))
    }

    /// Level `shown`'s points in the frame of a fit's data, level `data`
    /// ([`Samples::pair`]), for the distance map of the points a designer
    /// sees: a coarser level of an approximating scheme reaches beyond the
    /// data, and its points there get the face's edge parameters (0 or 1).
    /// With an interpolating scheme, [`Samples::from_level`]'s parameters.
    pub fn in_frame_of(shown: (&Level, Grid<DVec3>), data: &Level, curve: CurveScheme) -> Samples {
        let ends = |x: &[f64]| curve.limit_ends(x);
        let (mut u, mut v) = raw_params(shown.0, ends);
        let (du, dv) = raw_params(data, ends);
        mapped(&mut u, (du[0], du[du.len() - 1]));
        mapped(&mut v, (dv[0], dv[dv.len() - 1]));
        Samples {
            points: shown.1,
            u,
            v,
        }
    }

    /// The design built at `depth`, with its parameters.
    pub fn build(design: &Design, depth: u32) -> Result<Self, FitError> {
        let mut b = Builder::new();
        b.build(design, depth)?;
        let (rows, cols) = b.point_shape();
        let points = Grid::new(rows, cols, b.mesh().positions.clone())?;
        let level = b.level().expect("built");
        Samples::from_level(level, points)
    }

    /// The design built at `depth` and at `depth + 1`, in one frame
    /// ([`Samples::pair`]): a fit's data and its check grid.
    pub fn build_pair(design: &Design, depth: u32) -> Result<(Self, Self), FitError> {
        let at = |depth: u32| -> Result<(Level, Grid<DVec3>), FitError> {
            let mut b = Builder::new();
            b.build(design, depth)?;
            let (rows, cols) = b.point_shape();
            let points = Grid::new(rows, cols, b.mesh().positions.clone())?;
            Ok((b.level().expect("built").clone(), points))
        };
        let (data, check) = (at(depth)?, at(depth + 1)?);
        Samples::pair(
            (&data.0, data.1),
            (&check.0, check.1),
            design.scheme().curve(),
        )
    }

    /// The diagonal of the points' axis-aligned bounding box.
    pub fn diagonal(&self) -> f64 {
        let [lo, hi] = crate::streamline::surface_mesh::bounds(self.points.data().iter().copied());
        (hi - lo).length()
    }
}
