//! A net built (`docs/math.md §12`, eq. 12.3 and "Growing the net"): the
//! design of the current nodes and its mesh at the fit depth. A net that
//! cannot be built sends the growth back to the last one, with that
//! insertion blocked and the next one the scores suggest made instead; a
//! net past the kernel's size cap ends the growth.

use super::insert::{apply, choose};
use super::plan::Plan;
use super::state::{Growth, Round};
use super::stops::{no_even_insertion, past_size_cap};
use crate::error::KernelError;
use crate::fit::construct::{BuildFailure, build_design};
use crate::fit::error::ReferenceFitError;
use crate::levels::design::Design;

/// Builds the design of the current nodes and its mesh (in the growth's
/// builder); on a net that cannot be built, how the round ends instead.
pub(super) fn build_net(
    plan: &Plan<'_, '_>,
    g: &mut Growth<'_, '_>,
) -> Result<Result<Design, Round>, ReferenceFitError> {
    let built = match build_design(&mut g.sampler, &g.nodes, &plan.setup) {
        Ok(d) => g
            .builder
            .build(&d, plan.opts.depth)
            .map(|_| d)
            .map_err(Some),
        Err(BuildFailure::Error(e)) => return Err(e),
        Err(_) => Err(None),
    };
    match built {
        Ok(d) => Ok(Ok(d)),
        Err(e) => go_back(plan, g, e).map(Err),
    }
}

/// After a net that could not be built (`e`: the kernel's refusal, or
/// `None` where the phantoms would not keep the positions increasing):
/// back to the last net with that insertion blocked and another made, or
/// the end of the growth (past the size cap, or no even insertion left);
/// any other refusal, and any of the smallest net, is the fit's.
fn go_back(
    plan: &Plan<'_, '_>,
    g: &mut Growth<'_, '_>,
    e: Option<KernelError>,
) -> Result<Round, ReferenceFitError> {
    let size = matches!(
        e,
        Some(KernelError::DepthTooLarge { .. } | KernelError::TooManyTangents { .. })
    );
    let uneven = matches!(e, None | Some(KernelError::ParamsNotIncreasing { .. }));
    match g.last.take() {
        Some(_) if size => Ok(Round::Stop(Some(past_size_cap(plan, &g.nodes)))),
        Some((prev, m, ins)) if uneven => {
            // back to the last net; that insertion is blocked
            g.blocked.push(ins);
            g.nodes = prev;
            let next = choose(
                &m,
                &g.blocked,
                g.nodes.cols.len() >= plan.cap_cols,
                g.nodes.rows.len() >= plan.cap_rows,
                false,
            );
            let Some(ins) = next else {
                return Ok(Round::Stop(Some(no_even_insertion())));
            };
            let before = g.nodes.clone();
            apply(&mut g.nodes, ins, plan.cap_rows, plan.cap_cols);
            g.last = Some((before, m, ins));
            Ok(Round::Grow)
        }
        _ => Err(match e {
            Some(e) => e.into(),
            None => ReferenceFitError::BadOption {
                what: "scheme",
                value: plan.opts.scheme.name().to_string(),
                accepted: "a scheme whose smallest net can be built at this depth",
            },
        }),
    }
}
