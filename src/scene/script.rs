//! Scripts: a RON list of steps, each a file operation, an edit (the
//! [`Edit`] a user makes in the editor) or an expectation checked by
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

use super::edit::{AuthorEdit, Edit};
use super::error::SceneError;
use super::format::{Finite, OrderSpec, Point, SchemeSpec, TuningSpec};
use super::format_v3::ContinuitySpec;
use super::patch_edit::PatchEdit;
use serde::de::{
    self, DeserializeOwned, DeserializeSeed, EnumAccess, VariantAccess, Visitor,
    value::EnumAccessDeserializer,
};
use serde::{Deserialize, Deserializer, Serialize, Serializer};
use std::fmt;
use std::path::{Path, PathBuf};

/// The most steps a script may hold (larger scripts are refused before running).
pub const MAX_STEPS: usize = 1_000_000;

/// A script file.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Script {
    /// The steps, run in order.
    pub steps: Vec<Step>,
}

/// One step: a file operation, an edit, or an expectation. In RON each is
/// written by its name alone (`SetDirection(row: 2, col: 4, dir: (1.0, 0.0, 0.4))`,
/// `Undo`, `ExpectSame(mark: "start", tolerance: 0.0)`): an edit step is the
/// very [`Edit`] the model applies, named by its variant (an authoring edit
/// by its [`AuthorEdit`] variant, a patch edit by its [`PatchEdit`] variant).
#[derive(Clone)]
pub enum Step {
    /// Opens a scene file (relative to the script) or `builtin:NAME`.
    Load(String),
    /// Saves the scene (relative to the script).
    Save(String),
    /// Exports the surface (relative to the script) by the extension: the
    /// mesh as `.obj`, `.stl` or `.glb`, the fitted B-spline surface as
    /// `.step`/`.stp` or `.igs`/`.iges` (default degree and tolerance).
    Export(String),
    /// Turns fine tuning on with this function (see the scene's `tuning`), or
    /// off with `None`: [`Edit::SetTuning`], the function checked when the
    /// step runs (a bad one is the step's error, which `ExpectError` can expect).
    SetTuning(Option<TuningSpec>),
    /// Fits a design to a face of a STEP or IGES file and opens it in place
    /// of the current one ([`FitStep`], docs/math.md §12).
    Fit(FitStep),
    /// An edit, sent to the model as it is.
    Edit(Edit),
    /// An expectation, checked against the model.
    Expect(Expect),
}

/// Every step's name, in the order an unknown step's message lists them
/// (as `docs/scenes.md` does): files, edits, expectations.
const STEPS: &[&str] = &[
    "Load",
    "Save",
    "Export",
    "Fit",
    "SetDirection",
    "Rotate",
    "SetLength",
    "ClearDetail",
    "SetScheme",
    "SetBlendOrder",
    "SetDisplayDepth",
    "SetEditDepth",
    "SetTuning",
    "SetTuningValue",
    "SetTuningConstraint",
    "SetInterpolateTangents",
    "NewDesign",
    "InsertRow",
    "InsertColumn",
    "DeleteRow",
    "DeleteColumn",
    "SetInitialDirection",
    "RotateInitial",
    "SetInitialLength",
    "SetInitialOrigin",
    "SetInitialOrder",
    "SetAnchor",
    "SetStreamlineLength",
    "RotateMany",
    "SetMirror",
    "Undo",
    "Redo",
    "ExpectPoint",
    "ExpectStats",
    "ExpectScene",
    "ExpectStreamlineLength",
    "ExpectMirrorSymmetric",
    "ExpectReferenceDeviation",
    "ExpectError",
    "Mark",
    "ExpectSame",
    "ExpectChanged",
    "ExpectEndsSame",
    "ExpectShifted",
    "AddPatch",
    "SetPatch",
    "RemovePatch",
    "RenamePatch",
    "HidePatch",
    "ExpectSeam",
];

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

