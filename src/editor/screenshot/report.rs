//! The screenshot run's report, for GUI tests: the model and the views as
//! they were when the picture was taken (`REPORT`, JSON), with the largest
//! gap between what the views show and the model.

use super::super::coords::to_view;
use super::super::handles::sphere_view::{SubdividedPoints, cloud_points};
use super::super::interaction::Selection;
use super::super::loop_mesh::MeshView;
use super::super::surface::reference_map::ReferenceField;
use super::super::surface::shaded::{ShownSurface, SurfaceEntity};
use super::super::view::frame_timing::FrameTiming;
use super::{ScreenshotRequest, ShotProgress};
use crate::ecs::components::{LevelData, SubdivisionLevel};
use crate::ecs::patch::PatchRef;
use crate::ecs::{History, Model, Stats, SurfaceData};
use bevy::ecs::system::SystemParam;
use bevy::mesh::VertexAttributeValues;
use bevy::prelude::*;
use std::path::{Path, PathBuf};

/// What a GUI test reads back after the run.
#[derive(serde::Serialize)]
pub(super) struct Report {
    /// The file the scene was opened from or saved to.
    path: Option<PathBuf>,
    /// The scene's name.
    scene: String,
    undo: usize,
    redo: usize,
    unsaved: bool,
    selection: Option<(usize, usize)>,
    last_edit: String,
    net: Vec<[f64; 3]>,
    cols: usize,
    /// The initial curve's control tangents.
    initial: Vec<[f64; 3]>,
    /// The model's systems in frames with an edit: last and largest (ms).
    model_ms: (f64, f64),
    /// All our systems (model and editor) in frames with an edit: last and largest (ms).
    ours_ms: (f64, f64),
    /// Display depth.
    depth: u32,
    /// Per system over frames with an edit: total ms, largest ms, frames
    /// (`STREAMLINE_STUDIO_METER_DETAIL=1`).
    detail: Vec<(String, f64, f64, u32)>,
    /// The dearest frame with an edit, system by system (ms), with the detail.
    worst_frame: Vec<(String, f64)>,
    /// All our systems in each frame with an edit (ms), oldest first.
    ours_frames: Vec<f64>,
    /// With the detail: page faults and involuntary context switches in our
    /// systems in each of those frames.
    frame_faults: Vec<[u64; 2]>,
    /// With the detail: a fixed piece of work's CPU µs at four points of
    /// each of those frames (how fast the machine was).
    frame_probe: Vec<Vec<f64>>,
    /// Frames drawn while a mesh was being opened off the frame.
    busy_frames: u32,
    /// The Loop mesh panel's last error, if any.
    mesh_error: Option<String>,
    /// The largest gap between what the views show and the model, when the
    /// picture was taken: the surface mesh's positions and normals against
    /// the model's points and normals, the sphere view's points against the
    /// display depth's tangents it shows (`sphere_view::cloud_points`; each
    /// made `f32` as the views make it; `0`
    /// when every row and column that edits rewrote in place got there).
    shown_gap: Option<f64>,
    /// A document's patches as drawn: name, shown, vertices of its mesh
    /// (0 for the first patch while its incremental mesh shows it).
    patches: Vec<(String, bool, usize)>,
    /// The active patch's name.
    active_patch: Option<String>,
    /// The seams as drawn: A, B, edge, continuity, verdict, gap, angle (°),
    /// curvature deviation (`NaN` when not measured).
    seams: Vec<SeamShown>,
    /// The map to the reference (Analysis ▸ to reference), once measured.
    reference: Option<ReferenceShown>,
}

/// The map to the reference in the report: its largest and mean distance,
/// its tolerance, and its last measurement's points, whether it was made
/// during a drag, and how many there were
/// ([`ReferenceField`]).
#[derive(serde::Serialize)]
struct ReferenceShown {
    max: f64,
    mean: f64,
    tolerance: f64,
    measured: usize,
    live: bool,
    generation: u64,
}

/// A seam in the report: A, B, edge, continuity, verdict, gap, angle (°),
/// curvature deviation.
type SeamShown = (String, String, String, String, String, f64, f64, f64);

/// The patches and seams a GUI test reads back.
pub(super) type PatchReport<'w, 's> = (
    Res<'w, crate::editor::seams::Seams>,
    Res<'w, crate::editor::surface::patches::PatchMeshes>,
    Res<'w, crate::ecs::joined::ActivePatch>,
    Query<
        'w,
        's,
        (
            Entity,
            &'static crate::ecs::joined::PatchSlot,
            Has<crate::ecs::joined::PatchHidden>,
            Option<&'static crate::ecs::joined::PatchSurface>,
        ),
    >,
);

/// What the report is made from.
#[derive(SystemParam)]
pub(super) struct ReportSources<'w, 's> {
    model: Res<'w, Model>,
    patch: PatchRef<'w, 's>,
    history: Res<'w, History>,
    stats: Res<'w, Stats>,
    timing: Res<'w, FrameTiming>,
    /// The Loop mesh panel (its last error; whether it is opening a mesh).
    pub(super) mesh: Res<'w, MeshView>,
    reference: Res<'w, ReferenceField>,
    pub(super) patches: PatchReport<'w, 's>,
}

