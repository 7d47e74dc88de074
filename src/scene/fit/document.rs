//! The patches of a document as B-spline faces (docs/math.md §10, §11): one
//! shell whose seams are shared ([`streamline_kernel::nurbs::fit_shell`]; STEP,
//! and IGES as separate faces) or each patch alone (a design of one patch:
//! [`super::surface`]).
//! Which sampling reaches the tolerance is the exporter's business, not the
//! designer's: every patch is sampled at one depth (so a seam's points stay
//! one set of points and its edge stays shared), starting from the one
//! asked for, and when a face needs more control points than its grid has
//! points, or cannot meet the tolerance with its seams held, the whole
//! document is sampled one depth deeper, up to [`max_fit_depth`]. Only when
//! even the deepest grid is not enough is the fit refused
//! ([`FitError::TooFewPointsAtDeepest`], whose message says to loosen the
//! tolerance). A patch whose start moves between depths, on an earlier
//! patch's edge of an approximating scheme, is measured from where it
//! starts ([`PatchGrid::hold_start`], docs/math.md §11.5, "A start that
//! moves"), and at the points it was fitted to as well.

use crate::scene::design::document::Document;
use crate::scene::design::document_build::{BuildError, BuiltDocument};
use std::borrow::Cow;
use std::fmt;
use std::time::Instant;
use streamline_kernel::SurfaceScheme;
use streamline_kernel::joins::{Continuity, Edge};
use streamline_kernel::nurbs::{
    Direction, FitError, FitOptions, FitReport, PatchGrid, Samples, SeamSpec, ShellError,
    ShellFace, ShellFit, ShellSeam, face_deviation, fit, fit_shell,
};

/// The most points the check grid of an export may have: the fit at depth
/// `d` is checked at every point of depth `d + 1` (docs/math.md §10), and
/// the deepest export depth is the last whose check grid stays within this
/// (a 2049 × 1025 grid; the car's depth 6, whose check grid of 1025 × 641
/// points builds and measures in about a second on one core).
pub const MAX_CHECK_POINTS: usize = 1 << 21;

/// The deepest depth a document is sampled at: the last at which every
/// patch's check grid (one depth finer) has at most [`MAX_CHECK_POINTS`]
/// points and passes the kernel's size limits.
pub fn max_fit_depth(doc: &Document) -> u32 {
    doc.patches
        .iter()
        .map(|p| {
            let d = &p.design;
            let (rows, cols) = (d.net().rows(), d.net().cols());
            let mut depth = 0;
            while let Ok((r, c)) = d.scheme().check_depth(rows, cols, depth + 2) {
                if r.saturating_mul(c + 1) > MAX_CHECK_POINTS {
                    break;
                }
                depth += 1;
            }
            depth
        })
        .min()
        .unwrap_or(0)
}

/// How the faces are fitted.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FaceFit {
    /// One shell, each seam's boundary curve fitted once and shared (STEP,
    /// IGES).
    Shell,
    /// Each patch alone, as a face of its own (a design of one patch).
    Alone,
}

/// The faces of a document.
#[derive(Debug, Clone)]
pub struct DocumentFit {
    /// The depth every patch was sampled at (checked one deeper).
    pub depth: u32,
    /// One per patch, in the document's order.
    pub faces: Vec<ShellFace>,
    /// One per seam (empty for [`FaceFit::Alone`]).
    pub seams: Vec<ShellSeam>,
    /// For [`FaceFit::Alone`], each face's fit report (one per patch);
    /// empty for a shell.
    pub reports: Vec<FitReport>,
    /// The points each face was fitted to and checked at.
    pub grids: Vec<PatchGrid>,
    /// Seconds the fits took (the builds not counted).
    pub seconds: f64,
}

/// Why a document was not fitted.
#[derive(Debug, Clone, PartialEq)]
pub enum DocumentFitError {
    /// The document could not be built deeper.
    Build(BuildError),
    /// A face or seam was refused.
    Shell(ShellError),
}

impl fmt::Display for DocumentFitError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            DocumentFitError::Build(e) => write!(f, "{e}"),
            DocumentFitError::Shell(e) => write!(f, "{e}"),
        }
    }
}

impl std::error::Error for DocumentFitError {}

/// `built` when it holds depth `depth`, else the document built to it.
pub fn built_to<'a>(
    doc: &Document,
    built: &'a BuiltDocument,
    depth: u32,
) -> Result<Cow<'a, BuiltDocument>, BuildError> {
    if built.depth >= depth && built.patches.len() == doc.patches.len() {
        Ok(Cow::Borrowed(built))
    } else {
        doc.build(depth).map(Cow::Owned)
    }
}

