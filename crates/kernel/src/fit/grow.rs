//! The fit of a reference (`docs/math.md §12`, "Growing the net"): from the
//! smallest net, one column or one row at a time where the design is
//! furthest from the reference, until the design's mesh at the fit depth is
//! within the tolerance both ways, or the net reaches its cap.
//!
//! **Measuring** (eq. 12.6): every point of the mesh at the fit depth is
//! expected where its row's `t` and its arc length say (the fraction of the
//! row's length); Gauss–Newton from there finds the closest point of the
//! reference. Both ways (eq. 12.7): the reference sampled at the same places
//! and at the cells' centres (twice the mesh's points), each to the mesh's
//! triangles around where it is expected.
//!
//! **Where to grow**: the position error a row gathers is the integral of
//! its tangent error, so the fit localises by the tangent error instead:
//! each level tangent's angle to the reference's tangent at its arc length,
//! times its interval `ds`, summed over a cell of the node grid (one
//! interval between node rows × one between node columns). In the worst
//! cell, if the error on the node rows bounding it is at least half of the
//! error between them, the rows are already as good as the columns let them
//! be: a column is inserted at the middle of the cell's column interval;
//! otherwise a row in the middle of its row interval. After an insertion a
//! neighbouring interval more than twice as long is halved too, so that the
//! positions stay graded (the 4-point rule keeps them increasing).
//!
//! * `checks`: the options and the reference checked before the fit starts;
//! * `insert`: which column or row to insert, and the graded insertion.

mod checks;
mod insert;

use self::checks::{check_options, check_reference};
use self::insert::{Insert, apply, choose, chord_insert};
use super::closest::Distances;
use super::construct::{
    BuildFailure, Nodes, Sampler, Setup, anchor_fraction, build_design, initial_nodes, phantoms,
};
use super::error::ReferenceFitError;
use super::initial::fit_initial;
use super::measure::{Measure, RowCache, breaks, from_reference, interval, measure};
use super::options::{Along, ReferenceFitOptions, Tolerance};
use super::reference::{AnchorCurve, Frame, ReferenceSurface, Swapped};
use crate::error::KernelError;
use crate::levels::builder::Builder;
use crate::levels::design::Design;
use crate::levels::surface::SurfaceScheme;
use std::time::Instant;

/// A design fitted to a reference, and how well it fits.
#[derive(Debug, Clone)]
pub struct ReferenceFit {
    /// The design (the best reached when not within the tolerance).
    pub design: Design,
    /// Its control net, `(rows, columns)`.
    pub net: (usize, usize),
    /// The fit depth it was measured at.
    pub depth: u32,
    /// The absolute tolerance used.
    pub tolerance: f64,
    /// From every point of the design's mesh at the fit depth to the reference.
    pub to_reference: Distances,
    /// From the reference (twice as densely sampled as the mesh) to the mesh.
    pub from_reference: Distances,
    /// Whether both are within the tolerance.
    pub within: bool,
    /// Why not, when not.
    pub why: Option<String>,
    /// The initial curve's largest distance to the reference's anchor curve.
    pub initial_deviation: f64,
    /// Its control tangents.
    pub initial_tangents: usize,
    /// Nets built and measured.
    pub steps: usize,
    /// Wall-clock seconds the fit took.
    pub seconds: f64,
}

/// The best design met so far.
struct Best {
    design: Design,
    nodes: Nodes,
    key: f64,
    to: Distances,
    from: Option<Distances>,
    /// Whether `to` was measured at every point.
    full: bool,
    /// Its furthest measured point (`Measure::worst`).
    worst: (f64, f64, f64, f64),
}

/// Meshes with more points than this are measured at every other row and
/// column while the net grows (every point once within the tolerance).
const STRIDE_FROM: usize = 40_000;

/// The fit stops when this many nets in a row come no closer (by 1 %) than
/// the best one.
const STALL_NETS: usize = 24;

/// With one direction at its cap, the fit stops when this many nets in a
/// row come no closer (by 1 %) than the best one.
const FULL_STALL_NETS: usize = 4;

/// [`fit_reference_with`] without a progress hook.
pub fn fit_reference(
    reference: &dyn ReferenceSurface,
    opts: &ReferenceFitOptions,
) -> Result<ReferenceFit, ReferenceFitError> {
    fit_reference_with(reference, opts, &mut |_| true)
}

