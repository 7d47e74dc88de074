//! Where a GUI test's pointer goes, written while the screenshot run goes
//! on: the selected handle's arrow and its point on the sphere view
//! (`REPORT.at`), and each patch's middle (`REPORT.patches`).

use super::super::coords::to_view;
use super::super::handles::sphere_view::SphereCamera;
use super::super::interaction::{HandleQuery, MainCamera, Selection};
use super::ScreenshotRequest;
use super::report::PatchReport;
use bevy::prelude::*;

/// Writes `REPORT.patches`: for each patch drawn from its stack, its name
/// and its middle vertex in window pixels (`name x y` a line), where a GUI
/// test clicks to choose it.
pub(super) fn write_patch_positions(
    req: &ScreenshotRequest,
    (_, patch_meshes, _, slots): &PatchReport,
    camera: &Query<(&Camera, &GlobalTransform), With<MainCamera>>,
) -> bool {
    let Some(report) = &req.report else {
        return true;
    };
    let Ok((cam, gt)) = camera.single() else {
        return false;
    };
    let mut text = String::new();
    for (e, slot, _, surface) in slots {
        let Some((points, _)) = surface.and_then(|s| patch_meshes.mesh(e, s)) else {
            continue;
        };
        let Some(mid) = points.data().get(points.data().len() / 2) else {
            continue;
        };
        if let Ok(q) = cam.world_to_viewport(gt, to_view(*mid)) {
            text += &format!("{} {} {}\n", slot.name, q.x.round(), q.y.round());
        }
    }
    let mut at = report.clone().into_os_string();
    at.push(".patches");
    std::fs::write(at, text).is_ok()
}

/// Writes `REPORT.at`: the selected handle's shaft midpoint in window
/// pixels, unless it holds that already (`last`, what it holds).
pub(super) fn write_handle_position(
    req: &ScreenshotRequest,
    selection: &Selection,
    arrows: &HandleQuery,
    camera: &Query<(&Camera, &GlobalTransform), With<MainCamera>>,
    sphere: &Query<(&Camera, &GlobalTransform), With<SphereCamera>>,
    last: &mut String,
) -> bool {
    let (Some(report), Some(h)) = (&req.report, selection.primary()) else {
        return true;
    };
    let (Some(a), Ok((cam, gt))) = (arrows.find(h), camera.single()) else {
        return false;
    };
    let mid = a.base + a.dir * (a.length * 0.6);
    let Ok(p) = cam.world_to_viewport(gt, to_view(mid)) else {
        return false;
    };
    // second line: the handle's point on the sphere view
    let Ok((scam, sgt)) = sphere.single() else {
        return false;
    };
    let Ok(q) = scam.world_to_viewport(sgt, to_view(a.dir)) else {
        return false;
    };
    let mut at = report.clone().into_os_string();
    at.push(".at");
    let text = format!(
        "{} {}\n{} {}\n",
        p.x.round(),
        p.y.round(),
        q.x.round(),
        q.y.round()
    );
    if text == *last {
        return true;
    }
    // whole or not at all: a script may be reading it
    let mut tmp = at.clone();
    tmp.push(".tmp");
    let ok = std::fs::write(&tmp, &text).is_ok() && std::fs::rename(&tmp, &at).is_ok();
    if ok {
        *last = text;
    }
    ok
}