/// Whether a refusal may pass one depth deeper.
fn deeper_helps(e: &ShellError) -> bool {
    matches!(
        e,
        ShellError::Fit {
            error: FitError::TooFewPoints { .. },
            ..
        } | ShellError::OverTolerance { .. }
    )
}

/// The approximating scheme that moves where patch `i` starts between
/// depths (docs/math.md §11.5, "A start that moves"): its own or that of a
/// patch down its chain of starts. None for a patch on its own initial
/// curve, for a G2 chain's later patch (one net with the patch before it,
/// cut where Eq. 69 says) and where every such patch is on Kobbelt's
/// scheme, whose edges stay put.
fn moving_start(doc: &Document, i: usize) -> Option<SurfaceScheme> {
    let (_, join) = doc.parent(i)?;
    if join.edge == Edge::End && join.continuity == Continuity::G2 {
        return None;
    }
    let mut at = Some(i);
    while let Some(k) = at {
        let scheme = doc.patches[k].design.scheme();
        if !scheme.is_interpolatory() {
            return Some(scheme);
        }
        at = doc.parent(k).map(|(p, _)| p);
    }
    None
}

/// At the deepest depth, a grid too coarse says so with the depth, and for
/// a patch whose start moves between depths ([`moving_start`]) with the
/// scheme that moves it.
fn at_deepest(doc: &Document, e: ShellError, depth: u32) -> ShellError {
    match e {
        ShellError::Fit {
            patch,
            error:
                FitError::TooFewPoints {
                    direction,
                    points,
                    tolerance,
                    reached,
                },
        } => {
            let scheme = doc.index(&patch).and_then(|i| moving_start(doc, i));
            ShellError::Fit {
                patch,
                error: FitError::TooFewPointsAtDeepest {
                    direction,
                    points,
                    tolerance,
                    reached,
                    depth,
                    moving: scheme,
                },
            }
        }
        // a moved check grid left the data points over the tolerance
        ShellError::OverTolerance {
            patch,
            reached,
            tolerance,
        } => match doc.index(&patch).and_then(|i| moving_start(doc, i)) {
            Some(scheme) => ShellError::Fit {
                patch,
                error: FitError::TooFewPointsAtDeepest {
                    direction: Direction::U,
                    points: 0,
                    tolerance,
                    reached,
                    depth,
                    moving: Some(scheme),
                },
            },
            None => ShellError::OverTolerance {
                patch,
                reached,
                tolerance,
            },
        },
        e => e,
    }
}

/// The faces of the patches whose check grids were moved onto where they
/// start ([`PatchGrid::hold_start`]) measured at their data points too:
/// those are not among the points the fit measured, and what the move
/// leaves (docs/math.md §11.5, "A start that moves") can set them apart
/// from the check grid. A face over its tolerance there is refused as over
/// it, and the document is sampled one depth deeper.
fn data_within(grids: &[PatchGrid], shell: &ShellFit, held: &[bool]) -> Result<(), ShellError> {
    for (i, f) in shell.faces.iter().enumerate().filter(|&(i, _)| held[i]) {
        let data = Samples {
            points: grids[i].data.points.clone(),
            u: grids[i].data.u.clone(),
            v: f.v.0.clone(),
        };
        let reached = face_deviation(shell, i, &data).max;
        if reached > f.tolerance {
            return Err(ShellError::OverTolerance {
                patch: f.name.clone(),
                reached,
                tolerance: f.tolerance,
            });
        }
    }
    Ok(())
}

