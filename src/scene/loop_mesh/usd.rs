//! USD out (docs/loop.md, "USD out"): a Loop control mesh as a `UsdGeomMesh` in
//! `.usda` text, `subdivisionScheme = "loop"` and `interpolateBoundary` the
//! rule it was interpolated for, so a USD renderer (OpenSubdiv inside) draws
//! the interpolating surface. USD has no token for 002's boundary rule: writing
//! it is refused.

use crate::scene::files::error::SceneError;
use crate::scene::files::io::write_atomic;
use glam::DVec3;
use std::fmt::Write;
use std::path::Path;
use streamline_kernel::loop_subdiv::subdivide::BoundaryRule;

/// Why a rule cannot be written to USD, or `None` when it can.
pub fn refusal(rule: BoundaryRule) -> Option<String> {
    rule.usd_token().is_none().then(|| {
        format!(
            "USD has no boundary rule for `{}` (002's); interpolate with edge-only (USD edgeOnly) or edge-and-corner (USD edgeAndCorner, its default) to write USD",
            rule.name()
        )
    })
}

/// Whether `path` names a USD file (`.usda`, `.usdc`, `.usd`).
pub fn is_usd(path: &Path) -> bool {
    matches!(
        path.extension().and_then(|e| e.to_str()),
        Some("usda" | "usdc" | "usd")
    )
}

/// The `.usda` text of the mesh (points in float, as USD's `point3f[]` holds them).
pub fn usda(
    positions: &[DVec3],
    faces: &[[u32; 3]],
    rule: BoundaryRule,
    comment: &str,
) -> Result<String, String> {
    if let Some(why) = refusal(rule) {
        return Err(why);
    }
    let token = rule.usd_token().expect("refused above");
    let f32s = |p: &DVec3| [p.x as f32, p.y as f32, p.z as f32];
    let (mut lo, mut hi) = ([f32::INFINITY; 3], [f32::NEG_INFINITY; 3]);
    for p in positions {
        let q = f32s(p);
        for k in 0..3 {
            lo[k] = lo[k].min(q[k]);
            hi[k] = hi[k].max(q[k]);
        }
    }
    let doc: String = comment
        .chars()
        .map(|c| match c {
            '"' | '\\' => '\'',
            '\n' => ' ',
            c => c,
        })
        .collect();
    let mut s = String::with_capacity(positions.len() * 48 + faces.len() * 24);
    let _ = writeln!(s, "#usda 1.0");
    let _ = writeln!(
        s,
        "(\n    defaultPrim = \"ControlMesh\"\n    doc = \"{doc}\"\n    upAxis = \"Y\"\n)\n"
    );
    let _ = writeln!(s, "def Mesh \"ControlMesh\"\n{{");
    let v3 = |q: [f32; 3]| format!("({:?}, {:?}, {:?})", q[0], q[1], q[2]);
    let _ = writeln!(s, "    float3[] extent = [{}, {}]", v3(lo), v3(hi));
    s.push_str("    int[] faceVertexCounts = [");
    for i in 0..faces.len() {
        s.push_str(if i == 0 { "3" } else { ", 3" });
    }
    s.push_str("]\n    int[] faceVertexIndices = [");
    for (i, f) in faces.iter().enumerate() {
        let sep = if i == 0 { "" } else { ", " };
        let _ = write!(s, "{sep}{}, {}, {}", f[0], f[1], f[2]);
    }
    let _ = writeln!(s, "]\n    uniform token interpolateBoundary = \"{token}\"");
    s.push_str("    uniform token orientation = \"rightHanded\"\n    point3f[] points = [");
    for (i, p) in positions.iter().enumerate() {
        if i > 0 {
            s.push_str(", ");
        }
        s.push_str(&v3(f32s(p)));
    }
    s.push_str("]\n    uniform token subdivisionScheme = \"loop\"\n}\n");
    Ok(s)
}

/// Writes the control mesh as `.usda` text, atomically; refuses 002's rule and
/// the binary `.usdc`.
pub fn write(
    path: &Path,
    positions: &[DVec3],
    faces: &[[u32; 3]],
    rule: BoundaryRule,
    comment: &str,
) -> Result<(), SceneError> {
    if path.extension().and_then(|e| e.to_str()) != Some("usda") {
        return Err(SceneError::file(
            path,
            "only USD text is written; name the file NAME.usda",
        ));
    }
    let text = usda(positions, faces, rule, comment).map_err(|e| SceneError::file(path, e))?;
    write_atomic(path, text.as_bytes(), |b| {
        if b.starts_with(b"#usda 1.0\n") {
            Ok(())
        } else {
            Err("not a .usda file".into())
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn usda_names_the_scheme_and_the_rule_and_refuses_paper() {
        let p = [DVec3::ZERO, DVec3::X, DVec3::new(0.0, 1.0, 0.5)];
        let s = usda(
            &p,
            &[[0, 1, 2]],
            BoundaryRule::EdgeOnly,
            "a \"quoted\" note",
        )
        .unwrap();
        assert!(s.starts_with("#usda 1.0\n"));
        assert!(s.contains("uniform token subdivisionScheme = \"loop\""));
        assert!(s.contains("uniform token interpolateBoundary = \"edgeOnly\""));
        assert!(s.contains("int[] faceVertexIndices = [0, 1, 2]"));
        assert!(
            s.contains("point3f[] points = [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.5)]")
        );
        assert!(s.contains("doc = \"a 'quoted' note\""));
        let e = usda(&p, &[[0, 1, 2]], BoundaryRule::Paper, "").unwrap_err();
        assert!(
            e.contains("edge-only") && e.contains("edge-and-corner"),
            "{e}"
        );
    }
}
