//! Scripts: a RON list of steps, each a file operation, an edit (the
//! [`Edit`](crate::scene::edits::edit::Edit) a user makes in the editor) or an expectation checked by
//! `streamline-studio play`.
//!
//! ```ron
//! (steps: [
//!     Load("../../scenes/car1.ron"),          // paths are relative to the script
//!     SetDirection(row: 2, col: 4, dir: (1.0, 0.0, 0.4)),
//!     ExpectStats(max_reintegrated: Some(40)),
//!     Undo,
//!     ExpectSame(mark: "start", tolerance: 0.0),
//! ])
//! ```
//!
//! The steps are [`step::Step`] (read by name, each handed to the type that
//! has it: an edit, an [`expect::Expect`] or a [`fit_step::FitStep`]); where
//! a script may write is [`output`].

pub mod expect;
pub mod fit_step;
pub mod output;
pub mod step;

use crate::scene::files::error::SceneError;
use serde::{Deserialize, Serialize};
use std::path::Path;
use step::Step;

/// The most steps a script may hold (larger scripts are refused before running).
pub const MAX_STEPS: usize = 1_000_000;

/// A script file.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Script {
    /// The steps, run in order.
    pub steps: Vec<Step>,
}

impl Script {
    /// Parses script text.
    pub fn parse(text: &str, file: &Path) -> Result<Self, SceneError> {
        if text.trim().is_empty() {
            return Err(SceneError::at(
                file,
                1,
                1,
                "the file is empty; a script is `(steps: [ … ])` — see tests/scripts/01-set-direction.ron",
            ));
        }
        let s: Script = ron::Options::default()
            .from_str(text)
            .map_err(|e| SceneError::ron(file, text, &e))?;
        if s.steps.len() > MAX_STEPS {
            return Err(SceneError::locate(
                file,
                text,
                "steps",
                format!(
                    "{} steps is over the limit of {MAX_STEPS}; split the script",
                    s.steps.len()
                ),
            ));
        }
        Ok(s)
    }

    /// Reads a script file.
    pub fn load(path: &Path) -> Result<Self, SceneError> {
        let text =
            crate::scene::files::io::read_text(path, crate::scene::files::io::MAX_SCENE_BYTES)?;
        Script::parse(&text, path)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::edits::edit::{AuthorEdit, Edit};

    #[test]
    fn steps_read_back_as_themselves() {
        let text = "(steps: [Rotate(row: 1, col: 2, axis: (0.0, 0.0, 1.0), degrees: 0.1), \
            InsertColumn(at: 3), DeleteRow(1), NewDesign(rows: 4, cols: 5, length: 2.0, \
            template: Flat(width: 1.0)), Load(\"a.ron\"), Mark(\"m\")])";
        let s = Script::parse(text, Path::new("t.ron")).unwrap();
        assert!(matches!(
            s.steps[1],
            Step::Edit(Edit::Author(AuthorEdit::InsertColumn { at: 3 }))
        ));
        assert!(s.steps[5].is_expectation());
        let again = ron::to_string(&s).unwrap();
        let back = Script::parse(&again, Path::new("t.ron")).unwrap();
        assert_eq!(ron::to_string(&back).unwrap(), again);
        assert_eq!(format!("{:?}", back.steps[4]), "Load(\"a.ron\")");
        assert_eq!(format!("{:?}", back.steps[5]), "Mark(\"m\")");
    }

    #[test]
    fn angles_read_back_as_the_same_radians() {
        for d in [0.1, 12.3456, -7.77777, 1e-320, 1e308, -0.0, 359.9999999] {
            let text = format!(
                "(steps: [RotateInitial(index: 0, axis: (0.0, 0.0, 1.0), degrees: {d:e})])"
            );
            let s = Script::parse(&text, Path::new("t.ron")).unwrap();
            let again = ron::to_string(&s).unwrap();
            let back = Script::parse(&again, Path::new("t.ron")).unwrap();
            let radians = |s: &Script| match &s.steps[0] {
                Step::Edit(Edit::Author(AuthorEdit::RotateInitial { radians, .. })) => *radians,
                _ => unreachable!(),
            };
            assert_eq!(radians(&back).to_bits(), radians(&s).to_bits(), "{d}");
        }
    }
}