/// Fits every patch of `doc` (built as `built`, built again deeper when
/// needed) sampled at `depth` or as much deeper as the tolerance needs
/// (module docs), as one shell or each alone.
pub fn fit_document(
    doc: &Document,
    built: &BuiltDocument,
    depth: u32,
    opts: &FitOptions,
    how: FaceFit,
) -> Result<DocumentFit, DocumentFitError> {
    let deepest = max_fit_depth(doc).max(depth);
    let mut depth = depth;
    let mut seconds = 0.0;
    loop {
        let b = built_to(doc, built, depth + 1).map_err(DocumentFitError::Build)?;
        let held: Vec<bool> = (0..doc.patches.len())
            .map(|i| moving_start(doc, i).is_some())
            .collect();
        let grids = b
            .patches
            .iter()
            .zip(&doc.patches)
            .enumerate()
            .map(|(i, (s, p))| {
                let mut grid = PatchGrid::from_stack(&p.name, s, depth, p.design.scheme().curve())
                    .map_err(|error| {
                        DocumentFitError::Shell(ShellError::Fit {
                            patch: p.name.clone(),
                            error,
                        })
                    })?;
                // measured from where it starts at this depth (§11.5)
                if held[i] {
                    grid.hold_start();
                }
                Ok(grid)
            })
            .collect::<Result<Vec<_>, _>>()?;
        let start = Instant::now();
        let result = match how {
            FaceFit::Shell => {
                let specs: Vec<SeamSpec> = b
                    .seams
                    .iter()
                    .map(|s| SeamSpec {
                        a: s.a,
                        b: s.b,
                        join: s.join,
                    })
                    .collect();
                fit_shell(&grids, &specs, opts).and_then(|f| {
                    data_within(&grids, &f, &held)?;
                    Ok((f.faces, f.seams, Vec::new()))
                })
            }
            FaceFit::Alone => fit_each(&grids, opts).and_then(|(faces, r)| {
                let shell = ShellFit {
                    faces,
                    seams: Vec::new(),
                };
                data_within(&grids, &shell, &held)?;
                Ok((shell.faces, Vec::new(), r))
            }),
        };
        seconds += start.elapsed().as_secs_f64();
        match result {
            Ok((faces, seams, reports)) => {
                return Ok(DocumentFit {
                    depth,
                    faces,
                    seams,
                    reports,
                    grids,
                    seconds,
                });
            }
            Err(e) if deeper_helps(&e) && depth < deepest => depth += 1,
            Err(e) => return Err(DocumentFitError::Shell(at_deepest(doc, e, depth))),
        }
    }
}

/// Each patch fitted alone, as a face of its own, with its fit report.
fn fit_each(
    grids: &[PatchGrid],
    opts: &FitOptions,
) -> Result<(Vec<ShellFace>, Vec<FitReport>), ShellError> {
    let mut faces = Vec::with_capacity(grids.len());
    let mut reports = Vec::with_capacity(grids.len());
    for p in grids {
        let f = fit(&p.data, &p.check, opts).map_err(|error| ShellError::Fit {
            patch: p.name.clone(),
            error,
        })?;
        faces.push(ShellFace {
            name: p.name.clone(),
            surface: f.surface,
            deviation: f.report.deviation,
            tolerance: f.report.tolerance,
            v: (p.data.v.clone(), p.check.v.clone()),
        });
        reports.push(f.report);
    }
    Ok((faces, reports))
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::Path;

    /// A refusal at the deepest depth names the moving edge only for a
    /// patch on an earlier patch's edge where either is on an approximating
    /// scheme (docs/math.md §11.5): the wing (on the hood's edge) of
    /// hood-screen-wing turned
    /// Catmull–Clark, and the Kobbelt wing on a Catmull–Clark hood; not
    /// the root, the hood; not the wing when both are Kobbelt.
    #[test]
    fn only_an_approximating_patch_on_an_edge_is_said_to_move() {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/hood-screen-wing.ron");
        let doc = crate::scene::design::document_io::load(&path).unwrap();
        let turned = |scheme| {
            let mut d = doc.clone();
            for p in &mut d.patches {
                p.design.set_scheme(scheme).unwrap();
            }
            d
        };
        let refused = |d: &Document, patch: &str| {
            let e = ShellError::Fit {
                patch: patch.into(),
                error: FitError::TooFewPoints {
                    direction: Direction::U,
                    points: 9,
                    tolerance: 1e-4,
                    reached: 1.234e-3,
                },
            };
            at_deepest(d, e, 8).to_string()
        };
        let cc = turned(SurfaceScheme::CatmullClark);
        let wing = refused(&cc, "wing");
        assert!(
            wing.contains(
                "starts on the edge of an earlier patch, and on the Catmull–Clark scheme"
            ) && wing.contains("at least 1.3e-3"),
            "{wing}"
        );
        let hood = refused(&cc, "hood");
        assert!(hood.contains("needs more control points"), "{hood}");
        let kobbelt = refused(&doc, "wing");
        assert!(kobbelt.contains("needs more control points"), "{kobbelt}");
        // a Kobbelt wing on a Catmull–Clark hood: the hood's edge moves
        let mut under = doc.clone();
        let hood = under.index("hood").unwrap();
        under.patches[hood]
            .design
            .set_scheme(SurfaceScheme::CatmullClark)
            .unwrap();
        let on_cc = refused(&under, "wing");
        assert!(on_cc.contains("on the Catmull–Clark scheme"), "{on_cc}");
    }
}