/// One expectation: checked by `streamline-studio play`, not sent to the model.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum Expect {
    /// Point `index` of streamline `row` (display depth) is within `tolerance` of `near`.
    ExpectPoint {
        row: usize,
        index: usize,
        near: Point,
        tolerance: Finite,
    },
    /// Bounds on what the last edit recomputed.
    ExpectStats {
        #[serde(default)]
        max_reblended: Option<usize>,
        #[serde(default)]
        max_reintegrated: Option<usize>,
        #[serde(default)]
        min_reintegrated: Option<usize>,
        #[serde(default)]
        full_rebuild: Option<bool>,
    },
    /// Properties of the scene.
    ExpectScene {
        #[serde(default)]
        display_depth: Option<u32>,
        #[serde(default)]
        edit_depth: Option<u32>,
        #[serde(default)]
        scheme: Option<SchemeSpec>,
        #[serde(default)]
        blend_order: Option<OrderSpec>,
        #[serde(default)]
        streamlines: Option<usize>,
        #[serde(default)]
        details: Option<usize>,
        #[serde(default)]
        can_undo: Option<bool>,
        #[serde(default)]
        can_redo: Option<bool>,
        #[serde(default)]
        tuning: Option<bool>,
        #[serde(default)]
        interpolate_tangents: Option<bool>,
        /// Control rows of the net.
        #[serde(default)]
        rows: Option<usize>,
        /// Control columns of the net.
        #[serde(default)]
        cols: Option<usize>,
        /// Mirror symmetry on.
        #[serde(default)]
        mirror: Option<bool>,
        /// The anchor column.
        #[serde(default)]
        anchor: Option<usize>,
        /// The initial curve's QI order.
        #[serde(default)]
        initial_order: Option<usize>,
    },
    /// Control row `row`'s streamline is `length` long, within `tolerance`.
    ExpectStreamlineLength {
        row: usize,
        length: Finite,
        tolerance: Finite,
    },
    /// The surface shown (both halves when mirrored) equals its reflection in
    /// the mirror plane within `tolerance`, and the mirror is on.
    ExpectMirrorSymmetric { tolerance: Finite },
    /// Every streamline point of the first patch at the display depth (the
    /// design's own half when mirrored) is within `max` of the face the
    /// design's `reference` names, and, with `min: Some(m)`, some point is
    /// further than `m` (a design edited away from its reference); the
    /// distance is to the closest point of the face (docs/math.md §12,
    /// eq. 12.6). A design without a reference, or a reference file that
    /// cannot be read, is the step's error (which `ExpectError` can expect).
    ExpectReferenceDeviation {
        max: Finite,
        #[serde(default)]
        min: Option<Finite>,
    },
    /// The previous step failed with a message containing this text.
    ExpectError(String),
    /// Remembers every streamline point under a name.
    Mark(String),
    /// Every streamline point is within `tolerance` of those remembered under `mark`.
    ExpectSame { mark: String, tolerance: Finite },
    /// Every streamline point differs from `mark` by more than `tolerance` somewhere.
    ExpectChanged { mark: String, tolerance: Finite },
    /// The first and last points of every streamline are within `tolerance` of those under `mark`.
    ExpectEndsSame { mark: String, tolerance: Finite },
    /// Every streamline point is the one under `mark` moved by `by`, within `tolerance`.
    ExpectShifted {
        mark: String,
        by: Point,
        tolerance: Finite,
    },
    /// The seam between patches `a` and `b` (which starts on `a`) has
    /// `continuity`, a gap of at most `max_gap` and a normal angle of at
    /// most `max_angle_deg` (docs/math.md §11). Naming a patch that is not
    /// there, or two patches without a seam, is the step's error (which
    /// `ExpectError` can expect).
    ExpectSeam {
        a: String,
        b: String,
        continuity: ContinuitySpec,
        max_gap: Finite,
        max_angle_deg: Finite,
    },
}

impl Step {
    /// Whether the step is an expectation (checked, not sent to the model).
    pub fn is_expectation(&self) -> bool {
        matches!(self, Step::Expect(_))
    }
}

/// As written in the script: the edit or expectation by its own name.
impl fmt::Debug for Step {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Step::Load(p) => f.debug_tuple("Load").field(p).finish(),
            Step::Save(p) => f.debug_tuple("Save").field(p).finish(),
            Step::Export(p) => f.debug_tuple("Export").field(p).finish(),
            Step::SetTuning(t) => f.debug_tuple("SetTuning").field(t).finish(),
            Step::Fit(x) => fmt::Debug::fmt(x, f),
            Step::Edit(Edit::Author(a)) => fmt::Debug::fmt(a, f),
            Step::Edit(Edit::Patch(p)) => fmt::Debug::fmt(p, f),
            Step::Edit(e) => fmt::Debug::fmt(e, f),
            Step::Expect(x) => fmt::Debug::fmt(x, f),
        }
    }
}

