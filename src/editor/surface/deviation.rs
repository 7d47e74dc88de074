//! The deviation map (docs/cad.md): the shown surface coloured by its
//! distance to the B-spline surface the CAD export fits (docs/math.md §10),
//! green within the tolerance, yellow up to twice it, red beyond. A design
//! of several patches is measured against the faces of the one STEP shell
//! it exports (seams held, docs/math.md §11). One map holds every patch's
//! distances, by its entity, the first patch's as any other's
//! ([`DeviationField::maps`], made by [`DeviationField::refit`]); each
//! patch's mesh takes its coordinates from it ([`DeviationField::uv`]).
//!
//! The fit is redone at the display depth after each edit when the last one
//! took less than [`FRAME_BUDGET_S`]; a slower fit waits until no mouse
//! button is held (the drag has ended).

use crate::scene::Scene;
use crate::scene::design::document::Document;
use crate::scene::fit::deviation::document_deviation;
use crate::scene::fit::surface;
use bevy::prelude::*;
use std::collections::HashMap;
use streamline_kernel::nurbs::FitOptions;

/// A frame at 60 Hz, seconds: a fit within it is redone on every edit.
pub const FRAME_BUDGET_S: f64 = 1.0 / 60.0;

/// The last fit behind the map and its figures.
#[derive(Resource, Debug, Default)]
pub struct DeviationField {
    /// Every measured patch's distances, by its entity: empty until the map
    /// is shown or when the fit failed.
    pub maps: HashMap<Entity, PatchDistances>,
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
    /// With several patches, each face's figures, in the document's order
    /// (empty for one patch: the figures above are its face's).
    pub faces: Vec<FaceFigures>,
    /// With several patches: the shell had to be sampled at this depth,
    /// deeper than the one shown, to meet the tolerance (the map measures
    /// the points shown against it, as the one-patch map does).
    pub deeper: Option<u32>,
    /// Counts the fits (what the other patches' maps were made from).
    pub generation: u64,
    /// With several patches, when the first patch is shown over both halves
    /// of a mirrored document: its one-patch fit's figures, which its
    /// colours are measured against.
    pub first_alone: Option<FaceFigures>,
}

/// A patch's part of the map: the distance of each shown point to its
/// fitted surface (row-major, as its mesh's points) and the tolerance it is
/// coloured against (its face's).
#[derive(Debug, Clone, PartialEq)]
pub struct PatchDistances {
    pub distances: Vec<f64>,
    pub tolerance: f64,
}

/// One face of a shell: the patch's name, its tolerance, largest and mean
/// deviation (checked one depth finer) and poles.
#[derive(Debug, Clone, PartialEq)]
pub struct FaceFigures {
    pub name: String,
    pub tolerance: f64,
    pub max: f64,
    pub mean: f64,
    pub poles: (usize, usize),
}

impl DeviationField {
    /// Whether edits refit at once (the last fit stayed within a frame).
    pub fn live(&self) -> bool {
        self.seconds <= FRAME_BUDGET_S
    }

    /// The map's coordinates on patch `p`'s mesh ([`band_u`] of each
    /// distance against its tolerance); `None` when it was not measured.
    pub fn uv(&self, p: Entity) -> Option<Vec<[f32; 2]>> {
        let m = self.maps.get(&p)?;
        Some(
            m.distances
                .iter()
                .map(|&d| [band_u(d, m.tolerance), 0.5])
                .collect(),
        )
    }

