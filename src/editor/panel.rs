//! The egui side panel: a thin view over [`DesignState`] that changes settings and
//! marks the design dirty; it never computes geometry.

use super::state::DesignState;
use bevy::prelude::*;
use bevy_egui::{EguiContexts, EguiPrimaryContextPass, egui};
use streamline_kernel::curve::OMEGA_MAX;
use streamline_kernel::{BlendOrder, SurfaceScheme};

pub struct PanelPlugin;

impl Plugin for PanelPlugin {
    fn build(&self, app: &mut App) {
        app.add_systems(EguiPrimaryContextPass, panel);
    }
}

fn panel(mut contexts: EguiContexts, mut state: ResMut<DesignState>) -> Result {
    let ctx = contexts.ctx_mut()?;
    let mut root = egui::Ui::new(
        ctx.clone(),
        "viewport".into(),
        egui::UiBuilder::new()
            .layer_id(egui::LayerId::background())
            .max_rect(ctx.viewport_rect()),
    );
    egui::Panel::left("design_panel")
        .resizable(true)
        .default_size(250.0)
        .show(&mut root, |ui| {
            ui.heading("Streamline Studio");
            ui.label(egui::RichText::new(&state.name).weak());
            ui.separator();
            subdivision(ui, &mut state);
            ui.separator();
            stats(ui, &state);
        });
    Ok(())
}

fn subdivision(ui: &mut egui::Ui, state: &mut DesignState) {
    ui.strong("Subdivision");
    let mut scheme = state.design.scheme;
    let omega = match scheme {
        SurfaceScheme::Kobbelt { omega } => omega,
        _ => 1.0,
    };
    egui::ComboBox::from_label("scheme")
        .selected_text(scheme.name())
        .show_ui(ui, |ui| {
            ui.selectable_value(&mut scheme, SurfaceScheme::Kobbelt { omega }, "kobbelt")
                .on_hover_text("4-point ⊗ 4-point: interpolates the control tangents");
            ui.selectable_value(&mut scheme, SurfaceScheme::CatmullClark, "catmull-clark")
                .on_hover_text("cubic B-spline ⊗ cubic B-spline: approximating, smoothest");
            ui.selectable_value(&mut scheme, SurfaceScheme::DooSabin, "doo-sabin")
                .on_hover_text("Chaikin ⊗ Chaikin: approximating, fastest");
        })
        .response
        .on_hover_text("How tangents are blended on the Gaussian sphere");
    if let SurfaceScheme::Kobbelt { omega } = &mut scheme {
        ui.add(egui::Slider::new(omega, 0.0..=OMEGA_MAX - 1e-3).text("ω"))
            .on_hover_text("4-point tension: 0 is the quadratic rule, 1 the classic 4-point; larger bulges more");
    }
    let mut order = state.design.order;
    ui.horizontal(|ui| {
        ui.radio_value(&mut order, BlendOrder::SFirst, "s-first")
            .on_hover_text("Blend along each streamline first, then across");
        ui.radio_value(&mut order, BlendOrder::TFirst, "t-first")
            .on_hover_text("Blend across streamlines first, then along");
    });
    let mut depth = state.depth;
    ui.add(egui::Slider::new(&mut depth, 0..=6).text("display depth"))
        .on_hover_text(
            "Subdivision levels shown: each level doubles the tangents in both directions",
        );
    if scheme != state.design.scheme || order != state.design.order || depth != state.depth {
        state.design.scheme = scheme;
        state.design.order = order;
        state.depth = depth;
        state.dirty = true;
    }
}

fn stats(ui: &mut egui::Ui, state: &DesignState) {
    ui.strong("Stats");
    if let Some(err) = &state.error {
        ui.colored_label(egui::Color32::LIGHT_RED, err);
    }
    let net = &state.design.net;
    ui.label(format!("control net: {} × {}", net.cols(), net.rows()));
    if let Some(b) = &state.built {
        let g = &b.level.tangents;
        ui.label(format!(
            "tangents: {} × {} = {}",
            g.cols(),
            g.rows(),
            g.cols() * g.rows()
        ));
        ui.label(format!("streamlines: {}", g.rows()));
        ui.label(format!("triangles: {}", b.mesh.triangle_count()));
    }
    ui.label(format!("full build: {:.0} µs", state.build_us))
        .on_hover_text("blend + integrate + mesh, on the last change");
}
