//! The integrate stage: streamlines whose tangents changed are integrated
//! again (Eq. 65) and placed on the initial curve (Eqs. 1–2).

use super::components::*;
use super::resources::Stats;
use bevy::prelude::*;
use std::time::Instant;
use streamline_kernel::streamline::place_into;

pub(crate) fn integrate(
    mut lines: Query<(&StreamlineTangents, &mut StreamlinePoints), Changed<StreamlineTangents>>,
    mut stats: ResMut<Stats>,
) {
    let t0 = Instant::now();
    let mut n = 0;
    for (t, mut p) in &mut lines {
        place_into(&t.tangents, &t.s, t.sigma, t.origin, &mut p.0);
        n += 1;
    }
    if n > 0 {
        stats.last.streamlines_reintegrated += n;
        stats.last.us_integrate += t0.elapsed().as_secs_f64() * 1e6;
    }
}
