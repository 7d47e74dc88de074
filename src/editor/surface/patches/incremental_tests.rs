//! Tests of the first patch's incremental drawing (`super::incremental`)
//! through the one sync: the staging pair swapped in, the changed windows
//! written in place, a hidden surface left alone.

use super::super::analysis_display::AnalysisSettings;
use super::super::shaded::{
    MIRROR_SHADE, ShadedMaterial, ShownSurface, SurfaceEntity, mirror_shades, to_bevy_mesh,
};
use super::{PatchMeshes, sync_surfaces};
use crate::ecs::vertex_mirror::VertexMirror;
use crate::ecs::{Edit, EditMessage, ModelPlugin, ModelSet, SurfaceData};
use crate::scene::Scene;
use bevy::math::DVec3;
use bevy::mesh::{Indices, VertexAttributeValues};
use bevy::prelude::*;

/// Runs the mesh sync only on every `every`-th frame.
#[derive(Resource)]
struct SyncEvery(u64, u64);

/// Counts the frames (before the model's systems).
fn count(mut every: ResMut<SyncEvery>) {
    every.1 += 1;
}

fn due(every: Res<SyncEvery>) -> bool {
    (every.1 - 1).is_multiple_of(every.0)
}

/// The model with the mesh sync (no window, no renderer). Without the
/// time plugin's fixed steps, messages are dropped after two frames, as
/// strictly as Bevy ever drops them: a reader that skips two frames
/// misses some.
fn app(every: u64, mirror: bool) -> App {
    let mut s = Scene::from_design("car1", streamline_kernel::levels::presets::car1(), 3);
    s.edit_depth = 0;
    let mut app = App::new();
    app.add_plugins(TaskPoolPlugin::default())
        .add_plugins(ModelPlugin::new(s))
        .init_resource::<Assets<Mesh>>()
        .init_resource::<ShownSurface>()
        .init_resource::<AnalysisSettings>()
        .insert_resource(ShadedMaterial(Handle::default()))
        .init_resource::<PatchMeshes>()
        .insert_resource(SyncEvery(every, 0))
        .add_systems(First, count)
        .add_systems(Update, sync_surfaces.after(ModelSet::Output).run_if(due));
    if mirror {
        app.init_resource::<VertexMirror>();
    }
    let mesh = app
        .world_mut()
        .resource_mut::<Assets<Mesh>>()
        .add(to_bevy_mesh(&[], &[], &[]));
    app.world_mut().spawn((SurfaceEntity, Mesh3d(mesh)));
    app
}

/// The Bevy mesh holds the model's surface, bit for bit (as `f32`).
fn mesh_is_model(app: &mut App) -> Result<(), String> {
    let w = app.world_mut();
    let handle = w
        .query_filtered::<&Mesh3d, With<SurfaceEntity>>()
        .single(w)
        .map_err(|e| e.to_string())?
        .0
        .clone();
    let data = w.resource::<SurfaceData>();
    let meshes = w.resource::<Assets<Mesh>>();
    let mesh = meshes.get(&handle).ok_or("no mesh")?;
    let bits = |v: &[DVec3]| -> Vec<[u32; 3]> {
        v.iter()
            .map(|p| p.as_vec3().to_array().map(f32::to_bits))
            .collect()
    };
    let got = |a| match mesh.attribute(a) {
        Some(VertexAttributeValues::Float32x3(v)) => {
            Ok(v.iter().map(|p| p.map(f32::to_bits)).collect::<Vec<_>>())
        }
        _ => Err("no attribute".to_string()),
    };
    if got(Mesh::ATTRIBUTE_POSITION)? != bits(data.points.data()) {
        return Err("positions differ".into());
    }
    if got(Mesh::ATTRIBUTE_NORMAL)? != bits(&data.normals) {
        return Err("normals differ".into());
    }
    match mesh.indices() {
        Some(Indices::U32(i)) if *i == data.indices => Ok(()),
        _ => Err("triangles differ".into()),
    }
}

