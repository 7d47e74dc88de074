//! The scene file, version 3: several patches (docs/math.md §11). The
//! design keeps `name`, `display_depth`, `edit_depth`, `mirror`, `view` and
//! its `reference` (docs/math.md §12, [`super::reference_link`]);
//! each patch holds every per-surface field of version 2
//! ([`super::format::SceneFile`]) and a unique `name`, and its `initial` is
//! either its own curve or an edge of an earlier patch. Every field is checked
//! while it is read, as in version 2 (so errors carry a line and column);
//! unknown fields are errors.
//!
//! ```ron
//! (
//!     version: 3,
//!     name: "hood-screen-wing",
//!     display_depth: 4,
//!     edit_depth: 0,
//!     mirror: false,
//!     view: (yaw: -35.0, pitch: 28.0, distance: 8.0, target: (1.0, 0.0, 0.5)),
//!     reference: Some((path: "panel.step", face: 2)),   // optional (docs/math.md §12)
//!     patches: [
//!         (
//!             name: "hood",
//!             tangents: [[…], …], s: [[…], …], t: […], anchor: 0,
//!             initial: Curve(tangents: [(0.0, 1.0, 0.1), …], order: 3, length: 1.6, origin: (0.0, -0.8, 0.6)),
//!             scheme: Kobbelt(omega: 1.0), blend_order: SFirst, details: [], tuning: None,
//!         ),
//!         (
//!             name: "screen",
//!             …,
//!             initial: Edge(patch: "hood", edge: End, continuity: G2),
//!             …,
//!         ),
//!     ],
//! )
//! ```

use super::format::{
    DetailSpec, Dir, Finite, InitialSpec, OrderSpec, Point, SRow, SceneFile, SchemeSpec,
    TuningSpec, VERSION, Version, ViewSpec,
};
use super::reference_link::ReferenceSpec;
use serde::de::Error as _;
use serde::{Deserialize, Deserializer, Serialize};
use streamline_kernel::joins::{Continuity, Edge};

pub use super::format::VERSION_PATCHES;

/// A version-3 scene file as written on disk.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DocumentFile {
    /// Always 3.
    pub version: Version3,
    /// A display name.
    #[serde(default)]
    pub name: String,
    /// Levels shown.
    #[serde(default = "default_display_depth")]
    pub display_depth: u32,
    /// Level whose tangents are the handles.
    #[serde(default)]
    pub edit_depth: u32,
    /// Mirror symmetry in the first patch's plane (docs/math.md §9, §11).
    #[serde(default)]
    pub mirror: bool,
    /// The camera.
    #[serde(default)]
    pub view: ViewSpec,
    /// The reference the design was fitted to or is measured against
    /// (docs/math.md §12): its path relative to this file's folder and the
    /// face; absent when there is none.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub reference: Option<ReferenceSpec>,
    /// The patches, each starting on its own curve or on an earlier patch's edge.
    pub patches: Vec<PatchFile>,
}

fn default_display_depth() -> u32 {
    3
}

/// One patch of a version-3 file: the per-surface fields of version 2 and a name.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PatchFile {
    /// Unique, `[A-Za-z0-9_-]`, 1–32 characters.
    pub name: String,
    /// Control tangents, one row per streamline.
    pub tangents: Vec<Vec<Dir>>,
    /// Arc-length parameter of each tangent, same shape as `tangents`.
    pub s: Vec<SRow>,
    /// Per row, the arc length where its streamline starts (on the initial
    /// curve, or along the edge it starts on).
    pub t: Vec<Finite>,
    /// The anchor column (0 for a patch that starts on an edge).
    #[serde(default)]
    pub anchor: usize,
    /// Where the patch starts.
    pub initial: StartSpec,
    /// The subdivision scheme.
    pub scheme: SchemeSpec,
    /// Which direction is blended first.
    #[serde(default)]
    pub blend_order: OrderSpec,
    /// Multiresolution details (docs/math.md §5).
    #[serde(default)]
    pub details: Vec<DetailSpec>,
    /// Fine tuning (docs/math.md §6).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tuning: Option<TuningSpec>,
    /// Progressive interpolation of the control tangents (docs/math.md §7).
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub interpolate_tangents: bool,
}

/// Where a patch starts: its own QI curve, or an edge of an earlier patch.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum StartSpec {
    /// Its own initial curve, as version 2's `initial`.
    Curve {
        /// The curve's control tangents.
        tangents: Vec<Dir>,
        /// QI order (2–8; 3 is usual).
        order: usize,
        /// Arc length.
        length: Finite,
        /// Start point.
        origin: Point,
    },
    /// On `edge` of the earlier patch `patch`, with `continuity` across it.
    Edge {
        /// The patch it starts on.
        patch: String,
        /// `End`, `First` or `Last`.
        edge: EdgeSpec,
        /// `G0`, `G1` or `G2`.
        continuity: ContinuitySpec,
    },
}

impl StartSpec {
    /// From version 2's initial curve.
    pub fn curve(c: &InitialSpec) -> Self {
        StartSpec::Curve {
            tangents: c.tangents.clone(),
            order: c.order,
            length: c.length,
            origin: c.origin,
        }
    }

    /// The initial curve, if the patch has its own.
    pub fn initial(&self) -> Option<InitialSpec> {
        match self {
            StartSpec::Curve {
                tangents,
                order,
                length,
                origin,
            } => Some(InitialSpec {
                tangents: tangents.clone(),
                order: *order,
                length: *length,
                origin: *origin,
            }),
            StartSpec::Edge { .. } => None,
        }
    }
}

/// An edge of the patch a patch starts on (docs/math.md §11).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum EdgeSpec {
    /// The curve of the streamlines' last points: a chain.
    End,
    /// The first streamline (control row 0): a side join.
    First,
    /// The last streamline: a side join.
    Last,
}

