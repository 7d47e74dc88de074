//! A G2 run's merged levels, kept on its first patch between edits
//! (docs/math.md §11.1, Eqs. 68–70), so that an edit re-blends only the
//! merged window it reaches. [`build_joined`](super::build::build_joined)
//! moves the state and the run's stacks out, brings them up to date with
//! [`run`] and puts them back: the kernel's [`G2State`] re-blends the merged
//! net inside the edit's window and cuts again, in place, only the rows that
//! moved, bit for bit what [`streamline_kernel::joins::merged::g2_run`]
//! builds whole.

use bevy::prelude::*;
use streamline_kernel::joins::PatchParts;
use streamline_kernel::joins::RowSpan;
use streamline_kernel::joins::g2_state::G2State;
use streamline_kernel::joins::{JoinError, Stack};

/// The merged levels and points of the G2 run this patch heads (`None`
/// while they are moved out, or after a failed build).
#[derive(Component, Debug, Default)]
pub struct G2RunState(pub Option<G2State>);

/// What a run's build did: each member's stack, whether it changed, the
/// rows of its finest points placed again (`None` with a change: all of
/// them) and the first column placed again in those rows (0: all of them),
/// and per depth the rows of every member's level whose tangents or
/// parameters may have changed (`None`: a whole build, every row).
pub(crate) struct RunBuilt {
    pub stacks: Vec<Stack>,
    pub changed: Vec<bool>,
    pub rows: Vec<Option<RowSpan>>,
    pub cols: Vec<usize>,
    pub levels: Option<Vec<Option<RowSpan>>>,
    /// The merged tangents re-blended (a whole build: every one of levels
    /// `1 ..= d`).
    pub reblended: usize,
}

/// The run of `designs` (each one's seam column the previous one's last,
/// with its details) at
/// `depth`: updated in place from `state` and the members' stacks as they
/// were (`old`, all of them, or `None`), or built whole into `state`. On an
/// error `state` is dropped, so the next build is whole.
pub(crate) fn run(
    state: &mut Option<G2State>,
    designs: &[PatchParts],
    depth: u32,
    old: Option<Vec<Stack>>,
) -> Result<RunBuilt, JoinError> {
    if let (Some(st), Some(mut stacks)) = (state.as_mut(), old) {
        return match st.update_parts(designs, depth, &mut stacks) {
            Ok(u) => Ok(RunBuilt {
                stacks,
                changed: u.changed,
                rows: u.rows,
                cols: u.cols,
                levels: (!u.whole).then_some(u.levels),
                reblended: u.reblended,
            }),
            Err(e) => {
                *state = None;
                Err(e)
            }
        };
    }
    match G2State::build_parts(designs, depth) {
        Ok((st, stacks)) => {
            let reblended = st.whole_count();
            *state = Some(st);
            let n = designs.len();
            Ok(RunBuilt {
                stacks,
                changed: vec![true; n],
                rows: vec![None; n],
                cols: vec![0; n],
                levels: None,
                reblended,
            })
        }
        Err(e) => {
            *state = None;
            Err(e)
        }
    }
}
