//! The mesh stage: the normals around the points that moved (the integrate
//! stage wrote the points themselves into the surface's rows), announced to
//! the surface's readers as a [`SurfaceChanged`] message.

use super::components::*;
use super::resources::{Stats, SurfaceChanged, SurfaceData};
use bevy::prelude::*;
use std::time::Instant;
use streamline_kernel::levels::dirty_window::{DirtyWindow, Span};
use streamline_kernel::streamline::surface_mesh::{normals_and_indices, normals_window};

pub(crate) fn patch_mesh(
    meter: Res<super::meter::CpuMeter>,
    changed: Query<(&Streamline, &StreamlinePoints), Changed<StreamlinePoints>>,
    mut surface: ResMut<SurfaceData>,
    mut stats: ResMut<Stats>,
    mut changes: MessageWriter<SurfaceChanged>,
) {
    let _meter = meter.start();
    let t0 = Instant::now();
    let s = &mut *surface;
    let (rows, cols) = (s.points.rows(), s.points.cols());
    // the rows that moved, and the first point that moved in any of them
    let mut span: Option<Span> = None;
    let mut from = cols;
    for (line, p) in &changed {
        if line.row < rows {
            span = Some(span.map_or(Span::single(line.row), |s| s.union(Span::single(line.row))));
            from = from.min(p.moved_from);
        }
    }
    let Some(span) = span else {
        stats.collecting = false;
        return;
    };
    let window = if s.reshaped || s.normals.len() != rows * cols {
        normals_and_indices(&s.points, &mut s.normals, &mut s.indices);
        s.reshaped = false;
        None
    } else {
        // same shape: the triangles stay, only the normals around the points
        // that moved are rewritten (a drag on the car at depth 5 moves nearly
        // every row; rewriting 82k triangles would be wasted); a normal reads
        // its neighbours across and along
        let around = DirtyWindow {
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
        Some(around)
    };
    changes.write(SurfaceChanged { window });
    stats.last.mesh_rows += span.len();
    stats.last.us_mesh += t0.elapsed().as_secs_f64() * 1e6;
    stats.collecting = false;
}
