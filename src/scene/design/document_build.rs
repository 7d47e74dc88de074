//! A document built in the kernel's terms (docs/math.md §11), without Bevy:
//! every patch's levels and streamline points at each depth up to `d`
//! through the kernel's joins — a patch on its own curve alone, a G2 chain
//! (from a patch on its own curve, through each G2 `End` join) as one merged
//! net cut at its seams ([`g2_run_parts`]), a G0/G1 chain on its patch's points
//! ([`chain`]), a side join on its patch's first or last streamline
//! ([`side`]) — and one [`SeamReport`] per join at depth `d`.
//!
//! Every patch is built with what it adds to its control net: its
//! multiresolution details, its fine tuning and its tangent interpolation
//! ([`PatchScene::effective_design`], [`PatchScene::parts`]). A G2 run is
//! one merged net of its members' control nets, subdivided with their
//! details; the document's checks ([`super::document_check`]) refuse fine
//! tuning and tangent interpolation on its members, so nothing is dropped.

use super::document::{Document, PatchScene};
use std::fmt;
use streamline_kernel::Design;
use streamline_kernel::joins::chain::chain;
use streamline_kernel::joins::merged::{g2_run_parts, merge_g2};
use streamline_kernel::joins::side::side;
use streamline_kernel::joins::{
    Continuity, Edge, Join, JoinError, PatchParts, SeamReport, Stack, seam_at,
};

/// The patches of a document built to one depth, and its seams.
#[derive(Debug, Clone)]
pub struct BuiltDocument {
    /// The depth built to.
    pub depth: u32,
    /// Each patch's levels and points at depths `0 ..= depth`, in the document's order.
    pub patches: Vec<Stack>,
    /// One per join, in the order of the patches that start on an edge.
    pub seams: Vec<Seam>,
}

/// A join and its seam report at the built depth.
#[derive(Debug, Clone)]
pub struct Seam {
    /// The patch started on (`A`).
    pub a: usize,
    /// The patch that starts on it (`B`).
    pub b: usize,
    /// The edge of `A` and the continuity.
    pub join: Join,
    /// Largest gap, normal angle and curvature deviation (docs/math.md §11.3).
    pub report: SeamReport,
}

/// Why a document cannot be built: the patch at fault and what to do.
#[derive(Debug, Clone, PartialEq)]
pub struct BuildError {
    /// The patch at fault.
    pub patch: usize,
    /// What is wrong, naming the patches, and what to do.
    pub message: String,
}

impl fmt::Display for BuildError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.message)
    }
}

impl std::error::Error for BuildError {}

/// A join's error as a message naming both patches (the kernel's messages
/// call them `A` and `B`).
fn join_error(doc: &Document, b: usize, e: &JoinError) -> BuildError {
    let p = &doc.patches[b];
    let message = match doc.parent(b) {
        Some((a, join)) => format!(
            "patch `{}` starts on `{}` (A = `{}`, B = `{}`, edge {}, {}): {e}",
            p.name,
            doc.patches[a].name,
            doc.patches[a].name,
            p.name,
            join.edge.name(),
            join.continuity.name()
        ),
        None => format!("patch `{}`: {e}", p.name),
    };
    BuildError { patch: b, message }
}

/// Whether `join` is a G2 chain (edge `End`, G2): one merged net (docs/math.md §11.1).
pub fn is_g2_chain(join: Join) -> bool {
    join.edge == Edge::End && join.continuity == Continuity::G2
}

/// The G2 run that starts at patch `first`: it, then the patch G2-chained
/// on its `End`, and so on (the checks allow at most one per patch).
pub fn g2_run_from(doc: &Document, first: usize) -> Vec<usize> {
    let mut run = vec![first];
    loop {
        let last = *run.last().expect("a run has a patch");
        let next = (last + 1..doc.patches.len()).find(|&k| {
            doc.parent(k)
                .is_some_and(|(a, j)| a == last && is_g2_chain(j))
        });
        match next {
            Some(k) => run.push(k),
            None => return run,
        }
    }
}

impl PatchScene {
    /// The design its levels are built from: its own, or with
    /// `interpolate_tangents` the net whose limit passes through its
    /// interior tangents (docs/math.md §7; border tangents, so a seam
    /// column, are kept).
    pub fn effective_design(&self) -> Design {
        super::model::effective_design(&self.design, self.interpolate_tangents)
    }

