//! Scene files: the shipped scenes, save → load identity, located errors,
//! atomic saving.

use proptest::prelude::*;
use std::path::Path;
use streamline_studio::scene::{Scene, builtin, io};

/// The shipped scenes are the kernel presets written out (set
/// `REGENERATE_SCENES=1` to write them again after changing a preset).
#[test]
fn shipped_scenes_match_presets() {
    for (name, _) in builtin::SCENES {
        let preset = builtin::preset(name).expect("every shipped scene has a preset");
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("scenes/{name}.ron"));
        if std::env::var_os("REGENERATE_SCENES").is_some() {
            std::fs::write(&path, preset.to_ron()).unwrap();
            continue; // the compiled-in copies are stale until the next build
        }
        let loaded = io::load(&path).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(
            loaded.to_file(),
            preset.to_file(),
            "{name}.ron differs from its preset"
        );
        let compiled = builtin::scene(name).unwrap();
        assert_eq!(
            compiled.to_file(),
            loaded.to_file(),
            "{name}: the compiled-in copy is stale"
        );
    }
    assert_eq!(builtin::default_scene().name, "car1");
}
