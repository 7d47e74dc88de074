//! A script's step: its kinds ([`Step`]) and its reading by name: the
//! name read first, the rest of the step handed to the type that has a
//! variant of that name, so that every error keeps its place in the file.

use super::expect::Expect;
use super::fit_step::FitStep;
use crate::scene::edits::edit::{AuthorEdit, Edit};
use crate::scene::edits::patch_edit::PatchEdit;
use crate::scene::files::format::TuningSpec;
use serde::de::{
    self, DeserializeOwned, DeserializeSeed, EnumAccess, VariantAccess, Visitor,
    value::EnumAccessDeserializer,
};
use serde::{Deserialize, Deserializer, Serialize, Serializer};
use std::fmt;

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
}
