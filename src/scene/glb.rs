//! Binary glTF 2.0 (`.glb`): the surface's triangle mesh with vertex
//! normals, and the analysis colours as `COLOR_0` when a map is shown
//! (docs/math.md §10). The document is built with `gltf-json` and framed by the
//! `gltf` crate's GLB writer (gltf-rs); positions, normals and colours are
//! `f32`, indices `u32`, all in one binary chunk.

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

/// The `.glb` bytes of `mesh`, with `colors` (linear RGBA, one per vertex) as `COLOR_0`.
pub fn glb_bytes(
    mesh: &SurfaceMesh,
    name: &str,
    colors: Option<&[[f32; 4]]>,
) -> Result<Vec<u8>, String> {
    let n = mesh.positions.len();
    if colors.is_some_and(|c| c.len() != n) {
        return Err("one colour per vertex is needed".into());
    }
    let mut bin = Vec::with_capacity(n * 40 + mesh.indices.len() * 4);
    let (mut lo, mut hi) = ([f32::INFINITY; 3], [f32::NEG_INFINITY; 3]);
    for p in &mesh.positions {
        let p = [p.x as f32, p.y as f32, p.z as f32];
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
        f32s(&mut bin, p);
    }
    let normals_at = bin.len();
    for v in &mesh.normals {
        f32s(&mut bin, [v.x as f32, v.y as f32, v.z as f32]);
    }
    let colors_at = bin.len();
    if let Some(c) = colors {
        for rgba in c {
            f32s(&mut bin, *rgba);
        }
    }
    let indices_at = bin.len();
    for i in &mesh.indices {
        bin.extend_from_slice(&i.to_le_bytes());
    }
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
    let array = json::buffer::Target::ArrayBuffer;
    let vp = view(&mut root, 0, normals_at, array);
    let vn = view(&mut root, normals_at, colors_at - normals_at, array);
    let vc = colors.map(|_| view(&mut root, colors_at, indices_at - colors_at, array));
    let vi = view(
        &mut root,
        indices_at,
        total - indices_at,
        json::buffer::Target::ElementArrayBuffer,
    );
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
    let ap = accessor(&mut root, vp, n, T::Vec3, C::F32, Some((lo, hi)));
    let an = accessor(&mut root, vn, n, T::Vec3, C::F32, None);
    let ac = vc.map(|v| accessor(&mut root, v, n, T::Vec4, C::F32, None));
    let ai = accessor(&mut root, vi, mesh.indices.len(), T::Scalar, C::U32, None);
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
        name: Some(name.to_string()),
        primitives: vec![primitive],
        weights: None,
    });
    let node = root.push(json::Node {
        mesh: Some(m),
        name: Some(name.to_string()),
        ..Default::default()
    });
    let scene = root.push(json::Scene {
        extensions: Default::default(),
        extras: Default::default(),
        name: None,
        nodes: vec![node],
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
