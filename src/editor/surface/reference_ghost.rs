//! The reference as a ghost (View ▸ Reference, docs/math.md §12): the face
//! the design's `reference` names, drawn as a translucent, lightly shaded
//! mesh over the design (alpha blended, so it writes no depth and hides
//! nothing). A B-spline face is sampled [`GHOST_SAMPLES`] × [`GHOST_SAMPLES`]
//! over its parameter domain; a triangle mesh reference (an OBJ or STL) is
//! drawn as its own triangles ([`ghost_triangles`]).
//!
//! While File ▸ Import surface… or File ▸ Reference… is open with a face
//! chosen, that face is drawn instead, in another colour, so the designer
//! sees which face they pick: the dialogs keep it in [`GhostPreview`]. The mesh is built again only when what is
//! drawn changes (the file, the face, or preview against reference); a
//! file that cannot be read is [`ReferenceGhost::error`], shown in the File
//! panel, and nothing is drawn.
//!
//! The geometry is kept in [`ReferenceGhost`] in `f64` (what the tests
//! check against the face); the Bevy mesh is made from it only where the
//! renderer's assets exist.

use super::super::coords::kernel_to_view;
use super::super::interaction::EditorSet;
use crate::ecs::patch::PatchRef;
use bevy::asset::RenderAssetUsages;
use bevy::mesh::{Indices, PrimitiveTopology};
use bevy::prelude::*;
use std::path::PathBuf;
use std::sync::Arc;
use streamline_kernel::fit::ReferenceSurface;
use streamline_kernel::streamline::surface_mesh::{SurfaceMesh, write_indices};
use streamline_kernel::{DVec3, Grid};
use streamline_reference::ReferenceFile;

/// Samples of a B-spline face along each parameter.
pub const GHOST_SAMPLES: usize = 64;

/// What the ghost shows: a file's face, as the design's reference or as a
/// dialog's choice (preview).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct GhostKey {
    /// The reference file.
    pub path: PathBuf,
    /// The face in it.
    pub face: usize,
    /// The face chosen in an open dialog (drawn in the preview colour).
    pub preview: bool,
}

/// The ghost's state: whether it is shown, what it was built for, and its
/// triangles in kernel coordinates.
#[derive(Resource, Debug, Default)]
pub struct ReferenceGhost {
    /// View ▸ Reference: draw the design's reference.
    pub shown: bool,
    /// What the geometry was built for (also when that failed); `None`
    /// when nothing is to be drawn.
    pub key: Option<GhostKey>,
    /// Why the face could not be read or drawn.
    pub error: Option<String>,
    /// The vertices (kernel coordinates, metres).
    pub positions: Vec<DVec3>,
    /// Three indices into [`Self::positions`] a triangle.
    pub indices: Vec<u32>,
    /// Counts the builds (the Bevy mesh follows it).
    pub generation: u64,
}

/// The face chosen in an open dialog (File ▸ Import surface…, File ▸
/// Reference…): its file, the face, and the file as read. The dialogs keep
/// it (`files::reference`); the ghost draws it before the reference.
#[derive(Resource, Debug, Default, Clone)]
pub struct GhostPreview(pub Option<(PathBuf, usize, Arc<ReferenceFile>)>);

/// Where the ghost's geometry is built: a dialog's [`GhostPreview`] is kept
/// before it.
#[derive(SystemSet, Debug, Clone, PartialEq, Eq, Hash)]
pub struct GhostBuild;

/// Marks the ghost's mesh entity.
#[derive(Component)]
pub struct GhostEntity;

/// The ghost's two materials: the reference's and a dialog's preview.
#[derive(Resource)]
struct GhostMaterials {
    reference: Handle<StandardMaterial>,
    preview: Handle<StandardMaterial>,
}

pub struct ReferenceGhostPlugin;

impl Plugin for ReferenceGhostPlugin {
    fn build(&self, app: &mut App) {
        app.init_resource::<ReferenceGhost>()
            .init_resource::<GhostPreview>()
            .add_systems(
                Update,
                build_ghost.in_set(EditorSet::Present).in_set(GhostBuild),
            )
            .add_systems(
                Update,
                draw_ghost
                    .in_set(EditorSet::Present)
                    .after(build_ghost)
                    .run_if(resource_exists::<Assets<Mesh>>)
                    .run_if(resource_exists::<Assets<StandardMaterial>>),
            );
    }
}

/// The positions and triangles of face `face` of `file`: a triangle mesh's
/// own (an OBJ or STL reference), or a B-spline face sampled
/// [`GHOST_SAMPLES`]² over its domain.
pub fn ghost_triangles(
    file: &ReferenceFile,
    face: usize,
) -> Result<(Vec<DVec3>, Vec<u32>), String> {
    if let Some(mesh) = file.mesh(face).map_err(|e| e.to_string())? {
        let indices = mesh.triangles().iter().flatten().copied().collect();
        return Ok((mesh.positions().to_vec(), indices));
    }
    let surface = file.surface(face).map_err(|e| e.to_string())?;
    Ok(sample_surface(surface, GHOST_SAMPLES))
}

/// `n × n` points of `surface` over its domain, row `i` at
/// `u = u0 + (u1 − u0)·i/(n − 1)`, column `j` at the same fraction of `v`,
/// and the triangles of that grid.
pub fn sample_surface(surface: &dyn ReferenceSurface, n: usize) -> (Vec<DVec3>, Vec<u32>) {
    let n = n.max(2);
    let ([u0, u1], [v0, v1]) = surface.domain();
    let at = |a: f64, b: f64, k: usize| a + (b - a) * k as f64 / (n - 1) as f64;
    let mut positions = Vec::with_capacity(n * n);
    for i in 0..n {
        for j in 0..n {
            positions.push(surface.point(at(u0, u1, i), at(v0, v1, j)));
        }
    }
    let mut indices = Vec::new();
    write_indices(n, n, &mut indices);
    (positions, indices)
}

