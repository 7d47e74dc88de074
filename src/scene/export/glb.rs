//! Binary glTF 2.0 (`.glb`): the surface's triangle mesh with vertex
//! normals, and the analysis colours as `COLOR_0` when a map is shown
//! (docs/math.md §10). The document is built with `gltf-json` and framed by the
//! `gltf` crate's GLB writer (gltf-rs); positions, normals and colours are
//! `f32`, indices `u32`, all in one binary chunk. Several patches: one
//! node and one mesh per patch, named for it ([`glb_parts_bytes`]).

use gltf::json;
use json::validation::Checked::Valid;
use json::validation::USize64;
use std::borrow::Cow;
use std::collections::BTreeMap;
use streamline_kernel::streamline::surface_mesh::SurfaceMesh;

fn f32s(out: &mut Vec<u8>, values: impl IntoIterator<Item = f32>) {
    for v in values {
        out.extend_from_slice(&v.to_le_bytes());
    }
}

/// One mesh of a `.glb`: a node and a mesh named `name`, with `colors`
/// (linear RGBA, one per vertex) as `COLOR_0`.
#[derive(Debug, Clone, Copy)]
pub struct GlbPart<'a> {
    /// The node's and the mesh's name.
    pub name: &'a str,
    /// The triangles with their normals.
    pub mesh: &'a SurfaceMesh,
    /// Analysis colours, if a map is shown.
    pub colors: Option<&'a [[f32; 4]]>,
}

/// Where one part's arrays sit in the binary chunk, and its position bounds.
struct Laid {
    positions: usize,
    normals: usize,
    colors: Option<usize>,
    indices: usize,
    end: usize,
    bounds: ([f32; 3], [f32; 3]),
}

/// Appends a part's positions, normals, colours and indices to `bin`.
fn lay(bin: &mut Vec<u8>, part: &GlbPart) -> Laid {
    let mesh = part.mesh;
    let positions = bin.len();
    let (mut lo, mut hi) = ([f32::INFINITY; 3], [f32::NEG_INFINITY; 3]);
    for p in &mesh.positions {
        let p = [p.x as f32, p.y as f32, p.z as f32];
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
        f32s(bin, p);
    }
    let normals = bin.len();
    for v in &mesh.normals {
        f32s(bin, [v.x as f32, v.y as f32, v.z as f32]);
    }
    let colors = part.colors.map(|c| {
        let at = bin.len();
        for rgba in c {
            f32s(bin, *rgba);
        }
        at
    });
    let indices = bin.len();
    for i in &mesh.indices {
        bin.extend_from_slice(&i.to_le_bytes());
    }
    Laid {
        positions,
        normals,
        colors,
        indices,
        end: bin.len(),
        bounds: (lo, hi),
    }
}

