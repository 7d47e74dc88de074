//! The mesh stage: the normals around the points that moved (the integrate
//! stage wrote the points themselves into the surface's rows), announced to
//! the surface's readers as a [`SurfaceChanged`] message. While the editor
//! defers them ([`DeferNormals`]) a steady drag's `f64` normals are left
//! behind and made when it ends: made only as the renderer's `f32` staging
//! pair, or not at all while nothing draws the surface (the staging paused,
//! [`VertexMirror::set_paused`]: a G2 run's first patch, drawn as its cut).

use super::components::*;
use super::resources::{DeferNormals, Stats, SurfaceChanged, SurfaceData};
use super::vertex_mirror::{VertexMirror, stream_f64};
use bevy::prelude::*;
use std::time::Instant;
use streamline_kernel::DVec3;
use streamline_kernel::levels::dirty_window::{DirtyWindow, Span};
use streamline_kernel::streamline::surface_mesh::{
    normals_and_indices, normals_rows_into, normals_window,
};

/// The first patch's streamlines whose points moved (a joined patch's,
/// [`JoinedChild`], are rows of its own stack).
type MovedLines = (Changed<StreamlinePoints>, Without<JoinedChild>);

pub(crate) fn patch_mesh(
    meter: Res<super::meter::CpuMeter>,
    changed: Query<(&Streamline, &StreamlinePoints), MovedLines>,
    mut surface: ResMut<SurfaceData>,
    mut stats: ResMut<Stats>,
    mut changes: MessageWriter<SurfaceChanged>,
    // the renderer's staging pair, if one is wanted, and whether the
    // surface's own normals may wait ([`DeferNormals`])
    (mirror, defer): (Option<ResMut<VertexMirror>>, Res<DeferNormals>),
    mut scratch: Local<Vec<DVec3>>,
) {
    let _meter = meter.start();
    let t0 = Instant::now();
    // a paused staging pair is not written (nothing draws the surface)
    let mut mirror = mirror.filter(|m| !m.paused());
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
        // a frame with nothing to do makes what a drag left behind
        if !defer.0 && s.normals_behind.is_some() {
            catch_up(s);
        }
        stats.collecting = false;
        return;
    };
    let window = if s.reshaped || s.normals.len() != rows * cols {
        normals_and_indices(&s.points, &mut s.normals, &mut s.indices);
        s.reshaped = false;
        s.normals_behind = None;
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
            // nothing draws them: left behind while deferred
            None if defer.0 => {
                s.normals_behind = Some(s.normals_behind.map_or(around, |b| b.union(around)));
            }
            None => {
                catch_up(s);
                normals_in(s, around)
            }
            Some(m) => normals_and_mirror(s, around, m, &mut scratch, defer.0),
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
///
/// When the staging pair lacks exactly `around` (every frame of a drag
/// after its first), a chunk's normals are made in `scratch` and stored
/// from there into the surface and, as `f32`, into the staging pair, all
/// with streaming stores ([`super::vertex_mirror::stream_f32`]): after a
/// software-rendered frame none of those lines is in the cache, and a plain
/// store would read each one from memory first (on the car at depth 6,
/// 6.8 MB of the frame's reads). There, when `defer` ([`DeferNormals`]),
/// the surface's `f64` normals are left behind in `around`, provided what
/// was left behind before lies in it (the normal just before the window,
/// which a degenerate point takes, is then exact); not deferred, that path
/// makes them all, those left behind included. Every other path first makes
/// what was left behind.
fn normals_and_mirror(
    s: &mut SurfaceData,
    around: DirtyWindow,
    m: &mut VertexMirror,
    scratch: &mut Vec<DVec3>,
    defer: bool,
) {
    let cols = s.points.cols();
    let write = m.to_write(around, s.points.data().len());
    // the streamed path rewrites all of `around`: what was left behind
    // inside it is made there (the frame a drag ends with an edit costs no
    // more than before), or left behind again when `defer`
    let streamed =
        write == Some(around) && s.normals_behind.is_none_or(|b| around.union(b) == around);
    if !streamed {
        catch_up(s);
    }
    let leave = defer && streamed;
    let Some(write) = write else {
        normals_in(s, around);
        m.write_all(s);
        return;
    };
    let step = (MIRROR_CHUNK_POINTS / cols.max(1)).max(1);
    if write == around {
        streamed_window(s, around, m, scratch, step, leave);
        return;
    }
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

/// [`normals_and_mirror`]'s fused path: `step` rows at a time, the normals
/// of `around` into `scratch` (their row's normal before the window first,
/// which a degenerate point there takes), then stored: into the staging
/// pair, and into the surface unless `leave` (then `around` is left behind).
fn streamed_window(
    s: &mut SurfaceData,
    around: DirtyWindow,
    m: &mut VertexMirror,
    scratch: &mut Vec<DVec3>,
    step: usize,
    leave: bool,
) {
    let cols = s.points.cols();
    let c0 = around.cols.lo;
    let mut lo = around.rows.lo;
    while lo <= around.rows.hi {
        let hi = (lo + step - 1).min(around.rows.hi);
        scratch.resize((hi - lo + 1) * cols, DVec3::Z);
        if c0 > 0 {
            for r in lo..=hi {
                scratch[(r - lo) * cols + c0 - 1] = s.normals[r * cols + c0 - 1];
            }
        }
        normals_rows_into(s.points.data(), cols, lo, hi, c0, scratch);
        for r in lo..=hi {
            let (at, made) = (
                r * cols + c0,
                &scratch[(r - lo) * cols + c0..(r - lo + 1) * cols],
            );
            if !leave {
                stream_f64(&mut s.normals[at..(r + 1) * cols], made);
            }
            m.stream_row(at, &s.points.data()[at..(r + 1) * cols], made);
        }
        lo = hi + 1;
    }
    s.normals_behind = leave.then_some(around);
    m.written(around);
}

/// Makes the normals the mesh stage left behind ([`DeferNormals`]), the
/// same numbers as if made then (a normal reads only the points around it,
/// and a degenerate point the normal before it in its row, made first). A
/// surface given a new shape since is made whole by the mesh stage.
fn catch_up(s: &mut SurfaceData) {
    let Some(w) = s.normals_behind.take() else {
        return;
    };
    if s.reshaped || s.normals.len() != s.points.data().len() || w.rows.hi >= s.points.rows() {
        return;
    }
    normals_in(s, w);
}

/// The surface's normals of the points in `w` (to the end of their rows).
fn normals_in(s: &mut SurfaceData, w: DirtyWindow) {
    let cols = s.points.cols();
    normals_window(
        s.points.data(),
        cols,
        w.rows.lo,
        w.rows.hi,
        w.cols.lo,
        &mut s.normals,
    );
}

#[cfg(test)]
mod tests {
    use super::*;
    use streamline_kernel::Grid;

    /// A wavy sheet of `rows × cols` points, `t` moving its hump.
    fn sheet(rows: usize, cols: usize, t: f64) -> Grid<DVec3> {
        let mut data = Vec::with_capacity(rows * cols);
        for r in 0..rows {
            for c in 0..cols {
                let (x, y) = (c as f64 * 0.3, r as f64 * 0.4);
                data.push(DVec3::new(x, y, (x * 0.7 + t).sin() * (y * 0.5).cos()));
            }
        }
        Grid::new(rows, cols, data).unwrap()
    }

    /// The first point whose bits differ, if any.
    fn first_difference<T: Copy, B: PartialEq>(
        a: &[T],
        b: &[T],
        bits: impl Fn(T) -> B,
    ) -> Option<usize> {
        if a.len() != b.len() {
            return Some(a.len().min(b.len()));
        }
        (0..a.len()).find(|&i| bits(a[i]) != bits(b[i]))
    }

    fn bits64(p: DVec3) -> [u64; 3] {
        p.to_array().map(f64::to_bits)
    }

    fn bits32(p: [f32; 3]) -> [u32; 3] {
        p.map(f32::to_bits)
    }

    fn f32s(v: &[DVec3]) -> Vec<[f32; 3]> {
        v.iter().map(|p| p.as_vec3().to_array()).collect()
    }

    /// Moves the points of `w` less its first and last row and first column
    /// (whose normals read the moved points, as the mesh stage widens the
    /// moved rows) to the sheet at `t`.
    fn move_points(s: &mut SurfaceData, w: DirtyWindow, t: f64) {
        let (rows, cols) = (s.points.rows(), s.points.cols());
        let new = sheet(rows, cols, t);
        for r in w.rows.lo + 1..w.rows.hi {
            for c in w.cols.lo + 1..cols {
                s.points.set(r, c, new.get(r, c));
            }
        }
    }

    /// A 40 × 300 sheet with its normals and triangles, as shown (the
    /// staging pair up to date and nothing lacking), and the window of an
    /// edit of rows 3 ..= 33 from column 120 on.
    fn shown_sheet() -> (SurfaceData, VertexMirror, DirtyWindow) {
        let (rows, cols) = (40, 300);
        let mut s = SurfaceData {
            points: sheet(rows, cols, 0.0),
            ..default()
        };
        normals_and_indices(&s.points, &mut s.normals, &mut s.indices);
        let mut m = VertexMirror::default();
        m.write_all(&s);
        m.shown_rebuilt();
        let around = DirtyWindow {
            rows: Span { lo: 3, hi: 33 },
            cols: Span {
                lo: 120,
                hi: cols - 1,
            },
        };
        (s, m, around)
    }

    /// The fused path (the staging pair lacks exactly the window: every frame
    /// of a drag after its first) writes the normals of the plain path, bit
    /// for bit, into the surface and, as `f32`, into the staging pair; a
    /// degenerate point on the window's first column takes the normal just
    /// before the window, as there. Control: the plain path's normals differ
    /// from the old ones in the window, so the comparison can fail.
    #[test]
    fn the_streamed_window_is_the_plain_path_bit_for_bit() {
        let (mut s, mut m, around) = shown_sheet();
        let (rows, cols) = (s.points.rows(), s.points.cols());
        // an edit moved rows 3 ..= 33 from column 120 on; on row 10 the
        // first column of the window is degenerate (its neighbours along
        // the row coincide)
        let new = sheet(rows, cols, 0.8);
        for r in around.rows.lo..=around.rows.hi {
            for c in around.cols.lo..cols {
                s.points.set(r, c, new.get(r, c));
            }
        }
        let p = s.points.get(10, 119);
        s.points.set(10, 121, p);
        let mut plain = s.clone();
        normals_window(
            plain.points.data(),
            cols,
            around.rows.lo,
            around.rows.hi,
            around.cols.lo,
            &mut plain.normals,
        );
        assert_eq!(
            plain.normals[10 * cols + 120],
            plain.normals[10 * cols + 119]
        );
        assert!(
            first_difference(&plain.normals, &s.normals, bits64).is_some(),
            "control"
        );

        let mut scratch = vec![DVec3::splat(f64::NAN); 7];
        assert_eq!(m.to_write(around, rows * cols), Some(around));
        normals_and_mirror(&mut s, around, &mut m, &mut scratch, false);
        assert_eq!(first_difference(&s.normals, &plain.normals, bits64), None);

        let (mut positions, mut normals) =
            (vec![[0.0; 3]; rows * cols], vec![[0.0; 3]; rows * cols]);
        assert!(m.swap(&mut positions, &mut normals, rows * cols));
        assert_eq!(
            first_difference(&positions, &f32s(plain.points.data()), bits32),
            None
        );
        assert_eq!(
            first_difference(&normals, &f32s(&plain.normals), bits32),
            None
        );
    }

    /// The normals of every point of `points`, made whole (not windowed).
    fn whole(points: &Grid<DVec3>) -> Vec<DVec3> {
        let (mut normals, mut indices) = (Vec::new(), Vec::new());
        normals_and_indices(points, &mut normals, &mut indices);
        normals
    }

    /// Deferred ([`DeferNormals`]): two steady frames of a drag leave the
    /// surface's `f64` normals behind in their window (control: they are the
    /// old ones there), while the staging pair gets the exact ones as `f32`,
    /// a degenerate point on the window's first column included; the copy
    /// for export makes them; catching up gives the numbers of the whole
    /// surface made afresh, bit for bit. A window that does not hold what
    /// was left behind catches up first.
    #[test]
    fn normals_left_behind_in_a_drag_are_made_exactly_when_it_ends() {
        let (mut s, mut m, around) = shown_sheet();
        let (rows, cols) = (s.points.rows(), s.points.cols());
        // the reader's pair: the surface as shown
        let (mut positions, mut normals) = (f32s(s.points.data()), f32s(&s.normals));
        let mut scratch = Vec::new();
        let before = s.normals.clone();
        for (frame, t) in [0.8, 1.3].into_iter().enumerate() {
            move_points(&mut s, around, t);
            let p = s.points.get(10, 119);
            s.points.set(10, 121, p);
            normals_and_mirror(&mut s, around, &mut m, &mut scratch, true);
            assert_eq!(s.normals_behind, Some(around), "frame {frame}");
            assert_eq!(
                first_difference(&s.normals, &before, bits64),
                None,
                "frame {frame}: the f64 normals were left as they were"
            );
            let want = whole(&s.points);
            assert_ne!(first_difference(&want, &before, bits64), None, "control");
            assert_eq!(
                first_difference(&s.mesh().normals, &want, bits64),
                None,
                "frame {frame}: the export's copy"
            );
            assert!(m.swap(&mut positions, &mut normals, rows * cols));
            assert_eq!(
                first_difference(&normals, &f32s(&want), bits32),
                None,
                "frame {frame}: the drawn normals"
            );
        }
        catch_up(&mut s);
        assert_eq!(s.normals_behind, None);
        assert_eq!(
            first_difference(&s.normals, &whole(&s.points), bits64),
            None
        );

        // left behind, then the frame the drag ends with an edit of the same
        // window: made there, with the edit's
        normals_and_mirror(&mut s, around, &mut m, &mut scratch, true);
        assert!(m.swap(&mut positions, &mut normals, rows * cols));
        move_points(&mut s, around, 1.7);
        normals_and_mirror(&mut s, around, &mut m, &mut scratch, false);
        assert_eq!(s.normals_behind, None);
        assert_eq!(
            first_difference(&s.normals, &whole(&s.points), bits64),
            None
        );
        assert!(m.swap(&mut positions, &mut normals, rows * cols));

        // left behind again, then a window that does not hold what was left
        // (it starts later): the mesh stage makes what it left first
        normals_and_mirror(&mut s, around, &mut m, &mut scratch, true);
        assert!(m.swap(&mut positions, &mut normals, rows * cols));
        assert_eq!(s.normals_behind, Some(around));
        let later = DirtyWindow {
            rows: Span { lo: 5, hi: 15 },
            cols: Span {
                lo: 200,
                hi: cols - 1,
            },
        };
        move_points(&mut s, later, 2.1);
        normals_and_mirror(&mut s, later, &mut m, &mut scratch, true);
        assert_eq!(s.normals_behind, None);
        let want = whole(&s.points);
        assert_eq!(first_difference(&s.normals, &want, bits64), None);
        assert!(m.swap(&mut positions, &mut normals, rows * cols));
        assert_eq!(first_difference(&normals, &f32s(&want), bits32), None);
    }

    /// Through the pipeline: a drag on the car with [`DeferNormals`] on
    /// leaves the normals behind; the first frame after it (deferral off,
    /// no edit) makes them, equal bit for bit to the whole surface's normals
    /// made afresh. Control: before that frame they differ.
    #[test]
    fn the_frame_after_a_deferred_drag_makes_the_normals() {
        use crate::ecs::{self, Edit};
        use crate::scene::Scene;
        let mut app = ecs::headless_app(Scene::from_design(
            "car",
            streamline_kernel::levels::presets::car1(),
            4,
        ));
        app.init_resource::<VertexMirror>();
        app.insert_resource(DeferNormals(true));
        app.update();
        for radians in [0.05, -0.02, 0.04] {
            ecs::send(
                &mut app,
                Edit::Rotate {
                    row: 2,
                    col: 4,
                    axis: DVec3::Y,
                    radians,
                },
            );
            app.update();
        }
        let s = app.world().resource::<SurfaceData>();
        assert!(s.normals_behind().is_some());
        assert_ne!(
            first_difference(&s.normals, &whole(&s.points), bits64),
            None,
            "control"
        );
        app.insert_resource(DeferNormals(false));
        app.update();
        let s = app.world().resource::<SurfaceData>();
        assert_eq!(s.normals_behind(), None);
        assert_eq!(
            first_difference(&s.normals, &whole(&s.points), bits64),
            None
        );
    }
}
