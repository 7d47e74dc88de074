//! The handles on screen and what the pointer does with them, over the
//! interaction core that holds them: drawing them as arrows (`arrows`),
//! picking and turning one (`picking`), box selection (`box_select`), the
//! Gaussian sphere inset (`sphere_view`) with its handles' points (`sphere_dots`), and structure
//! edits on an arrow's row or column (`structure`).

pub(super) mod arrows;
pub(super) mod box_select;
pub(super) mod picking;
pub(super) mod sphere_dots;
pub(super) mod sphere_view;
pub(super) mod structure;
