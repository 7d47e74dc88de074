//! The scene file, version 2 (RON; version 1, the same without `mirror`,
//! is read unchanged and saved as version 2; version 3, several patches, is
//! [`super::format_v3`]). Every field is checked while it is read,
//! so an error carries the line and column of the bad value: tangents must be
//! finite and non-zero ([`Dir`]), each row of `s` finite and strictly
//! increasing ([`SRow`]), ω in range; unknown fields are errors.
//!
//! ```ron
//! (
//!     version: 2,
//!     name: "car1",
//!     tangents: [[(1.0, 0.0, 0.3), …], …],   // one row per streamline
//!     s: [[0.0, 0.55, …], …],               // arc length of each tangent
//!     t: [0.0, 0.4, …],                      // per row: arc length on the initial curve
//!     anchor: 0,
//!     initial: (tangents: [(0.0, 1.0, 0.5), …], order: 3, length: 2.0, origin: (0.0, -0.95, 0.25)),
//!     scheme: Kobbelt(omega: 1.0),           // or CatmullClark, DooSabin
//!     blend_order: SFirst,                   // or TFirst
//!     display_depth: 4,
//!     edit_depth: 0,
//!     details: [],                           // (level, row, col, local: (x, y, z))
//!     view: (yaw: 35.0, pitch: 25.0, distance: 8.0, target: (2.2, 0.0, 0.5)),
//!     tuning: None,                          // or Some((degree_s: 2, degree_t: 2, values: [[…]], constraint: Free))
//!     mirror: false,                         // version 2: mirror symmetry about row 0 (docs/math.md §9)
//!     reference: Some((path: "panel.step", face: 2)), // optional: the file fitted to (docs/math.md §12)
//! )
//! ```

use super::reference_link::ReferenceSpec;
use serde::de::Error as _;
use serde::{Deserialize, Deserializer, Serialize};
use streamline_kernel::DVec3;
use streamline_kernel::curve::scheme::OMEGA_MAX;

/// The version this build writes for one surface.
pub const VERSION: u32 = 2;

/// The version of a file with several patches (its own format:
/// [`super::format_v3`]).
pub const VERSION_PATCHES: u32 = 3;

/// The oldest version this build reads.
pub const OLDEST_VERSION: u32 = 1;

/// A scene file as written on disk.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneFile {
    /// 1 or 2.
    pub version: Version,
    /// A display name.
    #[serde(default)]
    pub name: String,
    /// Control tangents, one row per streamline.
    pub tangents: Vec<Vec<Dir>>,
    /// Arc-length parameter of each tangent, same shape as `tangents`.
    pub s: Vec<SRow>,
    /// Per row, the arc length along the initial curve where its streamline starts.
    pub t: Vec<Finite>,
    /// The anchor column (where each streamline meets the initial curve).
    #[serde(default)]
    pub anchor: usize,
    /// The initial curve.
    pub initial: InitialSpec,
    /// The subdivision scheme.
    pub scheme: SchemeSpec,
    /// Which direction is blended first.
    #[serde(default)]
    pub blend_order: OrderSpec,
    /// Levels shown.
    #[serde(default = "default_display_depth")]
    pub display_depth: u32,
    /// Level whose tangents are the handles.
    #[serde(default)]
    pub edit_depth: u32,
    /// Multiresolution details (docs/math.md §5).
    #[serde(default)]
    pub details: Vec<DetailSpec>,
    /// The camera.
    #[serde(default)]
    pub view: ViewSpec,
    /// Fine tuning (docs/math.md §6): absent or `None` when off.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tuning: Option<TuningSpec>,
    /// Catmull–Clark and Doo–Sabin pass through the interior control
    /// tangents at the limit (progressive interpolation on the sphere).
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub interpolate_tangents: bool,
    /// Version 2: the design is the half of a surface symmetric about the
    /// plane through the initial curve's start, perpendicular to its first
    /// tangent (`docs/math.md §9`); row 0 is the seam.
    #[serde(default)]
    pub mirror: bool,
    /// The reference the design was fitted to or is measured against
    /// (docs/math.md §12): its path relative to this file's folder and the
    /// face ([`super::reference_link`]); absent when there is none.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub reference: Option<ReferenceSpec>,
}

