//! IGES (5.3, fixed-format ASCII): the rational B-spline surfaces (entity
//! 128) of a file as references.
//!
//! No maintained Rust crate reads IGES, and the part needed is small, so the
//! reader is written here:
//!
//! - lines of 80 columns, the section letter in column 73 (`S`tart,
//!   `G`lobal, `D`irectory, `P`arameter, `T`erminate, in that order) and
//!   the sequence number in 74–80; a file without line breaks is read as
//!   80-byte records. Compressed and binary IGES are refused;
//! - the global section (columns 1–72 of its lines, run together): its
//!   parameter and record delimiters (fields 1 and 2, `,` and `;` when
//!   empty), Hollerith strings `nH…`, the model space scale (field 13, 1
//!   when empty), the unit flag (field 14: 1 inch, 2 millimetre, 4 foot,
//!   5 mile, 6 metre, 7 kilometre, 8 mil, 9 micrometre, 10 centimetre,
//!   11 microinch, 3 the unit named in field 15). Model space coordinates
//!   are divided by the scale ("ratio of model space to real world"), so
//!   `metres_per_unit` is the unit's metres over the scale;
//! - directory entries, two lines of nine 8-column fields each: entity
//!   type, parameter data pointer, transformation matrix (entity 124,
//!   applied to the poles, through its own matrix in turn), parameter line
//!   count;
//! - parameter data (columns 1–64 of its lines, run together) of entity
//!   128: `K1 K2 M1 M2 PROP1..PROP5`, the `u` knots, the `v` knots, the
//!   weights and the control points (`u` index fastest, as the kernel's
//!   grid holds them: one row per `v` index), `U0 U1 V0 V1`. Weights all
//!   equal, or `PROP3 = 1` (polynomial), give a non-rational surface;
//!   closed is `PROP1`/`PROP2`; periodic, as for STEP, is a knot vector
//!   that is not clamped (`PROP4`/`PROP5` are not used).
//!
//! The faces, in directory order: every trimmed surface (144), bounded
//! surface (143) and face (510), and every 128 that none of them has as
//! its surface. A face is untrimmed when:
//!
//! - a 144 has no inner boundary and either no outer one (`N1 = 0`: the
//!   surface's own boundary) or an outer curve on a parametric surface
//!   (142) whose parameter-space curve is made of lines (110), B-spline
//!   curves (126) or composites (102) of them that each lie along one side
//!   of the surface's domain (all their points within 1e-6 of the domain's
//!   diagonal from it);
//! - a 143 has one boundary (141) whose parameter-space curves (each
//!   model-space curve having at least one) all lie along the domain's
//!   sides, as for a 144;
//! - a 510 has one loop (508) of at most four edges whose vertices (502)
//!   all lie on the surface's corners (the STEP rule);
//! - a lone 128 is untrimmed;
//!
//! and in every case `U0 U1 V0 V1` of the 128 cover its whole knot domain.
//! Anything else is trimmed. A face on another surface is a plane (108, 190:
//! no area or box is computed) or `Other`, and reported trimmed.
//!
//! Errors name the file line and column of the value at fault in the
//! parameter section, or of the field of its directory entry.

use crate::FaceData;
use crate::error::ReferenceError;
use std::cell::Cell;
use std::path::Path;
use streamline_kernel::nurbs::rational::NurbsSurface;

/// What an IGES file gives: its length unit and its faces.
pub(crate) struct IgesFile {
    pub unit: String,
    pub metres_per_unit: f64,
    pub faces: Vec<FaceData>,
}

mod boundaries;
mod directory;
mod faces;
mod global;
mod params;
mod records;
mod surfaces;
mod transforms;

use directory::{De, directory};
use global::{Global, global};
use params::Params;
use records::*;

/// The deepest chain of composite curves or transformation matrices
/// followed (a cycle would otherwise never end).
const MAX_CHAIN: usize = 16;

/// Reads the faces of an IGES file.
pub(crate) fn read(path: &Path, bytes: &[u8]) -> Result<IgesFile, ReferenceError> {
    let lines = split_lines(bytes);
    let (g, d, p) = sections(path, &lines)?;
    let global = global(path, &g)?;
    let file = File {
        path,
        global: &global,
        des: directory(path, &d)?,
        p: &p,
        poles_read: Cell::new(0),
    };
    let faces = file.faces()?;
    Ok(IgesFile {
        unit: global.unit.clone(),
        metres_per_unit: global.metres_per_unit,
        faces,
    })
}

