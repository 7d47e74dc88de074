//! A patch's levels kept between edits (docs/math.md §5, §11): every patch
//! but the first patch's own pipeline and a G2 run's members (whose merged
//! net is kept by [`super::g2`]) carries a [`KeptPatch`].
//! [`build_joined`](super::build::build_joined) moves the state and the
//! patch's stack out, brings them up to date with [`update`] and puts them
//! back: the kernel's [`PatchState`] re-blends the patch's levels inside
//! the edit's window, makes a join's fix again on every row, and places
//! again only the rows whose tangents, parameters or start moved, bit for
//! bit what the whole join builds (`crates/kernel/tests/patch_state_properties.rs`).

use bevy::prelude::*;
use streamline_kernel::joins::RowSpan;
use streamline_kernel::joins::patch_state::{PatchState, PatchUpdate, Start};
use streamline_kernel::joins::{JoinError, PatchParts, Stack};

/// The patch's kept levels (`None` while they are moved out, after a
/// failed build, or when another path built the patch last).
#[derive(Component, Debug, Default)]
pub struct KeptPatch(pub Option<PatchState>);

/// What the last build of a patch through its [`KeptPatch`] or its G2 run
/// did: the tangents it re-blended (a run's member: the run's merged
/// tangents), the rows of the display depth it placed again and whether it
/// was built whole. Tests, benches and the editor's Stats read it (the
/// first patch's pipeline reports the same in [`crate::ecs::Stats`]).
#[derive(Component, Debug, Clone, Default, PartialEq, Eq)]
pub struct PatchWork {
    /// Tangents re-blended over the levels `1 ..= d`.
    pub reblended: usize,
    /// The display depth's rows placed again (`None`: none).
    pub rows: Option<RowSpan>,
    /// Built whole.
    pub whole: bool,
}

impl PatchWork {
    /// Of a member of a G2 run that re-blended `reblended` merged tangents
    /// (built `whole` or not) and placed its finest rows `rows` again.
    pub(crate) fn of_run(reblended: usize, whole: bool, rows: Option<RowSpan>) -> Self {
        PatchWork {
            reblended,
            rows,
            whole,
        }
    }

    /// From a kernel update.
    pub fn of(u: &PatchUpdate) -> Self {
        PatchWork {
            reblended: u.reblended,
            rows: u.rows.last().copied().flatten(),
            whole: u.whole,
        }
    }
}

/// `parts` on `start` at `depth`: updated in place from `state` and the
/// patch's stack as it was (`old`), or built whole into `state`. On an
/// error `state` is dropped, so the next build is whole.
pub(crate) fn update(
    state: &mut Option<PatchState>,
    parts: PatchParts,
    start: Start,
    depth: u32,
    old: Option<Stack>,
) -> Result<(Stack, PatchUpdate), JoinError> {
    let done = match (state.as_mut(), old) {
        (Some(st), Some(mut stack)) => st
            .update(parts, start, depth, &mut stack)
            .map(|u| (stack, u)),
        _ => PatchState::build(parts, start, depth).map(|(st, stack)| {
            *state = Some(st);
            let u = PatchUpdate::whole(&stack);
            (stack, u)
        }),
    };
    if done.is_err() {
        *state = None;
    }
    done
}

/// A kept patch's update settled: `Ok(stack)` when it moved (its work, the
/// display depth's rows it placed again and each level's recorded for patch `i`),
/// `Err(stack)` when nothing moved (put back as it was, not marked changed).
pub(crate) fn settle(
    i: usize,
    (stack, u): (Stack, PatchUpdate),
    work: &mut [Option<PatchWork>],
    moved: &mut [Option<RowSpan>],
    level_rows: &mut [Option<Vec<Option<RowSpan>>>],
) -> Result<Stack, Stack> {
    work[i] = Some(PatchWork::of(&u));
    if !u.whole && u.rows.iter().all(Option::is_none) {
        return Err(stack);
    }
    // every row whose tangents or parameters moved is placed again
    level_rows[i] = (!u.whole).then(|| u.rows.clone());
    moved[i] = match u.whole {
        true => None,
        false => u.rows.last().copied().flatten(),
    };
    Ok(stack)
}
