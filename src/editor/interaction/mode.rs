//! The editor's mode: streamline modeling, or a triangle mesh opened in mesh
//! mode (paper 002), while which the streamline surface, its handles and the
//! sphere view step aside (`in_state`, and `OnEnter`/`OnExit` for what is
//! shown and hidden).

use bevy_state::prelude::*;

/// What the editor works on.
#[derive(States, Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum EditorMode {
    /// The streamline surface: handles, picking, the sphere view.
    #[default]
    Streamline,
    /// A triangle mesh and its interpolating Loop surface.
    Mesh,
}