/// What should be drawn now: a dialog's chosen face first, else the
/// design's reference when View ▸ Reference is on.
fn wanted(
    ghost: &ReferenceGhost,
    reference: Option<&crate::scene::files::reference_link::ReferenceLink>,
    preview: &GhostPreview,
) -> Option<(GhostKey, Option<Arc<ReferenceFile>>)> {
    if let Some((path, face, file)) = &preview.0 {
        return Some((
            GhostKey {
                path: path.clone(),
                face: *face,
                preview: true,
            },
            Some(Arc::clone(file)),
        ));
    }
    let r = reference.filter(|_| ghost.shown)?;
    Some((
        GhostKey {
            path: r.path.clone(),
            face: r.face,
            preview: false,
        },
        None,
    ))
}

/// Builds the ghost's geometry when what is to be drawn changes.
fn build_ghost(
    meter: Res<crate::ecs::meter::CpuMeter>,
    patch: PatchRef,
    preview: Res<GhostPreview>,
    mut ghost: ResMut<ReferenceGhost>,
) {
    let _meter = meter.start();
    let want = wanted(&ghost, patch.reference(), &preview);
    let key = want.as_ref().map(|(k, _)| k.clone());
    if ghost.key == key {
        return;
    }
    let built = want.map(|(k, file)| {
        let read = match file {
            Some(f) => Ok(f),
            None => streamline_reference::read(&k.path)
                .map(Arc::new)
                .map_err(|e| e.to_string()),
        };
        read.and_then(|f| ghost_triangles(&f, k.face))
    });
    let g = &mut *ghost;
    g.key = key;
    g.positions.clear();
    g.indices.clear();
    g.error = None;
    match built {
        Some(Ok((p, i))) => {
            g.positions = p;
            g.indices = i;
        }
        Some(Err(e)) => g.error = Some(e),
        None => {}
    }
    g.generation += 1;
}

/// Keeps the ghost's entity's mesh, material and visibility with [`ReferenceGhost`].
fn draw_ghost(
    mut commands: Commands,
    ghost: Res<ReferenceGhost>,
    mut meshes: ResMut<Assets<Mesh>>,
    mut materials: ResMut<Assets<StandardMaterial>>,
    mats: Option<Res<GhostMaterials>>,
    mut entity: Query<
        (
            &mut Mesh3d,
            &mut MeshMaterial3d<StandardMaterial>,
            &mut Visibility,
        ),
        With<GhostEntity>,
    >,
    mut seen: Local<Option<u64>>,
) {
    if *seen == Some(ghost.generation) {
        return;
    }
    let Some(mats) = mats else {
        let translucent = |c: Color, glow: LinearRgba| StandardMaterial {
            base_color: c,
            emissive: glow,
            alpha_mode: AlphaMode::Blend,
            perceptual_roughness: 0.8,
            double_sided: true,
            cull_mode: None,
            ..default()
        };
        commands.insert_resource(GhostMaterials {
            reference: materials.add(translucent(
                Color::srgba(1.0, 0.5, 0.1, 0.45),
                LinearRgba::rgb(0.35, 0.12, 0.0),
            )),
            preview: materials.add(translucent(
                Color::srgba(0.2, 1.0, 0.6, 0.45),
                LinearRgba::rgb(0.0, 0.3, 0.15),
            )),
        });
        return; // drawn on the next frame
    };
    *seen = Some(ghost.generation);
    let current = entity.single_mut().ok();
    if ghost.positions.is_empty() {
        // nothing to draw: hidden, its mesh kept until the next one
        if let Some((_, _, mut vis)) = current {
            super::shaded::set_visible(&mut vis, false);
        }
        return;
    }
    let mesh = meshes.add(ghost_mesh(&ghost.positions, &ghost.indices));
    let material = match ghost.key.as_ref().is_some_and(|k| k.preview) {
        true => mats.preview.clone(),
        false => mats.reference.clone(),
    };
    match current {
        // the old mesh goes when its last handle does
        Some((mut m, mut mat, mut vis)) => {
            m.0 = mesh;
            mat.0 = material;
            super::shaded::set_visible(&mut vis, true);
        }
        None => {
            commands.spawn((
                GhostEntity,
                Mesh3d(mesh),
                MeshMaterial3d(material),
                Transform::from_rotation(kernel_to_view()),
                Visibility::Inherited,
            ));
        }
    }
}

/// The ghost's Bevy mesh: its positions, the normals of the sampled grid
/// (a flat normal when the vertices are not a square grid), its triangles.
fn ghost_mesh(positions: &[DVec3], indices: &[u32]) -> Mesh {
    let n = positions.len().isqrt();
    let normals: Vec<[f32; 3]> = match Grid::new(n, n, positions.to_vec()) {
        Ok(g) if n >= 2 && n * n == positions.len() => SurfaceMesh::from_points(&g)
            .normals
            .iter()
            .map(|v| v.as_vec3().to_array())
            .collect(),
        _ => vec![[0.0, 0.0, 1.0]; positions.len()],
    };
    let pos: Vec<[f32; 3]> = positions.iter().map(|p| p.as_vec3().to_array()).collect();
    Mesh::new(
        PrimitiveTopology::TriangleList,
        RenderAssetUsages::default(),
    )
    .with_inserted_attribute(Mesh::ATTRIBUTE_POSITION, pos)
    .with_inserted_attribute(Mesh::ATTRIBUTE_NORMAL, normals)
    .with_inserted_indices(Indices::U32(indices.to_vec()))
}
