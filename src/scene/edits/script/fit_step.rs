//! The script step that fits a design to a reference ([`FitStep`]).

use crate::scene::files::format::Finite;
use serde::{Deserialize, Serialize};

/// The step that fits a design to a reference (docs/math.md §12, the `fit`
/// command's fit), written
///
/// ```ron
/// Fit(path: "panel.step", face: 0, along: U, tolerance: Relative(1e-4), depth: 5)
/// ```
///
/// with every field but `path` optional (the defaults shown; `max_net:
/// Some((rows, cols))` caps the net, 64 × 64 by default). The design
/// fitted replaces the current one as `Load` does (the history cleared), is
/// shown at the fit depth and keeps the file and face as its `reference`.
/// A file that cannot be read, a face that is not there or not a B-spline
/// surface, a face the fit refuses and a design not within the tolerance
/// are the step's error (which `ExpectError` can expect); the current design
/// then stays.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum FitStep {
    /// Fit face `face` of the STEP or IGES file `path` (relative to the script).
    Fit {
        /// The STEP (`.step`, `.stp`, `.p21`) or IGES (`.igs`, `.iges`) file.
        path: String,
        /// The face's index in the file (`streamline-studio faces` lists them).
        #[serde(default)]
        face: usize,
        /// The face's parameter the streamlines follow.
        #[serde(default)]
        along: AlongSpec,
        /// The largest allowed deviation, both ways.
        #[serde(default)]
        tolerance: ToleranceSpec,
        /// The fit depth: where the design is measured and shown (1–7).
        #[serde(default = "default_fit_depth")]
        depth: u32,
        /// The largest net, `(rows, columns)` of control tangents (each 4
        /// to the authoring cap, which is the default).
        #[serde(default)]
        max_net: Option<(usize, usize)>,
    },
}

fn default_fit_depth() -> u32 {
    streamline_kernel::fit::options::DEFAULT_DEPTH
}

/// Which parameter of the face a fit's streamlines follow.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub enum AlongSpec {
    /// Rows are the face's iso-curves `v = const` (the default).
    #[default]
    U,
    /// Rows are the face's iso-curves `u = const`.
    V,
}

/// A fit's tolerance as a script writes it.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub enum ToleranceSpec {
    /// A fraction of the face's bounding-box diagonal (default `1e-4`).
    Relative(Finite),
    /// A distance in metres.
    Absolute(Finite),
}

impl Default for ToleranceSpec {
    fn default() -> Self {
        ToleranceSpec::Relative(Finite(
            streamline_kernel::fit::options::DEFAULT_RELATIVE_TOLERANCE,
        ))
    }
}

impl FitStep {
    /// The fit's options: the kernel's defaults with the step's direction,
    /// tolerance and depth.
    pub fn options(&self) -> streamline_kernel::fit::ReferenceFitOptions {
        use streamline_kernel::fit::{Along, ReferenceFitOptions, Tolerance};
        let FitStep::Fit {
            along,
            tolerance,
            depth,
            max_net,
            ..
        } = self;
        let defaults = ReferenceFitOptions::default();
        ReferenceFitOptions {
            along: match along {
                AlongSpec::U => Along::U,
                AlongSpec::V => Along::V,
            },
            tolerance: match tolerance {
                ToleranceSpec::Relative(r) => Tolerance::Relative(r.0),
                ToleranceSpec::Absolute(a) => Tolerance::Absolute(a.0),
            },
            depth: *depth,
            max_net: max_net.unwrap_or(defaults.max_net),
            ..defaults
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::edits::script::Script;
    use crate::scene::edits::script::expect::Expect;
    use crate::scene::edits::script::step::Step;
    use std::path::Path;

    #[test]
    fn fit_steps_take_defaults_and_read_back() {
        use streamline_kernel::fit::{Along, ReferenceFitOptions, Tolerance};
        let text = "(steps: [Fit(path: \"p.step\"), \
            Fit(path: \"q.igs\", face: 2, along: V, tolerance: Absolute(1e-3), depth: 4, \
            max_net: Some((8, 9))), ExpectReferenceDeviation(max: 1e-4), \
            ExpectReferenceDeviation(max: 1.0, min: Some(2e-3))])";
        let s = Script::parse(text, Path::new("t.ron")).unwrap();
        let Step::Fit(f) = &s.steps[0] else {
            panic!("{:?}", s.steps[0])
        };
        assert_eq!(f.options(), ReferenceFitOptions::default());
        let Step::Fit(g) = &s.steps[1] else {
            panic!("{:?}", s.steps[1])
        };
        let o = g.options();
        assert_eq!(
            (o.along, o.tolerance, o.depth, o.max_net),
            (Along::V, Tolerance::Absolute(1e-3), 4, (8, 9))
        );
        assert!(!s.steps[1].is_expectation() && s.steps[2].is_expectation());
        assert!(matches!(
            &s.steps[3],
            Step::Expect(Expect::ExpectReferenceDeviation {
                max: Finite(1.0),
                min: Some(Finite(m)),
            }) if *m == 2e-3
        ));
        let again = ron::to_string(&s).unwrap();
        let back = Script::parse(&again, Path::new("t.ron")).unwrap();
        assert_eq!(ron::to_string(&back).unwrap(), again);
        assert!(format!("{:?}", back.steps[0]).starts_with("Fit { path: \"p.step\", face: 0"));
        // negative control: an unknown field is an error at its place
        let bad = Script::parse(
            "(steps: [Fit(path: \"p.step\", faces: 1)])",
            Path::new("t.ron"),
        );
        assert!(bad.unwrap_err().to_string().contains("faces"));
    }
}