    /// Refits `doc`, whose patches are the entities `ids` (in its order)
    /// and whose first patch's scene is `first`, and measures every patch's
    /// points at the display depth into [`Self::maps`]. One patch is fitted
    /// as the one-face export fits it; several as the STEP export fits its
    /// shell, each patch against its face ([`Self::faces`]). A first patch
    /// shown with `first_points` points other than its face's (a mirrored
    /// document shows it over both halves, one surface) is measured against
    /// its one-patch fit instead, which is that surface's
    /// ([`Self::first_alone`]).
    pub fn refit(
        &mut self,
        first: &Scene,
        doc: &Document,
        ids: &[Entity],
        first_points: usize,
        opts: &FitOptions,
    ) {
        if doc.patches.len() < 2 {
            if let Some(&e) = ids.first() {
                self.refit_one(first, e, opts);
            }
            return;
        }
        let depth = first.display_depth;
        self.begin();
        let t0 = std::time::Instant::now();
        let result = document_deviation(doc, depth, opts);
        match result {
            Ok(d) => {
                self.deeper = (d.depth != depth).then_some(d.depth);
                self.error = None;
                let mut alone = false;
                for (i, (p, e)) in d.patches.into_iter().zip(ids).enumerate() {
                    if i == 0 {
                        self.tolerance = p.tolerance;
                        self.poles = p.poles;
                    }
                    self.faces.push(FaceFigures {
                        name: p.name,
                        tolerance: p.tolerance,
                        max: p.deviation.max,
                        mean: p.deviation.mean,
                        poles: p.poles,
                    });
                    let field = p.field;
                    if i == 0 && field.data().len() != first_points {
                        alone = true;
                        continue;
                    }
                    let distances = field.into_data();
                    (self.maps).insert(
                        *e,
                        PatchDistances {
                            distances,
                            tolerance: p.tolerance,
                        },
                    );
                }
                self.max = self.faces.iter().map(|f| f.max).fold(0.0, f64::max);
                let n = self.faces.len().max(1) as f64;
                self.mean = self.faces.iter().map(|f| f.mean).sum::<f64>() / n;
                if alone
                    && let (Some(&e), Ok((f, field))) =
                        (ids.first(), surface::fit_shown(first, opts))
                {
                    let r = &f.fit.report;
                    self.tolerance = r.tolerance;
                    let distances = field.into_data();
                    let tolerance = r.tolerance;
                    self.maps.insert(
                        e,
                        PatchDistances {
                            distances,
                            tolerance,
                        },
                    );
                    self.first_alone = Some(FaceFigures {
                        name: self.faces[0].name.clone(),
                        tolerance: r.tolerance,
                        max: r.deviation.max,
                        mean: r.deviation.mean,
                        poles: r.poles,
                    });
                }
            }
            Err(e) => self.error = Some(e.to_string()),
        }
        // a refusal is timed too: a slow one waits for the drag to end
        self.seconds = t0.elapsed().as_secs_f64();
    }

    /// Refits a one-patch design, `scene`, whose patch is the entity `e`,
    /// at its display depth with `opts`.
    fn refit_one(&mut self, scene: &Scene, e: Entity, opts: &FitOptions) {
        self.begin();
        let t0 = std::time::Instant::now();
        let result = surface::fit_shown(scene, opts);
        self.seconds = t0.elapsed().as_secs_f64();
        match result {
            Ok((f, field)) => {
                let r = &f.fit.report;
                self.tolerance = r.tolerance;
                self.max = r.deviation.max;
                self.mean = r.deviation.mean;
                self.poles = r.poles;
                let distances = field.into_data();
                let tolerance = r.tolerance;
                self.maps.insert(
                    e,
                    PatchDistances {
                        distances,
                        tolerance,
                    },
                );
                self.error = None;
            }
            Err(e) => self.error = Some(e.to_string()),
        }
    }

    /// Forgets the last fit's maps before a new one, which counts.
    fn begin(&mut self) {
        self.stale = false;
        self.generation += 1;
        self.maps.clear();
        self.faces.clear();
        self.deeper = None;
        self.first_alone = None;
    }
}

/// The map's `u` coordinate: a third of the ramp per tolerance, so the
/// three-texel ramp gives green (≤ tol), yellow (≤ 2 tol), red (beyond).
pub fn band_u(d: f64, tolerance: f64) -> f32 {
    ((d / tolerance.max(f64::MIN_POSITIVE)) / 3.0).clamp(0.0, 1.0) as f32
}