/// Fine tuning: a tensor B-spline scalar function `α(u, v)` scaling the
/// derivative along every streamline, and what the streamlines keep.
///
/// ```ron
/// tuning: Some((degree_s: 2, degree_t: 2, values: [[1.0, 1.2, 1.0], [1.0, 1.0, 1.0], [1.0, 0.8, 1.0]], constraint: Free)),
/// ```
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TuningSpec {
    /// Degree along the streamlines (0–5; 2 is usual).
    pub degree_s: usize,
    /// Degree across them (0–5; 2 is usual).
    pub degree_t: usize,
    /// Control values: one row per value across (`t`), one column per value along (`s`); 1 changes nothing.
    pub values: Vec<Vec<Finite>>,
    /// `Free`, `KeepEnds` or `KeepClosed`.
    #[serde(default)]
    pub constraint: ConstraintSpec,
}

/// What fine-tuned streamlines keep.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub enum ConstraintSpec {
    /// Nothing.
    #[default]
    Free,
    /// Both ends of every streamline.
    KeepEnds,
    /// The chord from first to last point (closed stays closed).
    KeepClosed,
}

fn default_display_depth() -> u32 {
    3
}

/// The file version of one surface; anything but 1 or 2 is refused while
/// reading (version 3, several patches, is [`super::format_v3::DocumentFile`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(transparent)]
pub struct Version(pub u32);

impl<'de> Deserialize<'de> for Version {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let v = u32::deserialize(d)?;
        let patches = VERSION_PATCHES;
        if v == patches {
            return Err(D::Error::custom(format!(
                "a version-{patches} file lists its surfaces under `patches: [ … ]`; move the surface fields into a patch `( name: \"main\", tangents: …, … )`, or write `version: {VERSION}`"
            )));
        }
        if !(OLDEST_VERSION..=VERSION).contains(&v) {
            return Err(D::Error::custom(format!(
                "scene version {v} is not supported; this build reads versions {OLDEST_VERSION} to {patches} (write `version: {VERSION}` for one surface or `version: {patches}` for several patches, or open the file with the build that wrote it)"
            )));
        }
        Ok(Version(v))
    }
}

/// A finite, non-zero direction `(x, y, z)`; normalised when used.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Dir(pub f64, pub f64, pub f64);

impl Dir {
    /// As a vector (not normalised).
    pub fn vec(self) -> DVec3 {
        DVec3::new(self.0, self.1, self.2)
    }

    /// From a vector.
    pub fn from_vec(v: DVec3) -> Self {
        Dir(v.x, v.y, v.z)
    }
}

impl<'de> Deserialize<'de> for Dir {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let (x, y, z) = <(f64, f64, f64)>::deserialize(d)?;
        let v = DVec3::new(x, y, z);
        if !v.is_finite() {
            return Err(D::Error::custom(format!(
                "direction ({x}, {y}, {z}) has a NaN or infinite component; give three finite numbers such as (1.0, 0.0, 0.0)"
            )));
        }
        if streamline_kernel::Tangent::new(v).is_err() {
            return Err(D::Error::custom(format!(
                "direction ({x}, {y}, {z}) is the zero vector and has no direction; give a non-zero direction such as (1.0, 0.0, 0.0)"
            )));
        }
        Ok(Dir(x, y, z))
    }
}

/// A finite number.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(transparent)]
pub struct Finite(pub f64);

impl<'de> Deserialize<'de> for Finite {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let v = f64::deserialize(d)?;
        if !v.is_finite() {
            return Err(D::Error::custom(format!(
                "{v} is not a finite number; give a finite number"
            )));
        }
        Ok(Finite(v))
    }
}

/// One row of arc-length parameters: finite and strictly increasing.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(transparent)]
pub struct SRow(pub Vec<f64>);

impl<'de> Deserialize<'de> for SRow {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let v = Vec::<f64>::deserialize(d)?;
        for (i, x) in v.iter().enumerate() {
            if !x.is_finite() {
                return Err(D::Error::custom(format!(
                    "s value {i} of this row is {x}; give finite arc lengths"
                )));
            }
            if i > 0 && *x <= v[i - 1] {
                return Err(D::Error::custom(format!(
                    "s must increase strictly along a row, but value {i} ({x}) is not greater than value {} ({}); make every interval positive",
                    i - 1,
                    v[i - 1]
                )));
            }
        }
        Ok(SRow(v))
    }
}

/// The initial curve: a QI curve of `order` through `tangents`, of arc length `length`, starting at `origin`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct InitialSpec {
    /// Its control tangents.
    pub tangents: Vec<Dir>,
    /// QI order (2–8; 3 is usual).
    pub order: usize,
    /// Arc length.
    pub length: Finite,
    /// Start point.
    pub origin: Point,
}

