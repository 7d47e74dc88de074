//! Autosave and recovery: unsaved work (the whole design, every patch:
//! version 2 for one patch, 3 for several) is written to a recovery file
//! every couple of minutes and on quit (atomically, verified, like any save); on
//! start the editor offers to recover it when it is newer than the scene's
//! file. A save removes it; so does discarding changes on quit.

use super::files::open_save::{Dialog, EditorDirs, FileUi};
use super::screenshot::ScreenshotRequest;
use crate::ecs::Model;
use crate::ecs::joined::JoinedRead;
use crate::ecs::patch::PatchRef;
use crate::scene::design::document::Document;
use crate::scene::{design::document_io, files::io};
use bevy::prelude::*;
use std::path::PathBuf;
use std::time::{Duration, Instant, SystemTime};

/// How often unsaved work is written to the recovery file.
#[derive(Resource, Debug, Clone)]
pub struct AutosaveConfig {
    /// The interval.
    pub interval: Duration,
}

impl Default for AutosaveConfig {
    fn default() -> Self {
        let secs = std::env::var("STREAMLINE_STUDIO_AUTOSAVE_SECS")
            .ok()
            .and_then(|s| s.parse::<u64>().ok())
            .filter(|&s| s > 0)
            .unwrap_or(120);
        AutosaveConfig {
            interval: Duration::from_secs(secs),
        }
    }
}

#[derive(Resource)]
struct AutosaveState {
    last: Instant,
    dirty: bool,
    was_unsaved: bool,
}

/// Where the recovery file came from.
#[derive(Debug, serde::Serialize, serde::Deserialize)]
struct RecoveryMeta {
    origin: Option<PathBuf>,
}

pub struct AutosavePlugin;

impl Plugin for AutosavePlugin {
    fn build(&self, app: &mut App) {
        app.init_resource::<AutosaveConfig>()
            .insert_resource(AutosaveState {
                last: Instant::now(),
                dirty: false,
                was_unsaved: false,
            })
            .add_systems(Startup, offer_recovery)
            .add_systems(Update, tick)
            .add_systems(Last, on_exit);
    }
}

/// Writes the recovery file of `doc` (and `origin`, the file it came from).
pub fn write_recovery(
    dirs: &EditorDirs,
    doc: &Document,
    origin: Option<&std::path::Path>,
) -> Result<(), String> {
    std::fs::create_dir_all(&dirs.home).map_err(|e| format!("{}: {e}", dirs.home.display()))?;
    document_io::save(doc, &dirs.recovery_file()).map_err(|e| e.to_string())?;
    let meta = RecoveryMeta {
        origin: origin.map(|p| std::path::absolute(p).unwrap_or(p.to_path_buf())),
    };
    let text = serde_json::to_string(&meta).map_err(|e| e.to_string())?;
    io::write_atomic(&dirs.recovery_meta(), text.as_bytes(), |_| Ok(())).map_err(|e| e.to_string())
}

fn remove_recovery(dirs: &EditorDirs) {
    let _ = std::fs::remove_file(dirs.recovery_file());
    let _ = std::fs::remove_file(dirs.recovery_meta());
}

fn offer_recovery(
    dirs: Res<EditorDirs>,
    model: Res<Model>,
    shot: Option<Res<ScreenshotRequest>>,
    mut ui: ResMut<FileUi>,
) {
    if shot.is_some() {
        return;
    }
    if let Some(d) = pending_recovery(&dirs, model.path.as_deref()) {
        ui.dialog = Some(d);
    }
}

/// The recovery offer, if the recovery file exists and is newer than the
/// scene's file (`scene`: `None` for a built-in scene).
pub fn pending_recovery(dirs: &EditorDirs, scene: Option<&std::path::Path>) -> Option<Dialog> {
    let modified = |p: &std::path::Path| std::fs::metadata(p).and_then(|m| m.modified()).ok();
    let saved = modified(&dirs.recovery_file())?;
    let origin = std::fs::read_to_string(dirs.recovery_meta())
        .ok()
        .and_then(|t| serde_json::from_str::<RecoveryMeta>(&t).ok())
        .and_then(|m| m.origin);
    if scene.and_then(modified).is_some_and(|t| t >= saved) {
        return None; // the scene was saved after the autosave
    }
    let age = SystemTime::now().duration_since(saved).unwrap_or_default();
    Some(Dialog::Recover {
        when: format!("{} min ago", age.as_secs() / 60),
        origin,
    })
}

