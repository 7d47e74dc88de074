//! The mesh stage: the normals around the points that moved (the integrate
//! stage wrote the points themselves into the surface's rows), announced to
//! the surface's readers as a [`SurfaceChanged`] message.

use super::components::*;
use super::resources::{Stats, SurfaceChanged, SurfaceData};
use super::vertex_mirror::VertexMirror;
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
    mut mirror: Option<ResMut<VertexMirror>>,
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
        if let Some(m) = mirror.as_deref_mut() {
            m.write_all(s);
        }
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
        match mirror.as_deref_mut() {
            None => normals_window(
                s.points.data(),
                cols,
                around.rows.lo,
                around.rows.hi,
                around.cols.lo,
                &mut s.normals,
            ),
            Some(m) => normals_and_mirror(s, around, m),
        }
        Some(around)
    };
    changes.write(SurfaceChanged { window });
    stats.last.mesh_rows += span.len();
    stats.last.us_mesh += t0.elapsed().as_secs_f64() * 1e6;
    stats.collecting = false;
}

/// Rows converted to `f32` after each chunk of normals: about 64k of points
/// and normals, which the conversion reads from the cache.
const MIRROR_CHUNK_POINTS: usize = 4096;

/// The normals in `around`, a chunk of rows at a time, each chunk then
/// converted into the renderer's staging buffers (with whatever they lacked
/// before); the normals are the same numbers as in one call (each reads
/// only the points around it).
fn normals_and_mirror(s: &mut SurfaceData, around: DirtyWindow, m: &mut VertexMirror) {
    let cols = s.points.cols();
    let Some(write) = m.to_write(around, s.points.data().len()) else {
        normals_window(
            s.points.data(),
            cols,
            around.rows.lo,
            around.rows.hi,
            around.cols.lo,
            &mut s.normals,
        );
        m.write_all(s);
        return;
    };
    let step = (MIRROR_CHUNK_POINTS / cols.max(1)).max(1);
    let mut lo = write.rows.lo;
    while lo <= write.rows.hi {
        let hi = (lo + step - 1).min(write.rows.hi);
        let (a, b) = (lo.max(around.rows.lo), hi.min(around.rows.hi));
        if a <= b {
            normals_window(s.points.data(), cols, a, b, around.cols.lo, &mut s.normals);
        }
        m.write_rows(s, lo..=hi, write.cols.lo..=write.cols.hi);
        lo = hi + 1;
    }
    m.written(around);
}
