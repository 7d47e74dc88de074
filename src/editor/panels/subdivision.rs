//! Subdivision: scheme, ω, blend order, display depth and edit depth.

use super::PanelCtx;
use crate::ecs::Edit;
use bevy_egui::egui;
use streamline_kernel::curve::scheme::OMEGA_MAX;
use streamline_kernel::{BlendOrder, SurfaceScheme};

/// The deepest level the sliders offer (the model refuses sizes past its cap).
const MAX_DEPTH: u32 = 7;

pub fn show(ui: &mut egui::Ui, p: &mut PanelCtx) {
    let (cur_scheme, cur_order) = (p.patch.design().scheme(), p.patch.design().order());
    let mut scheme = cur_scheme;
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
    let mut group = None;
    if let SurfaceScheme::Kobbelt { omega } = &mut scheme {
        let r = ui
            .add(egui::Slider::new(omega, 0.0..=OMEGA_MAX - 1e-3).text("ω"))
            .on_hover_text("4-point tension: 0 is the quadratic rule, 1 the classic 4-point; larger bulges more");
        group = Some(p.slider_group("omega", &r));
    }
    if scheme != cur_scheme {
        match group {
            // one drag of the ω slider is one undo step
            Some(g) => p.send_grouped(Edit::SetScheme(scheme), g),
            None => p.send(Edit::SetScheme(scheme)),
        }
    }
    let mut order = cur_order;
    ui.horizontal(|ui| {
        ui.radio_value(&mut order, BlendOrder::SFirst, "s-first")
            .on_hover_text("Blend along each streamline first, then across");
        ui.radio_value(&mut order, BlendOrder::TFirst, "t-first")
            .on_hover_text("Blend across streamlines first, then along");
    });
    if order != cur_order {
        p.send(Edit::SetBlendOrder(order));
    }
    let mut depth = p.patch.structure().display_depth;
    if ui
        .add(egui::Slider::new(&mut depth, 0..=MAX_DEPTH).text("display depth"))
        .on_hover_text(
            "Subdivision levels shown: each level doubles the tangents in both directions",
        )
        .changed()
    {
        p.send(Edit::SetDisplayDepth(depth));
    }
    let mut edit = p.patch.structure().edit_depth;
    if ui
        .add(egui::Slider::new(&mut edit, 0..=MAX_DEPTH).text("edit depth"))
        .on_hover_text("The level whose tangents the arrows edit: 0 moves control tangents; deeper levels add multiresolution details (docs/math.md §5)")
        .changed()
    {
        p.send(Edit::SetEditDepth(edit));
    }
    let mut interp = p.patch.structure().interpolate_tangents;
    let approximating =
        streamline_kernel::levels::tangent_interpolation::applies(p.patch.design().scheme());
    if ui
        .add_enabled(
            approximating,
            egui::Checkbox::new(&mut interp, "interpolate control tangents"),
        )
        .on_hover_text("Catmull–Clark and Doo–Sabin pass through your interior control tangents at the limit (progressive interpolation on the Gaussian sphere); the border ones stay as set")
        .on_disabled_hover_text("Kobbelt interpolates the control tangents already")
        .changed()
    {
        p.send(Edit::SetInterpolateTangents(interp));
    }
    let details = p.patch.details().len();
    ui.label(egui::RichText::new(format!("{details} multiresolution details")).weak())
        .on_hover_text(
            "Tangents turned at deeper levels, kept in the frame of the subdivided tangent",
        );
}