/// The design, every patch: its first patch's scene and the later patches.
#[derive(bevy::ecs::system::SystemParam)]
struct DesignRead<'w, 's> {
    patch: PatchRef<'w, 's>,
    joined: JoinedRead<'w, 's>,
}

impl DesignRead<'_, '_> {
    fn document(&self) -> Result<Document, String> {
        self.patch.scene().map(|s| self.joined.document(s))
    }
}

fn tick(
    meter: Res<crate::ecs::meter::CpuMeter>,
    dirs: Res<EditorDirs>,
    config: Res<AutosaveConfig>,
    model: Res<Model>,
    design: DesignRead,
    mut state: ResMut<AutosaveState>,
    mut ui: ResMut<FileUi>,
) {
    let _meter = meter.start();
    if model.is_changed() && model.unsaved {
        state.dirty = true;
    }
    // saved since: the recovery file is stale
    if state.was_unsaved && !model.unsaved {
        remove_recovery(&dirs);
        state.dirty = false;
    }
    state.was_unsaved = model.unsaved;
    if state.dirty && state.last.elapsed() >= config.interval {
        state.last = Instant::now();
        state.dirty = false;
        let written =
            (design.document()).and_then(|d| write_recovery(&dirs, &d, model.path.as_deref()));
        if let Err(e) = written {
            ui.errors.push(format!("autosave failed: {e}"));
        }
    }
}

fn on_exit(
    mut exits: MessageReader<AppExit>,
    dirs: Res<EditorDirs>,
    model: Res<Model>,
    design: DesignRead,
    ui: Res<FileUi>,
) {
    if exits.read().count() == 0 {
        return;
    }
    if model.unsaved
        && !ui.discarded
        && let Err(e) =
            (design.document()).and_then(|d| write_recovery(&dirs, &d, model.path.as_deref()))
    {
        error!("autosave on quit failed: {e}");
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::design::builtin;

    fn dirs(name: &str) -> EditorDirs {
        let home =
            std::env::temp_dir().join(format!("streamline-autosave-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&home);
        EditorDirs { home }
    }

    #[test]
    fn recovery_round_trip_and_offer() {
        let d = dirs("round");
        assert!(pending_recovery(&d, None).is_none(), "nothing saved yet");
        let mut scene = builtin::default_scene();
        scene.name = "edited car".into();
        let origin = d.home.join("car.ron");
        write_recovery(&d, &Document::from_scene(scene.clone()), Some(&origin)).unwrap();
        // the scene file does not exist: the autosave is newer
        match pending_recovery(&d, Some(&origin)) {
            Some(Dialog::Recover {
                origin: Some(o), ..
            }) => assert_eq!(o, origin),
            other => panic!("{other:?}"),
        }
        // the recovered scene is the saved one
        let back = document_io::load_scene(&d.recovery_file()).unwrap();
        assert_eq!(back.name, "edited car");
        assert_eq!(back.to_file(), scene.to_file());
        // a scene saved after the autosave: no offer
        std::thread::sleep(Duration::from_millis(20));
        document_io::save_scene(&scene, &origin).unwrap();
        assert!(pending_recovery(&d, Some(&origin)).is_none());
        // a built-in scene (no file): always offered
        assert!(pending_recovery(&d, None).is_some());
        remove_recovery(&d);
        assert!(pending_recovery(&d, None).is_none());
        let _ = std::fs::remove_dir_all(&d.home);
    }

    /// A design of several patches is autosaved whole (version 3) and
    /// recovered whole: the recovered document is the autosaved one.
    #[test]
    fn recovery_keeps_every_patch() {
        let d = dirs("patches");
        let hood =
            std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/hood-screen-wing.ron");
        let doc = document_io::load(&hood).unwrap();
        assert_eq!(doc.patches.len(), 3);
        write_recovery(&d, &doc, Some(&hood)).unwrap();
        let back = document_io::load(&d.recovery_file()).unwrap();
        assert_eq!(back.to_file(), doc.to_file());
        // one patch: the version-2 bytes a scene's save writes
        let scene = builtin::default_scene();
        write_recovery(&d, &Document::from_scene(scene.clone()), None).unwrap();
        let other = d.home.join("scene.ron");
        document_io::save_scene(&scene, &other).unwrap();
        assert_eq!(
            std::fs::read(d.recovery_file()).unwrap(),
            std::fs::read(&other).unwrap()
        );
        let _ = std::fs::remove_dir_all(&d.home);
    }
}
