//! Display: which arrows, labels, lines and views are drawn.

use crate::editor::handles::sphere_view::SphereSettings;
use crate::editor::interaction::HandleSettings;
use crate::editor::view::antialias::AntiAliasing;
use crate::editor::view::overlay::OverlaySettings;
use bevy::ecs::system::SystemParam;
use bevy::prelude::*;
use bevy_egui::egui;

/// What only the Display section touches: settings, each changed (and so
/// marked changed for the systems that follow it) only when a value is.
#[derive(SystemParam)]
pub struct DisplaySection<'w> {
    pub handles: ResMut<'w, HandleSettings>,
    pub overlay: ResMut<'w, OverlaySettings>,
    pub sphere: ResMut<'w, SphereSettings>,
    pub antialias: ResMut<'w, AntiAliasing>,
    pub seams: ResMut<'w, crate::editor::seams::SeamSettings>,
}

pub fn show(ui: &mut egui::Ui, p: &mut DisplaySection) {
    // the widgets edit copies; a setting is written only when it differs
    let mut h = p.handles.clone();
    let mut o = p.overlay.clone();
    let mut s = p.sphere.clone();
    widgets(ui, &mut h, &mut o, &mut s);
    p.handles.set_if_neq(h);
    p.overlay.set_if_neq(o);
    p.sphere.set_if_neq(s);
    let mut seams = p.seams.clone();
    ui.checkbox(&mut seams.show, "seams").on_hover_text(
        "The joins of a design of several patches, labelled G0/G1/G2 and coloured \
         green (meets its continuity), amber (near) or red (fails): see Analysis ▸ Seams",
    );
    p.seams.set_if_neq(seams);
    antialiasing(ui, p);
}

fn widgets(
    ui: &mut egui::Ui,
    h: &mut HandleSettings,
    o: &mut OverlaySettings,
    s: &mut SphereSettings,
) {
    ui.checkbox(&mut h.controls, "control arrows (yellow)")
        .on_hover_text("The level-0 control tangents at their streamline points");
    ui.checkbox(&mut h.refined, "refined arrows (red)")
        .on_hover_text("The tangents of the edit depth, when it is above 0");
    ui.checkbox(&mut h.every_other, "every other refined arrow")
        .on_hover_text("Thin the red arrows out: every other one in both directions");
    ui.checkbox(&mut h.labels, "index labels").on_hover_text(
        "Column numbers at the control arrows (head shapes cycle cone, ball, cross, ring)",
    );
    ui.checkbox(&mut o.streamlines, "streamlines")
        .on_hover_text("Draw the streamlines of the display depth as lines");
    ui.add_enabled(
        o.streamlines,
        egui::Slider::new(&mut o.max_streamlines, 2..=400)
            .text("at most")
            .logarithmic(true),
    )
    .on_hover_text("Streamlines drawn, spread evenly");
    ui.checkbox(&mut o.axes_and_grid, "axes and ground grid")
        .on_hover_text("Red x and green y axes, and a grid under the surface");
    ui.checkbox(&mut s.show, "Gaussian sphere view")
        .on_hover_text(
            "The inset with the tangents as points on the unit sphere; drag a point to edit it",
        );
    ui.checkbox(&mut s.subdivided, "subdivided tangents on the sphere")
        .on_hover_text(
            "The tangents of the display depth as small points; past depth 4 every \
             2^(depth − 4)-th along and across (at most a depth-4 density, the same outline)",
        );
    ui.add(egui::Slider::new(&mut s.fraction, 0.2..=0.7).text("sphere view size"))
        .on_hover_text("The inset's side as a share of the 3D view");
}

/// The 3D views' multisampling, with why it starts where it does.
fn antialiasing(ui: &mut egui::Ui, p: &mut DisplaySection) {
    let current = p.antialias.samples;
    let name = |n: u32| {
        if n == 1 {
            "off".to_string()
        } else {
            format!("{n}×")
        }
    };
    let hint = if p.antialias.software {
        "Multisample anti-aliasing of the 3D views. This adapter is a software renderer: \
         every sample is drawn by the CPU, so it starts off (about four times the frames of 4×)"
    } else {
        "Multisample anti-aliasing of the 3D views (smoother edges, more work for the GPU)"
    };
    ui.horizontal(|ui| {
        ui.label("anti-aliasing");
        let mut chosen = current;
        egui::ComboBox::from_id_salt("msaa")
            .selected_text(name(current))
            .show_ui(ui, |ui| {
                // only what the adapter offers (llvmpipe: off and 4×)
                for &n in &p.antialias.supported {
                    ui.selectable_value(&mut chosen, n, name(n));
                }
            })
            .response
            .on_hover_text(hint);
        if chosen != current {
            p.antialias.samples = chosen;
        }
    });
}