/// A template for a new design (`docs/math.md §9`).
///
/// ```ron
/// template: Flat(width: 2.0)
/// template: Cylinder(radius: 1.0, degrees: 120.0)
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub enum TemplateSpec {
    /// The rectangle `[0, length] × [0, width]` in `z = 0`.
    Flat {
        /// Extent across the streamlines.
        width: Finite,
    },
    /// Part of the cylinder `y² + (z − radius)² = radius²` over `degrees` (0 < φ < 360).
    Cylinder {
        /// The radius.
        radius: Finite,
        /// The arc's angle, degrees.
        degrees: Finite,
    },
}

impl TemplateSpec {
    /// The kernel's template.
    pub fn to_kernel(self) -> streamline_kernel::authoring::Template {
        use streamline_kernel::authoring::Template;
        match self {
            TemplateSpec::Flat { width } => Template::Flat { width: width.0 },
            TemplateSpec::Cylinder { radius, degrees } => Template::Cylinder {
                radius: radius.0,
                degrees: degrees.0,
            },
        }
    }

    /// From the kernel's template.
    pub fn from_kernel(t: streamline_kernel::authoring::Template) -> Self {
        use streamline_kernel::authoring::Template;
        match t {
            Template::Flat { width } => TemplateSpec::Flat {
                width: Finite(width),
            },
            Template::Cylinder { radius, degrees } => TemplateSpec::Cylinder {
                radius: Finite(radius),
                degrees: Finite(degrees),
            },
        }
    }
}

/// A finite point `(x, y, z)`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Point(pub f64, pub f64, pub f64);

impl Point {
    /// As a vector.
    pub fn vec(self) -> DVec3 {
        DVec3::new(self.0, self.1, self.2)
    }

    /// From a vector.
    pub fn from_vec(v: DVec3) -> Self {
        Point(v.x, v.y, v.z)
    }
}

impl<'de> Deserialize<'de> for Point {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let (x, y, z) = <(f64, f64, f64)>::deserialize(d)?;
        if !(x.is_finite() && y.is_finite() && z.is_finite()) {
            return Err(D::Error::custom(format!(
                "point ({x}, {y}, {z}) has a NaN or infinite coordinate; give finite numbers"
            )));
        }
        Ok(Point(x, y, z))
    }
}

/// The tensor-product scheme of the surface.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub enum SchemeSpec {
    /// Kobbelt (4-point ⊗ 4-point) with tension ω (0 ≤ ω < 2.472; 1 is the default).
    Kobbelt {
        /// The tension.
        omega: Omega,
    },
    /// Catmull–Clark on the regular grid.
    CatmullClark,
    /// Doo–Sabin on the regular grid.
    DooSabin,
}

/// ω of the 4-point rule, checked while reading.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(transparent)]
pub struct Omega(pub f64);

impl<'de> Deserialize<'de> for Omega {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let w = f64::deserialize(d)?;
        if !(w.is_finite() && (0.0..OMEGA_MAX).contains(&w)) {
            return Err(D::Error::custom(format!(
                "omega {w} is outside the 4-point rule's range 0 <= omega < {OMEGA_MAX:.6}; the default is 1.0"
            )));
        }
        Ok(Omega(w))
    }
}

/// Blend order.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub enum OrderSpec {
    /// Rows (along s) first.
    #[default]
    SFirst,
    /// Columns (along t) first.
    TFirst,
}

/// A multiresolution detail: the edited tangent at `(level, row, col)` in its local frame.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DetailSpec {
    /// Level (≥ 1).
    pub level: u32,
    /// Row at that level.
    pub row: usize,
    /// Column at that level.
    pub col: usize,
    /// The tangent in the local frame (z = the subdivided tangent).
    pub local: Dir,
}

/// The camera: orbit angles in degrees, distance and target.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ViewSpec {
    /// Angle about the vertical axis, degrees.
    pub yaw: Finite,
    /// Angle above the horizon, degrees.
    pub pitch: Finite,
    /// Distance from the target.
    pub distance: Finite,
    /// The point looked at.
    pub target: Point,
}

impl Default for ViewSpec {
    fn default() -> Self {
        ViewSpec {
            yaw: Finite(-35.0),
            pitch: Finite(28.0),
            distance: Finite(8.0),
            target: Point(0.0, 0.0, 0.0),
        }
    }
}
