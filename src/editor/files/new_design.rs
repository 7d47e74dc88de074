//! File ▸ New ▸ New design…: a dialog for a design from nothing
//! (`docs/math.md §9`): the control net's rows × columns (2–64 each), the
//! template (Flat with a width, Cylinder with a radius and an angle), the
//! streamline length and the scheme. Create sends the model's
//! `NewDesign` edit (after asking about unsaved changes, as every File ▸ New
//! does); the new scene comes unsaved, with display and edit depths chosen
//! for its size and a view that frames it.

use super::open_save::{self, FileUi, Pending};
use crate::ecs::authoring::AuthorEdit;
use crate::ecs::{EditMessage, Model};
use bevy::prelude::*;
use bevy_egui::{EguiContexts, EguiPrimaryContextPass, egui};
use streamline_kernel::SurfaceScheme;
use streamline_kernel::authoring::Template;

/// The smallest and largest control net side (docs/math.md §9).
pub const SIDES: std::ops::RangeInclusive<usize> = 2..=64;

/// Which template the dialog builds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TemplateKind {
    /// The rectangle `[0, L] × [0, W]` in `z = 0`.
    Flat,
    /// Part of the cylinder `y² + (z − r)² = r²`.
    Cylinder,
}

/// The dialog's fields (kept between openings).
#[derive(Resource, Debug, Clone, PartialEq)]
pub struct NewDesignForm {
    /// Shown.
    pub open: bool,
    /// Control rows (streamlines).
    pub rows: usize,
    /// Control columns (tangents along a streamline).
    pub cols: usize,
    /// Flat or Cylinder.
    pub kind: TemplateKind,
    /// Flat: the width across the streamlines.
    pub width: f64,
    /// Cylinder: the radius.
    pub radius: f64,
    /// Cylinder: the angle of the arc, degrees.
    pub degrees: f64,
    /// Every streamline's length.
    pub length: f64,
    /// The scheme (index into [`SCHEMES`]).
    pub scheme: usize,
}

impl Default for NewDesignForm {
    fn default() -> Self {
        NewDesignForm {
            open: false,
            rows: 5,
            cols: 6,
            kind: TemplateKind::Flat,
            width: 2.0,
            radius: 1.0,
            degrees: 120.0,
            length: 4.0,
            scheme: 0,
        }
    }
}

/// The schemes offered, by name.
pub const SCHEMES: [(&str, SurfaceScheme); 3] = [
    (
        "Kobbelt (4-point, ω = 1/16)",
        SurfaceScheme::Kobbelt { omega: 1.0 / 16.0 },
    ),
    (
        "Catmull–Clark (cubic B-spline)",
        SurfaceScheme::CatmullClark,
    ),
    ("Doo–Sabin (Chaikin)", SurfaceScheme::DooSabin),
];

impl NewDesignForm {
    /// The template the fields describe.
    pub fn template(&self) -> Template {
        match self.kind {
            TemplateKind::Flat => Template::Flat { width: self.width },
            TemplateKind::Cylinder => Template::Cylinder {
                radius: self.radius,
                degrees: self.degrees,
            },
        }
    }

    /// The edit that makes the design (the model checks every value again).
    pub fn edit(&self) -> AuthorEdit {
        AuthorEdit::NewDesign {
            rows: self.rows,
            cols: self.cols,
            length: self.length,
            template: self.template(),
            scheme: SCHEMES[self.scheme.min(SCHEMES.len() - 1)].1,
        }
    }

    /// What is wrong with the fields, if anything (the Create button stays
    /// off and says so).
    pub fn problem(&self) -> Option<String> {
        let side = |n: usize, what: &str| {
            (!SIDES.contains(&n)).then(|| format!("{what} must be 2 to 64 (is {n})"))
        };
        side(self.rows, "rows")
            .or_else(|| side(self.cols, "columns"))
            .or_else(|| {
                (!(self.length.is_finite() && self.length > 0.0))
                    .then(|| "the streamline length must be above 0".to_string())
            })
            .or_else(|| match self.kind {
                TemplateKind::Flat => (!(self.width.is_finite() && self.width > 0.0))
                    .then(|| "the width must be above 0".to_string()),
                TemplateKind::Cylinder => {
                    if !(self.radius.is_finite() && self.radius > 0.0) {
                        Some("the radius must be above 0".into())
                    } else if !(self.degrees > 0.0 && self.degrees < 360.0) {
                        Some("the angle must lie strictly between 0° and 360°".into())
                    } else {
                        None
                    }
                }
            })
    }
}

pub struct NewDesignPlugin;

impl Plugin for NewDesignPlugin {
    fn build(&self, app: &mut App) {
        app.init_resource::<NewDesignForm>()
            .add_systems(EguiPrimaryContextPass, dialog);
    }
}

