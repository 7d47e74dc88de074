//! The deviation map (docs/cad.md): the shown surface coloured by its
//! distance to the B-spline surface the CAD export fits (docs/math.md §10),
//! green within the tolerance, yellow up to twice it, red beyond.
//!
//! The fit is redone at the display depth after each edit when the last one
//! took less than [`FRAME_BUDGET_S`]; a slower fit waits until no mouse
//! button is held (the drag has ended).

use crate::scene::Scene;
use crate::scene::cad;
use bevy::prelude::*;
use streamline_kernel::nurbs::{FitOptions, deviation_field};

/// A frame at 60 Hz, seconds: a fit within it is redone on every edit.
pub const FRAME_BUDGET_S: f64 = 1.0 / 60.0;

/// The last fit behind the map and its figures.
#[derive(Resource, Debug, Default)]
pub struct DeviationField {
    /// Distance of each shown point to the fitted surface (row-major, as the
    /// surface's points), `None` until the map is shown or when the fit failed.
    pub values: Option<Vec<f64>>,
    /// Absolute tolerance, largest and mean deviation (checked one depth
    /// finer), poles `(u, v)`.
    pub tolerance: f64,
    pub max: f64,
    pub mean: f64,
    pub poles: (usize, usize),
    /// Seconds the last fit took (samples, fit and field).
    pub seconds: f64,
    /// Why the last fit failed (what to do is in the message).
    pub error: Option<String>,
    /// The surface changed since the map was computed.
    pub stale: bool,
}

impl DeviationField {
    /// Whether edits refit at once (the last fit stayed within a frame).
    pub fn live(&self) -> bool {
        self.seconds <= FRAME_BUDGET_S
    }

    /// Refits `scene` at its display depth with `opts`.
    pub fn refit(&mut self, scene: &Scene, opts: &FitOptions) {
        let t0 = std::time::Instant::now();
        let depth = scene.display_depth;
        let result = cad::fit_scene(scene, depth, opts).and_then(|f| {
            let shown = cad::samples(scene, depth)?;
            let field = deviation_field(&f.fit.surface, &shown);
            Ok((f, field))
        });
        self.stale = false;
        self.seconds = t0.elapsed().as_secs_f64();
        match result {
            Ok((f, field)) => {
                let r = &f.fit.report;
                self.tolerance = r.tolerance;
                self.max = r.deviation.max;
                self.mean = r.deviation.mean;
                self.poles = r.poles;
                self.values = Some(field.into_data());
                self.error = None;
            }
            Err(e) => {
                self.values = None;
                self.error = Some(e.to_string());
            }
        }
    }
}

/// The map's `u` coordinate: a third of the ramp per tolerance, so the
/// three-texel ramp gives green (≤ tol), yellow (≤ 2 tol), red (beyond).
pub fn band_u(d: f64, tolerance: f64) -> f32 {
    ((d / tolerance.max(f64::MIN_POSITIVE)) / 3.0).clamp(0.0, 1.0) as f32
}

/// The three colours of the map.
pub const BANDS: [[u8; 3]; 3] = [[40, 170, 70], [235, 200, 40], [210, 45, 40]];