    /// `design` (its [`Self::effective_design`]) with this patch's details
    /// and fine tuning, as the joins build it.
    pub fn parts<'a>(&'a self, design: &'a Design) -> PatchParts<'a> {
        PatchParts::new(design, Some(&self.details), self.tuning.as_ref())
    }
}

/// The first patch of the G2 run patch `i` is in (`i` itself when it is in
/// none, or heads one).
pub fn g2_head(doc: &Document, mut i: usize) -> usize {
    while let Some((a, _)) = doc.parent(i).filter(|&(a, j)| a < i && is_g2_chain(j)) {
        i = a;
    }
    i
}

/// Every patch's [`Stack`] at depths `0 ..= depth`.
pub fn stacks(doc: &Document, depth: u32) -> Result<Vec<Stack>, BuildError> {
    let n = doc.patches.len();
    let effective: Vec<Design> = doc
        .patches
        .iter()
        .map(PatchScene::effective_design)
        .collect();
    let mut out: Vec<Option<Stack>> = vec![None; n];
    for i in 0..n {
        if out[i].is_some() {
            continue; // built with its G2 run
        }
        let p = &doc.patches[i];
        let Some((a, join)) = doc.parent(i) else {
            let run = g2_run_from(doc, i);
            if run.len() == 1 {
                out[i] = Some(
                    Stack::build_parts(p.parts(&effective[i]), depth)
                        .map_err(|e| join_error(doc, i, &JoinError::Kernel(e)))?,
                );
            } else {
                let parts: Vec<PatchParts> = run
                    .iter()
                    .map(|&k| doc.patches[k].parts(&effective[k]))
                    .collect();
                let built = g2_run_parts(&parts, depth).map_err(|e| blame_run(doc, &run, &e))?;
                for (k, s) in run.into_iter().zip(built) {
                    out[k] = Some(s);
                }
            }
            continue;
        };
        let Some(sa) = out.get(a).and_then(Option::as_ref).filter(|_| a < i) else {
            return Err(BuildError {
                patch: i,
                message: format!(
                    "patch `{}` starts on `{}`, which is not built before it; a patch starts on an earlier patch",
                    p.name, doc.patches[a].name
                ),
            });
        };
        let built = match (join.edge, join.continuity) {
            (Edge::End, Continuity::G2) => {
                return Err(BuildError {
                    patch: i,
                    message: format!(
                        "patch `{}` is G2-chained on `{}`, which does not start a G2 chain on its own curve; a G2 chain is one net from a patch with its own curve: join `{}` with G1",
                        p.name, doc.patches[a].name, p.name
                    ),
                });
            }
            (Edge::End, c) => chain(&effective[a], sa, p.parts(&effective[i]), c),
            (edge, c) => side(sa, p.parts(&effective[i]), edge, c),
        };
        out[i] = Some(built.map_err(|e| join_error(doc, i, &e))?);
    }
    Ok(out
        .into_iter()
        .map(|s| s.expect("every patch is built"))
        .collect())
}

/// The patch of a G2 run at fault: the first whose join to the previous
/// one is refused, else the run's last (the merged net's own build failed).
fn blame_run(doc: &Document, run: &[usize], e: &JoinError) -> BuildError {
    for w in run.windows(2) {
        let pair = [&doc.patches[w[0]].design, &doc.patches[w[1]].design];
        if let Err(pe) = merge_g2(&pair) {
            return join_error(doc, w[1], &pe);
        }
    }
    join_error(doc, *run.last().expect("a run has a patch"), e)
}

impl Document {
    /// Every patch built to `depth` through the kernel's joins, and every
    /// seam's report at `depth` (docs/math.md §11).
    pub fn build(&self, depth: u32) -> Result<BuiltDocument, BuildError> {
        let patches = stacks(self, depth)?;
        let mut seams = Vec::new();
        for b in 0..self.patches.len() {
            if let Some((a, join)) = self.parent(b) {
                let report = seam_at(&patches[a], &patches[b], join.edge, depth)
                    .map_err(|e| join_error(self, b, &e))?;
                seams.push(Seam { a, b, join, report });
            }
        }
        Ok(BuiltDocument {
            depth,
            patches,
            seams,
        })
    }
}
