//! The faces of an IGES file: the directory entries that make one, and
//! each face read from its base surface and its boundaries.

use super::{Base, File, Source};
use crate::error::ReferenceError;
use crate::geom;
use crate::{FaceData, SurfaceKind};

impl File<'_> {
    pub(super) fn faces(&self) -> Result<Vec<FaceData>, ReferenceError> {
        let mut sources: Vec<(usize, Source)> = Vec::new();
        let mut is_base = vec![false; self.des.len()];
        for k in 0..self.des.len() {
            let src = match self.des[k].etype {
                144 => {
                    let p = self.params(k)?;
                    let surf = self.need_ptr(&p, 1, "surface")?;
                    let n1 = p.int(2, "outer boundary flag N1")?;
                    let n2 = p.int(3, "number of inner boundaries N2")?;
                    let outer = if n1 != 0 {
                        self.ptr(&p, 4, "outer boundary")?
                    } else {
                        None
                    };
                    Source::Trimmed {
                        surf,
                        n1,
                        n2,
                        outer,
                    }
                }
                143 => {
                    let p = self.params(k)?;
                    let surf = self.need_ptr(&p, 2, "surface")?;
                    let n = p.count(3, "number of boundaries", 0, p.len())?;
                    let mut bounds = Vec::with_capacity(n);
                    for i in 0..n {
                        bounds.push(self.need_ptr(&p, 4 + i, "boundary")?);
                    }
                    Source::Bounded { surf, bounds }
                }
                510 => {
                    let p = self.params(k)?;
                    let surf = self.need_ptr(&p, 1, "surface")?;
                    let n = p.count(2, "number of loops", 0, p.len())?;
                    let mut loops = Vec::with_capacity(n);
                    for i in 0..n {
                        loops.push(self.need_ptr(&p, 4 + i, "loop")?);
                    }
                    Source::Face { surf, loops }
                }
                _ => continue,
            };
            match &src {
                Source::Trimmed { surf, .. }
                | Source::Bounded { surf, .. }
                | Source::Face { surf, .. } => {
                    is_base[*surf] = true;
                }
                Source::Lone => {}
            }
            sources.push((k, src));
        }
        for (k, (de, base)) in self.des.iter().zip(&is_base).enumerate() {
            if de.etype == 128 && !base {
                sources.push((k, Source::Lone));
            }
        }
        sources.sort_by_key(|s| s.0);
        if sources.is_empty() {
            return Err(ReferenceError::whole(
                self.path,
                "the file has no face: no rational B-spline surface (entity 128), trimmed surface (144), bounded surface (143) or face (510); export the reference as surfaces, not as curves, points or a mesh",
            ));
        }
        let mut faces = Vec::with_capacity(sources.len());
        for (k, src) in sources {
            faces.push(self.face(k, src)?);
        }
        Ok(faces)
    }

    fn face(&self, k: usize, src: Source) -> Result<FaceData, ReferenceError> {
        let s = match &src {
            Source::Trimmed { surf, .. }
            | Source::Bounded { surf, .. }
            | Source::Face { surf, .. } => *surf,
            Source::Lone => k,
        };
        let sde = &self.des[s];
        let entity = Self::who(sde);
        let line = self
            .p
            .get((sde.pstart.max(1) - 1) as usize)
            .map_or(sde.line, |l| l.number);
        let base = match sde.etype {
            128 => self.surface(s)?,
            108 | 190 => Base::Plane,
            _ => Base::Other,
        };
        let (surface, closed, sub) = match base {
            Base::BSpline(surface, closed, sub) => (surface, closed, sub),
            other => {
                let kind = if matches!(other, Base::Plane) {
                    SurfaceKind::Plane
                } else {
                    SurfaceKind::Other
                };
                return Ok(FaceData {
                    kind,
                    entity,
                    line,
                    surface: None,
                    mesh: None,
                    not_grid: None,
                    closed: [false; 2],
                    trimmed: true,
                    area: 0.0,
                    bbox: None,
                });
            }
        };
        let (area, bbox) = geom::area_and_bbox(&surface);
        let ([u0, u1], [v0, v1]) = surface.domain();
        let dom = [[u0, v0], [u1, v1]];
        let untrimmed = !sub
            && match &src {
                Source::Lone => true,
                Source::Trimmed { n1, n2, outer, .. } => {
                    *n2 == 0
                        && (*n1 == 0
                            || match outer {
                                Some(o) => self.outer_on_sides(*o, dom)?,
                                None => false,
                            })
                }
                Source::Bounded { bounds, .. } => match bounds.as_slice() {
                    [b] => self.boundary_on_sides(*b, dom)?,
                    _ => false,
                },
                Source::Face { loops, .. } => match loops.as_slice() {
                    [l] => self.loop_on_corners(*l, &surface, bbox)?,
                    _ => false,
                },
            };
        let kind = if surface.is_rational() {
            SurfaceKind::Rational
        } else {
            SurfaceKind::BSpline
        };
        Ok(FaceData {
            kind,
            entity,
            line,
            surface: Some(surface),
            mesh: None,
            not_grid: None,
            closed,
            trimmed: !untrimmed,
            area,
            bbox: Some(bbox),
        })
    }
}