/// The file's lines: split at line feeds (a carriage return before one
/// dropped), or 80-byte records when there is no line feed; blank lines
/// are skipped.
/// How a face's base surface reads.
enum Base {
    /// A 128, in metres, with its closed flags and whether `U0 U1 V0 V1`
    /// leave part of its knot domain out.
    BSpline(NurbsSurface, [bool; 2], bool),
    Plane,
    Other,
}

/// What makes a directory entry a face.
enum Source {
    /// A 144: base surface, N1, N2, outer boundary (142) when N1 ≠ 0.
    Trimmed {
        surf: usize,
        n1: i64,
        n2: i64,
        outer: Option<usize>,
    },
    /// A 143: base surface and its boundaries (141).
    Bounded { surf: usize, bounds: Vec<usize> },
    /// A 510: base surface and its loops (508).
    Face { surf: usize, loops: Vec<usize> },
    /// A 128 that no face has as its surface.
    Lone,
}

struct File<'a> {
    path: &'a Path,
    global: &'a Global,
    des: Vec<De>,
    p: &'a [Line<'a>],
    /// The poles of the faces read so far (at most
    /// [`MAX_FILE_POLES`](crate::error::MAX_FILE_POLES)).
    poles_read: Cell<usize>,
}

impl<'a> File<'a> {
    fn who(de: &De) -> String {
        format!("DE {} ({})", de.number, de.etype)
    }

    /// An error at a field of directory entry `de`.
    fn de_err(&self, de: &De, col: usize, msg: impl AsRef<str>) -> ReferenceError {
        ReferenceError::at(
            self.path,
            de.line,
            col,
            format!("{}: {}", Self::who(de), msg.as_ref()),
        )
    }

    /// The parameters of entry `k` (index into `des`).
    fn params(&self, k: usize) -> Result<Params<'a>, ReferenceError> {
        let de = &self.des[k];
        let count = de.pcount.max(1);
        let start = de.pstart;
        if start < 1 || start.saturating_add(count) - 1 > self.p.len() as i64 {
            return Err(self.de_err(
                de,
                9,
                format!(
                    "its parameter data (P line {start}, {count} lines) lies outside the parameter section's {} lines; {REEXPORT}",
                    self.p.len()
                ),
            ));
        }
        let lines = &self.p[(start - 1) as usize..(start - 1 + count) as usize];
        let t = Text::new(lines, 64);
        let who = Self::who(de);
        let (toks, end) = tokenize(
            self.path,
            &t,
            0,
            self.global.pd,
            self.global.rd,
            &format!("the parameters of {who}"),
        )?;
        let p = Params {
            path: self.path,
            t,
            toks,
            end,
            who,
        };
        let ty = p.int(0, "entity type")?;
        if ty != de.etype {
            return Err(p.err(
                0,
                format!(
                    "its parameters start with entity type {ty}, its directory entry says {}; {REEXPORT}",
                    de.etype
                ),
            ));
        }
        Ok(p)
    }

    /// The entry a pointer parameter names (its index into `des`); 0 →
    /// `None`.
    fn ptr(&self, p: &Params, k: usize, what: &str) -> Result<Option<usize>, ReferenceError> {
        let v = p.int(k, what)?;
        if v == 0 {
            return Ok(None);
        }
        let v = v.unsigned_abs() as usize;
        if v.is_multiple_of(2) || v / 2 >= self.des.len() {
            return Err(p.err(
                k,
                format!(
                    "its {what} (parameter {k}) points to DE {v}, which is not a directory entry (the file has {}, odd numbers 1 to {}); {REEXPORT}",
                    self.des.len(),
                    2 * self.des.len() - 1
                ),
            ));
        }
        Ok(Some(v / 2))
    }

    fn need_ptr(&self, p: &Params, k: usize, what: &str) -> Result<usize, ReferenceError> {
        self.ptr(p, k, what)?.ok_or_else(|| {
            p.err(
                k,
                format!("its {what} (parameter {k}) is 0, no entity; {REEXPORT}"),
            )
        })
    }
}
