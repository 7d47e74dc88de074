//! Loop mesh (paper 002): open an OBJ, interpolate its vertices with a Loop
//! surface (method, tolerance, depth shown), read the iteration count and the
//! errors, export the surface or its control mesh, close.

use crate::editor::files::open_save::{self, FileUi, PathAction};
use crate::editor::loop_mesh::MeshView;
use bevy::ecs::system::SystemParam;
use bevy::prelude::*;
use bevy_egui::egui;
use std::path::PathBuf;
use streamline_kernel::loop_subdiv::mesh_interpolation::Method;
use streamline_kernel::loop_subdiv::subdivide::BoundaryRule;

/// What only the Loop mesh section touches.
#[derive(SystemParam)]
pub struct MeshSection<'w> {
    pub view: ResMut<'w, MeshView>,
}

/// `files_ui`: the File feature's state, through which the file browser is asked.
pub fn show(ui: &mut egui::Ui, p: &mut MeshSection, files_ui: &mut FileUi) {
    let v = &mut p.view;
    ui.horizontal(|ui| {
        // typed on a copy: the view is marked changed only when the text is
        let mut input = v.text.input.clone();
        ui.add(egui::TextEdit::singleline(&mut input).desired_width(140.0))
            .on_hover_text("A triangle mesh (OBJ); polygons are split into fans of triangles");
        if input != v.text.input {
            v.text.input = input;
        }
        if ui
            .button("Open OBJ")
            .on_hover_text("Open the mesh and make a Loop surface pass through every vertex")
            .clicked()
        {
            let path = PathBuf::from(v.text.input.trim());
            v.open(path);
        }
        if ui
            .button("…")
            .on_hover_text("Pick the mesh in the file browser and open it")
            .clicked()
        {
            let typed = PathBuf::from(v.text.input.trim());
            let start = match typed.parent() {
                Some(d) if d.is_dir() => d.to_path_buf(),
                _ => std::env::current_dir().unwrap_or_default(),
            };
            open_save::browse(files_ui, PathAction::OpenMesh, start, None);
        }
    });
    if let Some(job) = &v.work.job {
        let (done, total) = job.progress.counts();
        let stage = job.progress.stage_name();
        ui.label(&job.label);
        let text = if total > 0 {
            format!("{stage}: {done} of {total}")
        } else {
            format!("{stage}…")
        };
        ui.add(egui::ProgressBar::new(job.progress.fraction()).text(text))
            .on_hover_text("Work runs off the frame: the editor stays responsive");
        let cancel = ui
            .button("Cancel")
            .on_hover_text("Stop it; what is shown stays as it was")
            .clicked();
        ui.ctx().request_repaint();
        if cancel {
            v.cancel();
            v.text.error = Some("cancelled; nothing changed".into());
        }
    }
    if let Some(e) = &v.text.error {
        ui.colored_label(egui::Color32::from_rgb(240, 110, 90), e)
            .on_hover_text("The last open or export failed; nothing else changed");
    }
    let Some(g) = &v.doc.given else {
        ui.label(egui::RichText::new("No mesh open: the streamline surface is shown.").weak());
        return;
    };
    let (mesh, topo) = (&g.0, &g.1);
    let (nv, nf, loops) = (mesh.positions.len(), mesh.faces.len(), topo.loops.len());
    ui.label(format!(
        "{nv} vertices, {nf} triangles, {}",
        if loops == 0 {
            "closed".to_string()
        } else {
            format!("{loops} boundary loops")
        }
    ))
    .on_hover_text(
        v.doc
            .path
            .as_ref()
            .map_or(String::new(), |p| p.display().to_string()),
    );
    let mut method = v.settings.method;
    ui.horizontal(|ui| {
        ui.radio_value(&mut method, Method::Plain, "plain")
            .on_hover_text("002's progressive iteration: V += V⁰ − V∞, boundary first");
        ui.radio_value(&mut method, Method::Fast, "fast")
            .on_hover_text("Conjugate gradients (interior) and BiCGSTAB (boundary) on the same system: fewer iterations");
    });
    if method != v.settings.method {
        v.settings.method = method;
        v.work.dirty = true;
    }
    let mut boundary = v.settings.boundary;
    ui.horizontal(|ui| {
        ui.label("boundary");
        for (rule, tip) in [
            (BoundaryRule::Paper, "002's rules (regular boundary vertices of valence 4, ⅝–⅜ edge points): the paper's surface; no renderer draws it, and USD cannot say it"),
            (BoundaryRule::EdgeOnly, "OpenSubdiv's VTX_BOUNDARY_EDGE_ONLY (USD edgeOnly; an option of OpenSubdiv-based renderers such as RenderMan and Houdini): boundary curves are cubic B-splines, no corners"),
            (BoundaryRule::EdgeAndCorner, "OpenSubdiv's VTX_BOUNDARY_EDGE_AND_CORNER, USD's default (edgeAndCorner; what a USD renderer draws when the file says nothing): as edge-only, and a boundary vertex with a single face stays put"),
        ] {
            ui.radio_value(&mut boundary, rule, rule.name()).on_hover_text(tip);
        }
    });
    if boundary != v.settings.boundary {
        v.settings.boundary = boundary;
        v.work.dirty = true;
    }
    let mut exp = -v.settings.tolerance.log10();
    if ui
        .add(egui::Slider::new(&mut exp, 2.0..=9.0).step_by(1.0).text("tolerance 10^-n"))
        .on_hover_text("Stop when every vertex is this close to its limit point (bounding box's largest side = 1; 002 uses 1e-3)")
        .changed()
    {
        v.settings.tolerance = 10f64.powf(-exp);
        v.work.dirty = true;
    }
    let mut depth = v.settings.depth;
    if ui
        .add(egui::Slider::new(&mut depth, 0..=crate::editor::loop_mesh::MAX_DEPTH).text("depth"))
        .on_hover_text("Loop subdivision levels of the control mesh shown (each multiplies the triangles by 4)")
        .changed()
    {
        v.settings.depth = depth;
        v.work.dirty = true;
    }
    let mut show_given = v.settings.show_given;
    ui.checkbox(&mut show_given, "given mesh").on_hover_text(
        "Draw the given mesh's edges (blue) and vertices (red crosses) over the surface",
    );
    if show_given != v.settings.show_given {
        v.settings.show_given = show_given;
    }
    if let Some(r) = v.doc.report {
        egui::Grid::new("mesh_stats").num_columns(2).striped(true).show(ui, |ui| {
            ui.label("iterations");
            ui.label(if loops > 0 {
                format!("{} ({} boundary + {} interior)", r.iterations(), r.boundary_iterations, r.interior_iterations)
            } else {
                r.iterations().to_string()
            })
            .on_hover_text("Applications of the limit operator");
            ui.end_row();
            ui.label("max error");
            ui.label(format!("{:.3e}", r.max_error))
                .on_hover_text("Largest distance from a given vertex to the surface's point for it, on the mesh scaled to a unit box");
            ui.end_row();
            ui.label("mean error");
            ui.label(format!("{:.3e}", r.avg_error));
            ui.end_row();
            ui.label("time");
            ui.label(format!("{:.1} ms{}", v.doc.seconds * 1e3, if r.converged { "" } else { " (did not converge)" }));
            ui.end_row();
        });
    }
    let stem = v
        .doc
        .path
        .as_ref()
        .and_then(|p| p.file_stem())
        .map_or("mesh".to_string(), |s| s.to_string_lossy().into_owned());
    ui.horizontal(|ui| {
        if ui
            .button("Export surface")
            .on_hover_text(format!(
                "Write the surface shown (OBJ); the browser proposes {stem}-loop.obj beside the input"
            ))
            .clicked()
        {
            let to = v.doc.path.as_ref().map_or(PathBuf::from("."), |p| {
                p.with_file_name(format!("{stem}-loop.obj"))
            });
            open_save::browse(files_ui, PathAction::ExportMeshSurface, to, None);
        }
        if ui
            .button("Export control")
            .on_hover_text(format!(
                "Write the control mesh (input's vertex order and faces, OBJ); the browser proposes {stem}-control.obj"
            ))
            .clicked()
        {
            let to = v.doc.path.as_ref().map_or(PathBuf::from("."), |p| {
                p.with_file_name(format!("{stem}-control.obj"))
            });
            open_save::browse(files_ui, PathAction::ExportMeshControl, to, None);
        }
        if ui
            .button("Export USD")
            .on_hover_text(format!(
                "Write the control mesh (the browser proposes {stem}-control.usda): a USD mesh with subdivisionScheme loop and the boundary rule, so USD renderers draw this surface (not for paper)"
            ))
            .clicked()
        {
            let to = v.doc.path.as_ref().map_or(PathBuf::from("."), |p| {
                p.with_file_name(format!("{stem}-control.usda"))
            });
            open_save::browse(files_ui, PathAction::ExportMeshUsd, to, None);
        }
        if ui
            .button("Close")
            .on_hover_text("Back to the streamline surface")
            .clicked()
        {
            v.close();
        }
    });
}
