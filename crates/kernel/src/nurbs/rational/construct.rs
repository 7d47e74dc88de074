//! Making a [`NurbsSurface`] (`docs/math.md §12`): from CAD data, every
//! inconsistency checked and named ([`NurbsError`]); from the non-rational
//! surface of the §10 export; and the same surface with `u` and `v`
//! exchanged or scaled about the origin.

use super::{MAX_DEGREE, NurbsError, NurbsSurface};
use crate::grid::Grid;
use crate::nurbs::surface::BSplineSurface;
use glam::DVec3;

fn check_knots(direction: char, degree: usize, knots: &[f64]) -> Result<(), NurbsError> {
    if degree == 0 || degree > MAX_DEGREE {
        return Err(NurbsError::BadDegree { direction, degree });
    }
    for (i, k) in knots.iter().enumerate() {
        if !k.is_finite() {
            let (row, col) = if direction == 'u' { (0, i) } else { (i, 0) };
            return Err(NurbsError::NonFinite {
                what: if direction == 'u' { "u knot" } else { "v knot" },
                row,
                col,
            });
        }
    }
    let mut run = 1;
    for i in 1..knots.len() {
        if knots[i] < knots[i - 1] {
            return Err(NurbsError::KnotsDecrease {
                direction,
                index: i,
            });
        }
        if knots[i] == knots[i - 1] {
            run += 1;
            if run > degree + 1 {
                return Err(NurbsError::KnotMultiplicity {
                    direction,
                    index: i,
                    multiplicity: run,
                    degree,
                });
            }
        } else {
            run = 1;
        }
    }
    Ok(())
}

impl NurbsSurface {
    /// A surface from CAD data. `knots_u`/`knots_v`: the full (expanded,
    /// with multiplicities) knot vectors; `poles`: rows index `v` (count =
    /// `knots_v.len() − degree_v − 1`), columns index `u` (count =
    /// `knots_u.len() − degree_u − 1`); `weights` the same shape when
    /// rational (all positive). Every inconsistency is a [`NurbsError`].
    pub fn new(
        degree_u: usize,
        degree_v: usize,
        knots_u: Vec<f64>,
        knots_v: Vec<f64>,
        poles: Grid<DVec3>,
        weights: Option<Grid<f64>>,
    ) -> Result<Self, NurbsError> {
        if poles.rows() == 0 || poles.cols() == 0 {
            return Err(NurbsError::Empty { what: "poles" });
        }
        check_knots('u', degree_u, &knots_u)?;
        check_knots('v', degree_v, &knots_v)?;
        for (direction, knots, degree, count) in [
            ('u', &knots_u, degree_u, poles.cols()),
            ('v', &knots_v, degree_v, poles.rows()),
        ] {
            if knots.len() < degree + 2 || knots.len() - degree - 1 != count || count < degree + 1 {
                return Err(NurbsError::PoleCountMismatch {
                    direction,
                    poles: count,
                    knots: knots.len(),
                    degree,
                });
            }
            if knots[degree] >= knots[count] {
                return Err(NurbsError::EmptyDomain { direction });
            }
        }
        for r in 0..poles.rows() {
            for c in 0..poles.cols() {
                if !poles.get(r, c).is_finite() {
                    return Err(NurbsError::NonFinite {
                        what: "pole",
                        row: r,
                        col: c,
                    });
                }
            }
        }
        if let Some(w) = &weights {
            if w.rows() != poles.rows() || w.cols() != poles.cols() {
                return Err(NurbsError::WeightShape {
                    rows: w.rows(),
                    cols: w.cols(),
                    pole_rows: poles.rows(),
                    pole_cols: poles.cols(),
                });
            }
            for r in 0..w.rows() {
                for c in 0..w.cols() {
                    let x = w.get(r, c);
                    if !x.is_finite() {
                        return Err(NurbsError::NonFinite {
                            what: "weight",
                            row: r,
                            col: c,
                        });
                    }
                    if x <= 0.0 {
                        return Err(NurbsError::NonPositiveWeight {
                            row: r,
                            col: c,
                            weight: x,
                        });
                    }
                }
            }
        }
        let hom = Self::homogeneous(&poles, weights.as_ref());
        Ok(NurbsSurface {
            degree_u,
            degree_v,
            knots_u,
            knots_v,
            poles,
            weights,
            hom,
        })
    }