/// A scripted drag: a control tangent turned a little each frame (one
/// undo group), a second one turned, the drag cancelled (Esc), an undo,
/// a redo and a depth change, so the changed windows move about.
fn script() -> Vec<Vec<Edit>> {
    let mut frames = Vec::new();
    for k in 0..20 {
        let a = 0.02 * k as f64;
        frames.push(vec![Edit::SetDirection {
            row: 4,
            col: 2,
            dir: DVec3::new(a.cos(), a.sin(), 0.3 * a),
        }]);
    }
    frames.push(vec![]);
    for k in 0..7 {
        frames.push(vec![Edit::Rotate {
            row: 0,
            col: 5,
            axis: DVec3::Z,
            radians: 0.03 * k as f64,
        }]);
    }
    frames.push(vec![Edit::CancelGroup(7)]);
    frames.push(vec![Edit::Undo]);
    frames.push(vec![]);
    frames.push(vec![
        Edit::Redo,
        Edit::SetLength {
            row: 8,
            col: 1,
            coefficient: 1.1,
        },
    ]);
    frames.push(vec![Edit::SetDisplayDepth(2)]);
    frames.push(vec![Edit::SetDirection {
        row: 2,
        col: 3,
        dir: DVec3::new(0.2, 1.0, 0.1),
    }]);
    frames.push(vec![]);
    frames.push(vec![]);
    frames
}

/// Plays [`script`] with the sync every `every` frames, checking the mesh
/// after each frame the sync ran; also returns how many of those copies
/// rewrote the whole mesh.
fn drag(every: u64, mirror: bool) -> (App, usize) {
    let mut app = app(every, mirror);
    app.update();
    let mut whole = 0;
    for (n, edits) in script().into_iter().enumerate() {
        for e in edits {
            // the second handle's turns are one group: Esc cancels them
            let group = matches!(e, Edit::Rotate { .. }).then_some(7);
            app.world_mut()
                .write_message(EditMessage { edit: e, group });
        }
        // set again by a copy of the whole mesh in this frame
        app.world_mut().resource_mut::<ShownSurface>().full = false;
        app.update();
        let synced = (app.world().resource::<SyncEvery>().1 - 1).is_multiple_of(every);
        if synced {
            if let Err(e) = mesh_is_model(&mut app) {
                panic!("frame {n}, sync every {every} frames, mirror {mirror}: {e}");
            }
            whole += usize::from(app.world().resource::<ShownSurface>().full);
        }
    }
    // the last frames synced or not, a frame with the sync brings it up
    while !(app.world().resource::<SyncEvery>().1).is_multiple_of(every) {
        app.update();
    }
    app.update();
    (app, whole)
}

/// The surface's changes reach the mesh sync as messages with
/// their windows, read with its own cursor; run only every second or
/// third frame during a drag, the mesh still equals the model bit for bit.
/// The mirrored half (the first half of the rows, the seam excluded) is
/// dimmed, the design's half keeps its colour, for odd (a primal
/// scheme's seam row) and even (a dual scheme's) row counts.
#[test]
fn mirror_shades_dim_exactly_the_reflected_rows() {
    for (rows, dimmed) in [(9, 4), (8, 4), (3, 1), (2, 1)] {
        let shades = mirror_shades(rows, 5);
        assert_eq!(shades.len(), rows * 5);
        for r in 0..rows {
            let want = if r < dimmed { MIRROR_SHADE } else { 1.0 };
            assert!(
                shades[r * 5..(r + 1) * 5].iter().all(|c| c[0] == want),
                "{rows} rows: row {r} should have shade {want}"
            );
        }
    }
}

