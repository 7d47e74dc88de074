//! The curvature comb (docs/math.md §4, §11): teeth along up to
//! `comb_lines` streamlines of every shown patch, normal to each, as long as
//! its curvature, all at one scale.

use super::super::coords::to_view;
use super::super::interaction::{EditorSet, SceneBounds};
use super::analysis_display::AnalysisSettings;
use crate::ecs::SurfaceData;
use crate::ecs::components::{LevelData, SubdivisionLevel};
use crate::ecs::joined::{PatchHidden, PatchSurface};
use crate::ecs::patch::Joined;
use bevy::prelude::*;
use streamline_kernel::analysis::comb;
use streamline_kernel::{DVec3, Grid};

pub struct CombsPlugin;

impl Plugin for CombsPlugin {
    fn build(&self, app: &mut App) {
        app.add_systems(Update, draw_combs.in_set(EditorSet::Present));
    }
}

/// One patch's streamlines for its combs: row `r` is the streamline of
/// points `points.row(r)`, tangents `tangents.row(r)` at arc lengths
/// `s.row(r)`.
struct CombRows<'a> {
    points: &'a Grid<DVec3>,
    tangents: &'a Grid<DVec3>,
    s: &'a Grid<f64>,
}

impl CombRows<'_> {
    /// Up to `lines` rows, spread evenly, the last one always.
    fn chosen(&self, lines: usize) -> impl Iterator<Item = usize> {
        let rows = self.points.rows();
        let step = rows.div_ceil(lines.max(1)).max(1);
        (0..rows).filter(move |&r| r.is_multiple_of(step) || r + 1 == rows)
    }
}

/// Combs on up to `comb_lines` streamlines of every shown patch, spread
/// evenly over each, all at one scale (the largest tooth of all is a tenth of
/// the scene, times the factor): the first patch's from its levels and
/// surface, a joined patch's from its stack's finest level (docs/math.md
/// §11).
#[allow(clippy::too_many_arguments)]
fn draw_combs(
    meter: Res<crate::ecs::meter::CpuMeter>,
    settings: Res<AnalysisSettings>,
    bounds: Res<SceneBounds>,
    patch: crate::ecs::patch::PatchRef,
    levels: Query<(&SubdivisionLevel, &LevelData)>,
    data: Res<SurfaceData>,
    joined: Query<&PatchSurface, (With<Joined>, Without<PatchHidden>)>,
    mut gizmos: Gizmos,
) {
    let _meter = meter.start();
    if !settings.comb {
        return;
    }
    let depth = patch.structure().display_depth;
    let mut patches = Vec::new();
    // the first patch's streamlines are its surface's rows
    if let Some((_, level)) = levels.iter().find(|(l, _)| l.0 == depth)
        && data.points.rows() > 0
        && data.points.rows() == level.0.tangents.rows()
    {
        patches.push(CombRows {
            points: &data.points,
            tangents: &level.0.tangents,
            s: &level.0.params.s,
        });
    }
    for stack in joined.iter().filter_map(PatchSurface::stack) {
        let finest = stack.finest();
        patches.push(CombRows {
            points: stack.finest_points(),
            tangents: &finest.tangents,
            s: &finest.params.s,
        });
    }
    let lines = settings.comb_lines;
    let kmax = (patches.iter())
        .flat_map(|p| p.chosen(lines).map(move |r| (p, r)))
        .flat_map(|(p, r)| {
            streamline_kernel::analysis::streamline_curvature(p.tangents.row(r), p.s.row(r))
        })
        .fold(0.0f64, f64::max);
    if kmax <= 0.0 {
        return;
    }
    let scale = settings.comb_scale * 0.1 * bounds.size() / kmax;
    let tooth = Color::srgba(0.95, 0.35, 0.85, 0.8);
    let hull = Color::srgb(0.95, 0.35, 0.85);
    for p in &patches {
        for r in p.chosen(lines) {
            let teeth = comb(p.points.row(r), p.tangents.row(r), p.s.row(r), scale);
            for c in &teeth {
                gizmos.line(to_view(c.base), to_view(c.tip), tooth);
            }
            gizmos.linestrip(teeth.iter().map(|c| to_view(c.tip)), hull);
        }
    }
}
