//! The shipped scenes (`scenes/*.ron`), compiled into the binary so the editor
//! opens the default scene from any directory.

use super::model::Scene;
use crate::scene::files::error::SceneError;
use std::path::Path;

/// Name and text of every shipped scene; the first is the default.
pub const SCENES: [(&str, &str); 7] = [
    ("car1", include_str!("../../../scenes/car1.ron")),
    ("car2", include_str!("../../../scenes/car2.ron")),
    ("qi-down", include_str!("../../../scenes/qi-down.ron")),
    ("qi-side", include_str!("../../../scenes/qi-side.ron")),
    ("qi-up", include_str!("../../../scenes/qi-up.ron")),
    ("minimal", include_str!("../../../scenes/minimal.ron")),
    ("car1-tuned", include_str!("../../../scenes/car1-tuned.ron")),
];

/// The default scene's name.
pub const DEFAULT: &str = "car1";

/// The names, for messages.
pub fn names() -> String {
    SCENES.map(|(n, _)| n).join(", ")
}

/// A shipped scene by name.
pub fn scene(name: &str) -> Result<Scene, SceneError> {
    let (n, text) = SCENES.iter().find(|(n, _)| *n == name).ok_or_else(|| {
        SceneError::file(
            Path::new(name),
            format!("no built-in scene of this name; use one of: {}", names()),
        )
    })?;
    Scene::parse(text, Path::new(&format!("scenes/{n}.ron")))
}

/// The default scene.
pub fn default_scene() -> Scene {
    scene(DEFAULT).expect("the shipped default scene is valid (tested)")
}

/// The kernel preset each shipped scene was written from, with its display depth.
pub fn preset(name: &str) -> Option<Scene> {
    use streamline_kernel::levels::presets;
    let (d, depth) = match name {
        "car1" => (presets::car1(), 4),
        "car2" => (presets::car2(), 4),
        "qi-down" => (presets::qi_demo(0), 4),
        "qi-side" => (presets::qi_demo(1), 4),
        "qi-up" => (presets::qi_demo(2), 4),
        "minimal" => (presets::minimal(), 2),
        "car1-tuned" => (presets::car1(), 4),
        _ => return None,
    };
    let mut s = Scene::from_design(name, d, depth);
    if name == "car1-tuned" {
        // fine tuning (paper 003): the middle of the roof stretched, the
        // front shortened, every streamline's ends kept
        let values = streamline_kernel::Grid::from_rows(&[
            vec![1.0, 0.8, 1.0, 1.0],
            vec![1.0, 1.0, 1.5, 1.0],
            vec![1.0, 0.8, 1.0, 1.0],
        ])
        .expect("3×4");
        s.tuning = Some(streamline_kernel::finetune::SurfaceTuning {
            function: streamline_kernel::finetune::bspline::TensorBSpline::new(2, 2, values)
                .expect("quadratic 3×4"),
            constraint: streamline_kernel::finetune::Constraint::KeepEnds,
        });
    }
    if name.starts_with("car") {
        s.view.target = crate::scene::files::format::Point(2.2, 0.0, 0.6);
    } else {
        s.view.target = crate::scene::files::format::Point(1.0, 0.0, 0.0);
        s.view.distance = crate::scene::files::format::Finite(5.0);
    }
    Some(s)
}
