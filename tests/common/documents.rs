//! Helpers shared by the document test files (`documents.rs`,
//! `documents_random.rs`).

use std::path::{Path, PathBuf};
use streamline_studio::kernel::DVec3;
use streamline_studio::scene::design::document::{Document, Start};

/// A fresh folder for test files, named by `tag` and the process.
pub fn tmpdir(tag: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("ss-documents-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// A shipped scene's path.
pub fn shipped(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("scenes/{name}.ron"))
}

/// Every f64 of a document, as bits: nets, parameters, initial curves, view.
pub fn bits(doc: &Document) -> Vec<u64> {
    let mut out = Vec::new();
    let v = |out: &mut Vec<u64>, p: DVec3| out.extend([p.x, p.y, p.z].map(f64::to_bits));
    for x in [doc.view.yaw.0, doc.view.pitch.0, doc.view.distance.0] {
        out.push(x.to_bits());
    }
    v(&mut out, doc.view.target.vec());
    for p in &doc.patches {
        for &t in p.design.net().data() {
            v(&mut out, t);
        }
        out.extend(p.design.params().s.data().iter().map(|x| x.to_bits()));
        out.extend(p.design.params().t.iter().map(|x| x.to_bits()));
        out.extend(p.design.params().sigma.iter().map(|x| x.to_bits()));
        if let Start::Curve(c) = &p.start {
            for d in &c.tangents {
                v(&mut out, d.vec());
            }
            out.push(c.length.0.to_bits());
            v(&mut out, c.origin.vec());
        }
    }
    out
}