/// Fits a streamline design to `reference` (`docs/math.md §12`).
/// `progress` is called after every net measured with a rough fraction done
/// in `[0, 1]`; returning `false` cancels the fit
/// ([`ReferenceFitError::Cancelled`]). Ends after at most one net per
/// column and row the cap allows.
pub fn fit_reference_with(
    reference: &dyn ReferenceSurface,
    opts: &ReferenceFitOptions,
    progress: &mut dyn FnMut(f64) -> bool,
) -> Result<ReferenceFit, ReferenceFitError> {
    let start = Instant::now();
    check_options(opts)?;
    let swapped = Swapped(reference);
    let r: &dyn ReferenceSurface = match opts.along {
        Along::U => reference,
        Along::V => &swapped,
    };
    let f = Frame::new(r, opts.along == Along::V)?;
    let tol = match opts.tolerance {
        Tolerance::Relative(x) => {
            if !(x.is_finite() && x > 0.0) {
                return Err(ReferenceFitError::BadTolerance { value: x });
            }
            x * f.diag
        }
        Tolerance::Absolute(a) => a,
    };
    if !(tol.is_finite() && tol > 0.0) {
        return Err(ReferenceFitError::BadTolerance { value: tol });
    }
    if f.closed_along() {
        return Err(ReferenceFitError::Closed { along: f.along() });
    }
    check_reference(&f)?;
    let fraction = anchor_fraction(opts.scheme, opts.anchor);
    let anchor = AnchorCurve::new(&f, fraction)?;
    let initial = fit_initial(&f, &anchor, 0.25 * tol)?;
    let lt = anchor.length();
    let setup = Setup {
        scheme: opts.scheme,
        order: opts.order,
        depth: opts.depth,
        anchor_fraction: fraction,
        initial: &initial.curve,
        length: lt,
        angle_tolerance: 1e-3 * tol / lt.max(f.diag),
    };
    let ph = 2 * phantoms(opts.scheme);
    let (cap_rows, cap_cols) = (opts.max_net.0 - ph, opts.max_net.1 - ph);
    let stop = 1e-3 * tol;
    let mut sampler = Sampler::new(&f, &anchor);
    let mut nodes = initial_nodes(opts.scheme, opts.anchor);
    let mut builder = Builder::new();
    let mut cache = RowCache::default();
    let mut best: Option<Best> = None;
    let mut blocked: Vec<Insert> = Vec::new();
    let mut last: Option<(Nodes, Measure, Insert)> = None;
    let mut steps = 0;
    let mut best_step = 0;
    let mut prev_key: Option<f64> = None;
    let mut flip_used = false;
    let mut last_across = false;
    let mut done = 0.0f64;
    let mut first_max = None;
    let why: Option<String>;
    loop {
        // build and measure the current nodes; on a net that cannot be
        // built, go back to the last one and block that insertion
        let built = match build_design(&mut sampler, &nodes, &setup) {
            Ok(d) => builder.build(&d, opts.depth).map(|_| d).map_err(Some),
            Err(BuildFailure::Error(e)) => return Err(e),
            Err(_) => Err(None),
        };
        let design = match built {
            Ok(d) => d,
            Err(e) => {
                let size = matches!(
                    e,
                    Some(KernelError::DepthTooLarge { .. } | KernelError::TooManyTangents { .. })
                );
                let uneven = matches!(e, None | Some(KernelError::ParamsNotIncreasing { .. }));
                match last.take() {
                    Some(_) if size => {
                        why = Some(format!(
                            "a net of {} × {} control tangents would pass the kernel's size cap at depth {}; loosen the tolerance or fit at a lower depth",
                            nodes.rows.len() + ph,
                            nodes.cols.len() + ph,
                            opts.depth
                        ));
                        break;
                    }
                    Some((prev, m, ins)) if uneven => {
                        // back to the last net; that insertion is blocked
                        blocked.push(ins);
                        nodes = prev;
                        let next = choose(
                            &m,
                            &blocked,
                            nodes.cols.len() >= cap_cols,
                            nodes.rows.len() >= cap_rows,
                            false,
                        );
                        let Some(ins) = next else {
                            why = Some(
                                "no row or column can be inserted any more without making the parameters uneven; loosen the tolerance"
                                    .to_string(),
                            );
                            break;
                        };
                        let before = nodes.clone();
                        apply(&mut nodes, ins, cap_rows, cap_cols);
                        last = Some((before, m, ins));
                        continue;
                    }
                    _ => {
                        return Err(match e {
                            Some(e) => e.into(),
                            None => ReferenceFitError::BadOption {
                                what: "scheme",
                                value: opts.scheme.name().to_string(),
                                accepted: "a scheme whose smallest net can be built at this depth",
                            },
                        });
                    }
                }
            }
        };
        steps += 1;
        let Some(level) = builder.level() else {
            return Err(ReferenceFitError::NonFinite { what: "mesh" });
        };
        let points = &builder.mesh().positions;
        // strided while far, every point once close
        let (rows_d, cols_d) = (level.tangents.rows(), level.tangents.cols());
        let mut stride = if rows_d * cols_d > STRIDE_FROM { 2 } else { 1 };
        let mut m = measure(
            &f,
            &anchor,
            &nodes,
            lt,
            level,
            points,
            (stride, stride),
            stop,
            fraction,
            &mut cache,
        )?;
        let mut to = Distances::of(&m.dist);
        if to.max <= tol && stride > 1 {
            // every point now (the strided rows lend theirs), the cells
            // scored as they were
            stride = 1;
            m = measure(
                &f,
                &anchor,
                &nodes,
                lt,
                level,
                points,
                (1, 2),
                stop,
                fraction,
                &mut cache,
            )?;
            to = Distances::of(&m.dist);
        }
        let mut from = None;
        let mut chord = None;
        if to.max <= tol {
            let (d, at) = from_reference(&f, &anchor, level, points, &m.tables)?;
            from = Some(Distances::of(&d));
            chord = Some(chord_insert(&nodes, lt, level, points, at));
        }
        let key = from.map_or(to.max, |d| d.max.max(to.max));
        // with an approximating scheme (whose node rows are not mesh rows,
        // so that the scores tell the directions apart less well), an
        // insertion that brought the design no closer sends the next one
        // the other way in the worst cell
        let no_gain = prev_key.is_some_and(|p| key > 0.99 * p);
        let flip = ph > 0 && no_gain && !flip_used;
        flip_used = flip;
        prev_key = Some(key);
        if best.as_ref().is_none_or(|b| key < 0.99 * b.key) {
            best_step = steps;
        }
        if best.as_ref().is_none_or(|b| key < b.key) {
            best = Some(Best {
                design: design.clone(),
                nodes: nodes.clone(),
                key,
                to,
                from,
                full: stride == 1,
                worst: m.worst,
            });
        }
        if from.is_some_and(|d| d.max <= tol) {
            why = None;
            break;
        }
        let fm = *first_max.get_or_insert(key);
        if fm > tol && key > 0.0 {
            let p = 1.0 - ((key / tol).ln() / (fm / tol).ln()).clamp(0.0, 1.0);
            done = done.max(0.95 * p);
        }
        if !progress(done) {
            return Err(ReferenceFitError::Cancelled);
        }
        let (col_full, row_full) = (nodes.cols.len() >= cap_cols, nodes.rows.len() >= cap_rows);
        // with one direction at its cap, only the other can grow: a few
        // nets that bring the design no closer say that it cannot
        let (psi_b, d_b, e_b, x_b) = best.as_ref().map_or(m.worst, |b| b.worst);
        let b = best.as_ref().map_or(key, |b| b.key);
        let other = if f.along() == 'u' { 'v' } else { 'u' };
        if (col_full || row_full) && steps - best_step >= FULL_STALL_NETS {
            why = Some(if col_full {
                format!(
                    "the columns reached their cap of {} control tangents and {FULL_STALL_NETS} more nets brought the design no closer than {b:.3e} (over the tolerance {tol:.3e}): the error lies along the rows (furthest at {:.0} % of their length), where the face turns faster than {} columns can follow; run the streamlines along {other}, loosen the tolerance or split the face",
                    opts.max_net.1,
                    100.0 * x_b,
                    opts.max_net.1,
                )
            } else {
                format!(
                    "the rows reached their cap of {} control tangents and {FULL_STALL_NETS} more nets brought the design no closer than {b:.3e} (over the tolerance {tol:.3e}): the error lies across the rows (furthest at {:.0} % of the initial curve), where the face changes faster than {} rows can follow; run the streamlines along {other}, loosen the tolerance or split the face",
                    opts.max_net.0,
                    100.0 * psi_b,
                    opts.max_net.0,
                )
            });
            break;
        }
        // an approximating scheme whose tangents are the face's but whose
        // rows stay off: more nets do not help
        if ph > 0 && steps - best_step >= FULL_STALL_NETS && d_b > tol && e_b < 0.5 * d_b {
            why = Some(format!(
                "{} approximates: {FULL_STALL_NETS} more nets brought the design no closer than {b:.3e} (over the tolerance {tol:.3e}); its tangents are the face's (they explain {e_b:.1e} of it) but its rows, blended from their neighbours, do not lie where the face's do (furthest at {:.0} % of the initial curve and {:.0} % of the rows' length); fit with the interpolating scheme (--scheme kobbelt), loosen the tolerance or split the face",
                opts.scheme.name(),
                100.0 * psi_b,
                100.0 * x_b,
            ));
            break;
        }
        if steps - best_step >= STALL_NETS {
            why = Some(format!(
                "the deviation stopped falling: {STALL_NETS} nets in a row came no closer than {:.3e} (over the tolerance {:.3e}); the face may have a crease or a degenerate edge: loosen the tolerance or split the face",
                best.as_ref().map_or(key, |b| b.key),
                tol
            ));
            break;
        }
        // a point much further than its row's tangent error explains is
        // off because its row is (its start, its length: what is blended
        // across the rows): a row there
        let (psi_w, d_w, e_w, _) = m.worst;
        // (not again right after such a row brought the design no closer;
        // with Doo–Sabin too, whose limit rows take the reference's lengths,
        // not with Catmull–Clark, whose distance along the rows that the
        // tangents do not explain is its columns' doing: a cylinder, whose
        // rows are all alike, needs columns)
        let rows_mend = !matches!(opts.scheme, SurfaceScheme::CatmullClark);
        let across = (rows_mend && chord.is_none() && d_w > tol && e_w < 0.5 * d_w)
            .then(|| Insert::Row(interval(&breaks(&nodes.rows), psi_w)))
            .filter(|_| !(no_gain && last_across));
        last_across = across.is_some();
        let next = match chord.or(across) {
            Some(ins @ Insert::Row(_)) if !row_full && !blocked.contains(&ins) => Some(ins),
            Some(ins @ Insert::Column(_)) if !col_full && !blocked.contains(&ins) => Some(ins),
            _ => choose(&m, &blocked, col_full, row_full, flip),
        };
        let Some(ins) = next else {
            why = Some(format!(
                "the net reached its cap of {} × {} control tangents with the design at best {:.3e} from the reference, over the tolerance {:.3e}; raise the cap, loosen the tolerance or split the face",
                opts.max_net.0,
                opts.max_net.1,
                best.as_ref().map_or(key, |b| b.key),
                tol
            ));
            break;
        };
        let before = nodes.clone();
        apply(&mut nodes, ins, cap_rows, cap_cols);
        if nodes == before {
            blocked.push(ins);
        }
        last = Some((before, m, ins));
    }
    let Some(mut b) = best else {
        return Err(ReferenceFitError::NonFinite { what: "design" });
    };
    if b.from.is_none() || !b.full {
        builder.build(&b.design, opts.depth)?;
        if let Some(level) = builder.level() {
            let points = &builder.mesh().positions;
            let m = measure(
                &f,
                &anchor,
                &b.nodes,
                lt,
                level,
                points,
                (1, 2),
                stop,
                fraction,
                &mut cache,
            )?;
            b.to = Distances::of(&m.dist);
            b.from = Some(Distances::of(
                &from_reference(&f, &anchor, level, points, &m.tables)?.0,
            ));
        }
    }
    let from = b.from.unwrap_or_default();
    let within = b.to.max <= tol && from.max <= tol;
    let why = if within {
        None
    } else {
        why.or_else(|| {
            Some(format!(
                "the design came within {:.3e} of the reference, over the tolerance {:.3e}",
                b.to.max.max(from.max),
                tol
            ))
        })
    };
    let _ = progress(1.0);
    Ok(ReferenceFit {
        net: (b.design.net().rows(), b.design.net().cols()),
        design: b.design,
        depth: opts.depth,
        tolerance: tol,
        to_reference: b.to,
        from_reference: from,
        within,
        why,
        initial_deviation: initial.deviation,
        initial_tangents: initial.curve.qi().tangents().len(),
        steps,
        seconds: start.elapsed().as_secs_f64(),
    })
}
