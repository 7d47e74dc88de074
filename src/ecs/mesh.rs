//! The mesh stage: rows of the surface mesh whose streamline moved are
//! rewritten, with the normals of their neighbours.

use super::components::*;
use super::resources::{Stats, SurfaceData};
use bevy::prelude::*;
use std::time::Instant;
use streamline_kernel::mesh::{normals_and_indices, normals_window};
use streamline_kernel::window::{Span, Window};
use streamline_kernel::{DVec3, Grid};

pub(crate) fn patch_mesh(
    meter: Res<super::meter::CpuMeter>,
    changed: Query<(&Streamline, &StreamlinePoints), Changed<StreamlinePoints>>,
    all: Query<(), With<Streamline>>,
    mut surface: ResMut<SurfaceData>,
    mut stats: ResMut<Stats>,
) {
    let _meter = meter.start();
    let t0 = Instant::now();
    let rows = all.iter().count();
    let mut span: Option<Span> = None;
    let mut cols = surface.points.cols();
    for (line, p) in &changed {
        cols = p.points.len();
        span = Some(span.map_or(Span::single(line.row), |s| s.union(Span::single(line.row))));
    }
    let Some(span) = span else {
        stats.collecting = false;
        return;
    };
    let s = &mut *surface;
    let reshaped = s.points.rows() != rows || s.points.cols() != cols;
    if reshaped {
        s.points = Grid::filled(rows, cols, DVec3::ZERO);
        s.row_bounds = vec![[DVec3::ZERO; 2]; rows];
    }
    if reshaped {
        for (line, p) in &changed {
            if line.row < rows && p.points.len() == cols {
                s.set_row_from(line.row, &p.points, 0);
            }
        }
        normals_and_indices(&s.points, &mut s.normals, &mut s.indices);
        s.changed = None;
    } else {
        // same shape: the triangles stay, only the points that moved and the
        // normals around them are rewritten (a drag on the car at depth 5
        // moves nearly every row; rewriting 82k triangles would be wasted)
        let mut from = cols;
        for (line, p) in &changed {
            if line.row < rows && p.points.len() == cols {
                s.set_row_from(line.row, &p.points, p.moved_from);
                from = from.min(p.moved_from);
            }
        }
        // a normal reads its neighbours across and along
        let around = Window {
            rows: span.widen(1, rows),
            cols: Span {
                lo: from.saturating_sub(1).min(cols - 1),
                hi: cols - 1,
            },
        };
        normals_window(
            s.points.data(),
            cols,
            around.rows.lo,
            around.rows.hi,
            around.cols.lo,
            &mut s.normals,
        );
        s.changed = Some(around);
    }
    s.generation += 1;
    stats.last.mesh_rows += span.len();
    stats.last.us_mesh += t0.elapsed().as_secs_f64() * 1e6;
    stats.collecting = false;
}