/// Hidden (a G2 run's first patch, drawn as its cut): the sync copies
/// nothing and pauses the staging pair, so in a drag with the normals
/// deferred the mesh stage makes no normals at all (left behind, the
/// staging pair untouched); after the drag, shown again, the mesh is
/// the model bit for bit. Controls: while hidden the mesh is not the
/// model, and the surface's normals are behind.
#[test]
fn a_hidden_surface_is_not_copied_and_is_exact_once_shown() {
    use crate::ecs::DeferNormals;
    let mut app = app(1, true);
    app.update();
    mesh_is_model(&mut app).unwrap();
    let e = app
        .world_mut()
        .query_filtered::<Entity, With<SurfaceEntity>>()
        .single(app.world())
        .unwrap();
    app.world_mut().entity_mut(e).insert(Visibility::Hidden);
    app.insert_resource(DeferNormals(true));
    for k in 1..=5 {
        let a = 0.03 * k as f64;
        app.world_mut().write_message(EditMessage {
            edit: Edit::SetDirection {
                row: 4,
                col: 2,
                dir: DVec3::new(a.cos(), a.sin(), 0.3 * a),
            },
            group: None,
        });
        app.update();
    }
    assert!(app.world().resource::<VertexMirror>().paused());
    assert!(
        app.world()
            .resource::<SurfaceData>()
            .normals_behind()
            .is_some()
    );
    assert!(mesh_is_model(&mut app).is_err(), "control: not copied");
    // shown while the normals are still behind, in a frame without an
    // edit: nothing is copied (not the normals left behind)
    let before = positions(&mut app);
    app.world_mut().entity_mut(e).insert(Visibility::Inherited);
    app.update();
    assert!(!app.world().resource::<VertexMirror>().paused());
    assert_eq!(positions(&mut app), before, "nothing copied yet");
    // the drag goes on shown: the staging pair is written whole, exact
    app.world_mut().write_message(EditMessage {
        edit: Edit::SetDirection {
            row: 4,
            col: 2,
            dir: DVec3::new(0.9, 0.3, 0.2),
        },
        group: None,
    });
    app.update();
    mesh_is_model(&mut app).unwrap();
    // hidden again, then the drag ends and the surface is shown
    app.world_mut().entity_mut(e).insert(Visibility::Hidden);
    app.update();
    app.insert_resource(DeferNormals(false));
    app.update();
    assert_eq!(app.world().resource::<SurfaceData>().normals_behind(), None);
    app.world_mut().entity_mut(e).insert(Visibility::Inherited);
    app.update();
    mesh_is_model(&mut app).unwrap();
}

/// The drawn mesh's positions, as bits.
fn positions(app: &mut App) -> Vec<[u32; 3]> {
    let w = app.world_mut();
    let handle = w
        .query_filtered::<&Mesh3d, With<SurfaceEntity>>()
        .single(w)
        .unwrap()
        .0
        .clone();
    match w
        .resource::<Assets<Mesh>>()
        .get(&handle)
        .unwrap()
        .attribute(Mesh::ATTRIBUTE_POSITION)
    {
        Some(VertexAttributeValues::Float32x3(v)) => {
            v.iter().map(|p| p.map(f32::to_bits)).collect()
        }
        _ => Vec::new(),
    }
}

#[test]
fn mesh_sync_that_skips_frames_ends_up_exact() {
    for every in [1, 2, 3] {
        for mirror in [false, true] {
            let (mut app, _) = drag(every, mirror);
            mesh_is_model(&mut app)
                .unwrap_or_else(|e| panic!("sync every {every}, mirror {mirror}: {e}"));
            assert!(app.world().resource::<ShownSurface>().built);
        }
    }
}

/// Every second frame the sync misses no message: it patches the union
/// of the windows, and copies the whole mesh only for the depth change
/// (a new shape); every third frame it has missed changes and copies all.
#[test]
fn mesh_sync_patches_windows_unless_it_missed_changes() {
    let frames = script().len();
    let (_, whole) = drag(1, false);
    assert_eq!(whole, 1, "every frame: only the depth change copies all");
    let (_, whole) = drag(2, false);
    assert_eq!(
        whole, 1,
        "every other frame: only the depth change copies all"
    );
    let (_, whole) = drag(3, false);
    assert!(
        whole > frames / 6,
        "every third frame the sync missed changes: {whole} whole copies in {frames} frames"
    );
}

/// With the mesh stage's `f32` staging pair ([`VertexMirror`]) the sync
/// swaps buffers, and what each pair lacks is tracked by the mesh stage
/// itself: however many frames the sync skips, only the depth change
/// (new triangles) builds the mesh afresh; the mesh equals the model
/// bit for bit after every sync (checked in `drag`).
#[test]
fn mesh_sync_swaps_the_staged_pair_even_after_missed_changes() {
    for every in [1, 2, 3] {
        let (_, whole) = drag(every, true);
        assert_eq!(
            whole, 1,
            "sync every {every} frames: only the depth change copies all"
        );
    }
}
