//! What the growth of the net (`docs/math.md §12`, "Growing the net")
//! carries from one net to the next: the nodes to build, the buffers and
//! caches reused, the best design, the insertions blocked, and the counts
//! that say when the growth stops short.

use super::best::Best;
use super::insert::Insert;
use super::plan::Plan;
use crate::fit::construct::{Nodes, Sampler, initial_nodes};
use crate::fit::measure::{Measure, RowCache};
use crate::levels::builder::Builder;

/// The growth's state between nets.
pub(super) struct Growth<'f, 'a> {
    /// The nodes of the net to build next.
    pub(super) nodes: Nodes,
    /// Reference samples kept across nets.
    pub(super) sampler: Sampler<'f, 'a>,
    /// Builds each net's mesh at the fit depth.
    pub(super) builder: Builder,
    /// The rows of the last net measured.
    pub(super) cache: RowCache,
    pub(super) best: Option<Best>,
    /// Insertions that made a net that could not be built, or changed no
    /// node.
    pub(super) blocked: Vec<Insert>,
    /// The last net's nodes, its measurement and the insertion made after
    /// it: where the growth goes back to from a net that cannot be built.
    pub(super) last: Option<(Nodes, Measure, Insert)>,
    /// Nets built and measured.
    pub(super) steps: usize,
    /// The step that last came closer (by 1 %) than the best before it.
    pub(super) best_step: usize,
    /// The last net's largest distance, either way.
    pub(super) prev_key: Option<f64>,
    /// Whether the last insertion went the other way in the worst cell.
    pub(super) flip_used: bool,
    /// Whether the last insertion was a row at the furthest point.
    pub(super) last_across: bool,
    /// The fraction done reported so far.
    pub(super) done: f64,
    /// The first net's largest distance, either way.
    pub(super) first_max: Option<f64>,
}

impl<'f, 'a> Growth<'f, 'a> {
    /// The growth from the smallest net of the plan's scheme and anchor.
    pub(super) fn new(plan: &Plan<'f, 'a>) -> Self {
        Growth {
            nodes: initial_nodes(plan.opts.scheme, plan.opts.anchor),
            sampler: Sampler::new(plan.f, plan.anchor),
            builder: Builder::new(),
            cache: RowCache::default(),
            best: None,
            blocked: Vec::new(),
            last: None,
            steps: 0,
            best_step: 0,
            prev_key: None,
            flip_used: false,
            last_across: false,
            done: 0.0,
            first_max: None,
        }
    }
}

/// How a growth round ended.
pub(super) enum Round {
    /// The nodes of the next net are set.
    Grow,
    /// The growth ends: within the tolerance (`None`), or short of it and
    /// why.
    Stop(Option<String>),
}
