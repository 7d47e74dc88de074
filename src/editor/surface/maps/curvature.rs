//! The curvature maps' values (docs/math.md §4): each shown patch mesh's
//! `K` and `H`, made from the points it shows ([`surface_curvature`]) and
//! kept until they change, and the one colour limit every patch's map uses,
//! the one the legend shows with the values' range ([`CurvatureField`]), so
//! that a colour means the same value on every patch.

use super::super::analysis_display::{AnalysisSettings, CurvatureField, SurfaceMode};
use bevy::prelude::Entity;
use std::collections::HashMap;
use streamline_kernel::analysis::{SurfaceCurvature, surface_curvature};
use streamline_kernel::{DVec3, Grid};

/// The share of `|value|` the automatic limit covers (border spikes do not
/// wash the map out).
const ROBUST_SHARE: f64 = 0.98;

/// A patch mesh's curvature and its ranges.
struct PatchCurvature {
    values: SurfaceCurvature,
    gaussian: (f64, f64),
    mean: (f64, f64),
}

impl PatchCurvature {
    /// The values the map `mode` shows: `K` for the Gaussian map, else `H`.
    fn of(&self, mode: SurfaceMode) -> &[f64] {
        if mode == SurfaceMode::Gaussian {
            &self.values.gaussian
        } else {
            &self.values.mean
        }
    }
}

/// What the limit was chosen from.
#[derive(Debug, Clone, PartialEq)]
struct LimitKey {
    mode: SurfaceMode,
    /// The fixed limit's bits (`None`: automatic).
    fixed: Option<u64>,
    /// The meshes whose values it covers, in order.
    meshes: Vec<Entity>,
}

/// The curvature of the shown patch meshes, by mesh entity, and the limit
/// chosen from them.
#[derive(Default)]
pub(super) struct Curvatures {
    of: HashMap<Entity, PatchCurvature>,
    /// `None`: choose the limit again.
    limit: Option<LimitKey>,
}

impl Curvatures {
    /// Forgets mesh `e`'s values (what it shows changed, or it is gone).
    pub(super) fn forget(&mut self, e: Entity) {
        if self.of.remove(&e).is_some() {
            self.limit = None;
        }
    }

    /// Keeps the values of the meshes `keep` says.
    pub(super) fn retain(&mut self, keep: impl Fn(Entity) -> bool) {
        let before = self.of.len();
        self.of.retain(|e, _| keep(*e));
        if self.of.len() != before {
            self.limit = None;
        }
    }

    /// Makes mesh `e`'s values from `points` unless they are kept; the
    /// microseconds that took (0 when kept).
    pub(super) fn make(&mut self, e: Entity, points: &Grid<DVec3>) -> f64 {
        if self
            .of
            .get(&e)
            .is_some_and(|c| c.values.gaussian.len() == points.data().len())
        {
            return 0.0;
        }
        let t0 = std::time::Instant::now();
        let values = surface_curvature(points);
        let c = PatchCurvature {
            gaussian: SurfaceCurvature::range(&values.gaussian),
            mean: SurfaceCurvature::range(&values.mean),
            values,
        };
        self.of.insert(e, c);
        self.limit = None;
        t0.elapsed().as_secs_f64() * 1e6
    }

    /// Mesh `e`'s values of the map `mode` shows (`K` or `H`), if made.
    pub(super) fn values(&self, e: Entity, mode: SurfaceMode) -> Option<&[f64]> {
        Some(self.of.get(&e)?.of(mode))
    }

    /// The map's limit over the values of `meshes` (in a fixed order): the
    /// robust limit of all of them together ([`SurfaceCurvature::robust_limit`])
    /// or the fixed one; `field` takes it and the ranges of `K` and `H`.
    pub(super) fn limit(
        &mut self,
        settings: &AnalysisSettings,
        meshes: Vec<Entity>,
        field: &mut CurvatureField,
    ) -> f64 {
        let key = LimitKey {
            mode: settings.mode,
            fixed: (!settings.auto_range).then_some(settings.limit.to_bits()),
            meshes,
        };
        if self.limit.as_ref() == Some(&key) {
            return field.limit;
        }
        let made: Vec<&PatchCurvature> = key.meshes.iter().filter_map(|e| self.of.get(e)).collect();
        if made.is_empty() {
            // nothing shown: the legend keeps what it showed
            return field.limit;
        }
        let span = |r: fn(&PatchCurvature) -> (f64, f64)| {
            made.iter()
                .map(|&c| r(c))
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), (a, b)| {
                    (lo.min(a), hi.max(b))
                })
        };
        field.gaussian_range = span(|c| c.gaussian);
        field.mean_range = span(|c| c.mean);
        let mode = settings.mode;
        field.limit = if !settings.auto_range {
            settings.limit.abs().max(1e-12)
        } else if let [one] = made.as_slice() {
            SurfaceCurvature::robust_limit(one.of(mode), ROBUST_SHARE)
        } else {
            let all: Vec<f64> = made
                .iter()
                .flat_map(|c| c.of(mode).iter().copied())
                .collect();
            SurfaceCurvature::robust_limit(&all, ROBUST_SHARE)
        };
        self.limit = Some(key);
        field.limit
    }
}
