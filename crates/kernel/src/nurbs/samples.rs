//! A grid of surface points with the parameters the fit gives them
//! (docs/math.md §10): `u` per column is the average over the
//! rows of the normalised arc length `(s − s_first)/(s_last − s_first)` of
//! each point, `v` per row the normalised `(t − t_first)/(t_last − t_first)`.

use super::error::FitError;
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
    let ends = p.first() == Some(&0.0) && p.last() == Some(&1.0);
    if let Some(i) = p
        .windows(2)
        .position(|w| w[1].partial_cmp(&w[0]) != Some(std::cmp::Ordering::Greater))
    {
        return Err(FitError::BadSamples {
            problem: format!(
                "{what} parameter {} ({}) does not rise above the one before ({}); give strictly increasing parameters",
                i + 1,
                p[i + 1],
                p[i]
            ),
        });
    }
    if !ends {
        return Err(FitError::BadSamples {
            problem: format!("{what} parameters must run from exactly 0 to exactly 1"),
        });
    }
    Ok(())
}

impl Samples {
    /// Checks sizes, finiteness and that both parameter lists rise strictly from 0 to 1.
    pub fn new(points: Grid<DVec3>, u: Vec<f64>, v: Vec<f64>) -> Result<Self, FitError> {
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
        check_params(&u, "u")?;
        check_params(&v, "v")?;
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
    /// their parameters.
    pub fn from_level(level: &Level, points: Grid<DVec3>) -> Result<Self, FitError> {
        let s = &level.params.s;
        let (rows, n) = (s.rows(), s.cols());
        let width = n + 1;
        let mut u = vec![0.0; width];
        for r in 0..rows {
            let row = s.row(r);
            let (a, len) = (row[0], row[n - 1] - row[0]);
            for (k, x) in u.iter_mut().enumerate() {
                *x += (point_arclength(row, k) - a) / len;
            }
        }
        for x in &mut u {
            *x /= rows as f64;
        }
        u[0] = 0.0;
        u[width - 1] = 1.0;
        let t = &level.params.t;
        let (t0, span) = (t[0], t[rows - 1] - t[0]);
        let mut v: Vec<f64> = t.iter().map(|x| (x - t0) / span).collect();
        v[rows - 1] = 1.0;
        if let Some(r) = v
            .windows(2)
            .position(|w| w[1].partial_cmp(&w[0]) != Some(std::cmp::Ordering::Greater))
        {
            return Err(FitError::BadSamples {
                problem: format!(
                    "the row parameter t stops rising at row {} of {rows} at this depth (subdivision bends it back where rows are spaced very unevenly); space the rows more evenly",
                    r + 1
                ),
            });
        }
        Samples::new(points, u, v)
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

    /// The diagonal of the points' axis-aligned bounding box.
    pub fn diagonal(&self) -> f64 {
        let [lo, hi] = crate::streamline::surface_mesh::bounds(self.points.data().iter().copied());
        (hi - lo).length()
    }
}
