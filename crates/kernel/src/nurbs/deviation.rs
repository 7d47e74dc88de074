//! The distance from sampled surface points to a fitted B-spline surface,
//! each point compared with the fit at its own parameters (docs/math.md §10,
//! `docs/math.md §10`). This parametric distance `|S_ij − F(u_i, v_j)|` is
//! never less than the distance from `S_ij` to the nearest point of `F`, so
//! a fit within the tolerance by this measure is within it by any other.

use super::samples::Samples;
use super::surface::{BSplineSurface, BasisTable};
use crate::grid::Grid;

/// Largest and mean distance over a grid of samples.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Deviation {
    /// The largest distance.
    pub max: f64,
    /// The mean distance.
    pub mean: f64,
    /// Row and column of the sample with the largest distance.
    pub at: (usize, usize),
}

/// Distances with the largest per knot span of the surface, for refinement.
#[derive(Debug, Clone)]
pub(crate) struct Measured {
    pub deviation: Deviation,
    pub span_u: Vec<f64>,
    pub span_v: Vec<f64>,
}

/// Measures `surface` against `samples`; with `field`, also writes every distance.
pub(crate) fn measure(
    surface: &BSplineSurface,
    samples: &Samples,
    field: Option<&mut Vec<f64>>,
) -> Measured {
    match surface.knots_u.degree() {
        2 => measure_p::<2>(surface, samples, field),
        3 => measure_p::<3>(surface, samples, field),
        4 => measure_p::<4>(surface, samples, field),
        _ => measure_p::<5>(surface, samples, field),
    }
}

/// [`measure`] for degree `P` in `u` (unrolled: it runs at every check sample).
fn measure_p<const P: usize>(
    surface: &BSplineSurface,
    samples: &Samples,
    mut field: Option<&mut Vec<f64>>,
) -> Measured {
    debug_assert_eq!(surface.knots_u.degree(), P);
    let tu = BasisTable::new(&surface.knots_u, &samples.u);
    let mut span_u = vec![0.0f64; surface.knots_u.spans()];
    let mut span_v = vec![0.0f64; surface.knots_v.spans()];
    let (mut max, mut sum, mut at) = (0.0f64, 0.0, (0, 0));
    let mut curve = Vec::with_capacity(surface.poles.cols());
    if let Some(f) = field.as_deref_mut() {
        f.clear();
    }
    for (j, &v) in samples.v.iter().enumerate() {
        surface.curve_at_into(v, &mut curve);
        let row = samples.points.row(j);
        let (mut row_max, mut row_at) = (0.0f64, 0);
        for (i, ((first, b), q)) in tu.rows.iter().zip(row).enumerate() {
            let c = &curve[*first..*first + P + 1];
            let mut pt = c[0] * b[0];
            for a in 1..=P {
                pt += c[a] * b[a];
            }
            let d = (pt - *q).length();
            sum += d;
            if d > row_max {
                row_max = d;
                row_at = i;
            }
            let su = &mut span_u[*first];
            *su = su.max(d);
            if let Some(f) = field.as_deref_mut() {
                f.push(d);
            }
        }
        if row_max > max {
            max = row_max;
            at = (j, row_at);
        }
        let sv = &mut span_v[surface.knots_v.span(v)];
        *sv = sv.max(row_max);
    }
    let n = samples.points.data().len() as f64;
    Measured {
        deviation: Deviation {
            max,
            mean: sum / n,
            at,
        },
        span_u,
        span_v,
    }
}

/// Largest and mean distance from `samples` to `surface`.
pub fn deviation(surface: &BSplineSurface, samples: &Samples) -> Deviation {
    measure(surface, samples, None).deviation
}

/// The distance at every sample (the deviation map), shaped like the samples.
pub fn deviation_field(surface: &BSplineSurface, samples: &Samples) -> Grid<f64> {
    let mut f = Vec::with_capacity(samples.points.data().len());
    measure(surface, samples, Some(&mut f));
    Grid::new(samples.points.rows(), samples.points.cols(), f).expect("one per sample")
}