impl EdgeSpec {
    /// The kernel's edge.
    pub fn to_kernel(self) -> Edge {
        match self {
            EdgeSpec::End => Edge::End,
            EdgeSpec::First => Edge::First,
            EdgeSpec::Last => Edge::Last,
        }
    }

    /// From the kernel's.
    pub fn from_kernel(e: Edge) -> Self {
        match e {
            Edge::End => EdgeSpec::End,
            Edge::First => EdgeSpec::First,
            Edge::Last => EdgeSpec::Last,
        }
    }
}

/// The continuity across a join.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum ContinuitySpec {
    /// Position.
    G0,
    /// Tangency.
    G1,
    /// Curvature.
    G2,
}

impl ContinuitySpec {
    /// The kernel's continuity.
    pub fn to_kernel(self) -> Continuity {
        match self {
            ContinuitySpec::G0 => Continuity::G0,
            ContinuitySpec::G1 => Continuity::G1,
            ContinuitySpec::G2 => Continuity::G2,
        }
    }

    /// From the kernel's.
    pub fn from_kernel(c: Continuity) -> Self {
        match c {
            Continuity::G0 => ContinuitySpec::G0,
            Continuity::G1 => ContinuitySpec::G1,
            Continuity::G2 => ContinuitySpec::G2,
        }
    }
}

/// The version of a file with patches: 3, anything else refused while reading.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(transparent)]
pub struct Version3(pub u32);

impl<'de> Deserialize<'de> for Version3 {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let v = u32::deserialize(d)?;
        if v != VERSION_PATCHES {
            return Err(D::Error::custom(format!(
                "a file with `patches` is version {VERSION_PATCHES}, not {v}; write `version: {VERSION_PATCHES}`"
            )));
        }
        Ok(Version3(v))
    }
}

/// The version a scene file declares, read without parsing the rest: the
/// number after the first `version:` outside comments (a scan of the text),
/// else the `version` field of the record (a RON parse that skips the
/// rest); `None` when there is none or it is not a number.
pub fn declared_version(text: &str) -> Option<u32> {
    #[derive(Deserialize)]
    struct Probe {
        version: u32,
    }
    let scanned = || {
        let code = super::patch_text::code_only(text);
        let (line, col) = super::error::find_key(&code, "version")?;
        let rest: String = code.lines().nth(line - 1)?.chars().skip(col - 1).collect();
        let rest = rest["version".len()..].trim_start().strip_prefix(':')?;
        let digits: String = rest
            .trim_start()
            .chars()
            .take_while(char::is_ascii_digit)
            .collect();
        digits.parse().ok()
    };
    scanned().or_else(|| {
        ron::Options::default()
            .from_str::<Probe>(text)
            .ok()
            .map(|p| p.version)
    })
}

/// The longest patch name.
pub const MAX_PATCH_NAME: usize = 32;

/// What is wrong with a patch name (`[A-Za-z0-9_-]`, 1–32 characters), or `None`.
pub fn patch_name_problem(name: &str) -> Option<String> {
    let len = name.chars().count();
    if len == 0 {
        return Some(
            "a patch needs a name; give it one of 1 to 32 letters, digits, `_` or `-`, such as `hood`"
                .into(),
        );
    }
    if len > MAX_PATCH_NAME {
        return Some(format!(
            "patch name `{name}` has {len} characters, over the {MAX_PATCH_NAME} allowed; shorten it"
        ));
    }
    if let Some(c) = name
        .chars()
        .find(|c| !(c.is_ascii_alphanumeric() || *c == '_' || *c == '-'))
    {
        return Some(format!(
            "patch name `{name}` contains {c:?}; use only letters A–Z and a–z, digits, `_` and `-`"
        ));
    }
    None
}

/// The initial curve a patch that starts on an edge is given in memory: a
/// straight unit segment along `+y`. Its join gives the patch's start points
/// (docs/math.md §11), so this curve is never used to place it; it is not saved.
pub fn placeholder_initial() -> InitialSpec {
    InitialSpec {
        tangents: vec![Dir(0.0, 1.0, 0.0), Dir(0.0, 1.0, 0.0)],
        order: 2,
        length: Finite(1.0),
        origin: Point(0.0, 0.0, 0.0),
    }
}

/// Patch `i` of `f` as a version-2 file of its own, with `initial` as its
/// initial curve: the design's depths and view, and the mirror for the first
/// patch only; no reference (the design's is read once, placed at the top).
pub fn scene_file_of(f: &DocumentFile, i: usize, initial: InitialSpec) -> SceneFile {
    let p = &f.patches[i];
    SceneFile {
        version: Version(VERSION),
        name: f.name.clone(),
        tangents: p.tangents.clone(),
        s: p.s.clone(),
        t: p.t.clone(),
        anchor: p.anchor,
        initial,
        scheme: p.scheme,
        blend_order: p.blend_order,
        display_depth: f.display_depth,
        edit_depth: f.edit_depth,
        details: p.details.clone(),
        view: f.view,
        tuning: p.tuning.clone(),
        interpolate_tangents: p.interpolate_tangents,
        mirror: i == 0 && f.mirror,
        reference: None,
    }
}

/// The per-surface fields of a version-2 file as patch `name`, starting at `start`.
pub fn patch_file_of(sf: SceneFile, name: &str, start: StartSpec) -> PatchFile {
    PatchFile {
        name: name.to_string(),
        tangents: sf.tangents,
        s: sf.s,
        t: sf.t,
        anchor: sf.anchor,
        initial: start,
        scheme: sf.scheme,
        blend_order: sf.blend_order,
        details: sf.details,
        tuning: sf.tuning,
        interpolate_tangents: sf.interpolate_tangents,
    }
}