impl Serialize for Step {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        match self {
            Step::Load(p) => s.serialize_newtype_variant("Step", 0, "Load", p),
            Step::Save(p) => s.serialize_newtype_variant("Step", 1, "Save", p),
            Step::Export(p) => s.serialize_newtype_variant("Step", 2, "Export", p),
            Step::SetTuning(t) => s.serialize_newtype_variant("Step", 12, "SetTuning", t),
            Step::Fit(x) => x.serialize(s),
            Step::Edit(Edit::Author(a)) => a.serialize(s),
            Step::Edit(Edit::Patch(p)) => p.serialize(s),
            Step::Edit(e) => e.serialize(s),
            Step::Expect(x) => x.serialize(s),
        }
    }
}

/// Reads the step's name, then hands the rest of the step to the type that
/// has a variant of that name ([`Edit`], [`AuthorEdit`], [`PatchEdit`],
/// [`Expect`], [`FitStep`]): the
/// same reader goes on, so every error keeps its place in the file.
impl<'de> Deserialize<'de> for Step {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_enum("Step", STEPS, StepVisitor)
    }
}

struct StepVisitor;

impl<'de> Visitor<'de> for StepVisitor {
    type Value = Step;

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("a script step")
    }

    fn visit_enum<A: EnumAccess<'de>>(self, data: A) -> Result<Step, A::Error> {
        let (name, rest) = data.variant_seed(StepName)?;
        let named = |rest| EnumAccessDeserializer::new(Named { name, rest });
        Ok(match name {
            "Load" => Step::Load(rest.newtype_variant()?),
            "Save" => Step::Save(rest.newtype_variant()?),
            "Export" => Step::Export(rest.newtype_variant()?),
            "SetTuning" => Step::SetTuning(rest.newtype_variant()?),
            "Fit" => Step::Fit(FitStep::deserialize(named(rest))?),
            _ if names::<Expect>().contains(&name) => {
                Step::Expect(Expect::deserialize(named(rest))?)
            }
            _ if names::<PatchEdit>().contains(&name) => {
                Step::Edit(Edit::Patch(PatchEdit::deserialize(named(rest))?))
            }
            _ if names::<AuthorEdit>().contains(&name) => {
                Step::Edit(Edit::Author(AuthorEdit::deserialize(named(rest))?))
            }
            _ => Step::Edit(Edit::deserialize(named(rest))?),
        })
    }
}

/// A step's name, one of [`STEPS`].
struct StepName;

impl<'de> DeserializeSeed<'de> for StepName {
    type Value = &'static str;

    fn deserialize<D: Deserializer<'de>>(self, d: D) -> Result<&'static str, D::Error> {
        d.deserialize_identifier(self)
    }
}

impl Visitor<'_> for StepName {
    type Value = &'static str;

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("a step name")
    }

    fn visit_str<E: de::Error>(self, v: &str) -> Result<&'static str, E> {
        STEPS
            .iter()
            .find(|s| **s == v)
            .copied()
            .ok_or_else(|| E::unknown_variant(v, STEPS))
    }
}

/// A step whose name is read, as an enum for the type that has that name.
struct Named<V> {
    name: &'static str,
    rest: V,
}

impl<'de, V: VariantAccess<'de>> EnumAccess<'de> for Named<V> {
    type Error = V::Error;
    type Variant = V;

    fn variant_seed<S: DeserializeSeed<'de>>(self, seed: S) -> Result<(S::Value, V), V::Error> {
        let name = seed.deserialize(de::value::StrDeserializer::<V::Error>::new(self.name))?;
        Ok((name, self.rest))
    }
}

