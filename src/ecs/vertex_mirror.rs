//! The surface's vertices as `f32`, for a renderer that wants them: the mesh
//! stage converts a row's points and normals right after it computed the
//! row's normals (while they are in the cache), into a staging pair of
//! buffers; the reader swaps that pair with the one its mesh holds
//! ([`VertexMirror::swap`]) instead of converting the surface again from
//! memory that has gone cold (on the car at depth 6 a drag rewrites nearly
//! all of its 165,000 vertices every frame: about 0.9 ms a frame).
//!
//! Each of the two pairs records which points it lacks ([`Stale`]): the mesh
//! stage brings the staging pair up to date and adds its window to what the
//! other pair lacks; after a swap the pair that comes back lacks what the
//! shown one lacked. So a reader that skips frames swaps in an exact pair.
//! Present only where a renderer asks for it (the editor inserts it);
//! headless runs convert nothing.

use super::resources::SurfaceData;
use bevy::prelude::*;
use streamline_kernel::DVec3;
use streamline_kernel::levels::dirty_window::DirtyWindow;
use streamline_kernel::streamline::surface_mesh::coordinates;

/// Which points of a pair differ from [`SurfaceData`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Stale {
    /// All of them (or the pair has another shape).
    #[default]
    All,
    /// Those in this window (rows × columns of the points).
    Window(DirtyWindow),
    /// None.
    Nothing,
}

impl Stale {
    /// Also lacking `w` (`None`: everything).
    pub fn and(self, w: Option<DirtyWindow>) -> Stale {
        match (self, w) {
            (Stale::All, _) | (_, None) => Stale::All,
            (Stale::Nothing, Some(w)) => Stale::Window(w),
            (Stale::Window(a), Some(w)) => Stale::Window(a.union(w)),
        }
    }
}

/// The staging pair of `f32` positions and normals, and what each pair lacks.
#[derive(Resource, Debug, Default)]
pub struct VertexMirror {
    /// Positions of the staging pair, one per point of [`SurfaceData`].
    positions: Vec<[f32; 3]>,
    /// Normals of the staging pair.
    normals: Vec<[f32; 3]>,
    /// What the staging pair lacks.
    staged: Stale,
    /// What the reader's pair lacks.
    shown: Stale,
    /// Nothing draws the surface for now (the reader hides it): the mesh
    /// stage writes nothing here ([`Self::set_paused`]).
    paused: bool,
}

impl VertexMirror {
    /// The window the mesh stage must convert to bring the staging pair up
    /// to date after rewriting `around`: `around` and what the pair lacked
    /// already; `None` when it lacks everything (then [`Self::write_all`]).
    pub(crate) fn to_write(&self, around: DirtyWindow, points: usize) -> Option<DirtyWindow> {
        if self.positions.len() != points || self.normals.len() != points {
            return None;
        }
        match self.staged {
            Stale::All => None,
            Stale::Nothing => Some(around),
            Stale::Window(w) => Some(around.union(w)),
        }
    }

    /// Converts rows `rows` (columns `cols`) of the surface into the staging
    /// pair (call for each chunk of [`Self::to_write`]'s window, then
    /// [`Self::written`]).
    pub(crate) fn write_rows(
        &mut self,
        s: &SurfaceData,
        rows: std::ops::RangeInclusive<usize>,
        cols: std::ops::RangeInclusive<usize>,
    ) {
        let width = s.points.cols();
        for r in rows {
            let range = r * width + cols.start()..r * width + cols.end() + 1;
            self.stream_row(
                range.start,
                &s.points.data()[range.clone()],
                &s.normals[range],
            );
        }
    }

    /// Converts one row's run of `positions` and `normals`, which start at
    /// point `at`, into the staging pair (the mesh stage's fused path: the
    /// normals straight from its scratch rows).
    pub(crate) fn stream_row(&mut self, at: usize, positions: &[DVec3], normals: &[DVec3]) {
        let range = at..at + positions.len();
        stream_f32(&mut self.positions[range.clone()], positions);
        stream_f32(&mut self.normals[range], normals);
    }

    /// The staging pair is up to date; the reader's lacks `around` more.
    pub(crate) fn written(&mut self, around: DirtyWindow) {
        streamed();
        self.staged = Stale::Nothing;
        self.shown = self.shown.and(Some(around));
    }

    /// The whole surface (a new shape) into the staging pair; the reader's
    /// pair lacks everything.
    pub(crate) fn write_all(&mut self, s: &SurfaceData) {
        let n = s.points.data().len();
        self.positions.resize(n, [0.0; 3]);
        self.normals.resize(n, [0.0; 3]);
        write_f32(&mut self.positions, s.points.data());
        write_f32(&mut self.normals, &s.normals);
        self.staged = Stale::Nothing;
        self.shown = Stale::All;
    }

