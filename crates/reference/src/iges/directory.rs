//! The directory section of an IGES file: one entry (two lines of nine
//! 8-column fields) per entity.

use super::records::{Line, REEXPORT, clip};
use crate::error::ReferenceError;
use std::path::Path;

/// A directory entry.
pub(super) struct De {
    /// Its number: the sequence number of its first line (odd).
    pub(super) number: usize,
    pub(super) etype: i64,
    /// First parameter line (1-based within the P section).
    pub(super) pstart: i64,
    pub(super) transform: i64,
    pub(super) pcount: i64,
    /// The file line of its first line.
    pub(super) line: usize,
}

/// The directory entries.
pub(super) fn directory(path: &Path, lines: &[Line]) -> Result<Vec<De>, ReferenceError> {
    if !lines.len().is_multiple_of(2) {
        let l = lines[lines.len() - 1];
        return Err(ReferenceError::at(
            path,
            l.number,
            1,
            format!(
                "the directory section has {} lines; each entry takes two: {REEXPORT}",
                lines.len()
            ),
        ));
    }
    let field = |l: &Line, k: usize, what: &str| -> Result<i64, ReferenceError> {
        let s: String = l.text[8 * k..8 * k + 8]
            .iter()
            .filter(|c| **c != b' ')
            .map(|&c| c as char)
            .collect();
        match s.parse::<i64>() {
            Ok(v) => Ok(v),
            Err(_) if s.is_empty() => Ok(0),
            Err(_) => Err(ReferenceError::at(
                path,
                l.number,
                8 * k + 1,
                format!(
                    "the directory entry's {what} (columns {}–{}) is '{}', not an integer; {REEXPORT}",
                    8 * k + 1,
                    8 * k + 8,
                    clip(&s)
                ),
            )),
        }
    };
    let mut des = Vec::with_capacity(lines.len() / 2);
    for (k, pair) in lines.chunks(2).enumerate() {
        let (a, b) = (&pair[0], &pair[1]);
        des.push(De {
            number: 2 * k + 1,
            etype: field(a, 0, "entity type")?,
            pstart: field(a, 1, "parameter data pointer")?,
            transform: field(a, 6, "transformation matrix pointer")?,
            pcount: field(b, 3, "parameter line count")?,
            line: a.number,
        });
    }
    Ok(des)
}
