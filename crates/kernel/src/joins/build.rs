//! One join built whole (docs/math.md §11): `A` and `B` at every depth up to
//! `d`, whichever edge and continuity.

use crate::joins::chain::chain;
use crate::joins::error::JoinError;
use crate::joins::kinds::{Continuity, Edge, Join};
use crate::joins::merged::g2_run;
use crate::joins::side::side;
use crate::joins::stack::Stack;
use crate::levels::design::Design;

/// `A` and `B` (which starts on `A`'s `join.edge`) built to `depth`. `A` is
/// its own build except on a G2 chain, where both are cuts of one merged net
/// (docs/math.md §11.1). G2 on a side edge is refused.
pub fn join(a: &Design, b: &Design, join: Join, depth: u32) -> Result<(Stack, Stack), JoinError> {
    match (join.edge, join.continuity) {
        (Edge::End, Continuity::G2) => {
            let mut run = g2_run(&[a, b], depth)?;
            let b = run.pop().expect("two patches");
            let a = run.pop().expect("two patches");
            Ok((a, b))
        }
        (_, Continuity::G2) => Err(JoinError::SideG2),
        (Edge::End, c) => {
            let sa = Stack::build(a, depth)?;
            let sb = chain(a, &sa, b, c)?;
            Ok((sa, sb))
        }
        (edge, c) => {
            let sa = Stack::build(a, depth)?;
            let sb = side(&sa, b, edge, c)?;
            Ok((sa, sb))
        }
    }
}