    /// Pauses the staging (`true`: the reader hides the surface, so the mesh
    /// stage converts nothing, and may leave the surface's `f64` normals
    /// behind while they are deferred) or resumes it. Paused, the staging
    /// pair lacks everything, so the first change after it is resumed
    /// writes it whole.
    pub fn set_paused(&mut self, paused: bool) {
        self.paused = paused;
        if paused {
            self.staged = Stale::All;
        }
    }

    /// Whether the staging is paused ([`Self::set_paused`]).
    pub fn paused(&self) -> bool {
        self.paused
    }

    /// Whether the staging pair is up to date (a swap takes it when the
    /// shapes agree).
    pub fn staged_whole(&self) -> bool {
        self.staged == Stale::Nothing
    }

    /// What the reader's pair lacks.
    pub fn shown_stale(&self) -> Stale {
        self.shown
    }

    /// Swaps the staging pair with `positions` and `normals` (the reader's
    /// mesh buffers), when the staging pair is up to date and both have
    /// `points` entries and the reader's pair is not missing everything (a
    /// new shape also has new triangles: the reader builds its mesh afresh,
    /// then calls [`Self::shown_rebuilt`]). Returns whether it swapped.
    pub fn swap(
        &mut self,
        positions: &mut Vec<[f32; 3]>,
        normals: &mut Vec<[f32; 3]>,
        points: usize,
    ) -> bool {
        let ready = self.staged == Stale::Nothing
            && self.shown != Stale::All
            && [
                self.positions.len(),
                self.normals.len(),
                positions.len(),
                normals.len(),
            ]
            .iter()
            .all(|&n| n == points);
        if !ready {
            return false;
        }
        std::mem::swap(&mut self.positions, positions);
        std::mem::swap(&mut self.normals, normals);
        self.staged = self.shown;
        self.shown = Stale::Nothing;
        true
    }

    /// The reader built its mesh afresh from [`SurfaceData`].
    pub fn shown_rebuilt(&mut self) {
        self.shown = Stale::Nothing;
    }
}

/// [`write_f32`]'s numbers, stored with streaming (non-temporal) stores
/// where the target has them: the lines written are not read first. The
/// staging pair was last touched by the renderer, a whole software-rendered
/// frame (about 160 ms on llvmpipe) before, so every line of it is cold; a
/// plain store fetches each line from memory before overwriting it (on the
/// depth-6 drag, 3.4 MB a frame). Call [`streamed`] after the last one,
/// before the buffers are handed to another thread.
pub fn stream_f32(dst: &mut [[f32; 3]], src: &[DVec3]) {
    #[cfg(target_arch = "x86_64")]
    {
        use std::arch::x86_64::{_mm_cvtpd_ps, _mm_loadu_pd, _mm_movelh_ps, _mm_stream_ps};
        let (dst, src) = (dst.as_flattened_mut(), coordinates(src));
        let n = dst.len().min(src.len());
        // up to the first 16-byte boundary, plain stores
        let head = (dst.as_ptr().align_offset(16)).min(n);
        for i in 0..head {
            dst[i] = src[i] as f32;
        }
        let mut i = head;
        while i + 4 <= n {
            // SAFETY: SSE2 is part of the x86-64 baseline; i + 4 ≤ n, the
            // length of both slices; `dst + i` is 16-byte aligned (a multiple
            // of 4 floats past `head`).
            unsafe {
                let a = _mm_cvtpd_ps(_mm_loadu_pd(src.as_ptr().add(i)));
                let b = _mm_cvtpd_ps(_mm_loadu_pd(src.as_ptr().add(i + 2)));
                _mm_stream_ps(dst.as_mut_ptr().add(i), _mm_movelh_ps(a, b));
            }
            i += 4;
        }
        for i in i..n {
            dst[i] = src[i] as f32;
        }
    }
    #[cfg(not(target_arch = "x86_64"))]
    write_f32(dst, src);
}