/// The three colours of the map.
pub const BANDS: [[u8; 3]; 3] = [[40, 170, 70], [235, 200, 40], [210, 45, 40]];

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::design::document_io::load;
    use std::path::Path;
    use streamline_kernel::nurbs::Tolerance;

    fn hood_screen_wing() -> Document {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/hood-screen-wing.ron");
        load(&path).unwrap()
    }

    /// The points of the first patch as shown (what the editor's surface has).
    fn shown_points(scene: &Scene) -> usize {
        surface::samples(scene, scene.display_depth)
            .unwrap()
            .points
            .data()
            .len()
    }

    /// The fields go to their patches' entities, the first's as the
    /// others', each face's figures in the document's order; a shell sampled deeper than shown still colours
    /// the points shown and says how deep; a refusal says why, timed like a
    /// fit.
    #[test]
    fn a_document_fit_fills_each_patch_or_says_why_not() {
        let mut doc = hood_screen_wing();
        let ids = [
            Entity::from_bits(7),
            Entity::from_bits(8),
            Entity::from_bits(9),
        ];
        let first = doc.patch_scene(0);
        let n = shown_points(&first);
        let mut d = DeviationField::default();
        d.refit(&first, &doc, &ids, n, &FitOptions::default());
        assert_eq!(d.generation, 1);
        assert!(d.error.is_none() && d.deeper.is_none() && d.first_alone.is_none());
        let names: Vec<&str> = d.faces.iter().map(|f| f.name.as_str()).collect();
        assert_eq!(names, ["hood", "screen", "wing"]);
        assert_eq!(
            d.maps.get(&ids[0]).map(|m| m.distances.len()),
            Some(n),
            "the first patch's distances"
        );
        assert_eq!(d.maps.len(), 3);
        for (e, f) in ids.iter().zip(&d.faces) {
            let m = &d.maps[e];
            assert_eq!(m.tolerance, f.tolerance);
            assert!(m.distances.iter().all(|v| v.is_finite() && *v >= 0.0));
            let uv = d.uv(*e).unwrap();
            assert_eq!(uv.len(), m.distances.len());
            assert_eq!(uv[0][0], band_u(m.distances[0], m.tolerance));
        }
        assert_eq!(d.tolerance, d.faces[0].tolerance);
        assert_eq!(d.max, d.faces.iter().map(|f| f.max).fold(0.0, f64::max));
        assert!(!d.stale && d.seconds > 0.0);

        // depth 0's points cannot carry the tolerance: sampled at depth 4
        let mut shallow = first.clone();
        shallow.display_depth = 0;
        d.refit(
            &shallow,
            &doc,
            &ids,
            shown_points(&shallow),
            &FitOptions::default(),
        );
        assert_eq!(d.deeper, Some(4));
        assert_eq!(
            d.maps.get(&ids[0]).map(|m| m.distances.len()),
            Some(shown_points(&shallow))
        );
        assert_eq!(d.maps.len(), 3);
        assert_eq!(d.faces.len(), 3);

        // a tolerance no depth meets: refused, with the reason
        let tight = FitOptions {
            tolerance: Tolerance::Absolute(1e-12),
            ..FitOptions::default()
        };
        d.refit(&first, &doc, &ids, n, &tight);
        assert_eq!(d.generation, 3);
        let e = d.error.as_deref().expect("refused");
        assert!(e.contains("loosen the tolerance"), "{e}");
        assert!(d.maps.is_empty() && d.faces.is_empty());
        assert!(d.uv(ids[0]).is_none());
        assert!(d.seconds > 0.0, "a refusal is timed");

        // mirrored: the first patch is shown over both halves, one surface,
        // so its colours come from its one-patch fit, as one patch's do
        doc.mirror = true;
        let first = doc.patch_scene(0);
        let n = shown_points(&first);
        d.refit(&first, &doc, &ids, n, &FitOptions::default());
        let alone = d.first_alone.clone().expect("measured over both halves");
        let mut one = DeviationField::default();
        let alone_doc = Document::from_scene(first.clone());
        one.refit(&first, &alone_doc, &ids[..1], n, &FitOptions::default());
        assert_eq!(d.maps[&ids[0]], one.maps[&ids[0]]);
        assert_eq!(d.maps[&ids[0]].distances.len(), n);
        assert!(one.faces.is_empty(), "one patch: no shell");
        assert_eq!((alone.tolerance, alone.max), (one.tolerance, one.max));
        assert_eq!(d.tolerance, one.tolerance);
        assert_eq!(d.maps.len(), 3, "the other patches against their faces");
        assert_eq!(d.faces.len(), 3);
    }
}