/// Writes the report to `path`.
pub(super) fn write(path: &Path, sources: &ReportSources, selection: &Selection, p: &ShotProgress) {
    let ReportSources {
        model,
        patch,
        history,
        stats,
        timing,
        mesh,
        reference,
        patches: (seams, patch_meshes, active, slots),
    } = sources;
    // the control net, read from its handle entities
    let net = patch.net();
    let report = Report {
        path: model.path.clone(),
        scene: patch.name().to_string(),
        undo: history.undo_len(),
        redo: history.redo_len(),
        unsaved: model.unsaved,
        selection: selection.cell(),
        last_edit: stats.last.edit.clone(),
        net: net.data().iter().map(|v| v.to_array()).collect(),
        cols: net.cols(),
        initial: patch
            .design()
            .initial()
            .qi()
            .tangents()
            .iter()
            .map(|v| v.to_array())
            .collect(),
        model_ms: (timing.last_ms, timing.max_ms),
        ours_ms: (timing.ours_last_ms, timing.ours_max_ms),
        depth: patch.structure().display_depth,
        detail: timing
            .detail
            .iter()
            .map(|(k, v)| (k.clone(), v.0, v.1, v.2))
            .collect(),
        worst_frame: timing.worst_frame.clone(),
        ours_frames: timing.recent_frames.0.iter().copied().collect(),
        frame_faults: timing.recent_detail.iter().map(|d| d.faults).collect(),
        frame_probe: timing
            .recent_detail
            .iter()
            .map(|d| d.probe.clone())
            .collect(),
        busy_frames: p.busy_frames,
        mesh_error: mesh.text.error.clone(),
        shown_gap: p.shown_gap,
        patches: {
            let mut v: Vec<_> = slots.iter().collect();
            v.sort_by_key(|r| r.1.index);
            v.into_iter()
                .map(|(e, slot, hidden, surface)| {
                    let n = surface
                        .and_then(|s| patch_meshes.mesh(e, s))
                        .map_or(0, |(p, _)| p.data().len());
                    (slot.name.clone(), !hidden, n)
                })
                .collect()
        },
        active_patch: slots
            .iter()
            .find(|r| match active.0 {
                Some(e) => r.0 == e,
                None => r.1.index == 0,
            })
            .map(|r| r.1.name.clone()),
        seams: seams
            .lines
            .iter()
            .map(|l| {
                let r = l.report.as_ref();
                (
                    l.a_name.clone(),
                    l.b_name.clone(),
                    l.edge.name().to_string(),
                    l.continuity.name().to_string(),
                    l.verdict.name().to_string(),
                    r.map_or(f64::NAN, |r| r.gap),
                    r.map_or(f64::NAN, |r| r.angle_deg),
                    r.map_or(f64::NAN, |r| r.curvature_dev),
                )
            })
            .collect(),
        reference: reference.values.as_ref().map(|_| ReferenceShown {
            max: reference.distances.max,
            mean: reference.distances.mean,
            tolerance: reference.tolerance,
            measured: reference.measured,
            live: reference.live,
            generation: reference.generation,
        }),
    };
    if let Ok(text) = serde_json::to_string_pretty(&report) {
        let _ = std::fs::write(path, text);
    }
}

/// Measures [`Report::shown_gap`] once the picture is taken (reports only).
#[allow(clippy::too_many_arguments)]
pub(super) fn measure_shown_gap(
    req: Res<ScreenshotRequest>,
    mut p: ResMut<ShotProgress>,
    patch: crate::ecs::patch::PatchRef,
    data: Res<SurfaceData>,
    meshes: Res<Assets<Mesh>>,
    (surface, shown): (Query<&Mesh3d, With<SurfaceEntity>>, Res<ShownSurface>),
    points: Query<&Mesh3d, With<SubdividedPoints>>,
    levels: Query<(&SubdivisionLevel, &LevelData)>,
) {
    if req.report.is_none() || p.captured.is_none() || p.shown_gap.is_some() {
        return;
    }
    let attr = |m: &Mesh3d, a| f32x3(&meshes, m, a);
    let mut worst = 0.0f64;
    // (a G2 run's first patch shows its stack's cut instead)
    if let Ok(m) = surface.single()
        && !shown.from_stack
    {
        let (Some(pos), Some(nrm)) = (
            attr(m, Mesh::ATTRIBUTE_POSITION),
            attr(m, Mesh::ATTRIBUTE_NORMAL),
        ) else {
            return;
        };
        worst = worst.max(gap(pos, data.points.data().iter().map(|q| q.as_vec3())));
        worst = worst.max(gap(nrm, data.normals.iter().map(|q| q.as_vec3())));
    }
    let depth = patch.structure().display_depth;
    if let (Ok(m), Some((_, level))) = (points.single(), levels.iter().find(|(l, _)| l.0 == depth))
        && let Some(pos) = attr(m, Mesh::ATTRIBUTE_POSITION)
    {
        // the cloud shows at most a depth-4 density (`cloud_points`)
        let (rows, cols) = level.0.shape();
        let want: Vec<Vec3> = cloud_points(level.0.tangents.data(), rows, cols, depth)
            .map(to_view)
            .collect();
        worst = worst.max(gap(pos, want.into_iter()));
    }
    p.shown_gap = Some(worst);
}

/// A mesh's `Float32x3` attribute, if it has one.
fn f32x3<'a>(
    meshes: &'a Assets<Mesh>,
    m: &Mesh3d,
    attribute: bevy::mesh::MeshVertexAttribute,
) -> Option<&'a [[f32; 3]]> {
    match meshes.get(&m.0)?.attribute(attribute)? {
        VertexAttributeValues::Float32x3(v) => Some(v),
        _ => None,
    }
}

/// The largest coordinate gap between what a view shows and what it should
/// (`f64::MAX` when their sizes differ).
fn gap(shown: &[[f32; 3]], want: impl ExactSizeIterator<Item = Vec3>) -> f64 {
    if shown.len() != want.len() {
        return f64::MAX;
    }
    shown
        .iter()
        .zip(want)
        .map(|(a, b)| (Vec3::from_array(*a) - b).abs().max_element() as f64)
        .fold(0.0, f64::max)
}