    fn homogeneous(poles: &Grid<DVec3>, weights: Option<&Grid<f64>>) -> Vec<[f64; 4]> {
        poles
            .data()
            .iter()
            .enumerate()
            .map(|(i, p)| {
                let w = weights.map_or(1.0, |w| w.data()[i]);
                [p.x * w, p.y * w, p.z * w, w]
            })
            .collect()
    }

    /// The same surface with `u` and `v` exchanged: `swapped().point(v, u)
    /// == point(u, v)`.
    pub fn swapped(&self) -> NurbsSurface {
        let poles = self.poles.transpose();
        let weights = self.weights.as_ref().map(Grid::transpose);
        let hom = Self::homogeneous(&poles, weights.as_ref());
        NurbsSurface {
            degree_u: self.degree_v,
            degree_v: self.degree_u,
            knots_u: self.knots_v.clone(),
            knots_v: self.knots_u.clone(),
            poles,
            weights,
            hom,
        }
    }

    /// The surface scaled about the origin by `factor` (a unit conversion:
    /// 0.001 from millimetres to metres); weights and knots are unchanged.
    /// A factor that is not positive and finite leaves the surface as it is
    /// ([`Self::try_scaled`] says so as an error).
    pub fn scaled(&self, factor: f64) -> NurbsSurface {
        self.try_scaled(factor).unwrap_or_else(|_| self.clone())
    }

    /// [`Self::scaled`], refusing a factor that is not positive and finite
    /// (or that would overflow a pole).
    pub fn try_scaled(&self, factor: f64) -> Result<NurbsSurface, NurbsError> {
        if !(factor.is_finite() && factor > 0.0) {
            return Err(NurbsError::BadScale { factor });
        }
        let data: Vec<DVec3> = self.poles.data().iter().map(|p| *p * factor).collect();
        if data.iter().any(|p| !p.is_finite()) {
            return Err(NurbsError::BadScale { factor });
        }
        let poles = Grid::new(self.poles.rows(), self.poles.cols(), data)
            .map_err(|_| NurbsError::Empty { what: "poles" })?;
        let hom = Self::homogeneous(&poles, self.weights.as_ref());
        Ok(NurbsSurface {
            poles,
            hom,
            ..self.clone()
        })
    }

    /// The non-rational surface of the §10 export ([`BSplineSurface`], on
    /// `[0, 1]²`). Its fields are public, so it may be inconsistent: then
    /// this returns the bilinear patch through its corner poles (the origin
    /// when it has none); [`Self::try_from_bspline`] returns the error.
    pub fn from_bspline(s: &BSplineSurface) -> NurbsSurface {
        Self::try_from_bspline(s).unwrap_or_else(|_| {
            let g = &s.poles;
            let corner = |r: usize, c: usize| {
                if g.rows() > 0 && g.cols() > 0 {
                    let p = g.get(r.min(g.rows() - 1), c.min(g.cols() - 1));
                    if p.is_finite() {
                        return p;
                    }
                }
                DVec3::ZERO
            };
            let last_r = g.rows().saturating_sub(1);
            let last_c = g.cols().saturating_sub(1);
            let data = vec![
                corner(0, 0),
                corner(0, last_c),
                corner(last_r, 0),
                corner(last_r, last_c),
            ];
            let poles = Grid::new(2, 2, data).unwrap_or_else(|_| Grid::filled(2, 2, DVec3::ZERO));
            let hom = Self::homogeneous(&poles, None);
            NurbsSurface {
                degree_u: 1,
                degree_v: 1,
                knots_u: vec![0.0, 0.0, 1.0, 1.0],
                knots_v: vec![0.0, 0.0, 1.0, 1.0],
                poles,
                weights: None,
                hom,
            }
        })
    }

    /// [`Self::from_bspline`], returning the error of an inconsistent surface.
    pub fn try_from_bspline(s: &BSplineSurface) -> Result<NurbsSurface, NurbsError> {
        let (p, q) = s.degree();
        NurbsSurface::new(
            p,
            q,
            s.knots_u.knots().to_vec(),
            s.knots_v.knots().to_vec(),
            s.poles.clone(),
            None,
        )
    }
}
