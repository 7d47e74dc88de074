//! The checks across the patches of a document (docs/math.md §11, "Bad
//! input"), each a located error that names the patch and the fix: unique
//! names; every join on an *earlier* patch (so joins form a forest, never a
//! cycle); a G2 chain one net from a patch on its own curve, continued by
//! one patch per edge; no fine tuning or tangent interpolation on a G2
//! chain's patches (one merged net of their control nets) and no detail on
//! a G1 or G2 chain's seam column (its parent's); and then the kernel's own checks
//! of every join (rows of a chain, its seam column, schemes, side `t`, G2 on
//! a side edge), by building the document at depth 0 through the joins.
//! Each patch's own fields are checked before, as a version-2 scene's are.

use super::document::{Document, Start};
use super::document_build::{is_g2_chain, stacks};
use crate::scene::files::error::SceneError;
use crate::scene::files::patch_text::PatchText;
use std::path::Path;

/// `` `a`, `b` `` for messages.
fn listed<'a>(names: impl Iterator<Item = &'a str>) -> String {
    names
        .map(|n| format!("`{n}`"))
        .collect::<Vec<_>>()
        .join(", ")
}

/// Checks what spans patches; errors are placed by `place` in the file's text.
pub fn check_document(doc: &Document, file: &Path, place: &PatchText) -> Result<(), SceneError> {
    let at = |i: usize, key: &str, msg: String| {
        let (line, col) = place.in_patch(i, key);
        SceneError::at(file, line, col, msg)
    };
    let name = |i: usize| doc.patches[i].name.as_str();
    for i in 0..doc.patches.len() {
        if let Some(j) = (0..i).find(|&j| name(j) == name(i)) {
            return Err(at(
                i,
                "name",
                format!(
                    "patch name `{}` is used twice (patches {} and {}); give each patch its own name",
                    name(i),
                    j + 1,
                    i + 1
                ),
            ));
        }
    }
    for (i, p) in doc.patches.iter().enumerate() {
        let Start::Edge { patch, .. } = &p.start else {
            continue;
        };
        let curve = "`initial: Curve(tangents: […], order: 3, length: L, origin: (x, y, z))`";
        let earlier = listed((0..i).map(name));
        let fix = if i == 0 {
            format!("the first patch starts on its own curve: give it {curve}")
        } else {
            format!(
                "start it on one of the patches before it ({earlier}), or give it its own curve, {curve}"
            )
        };
        match doc.index(patch) {
            None => {
                return Err(at(
                    i,
                    "initial",
                    format!(
                        "patch `{}` starts on patch `{patch}`, which does not exist; {fix}",
                        p.name
                    ),
                ));
            }
            Some(j) if j >= i => {
                let what = if j == i {
                    "itself".to_string()
                } else {
                    format!(
                        "`{patch}`, which comes after it (patch {} of {})",
                        j + 1,
                        doc.patches.len()
                    )
                };
                let fix = if i == 0 || j == i {
                    fix
                } else {
                    format!(
                        "move `{patch}` before `{}`, or start `{}` on one of the patches before it ({earlier})",
                        p.name, p.name
                    )
                };
                return Err(at(
                    i,
                    "initial",
                    format!(
                        "patch `{}` starts on {what}, but a patch starts on an earlier one (so that joins cannot form a cycle); {fix}",
                        p.name
                    ),
                ));
            }
            Some(_) => {}
        }
    }
    for i in 0..doc.patches.len() {
        let Some((a, join)) = doc.parent(i) else {
            continue;
        };
        if !is_g2_chain(join) {
            continue;
        }
        if let Some((on, ja)) = doc.parent(a).filter(|&(_, ja)| !is_g2_chain(ja)) {
            return Err(at(
                i,
                "initial",
                format!(
                    "patch `{}` is G2-chained on `{}`, but `{}` starts on `{}`'s edge {} with {}; a G2 chain is subdivided as one net from a patch on its own curve: join `{}` with G1, or chain `{}` with G2 too",
                    name(i),
                    name(a),
                    name(a),
                    name(on),
                    ja.edge.name(),
                    ja.continuity.name(),
                    name(i),
                    name(a)
                ),
            ));
        }
        if let Some(k) = (0..i).find(|&k| {
            doc.parent(k)
                .is_some_and(|(ka, kj)| ka == a && is_g2_chain(kj))
        }) {
            return Err(at(
                i,
                "initial",
                format!(
                    "patch `{}` is G2-chained on `{}`'s End, but `{}` already is; a G2 chain is one net, so one patch continues it: chain `{}` on `{}`'s End, or join it with G1",
                    name(i),
                    name(a),
                    name(k),
                    name(i),
                    name(k)
                ),
            ));
        }
    }
    for (i, p) in doc.patches.iter().enumerate() {
        // a G2 run is one merged net of its members' control nets
        let in_g2 = doc.parent(i).is_some_and(|(_, j)| is_g2_chain(j))
            || (0..doc.patches.len())
                .any(|k| doc.parent(k).is_some_and(|(a, j)| a == i && is_g2_chain(j)));
        if in_g2 {
            let run = |key: &str, why: &str| {
                at(
                    i,
                    key,
                    format!(
                        "patch `{}` has `{key}`, but it is in a G2 chain, which is subdivided as one merged net of its patches' control nets (docs/math.md §11.1){why}; remove `{key}`, or join the patches with G1",
                        p.name
                    ),
                )
            };
            if p.tuning.is_some() {
                return Err(run(
                    "tuning",
                    ", and fine tuning scales a streamline's speed, so the curvature across the seam becomes κ/α on each side: G2 would hold only where both functions agree",
                ));
            }
            if super::model::interpolates(&p.design, p.interpolate_tangents) {
                return Err(run(
                    "interpolate_tangents",
                    ", whose interpolation is not the members' own",
                ));
            }
        }
        // a G1 chain's seam column is the parent's last column, one handle
        if let Some((a, join)) = doc.parent(i)
            && join.edge == streamline_kernel::joins::Edge::End
            && join.continuity != streamline_kernel::joins::Continuity::G0
            && let Some(&(l, r, _)) = p.details.keys().find(|&&(_, _, c)| c == 0)
        {
            return Err(at(
                i,
                "details",
                format!(
                    "patch `{}` has a detail at level {l}, row {r}, column 0, but column 0 is its seam with `{}` ({}), whose last column it is at every depth (one handle, docs/math.md §11.1); put the detail on `{}`'s last column instead",
                    p.name,
                    name(a),
                    join.continuity.name(),
                    name(a)
                ),
            ));
        }
    }
    stacks(doc, 0).map_err(|e| at(e.patch, "initial", e.message))?;
    Ok(())
}