/// The variant names `T`'s derived `Deserialize` reads: serde hands them to
/// `deserialize_enum`, where this deserializer catches them.
fn names<T: DeserializeOwned>() -> &'static [&'static str] {
    #[derive(Debug)]
    struct Names(&'static [&'static str]);
    impl fmt::Display for Names {
        fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
            f.write_str("variant names")
        }
    }
    impl std::error::Error for Names {}
    impl de::Error for Names {
        fn custom<M: fmt::Display>(_: M) -> Self {
            Names(&[])
        }
    }
    struct Probe;
    impl<'de> Deserializer<'de> for Probe {
        type Error = Names;
        fn deserialize_any<V: Visitor<'de>>(self, _: V) -> Result<V::Value, Names> {
            Err(Names(&[]))
        }
        fn deserialize_enum<V: Visitor<'de>>(
            self,
            _: &'static str,
            variants: &'static [&'static str],
            _: V,
        ) -> Result<V::Value, Names> {
            Err(Names(variants))
        }
        serde::forward_to_deserialize_any! {
            bool i8 i16 i32 i64 i128 u8 u16 u32 u64 u128 f32 f64 char str string
            bytes byte_buf option unit unit_struct newtype_struct seq tuple
            tuple_struct map struct identifier ignored_any
        }
    }
    match T::deserialize(Probe) {
        Err(Names(v)) => v,
        Ok(_) => &[],
    }
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
        let text = super::io::read_text(path, super::io::MAX_SCENE_BYTES)?;
        Script::parse(&text, path)
    }
}

/// Where a script's `Save` or `Export` of `p` writes, for a script in `dir`.
/// Scripts are data: they write only inside their own folder, so `p` must be
/// a relative path that never climbs above it (checked on the words of the
/// path; [`confine`] checks the folder on disk, links resolved).
pub fn output_path(dir: &Path, p: &str) -> Result<PathBuf, String> {
    use std::path::Component;
    let refuse = || {
        format!(
            "`{p}` would write outside the script's folder ({}); scripts write only there: give a relative path such as \"out/scene.ron\"",
            dir.display()
        )
    };
    let mut depth = 0i32;
    for c in Path::new(p).components() {
        match c {
            Component::Normal(_) => depth += 1,
            Component::CurDir => {}
            Component::ParentDir => depth -= 1,
            Component::RootDir | Component::Prefix(_) => depth = -1,
        }
        if depth < 0 {
            return Err(refuse());
        }
    }
    if depth == 0 {
        return Err(format!(
            "`{p}` names the script's folder itself, not a file; give a file name such as \"out/scene.ron\""
        ));
    }
    Ok(dir.join(p))
}

/// Creates the folder of `path` (from [`output_path`]) and checks that, with
/// symbolic links resolved, it still lies inside `dir`: a link inside the
/// script's folder cannot lead a write elsewhere.
pub fn confine(dir: &Path, path: &Path) -> Result<(), String> {
    let parent = path.parent().unwrap_or(dir);
    std::fs::create_dir_all(parent)
        .map_err(|e| format!("cannot create {}: {e}", parent.display()))?;
    let real_dir = dir
        .canonicalize()
        .map_err(|e| format!("cannot resolve {}: {e}", dir.display()))?;
    let real_parent = parent
        .canonicalize()
        .map_err(|e| format!("cannot resolve {}: {e}", parent.display()))?;
    let link_out = |p: &Path| {
        format!(
            "`{}` leads outside the script's folder ({}) through a symbolic link; scripts write only there",
            p.display(),
            real_dir.display()
        )
    };
    if !real_parent.starts_with(&real_dir) {
        return Err(link_out(path));
    }
    // the file itself may be a link to elsewhere
    if let Ok(meta) = std::fs::symlink_metadata(path)
        && meta.file_type().is_symlink()
    {
        return Err(link_out(path));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_step_name_is_read_by_one_type() {
        let mut read: Vec<&str> = ["Load", "Save", "Export", "SetTuning"]
            .into_iter()
            .chain(names::<Edit>().iter().copied())
            .chain(names::<AuthorEdit>().iter().copied())
            .chain(names::<Expect>().iter().copied())
            .chain(names::<PatchEdit>().iter().copied())
            .chain(names::<FitStep>().iter().copied())
            .collect();
        let mut listed = STEPS.to_vec();
        read.sort_unstable();
        listed.sort_unstable();
        assert_eq!(read, listed);
    }

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
