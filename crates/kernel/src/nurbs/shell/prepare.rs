//! A shell's patches prepared for its faces (docs/math.md §11): every seam
//! checked, each patch's row parameters (a chain's are its first patch's,
//! §11.1; a side join's are `w`, §11.2), each patch's fit alone (the knots
//! its face starts from, §10) and the chain groups that share `v` knots.

use super::{PatchGrid, SeamSpec, ShellError, fit_error};
use crate::joins::{Continuity, Edge};
use crate::nurbs::error::FitError;
use crate::nurbs::fit::{FitOptions, Tolerance, check_options, fit};
use crate::nurbs::samples::Samples;
use crate::nurbs::seam_params::{check_params, side_params};
use crate::nurbs::surface::BSplineSurface;

/// The margin of the fits alone (whose knots a shell starts from) under
/// the tolerance: room for what holding a seam costs. A face that cannot
/// be fitted within it alone starts from its fit within the tolerance
/// itself, else from the fit of its own points (the margin is a head start,
/// not a requirement: a margin the grid cannot reach refused every depth,
/// docs/math.md §10); the shell's own rounds then hold the tolerance.
const ALONE_MARGIN: f64 = 0.7;

/// Row parameters of a patch: at its data and at its check grid.
type Rows = (Vec<f64>, Vec<f64>);

/// A seam's part of the earlier face's edge (`ShellSeam::range`).
type Range = (f64, f64);

/// The shell's patches as its faces are fitted from them: one entry per
/// patch, but `ranges` (one per seam spec).
pub(super) struct Prepared<'a> {
    /// The patches.
    pub(super) patches: &'a [PatchGrid],
    /// The seam specs.
    pub(super) seams: &'a [SeamSpec],
    /// The degrees and tolerance.
    pub(super) opts: &'a FitOptions,
    /// The incoming seam of every patch.
    pub(super) incoming: Vec<Option<usize>>,
    /// The row parameters (`ShellFace::v`).
    pub(super) v: Vec<Rows>,
    /// Each seam's part of the earlier face's edge (`ShellSeam::range`).
    pub(super) ranges: Vec<Range>,
    /// The points fitted, with the row parameters `v`.
    pub(super) data: Vec<Samples>,
    /// The points measured, with the row parameters `v`.
    pub(super) check: Vec<Samples>,
    /// The absolute tolerance.
    pub(super) tols: Vec<f64>,
    /// Why the patch's fit alone at its check grid was refused, where it
    /// was started from its own points instead.
    pub(super) too_few: Vec<Option<FitError>>,
    /// The fit alone whose knots the face starts from.
    pub(super) alone: Vec<BSplineSurface>,
    /// The first patch of the patch's chain group (itself for a root).
    pub(super) root: Vec<usize>,
}

impl<'a> Prepared<'a> {
    /// The patches and seams checked and prepared (module docs).
    pub(super) fn new(
        patches: &'a [PatchGrid],
        seams: &'a [SeamSpec],
        opts: &'a FitOptions,
    ) -> Result<Prepared<'a>, ShellError> {
        let n = patches.len();
        let incoming = incoming_seams(patches, seams)?;
        let (v, ranges) = row_params(patches, seams, &incoming)?;
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
            let (tol, short, surface) = fit_alone_first(&data[i], &check[i], opts)
                .map_err(|e| fit_error(&patches[i].name, e))?;
            // a face started from its own points that the shell's rounds cannot
            // bring within the tolerance is refused as its fit alone was
            too_few.push(short);
            tols.push(tol);
            alone.push(surface);
        }
        let root = chain_roots(seams, &incoming);
        Ok(Prepared {
            patches,
            seams,
            opts,
            incoming,
            v,
            ranges,
            data,
            check,
            tols,
            too_few,
            alone,
            root,
        })
    }
}

/// The incoming seam of every patch, each seam checked: `a < b`, a patch
/// starts on one edge, no G2 on a side edge, a chain's patches have the
/// same rows.
fn incoming_seams(
    patches: &[PatchGrid],
    seams: &[SeamSpec],
) -> Result<Vec<Option<usize>>, ShellError> {
    let n = patches.len();
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
    Ok(incoming)
}

/// Row parameters: a chain's are its first patch's, a side join's are `w`
/// (its start points placed on the parent's edge, docs/math.md §11.2);
/// also each seam's range (`(0, 1)` for a chain).
fn row_params(
    patches: &[PatchGrid],
    seams: &[SeamSpec],
    incoming: &[Option<usize>],
) -> Result<(Vec<Rows>, Vec<Range>), ShellError> {
    let mut v: Vec<Rows> = patches
        .iter()
        .map(|p| (p.data.v.clone(), p.check.v.clone()))
        .collect();
    let mut ranges = vec![(0.0, 1.0); seams.len()];
    for b in 0..patches.len() {
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
    Ok((v, ranges))
}

/// A patch's tolerance and its fit alone, the knots its face starts from:
/// within `ALONE_MARGIN` of the tolerance, else within the tolerance, at
/// its check grid, else the same at its own points. Returns the tolerance,
/// the refusal at the check grid where the fit was made at its own points,
/// and the surface.
fn fit_alone_first(
    data: &Samples,
    check: &Samples,
    opts: &FitOptions,
) -> Result<(f64, Option<FitError>, BSplineSurface), FitError> {
    let tol = check_options(opts, data)?;
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
        let against = if on_check { check } else { data };
        match fit(data, against, &within(m * tol)) {
            Ok(f) => {
                found = Some(f);
                break;
            }
            Err(e @ FitError::TooFewPoints { .. }) if n + 1 < ladder.len() => {
                if on_check {
                    short = Some(e);
                }
            }
            Err(e) => return Err(e),
        }
    }
    let f = found.expect("the ladder returns or finds one");
    Ok((tol, short, f.surface))
}

/// The first patch of every patch's chain group: chain groups share their
/// `v` knots; a side-joined root also needs the knots of the piece of its
/// parent's edge.
fn chain_roots(seams: &[SeamSpec], incoming: &[Option<usize>]) -> Vec<usize> {
    let n = incoming.len();
    let mut root: Vec<usize> = (0..n).collect();
    for b in 0..n {
        if let Some(k) = incoming[b]
            && seams[k].join.edge == Edge::End
        {
            root[b] = root[seams[k].a];
        }
    }
    root
}