/// `dst.copy_from_slice(src)` with streaming stores, as [`stream_f32`].
pub fn stream_f64(dst: &mut [DVec3], src: &[DVec3]) {
    assert_eq!(dst.len(), src.len());
    #[cfg(target_arch = "x86_64")]
    {
        use std::arch::x86_64::{_mm_loadu_pd, _mm_stream_pd};
        let (dst, src) = (
            streamline_kernel::streamline::surface_mesh::coordinates_mut(dst),
            coordinates(src),
        );
        let n = dst.len();
        let head = (dst.as_ptr().align_offset(16)).min(n);
        dst[..head].copy_from_slice(&src[..head]);
        let mut i = head;
        while i + 2 <= n {
            // SAFETY: SSE2 is baseline; i + 2 ≤ n; `dst + i` is 16-byte aligned.
            unsafe { _mm_stream_pd(dst.as_mut_ptr().add(i), _mm_loadu_pd(src.as_ptr().add(i))) };
            i += 2;
        }
        dst[i..].copy_from_slice(&src[i..]);
    }
    #[cfg(not(target_arch = "x86_64"))]
    dst.copy_from_slice(src);
}

/// Orders the streaming stores before whatever follows (another thread
/// reading the buffers); nothing where there are none.
pub fn streamed() {
    #[cfg(target_arch = "x86_64")]
    // SAFETY: SSE is part of the x86-64 baseline.
    unsafe {
        std::arch::x86_64::_mm_sfence()
    };
}

/// `src` as `f32` into `dst`, the conversion of `DVec3::as_vec3` (each
/// component `as f32`), over the flat components.
pub fn write_f32(dst: &mut [[f32; 3]], src: &[DVec3]) {
    let dst = dst.as_flattened_mut();
    for (d, s) in dst.iter_mut().zip(coordinates(src)) {
        *d = *s as f32;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn write_f32_is_as_vec3() {
        let v: Vec<DVec3> = (0..50)
            .map(|i| DVec3::new(i as f64 * 0.1, -1e-40 * i as f64, 1e300 / (i as f64 + 1.0)))
            .chain([DVec3::new(-0.0, f64::NAN, f64::INFINITY)])
            .collect();
        let mut out = vec![[9.0f32; 3]; v.len()];
        write_f32(&mut out, &v);
        for (o, p) in out.iter().zip(&v) {
            assert_eq!(
                o.map(f32::to_bits),
                p.as_vec3().to_array().map(f32::to_bits)
            );
        }
    }

    /// Points whose coordinates are ordinary, huge, tiny, signed zeros,
    /// infinities and NaN.
    fn nasty_points(n: usize) -> Vec<DVec3> {
        let odd = [
            -0.0,
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            1e300,
            -1e-320,
            f64::from(f32::MAX) * 1.5,
            0.1,
        ];
        (0..n)
            .map(|i| {
                let f = |k: usize| {
                    if (i + k).is_multiple_of(5) {
                        odd[(i * 3 + k) % odd.len()]
                    } else {
                        (i as f64 + 0.37 * k as f64).sin() * 10f64.powi((i % 7) as i32 - 3)
                    }
                };
                DVec3::new(f(0), f(1), f(2))
            })
            .collect()
    }

    #[test]
    fn streamed_stores_write_the_same_bits_at_every_alignment() {
        for len in 0..24 {
            let src = nasty_points(len);
            // every start in a buffer: the 16-byte boundary falls anywhere
            // in the run (an `[f32; 3]` is 12 bytes, a `DVec3` 24)
            for start in 0..6 {
                let mut want = vec![[7.0f32; 3]; start + len + 2];
                let mut got = want.clone();
                write_f32(&mut want[start..start + len], &src);
                stream_f32(&mut got[start..start + len], &src);
                streamed();
                let bits = |v: &[[f32; 3]]| -> Vec<[u32; 3]> {
                    v.iter().map(|p| p.map(f32::to_bits)).collect()
                };
                assert_eq!(bits(&got), bits(&want), "f32, {len} points at {start}");

                let mut want = vec![DVec3::splat(7.0); start + len + 2];
                let mut got = want.clone();
                want[start..start + len].copy_from_slice(&src);
                stream_f64(&mut got[start..start + len], &src);
                streamed();
                let bits = |v: &[DVec3]| -> Vec<[u64; 3]> {
                    v.iter().map(|p| p.to_array().map(f64::to_bits)).collect()
                };
                assert_eq!(bits(&got), bits(&want), "f64, {len} points at {start}");
            }
        }
    }

    #[test]
    fn stale_windows_add_up() {
        let a = DirtyWindow::cell(1, 2);
        let b = DirtyWindow::cell(4, 0);
        assert_eq!(Stale::Nothing.and(Some(a)), Stale::Window(a));
        assert_eq!(Stale::Window(a).and(Some(b)), Stale::Window(a.union(b)));
        assert_eq!(Stale::Window(a).and(None), Stale::All);
        assert_eq!(Stale::All.and(Some(a)), Stale::All);
    }
}
