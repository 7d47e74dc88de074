//! Where the editor keeps its own files ([`EditorDirs`]): the recent-files
//! list, read at the start and written when it changes, and the recovery
//! file that autosave writes.

use bevy::prelude::Resource;
use std::path::PathBuf;

/// Where the editor keeps its own files: `recent.json` and the recovery file.
#[derive(Resource, Debug, Clone)]
pub struct EditorDirs {
    /// The folder.
    pub home: PathBuf,
}

impl EditorDirs {
    /// `$STREAMLINE_STUDIO_HOME`, else `$XDG_STATE_HOME/streamline-studio`,
    /// else `~/.local/state/streamline-studio`, else a folder in the temp dir.
    pub fn from_env() -> Self {
        let env = |k: &str| {
            std::env::var_os(k)
                .filter(|v| !v.is_empty())
                .map(PathBuf::from)
        };
        let home = env("STREAMLINE_STUDIO_HOME")
            .or_else(|| env("XDG_STATE_HOME").map(|p| p.join("streamline-studio")))
            .or_else(|| env("HOME").map(|p| p.join(".local/state/streamline-studio")))
            .unwrap_or_else(|| std::env::temp_dir().join("streamline-studio"));
        EditorDirs { home }
    }

    /// The recent-files list.
    pub fn recent_file(&self) -> PathBuf {
        self.home.join("recent.json")
    }

    /// The recovery scene written by autosave.
    pub fn recovery_file(&self) -> PathBuf {
        self.home.join("recovery.ron")
    }

    /// Where the recovery scene came from (its path, if it had one).
    pub fn recovery_meta(&self) -> PathBuf {
        self.home.join("recovery.json")
    }
}

/// The most recent files kept.
pub const RECENT_MAX: usize = 8;

/// The recent-files list, newest first (empty when there is none).
pub(super) fn read_recent(dirs: &EditorDirs) -> Vec<PathBuf> {
    let mut recent = std::fs::read_to_string(dirs.recent_file())
        .ok()
        .and_then(|t| serde_json::from_str::<Vec<PathBuf>>(&t).ok())
        .unwrap_or_default();
    recent.truncate(RECENT_MAX);
    recent
}

pub(super) fn save_recent(dirs: &EditorDirs, recent: &[PathBuf]) {
    let _ = std::fs::create_dir_all(&dirs.home);
    if let Ok(text) = serde_json::to_string_pretty(recent) {
        // a lost recent list is no loss of work; still written atomically
        let _ =
            crate::scene::files::io::write_atomic(&dirs.recent_file(), text.as_bytes(), |_| Ok(()));
    }
}