/// The `.glb` bytes of several meshes: one node and one mesh per part, in
/// one scene, all arrays in one binary chunk (docs/cad.md, "Several patches").
pub fn glb_parts_bytes(parts: &[GlbPart]) -> Result<Vec<u8>, String> {
    for p in parts {
        if p.colors.is_some_and(|c| c.len() != p.mesh.positions.len()) {
            return Err(format!("{}: one colour per vertex is needed", p.name));
        }
    }
    let mut bin = Vec::new();
    let laid: Vec<Laid> = parts.iter().map(|p| lay(&mut bin, p)).collect();
    let total = bin.len();

    let mut root = json::Root::default();
    root.asset.generator = Some(format!("Streamline Studio {}", env!("CARGO_PKG_VERSION")));
    let buffer = root.push(json::Buffer {
        byte_length: USize64::from(total),
        extensions: Default::default(),
        extras: Default::default(),
        name: None,
        uri: None,
    });
    let view = |root: &mut json::Root, offset: usize, len: usize, target| {
        root.push(json::buffer::View {
            buffer,
            byte_length: USize64::from(len),
            byte_offset: Some(USize64::from(offset)),
            byte_stride: None,
            extensions: Default::default(),
            extras: Default::default(),
            name: None,
            target: Some(Valid(target)),
        })
    };
    let accessor =
        |root: &mut json::Root, v, count: usize, ty, comp, bounds: Option<([f32; 3], [f32; 3])>| {
            root.push(json::Accessor {
                buffer_view: Some(v),
                byte_offset: None,
                count: USize64::from(count),
                component_type: Valid(json::accessor::GenericComponentType(comp)),
                extensions: Default::default(),
                extras: Default::default(),
                type_: Valid(ty),
                min: bounds.map(|b| json::Value::from(b.0.to_vec())),
                max: bounds.map(|b| json::Value::from(b.1.to_vec())),
                name: None,
                normalized: false,
                sparse: None,
            })
        };
    use json::accessor::{ComponentType as C, Type as T};
    let array = json::buffer::Target::ArrayBuffer;
    let mut nodes = Vec::with_capacity(parts.len());
    for (part, l) in parts.iter().zip(&laid) {
        let n = part.mesh.positions.len();
        let vp = view(&mut root, l.positions, l.normals - l.positions, array);
        let after_normals = l.colors.unwrap_or(l.indices);
        let vn = view(&mut root, l.normals, after_normals - l.normals, array);
        let vc = l
            .colors
            .map(|at| view(&mut root, at, l.indices - at, array));
        let vi = view(
            &mut root,
            l.indices,
            l.end - l.indices,
            json::buffer::Target::ElementArrayBuffer,
        );
        let ap = accessor(&mut root, vp, n, T::Vec3, C::F32, Some(l.bounds));
        let an = accessor(&mut root, vn, n, T::Vec3, C::F32, None);
        let ac = vc.map(|v| accessor(&mut root, v, n, T::Vec4, C::F32, None));
        let ai = accessor(
            &mut root,
            vi,
            part.mesh.indices.len(),
            T::Scalar,
            C::U32,
            None,
        );
        let mut attributes = BTreeMap::new();
        attributes.insert(Valid(json::mesh::Semantic::Positions), ap);
        attributes.insert(Valid(json::mesh::Semantic::Normals), an);
        if let Some(ac) = ac {
            attributes.insert(Valid(json::mesh::Semantic::Colors(0)), ac);
        }
        let primitive = json::mesh::Primitive {
            attributes,
            extensions: Default::default(),
            extras: Default::default(),
            indices: Some(ai),
            material: None,
            mode: Valid(json::mesh::Mode::Triangles),
            targets: None,
        };
        let m = root.push(json::Mesh {
            extensions: Default::default(),
            extras: Default::default(),
            name: Some(part.name.to_string()),
            primitives: vec![primitive],
            weights: None,
        });
        nodes.push(root.push(json::Node {
            mesh: Some(m),
            name: Some(part.name.to_string()),
            ..Default::default()
        }));
    }
    let scene = root.push(json::Scene {
        extensions: Default::default(),
        extras: Default::default(),
        name: None,
        nodes,
    });
    root.scene = Some(scene);
    let mut text = json::serialize::to_string(&root).map_err(|e| e.to_string())?;
    while text.len() % 4 != 0 {
        text.push(' ');
    }
    let length = 12 + 8 + text.len() + 8 + total;
    let glb = gltf::binary::Glb {
        header: gltf::binary::Header {
            magic: *b"glTF",
            version: 2,
            length: u32::try_from(length)
                .map_err(|_| "over the 4 GiB a .glb can hold".to_string())?,
        },
        json: Cow::Owned(text.into_bytes()),
        bin: Some(Cow::Owned(bin)),
    };
    glb.to_vec().map_err(|e| e.to_string())
}

/// A check of what was written: the GLB parses and its document validates.
pub fn verify(bytes: &[u8]) -> Result<(), String> {
    gltf::Gltf::from_slice(bytes)
        .map(|_| ())
        .map_err(|e| e.to_string())
}