fn dialog(
    meter: Res<crate::ecs::meter::CpuMeter>,
    mut contexts: EguiContexts,
    mut form: ResMut<NewDesignForm>,
    model: Res<Model>,
    mut files_ui: ResMut<FileUi>,
    mut edits: MessageWriter<EditMessage>,
    mut exit: MessageWriter<AppExit>,
) -> Result {
    let _meter = meter.start();
    if !form.open {
        return Ok(());
    }
    let ctx = contexts.ctx_mut()?;
    // edited on a copy: the resource is marked changed only when a field is
    let mut f = form.clone();
    let mut create = false;
    let mut open = true;
    egui::Window::new("New design")
        .id(egui::Id::new("new_design"))
        .collapsible(false)
        .resizable(false)
        .open(&mut open)
        .anchor(egui::Align2::CENTER_CENTER, [0.0, 0.0])
        .show(ctx, |ui| {
            egui::Grid::new("new_design_grid")
                .num_columns(2)
                .spacing([12.0, 6.0])
                .show(ui, |ui| {
                    ui.label("Rows (streamlines)");
                    ui.add(egui::DragValue::new(&mut f.rows).range(SIDES))
                        .on_hover_text("Control rows: one streamline each (2–64)");
                    ui.end_row();
                    ui.label("Columns (tangents)");
                    ui.add(egui::DragValue::new(&mut f.cols).range(SIDES))
                        .on_hover_text("Control tangents along each streamline (2–64)");
                    ui.end_row();
                    ui.label("Template");
                    ui.horizontal(|ui| {
                        ui.radio_value(&mut f.kind, TemplateKind::Flat, "Flat")
                            .on_hover_text("The rectangle [0, L] × [0, W] in z = 0");
                        ui.radio_value(&mut f.kind, TemplateKind::Cylinder, "Cylinder")
                            .on_hover_text(
                                "Part of the cylinder y² + (z − r)² = r², the initial curve an arc",
                            );
                    });
                    ui.end_row();
                    match f.kind {
                        TemplateKind::Flat => {
                            ui.label("Width W");
                            ui.add(
                                egui::DragValue::new(&mut f.width)
                                    .speed(0.02)
                                    .range(0.001..=1e4),
                            )
                            .on_hover_text(
                                "The initial curve's length: the extent across the streamlines (y)",
                            );
                            ui.end_row();
                        }
                        TemplateKind::Cylinder => {
                            ui.label("Radius r");
                            ui.add(
                                egui::DragValue::new(&mut f.radius)
                                    .speed(0.02)
                                    .range(0.001..=1e4),
                            )
                            .on_hover_text(
                                "The cylinder's radius (its axis is the line (·, 0, r))",
                            );
                            ui.end_row();
                            ui.label("Angle φ");
                            ui.add(
                                egui::DragValue::new(&mut f.degrees)
                                    .speed(1.0)
                                    .range(1.0..=359.0)
                                    .suffix("°"),
                            )
                            .on_hover_text(
                                "The arc of the initial curve (strictly between 0° and 360°)",
                            );
                            ui.end_row();
                        }
                    }
                    ui.label("Streamline length L");
                    ui.add(
                        egui::DragValue::new(&mut f.length)
                            .speed(0.02)
                            .range(0.001..=1e4),
                    )
                    .on_hover_text("Every streamline's length (x); each can be changed later");
                    ui.end_row();
                    ui.label("Scheme");
                    egui::ComboBox::from_id_salt("new_design_scheme")
                        .selected_text(SCHEMES[f.scheme.min(SCHEMES.len() - 1)].0)
                        .show_ui(ui, |ui| {
                            for (i, (name, _)) in SCHEMES.iter().enumerate() {
                                ui.selectable_value(&mut f.scheme, i, *name);
                            }
                        });
                    ui.end_row();
                });
            ui.separator();
            let problem = f.problem();
            ui.horizontal(|ui| {
                create = ui
                    .add_enabled(problem.is_none(), egui::Button::new("Create"))
                    .on_hover_text("Open the new design as an unsaved scene")
                    .on_disabled_hover_text(problem.clone().unwrap_or_default())
                    .clicked();
                if ui.button("Cancel").clicked() {
                    f.open = false;
                }
            });
            if let Some(p) = problem {
                ui.label(egui::RichText::new(p).color(egui::Color32::LIGHT_RED));
            }
        });
    if !open || create {
        f.open = false;
    }
    if create {
        open_save::request(
            Pending::NewDesign(Box::new(f.edit())),
            &model,
            &mut files_ui,
            &mut edits,
            &mut exit,
        );
    }
    if *form != f {
        *form = f;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn new_design_form_refuses_what_the_kernel_refuses() {
        let ok = NewDesignForm::default();
        assert_eq!(ok.problem(), None);
        for bad in [
            NewDesignForm {
                rows: 1,
                ..ok.clone()
            },
            NewDesignForm {
                cols: 65,
                ..ok.clone()
            },
            NewDesignForm {
                length: 0.0,
                ..ok.clone()
            },
            NewDesignForm {
                width: f64::NAN,
                ..ok.clone()
            },
            NewDesignForm {
                kind: TemplateKind::Cylinder,
                degrees: 360.0,
                ..ok.clone()
            },
            NewDesignForm {
                kind: TemplateKind::Cylinder,
                radius: -1.0,
                ..ok.clone()
            },
        ] {
            let p = bad.problem();
            assert!(p.is_some(), "{bad:?} was accepted");
            // and the model refuses the same values
            let AuthorEdit::NewDesign {
                rows,
                cols,
                length,
                template,
                scheme,
            } = bad.edit()
            else {
                unreachable!()
            };
            assert!(
                crate::scene::Scene::new_design(rows, cols, length, template, scheme).is_err(),
                "{bad:?}: the form says {p:?} but the model builds it"
            );
        }
        // what the form accepts, the model builds, at every template
        for kind in [TemplateKind::Flat, TemplateKind::Cylinder] {
            for scheme in 0..SCHEMES.len() {
                let f = NewDesignForm {
                    kind,
                    scheme,
                    rows: 2,
                    cols: 64,
                    ..ok.clone()
                };
                let AuthorEdit::NewDesign {
                    rows,
                    cols,
                    length,
                    template,
                    scheme,
                } = f.edit()
                else {
                    unreachable!()
                };
                let s = crate::scene::Scene::new_design(rows, cols, length, template, scheme)
                    .unwrap_or_else(|e| panic!("{f:?}: {e}"));
                assert_eq!((s.design.net().rows(), s.design.net().cols()), (2, 64));
            }
        }
    }
}
