//! The fixed-column layer of an IGES file (5.3, ASCII): its lines and
//! sections and the free-format fields of the global and parameter
//! sections (delimiters, Hollerith strings, numbers with located errors).
//! The global section's values, the directory entries and an entity's
//! parameters are read with them in `global`, `directory` and `params`.
//! What the entities mean is the parent module's.

use crate::error::ReferenceError;
use std::path::Path;

pub(super) const REEXPORT: &str =
    "the file is damaged or does not follow IGES 5.3: re-export it from the CAD system";

/// One line of the file (its line end removed) and its 1-based number.
#[derive(Clone, Copy)]
pub(super) struct Line<'a> {
    pub(super) text: &'a [u8],
    pub(super) number: usize,
}

/// Some columns of consecutive lines of one section, run together.
pub(super) struct Text<'a> {
    pub(super) bytes: Vec<u8>,
    pub(super) width: usize,
    pub(super) lines: &'a [Line<'a>],
}

impl<'a> Text<'a> {
    pub(super) fn new(lines: &'a [Line<'a>], width: usize) -> Self {
        let mut bytes = Vec::with_capacity(lines.len() * width);
        for l in lines {
            bytes.extend_from_slice(&l.text[..width]);
        }
        Text {
            bytes,
            width,
            lines,
        }
    }

    /// The file line and column of byte `off`.
    pub(super) fn pos(&self, off: usize) -> (usize, usize) {
        if self.lines.is_empty() {
            return (0, 0);
        }
        let k = (off / self.width).min(self.lines.len() - 1);
        (self.lines[k].number, off - k * self.width + 1)
    }
}

/// One field of free-format data: its byte range, and whether it is a
/// Hollerith string.
#[derive(Clone, Copy)]
pub(super) struct Tok {
    pub(super) start: usize,
    pub(super) end: usize,
    pub(super) hollerith: bool,
}

/// The fields from byte `from` up to the record delimiter, and the
/// delimiter's offset.
pub(super) fn tokenize(
    path: &Path,
    t: &Text,
    from: usize,
    pd: u8,
    rd: u8,
    whose: &str,
) -> Result<(Vec<Tok>, usize), ReferenceError> {
    let b = &t.bytes;
    let n = b.len();
    let mut toks = Vec::new();
    let mut i = from;
    let unterminated = |at: usize| {
        let (l, c) = t.pos(at);
        ReferenceError::at(
            path,
            l,
            c,
            format!(
                "{whose} end without the record delimiter '{}'; {REEXPORT}",
                rd as char
            ),
        )
    };
    loop {
        let mut j = i;
        while j < n && b[j] == b' ' {
            j += 1;
        }
        let digits = b[j.min(n)..]
            .iter()
            .take_while(|c| c.is_ascii_digit())
            .count();
        if digits > 0 && matches!(b.get(j + digits), Some(b'H' | b'h')) {
            let count = std::str::from_utf8(&b[j..j + digits])
                .ok()
                .and_then(|s| s.parse::<usize>().ok())
                .unwrap_or(usize::MAX);
            let s = j + digits + 1;
            if count > n - s {
                let (l, c) = t.pos(j);
                return Err(ReferenceError::at(
                    path,
                    l,
                    c,
                    format!(
                        "a string of {} characters runs past the end of {whose}; {REEXPORT}",
                        String::from_utf8_lossy(&b[j..j + digits])
                    ),
                ));
            }
            toks.push(Tok {
                start: s,
                end: s + count,
                hollerith: true,
            });
            i = s + count;
            while i < n && b[i] == b' ' {
                i += 1;
            }
            if i >= n {
                return Err(unterminated(n.saturating_sub(1)));
            }
            if b[i] == rd {
                return Ok((toks, i));
            }
            if b[i] != pd {
                let (l, c) = t.pos(i);
                return Err(ReferenceError::at(
                    path,
                    l,
                    c,
                    format!(
                        "'{}' follows a string where the delimiter '{}' or '{}' should; {REEXPORT}",
                        b[i] as char, pd as char, rd as char
                    ),
                ));
            }
            i += 1;
        } else {
            let mut e = i;
            while e < n && b[e] != pd && b[e] != rd {
                e += 1;
            }
            if e >= n {
                return Err(unterminated(n.saturating_sub(1)));
            }
            toks.push(Tok {
                start: i,
                end: e,
                hollerith: false,
            });
            if b[e] == rd {
                return Ok((toks, e));
            }
            i = e + 1;
        }
    }
}

/// A number field as text, blanks removed.
pub(super) fn field_text(t: &Text, tok: &Tok) -> String {
    t.bytes[tok.start..tok.end]
        .iter()
        .filter(|c| **c != b' ')
        .map(|&c| c as char)
        .collect()
}

/// A real: digits, sign, point and an `E` or `D` exponent only (so no
/// `NaN` or `inf`), finite. `None` for an empty field.
pub(super) fn parse_real(s: &str) -> Result<Option<f64>, String> {
    if s.is_empty() {
        return Ok(None);
    }
    if !s.bytes().any(|c| c.is_ascii_digit())
        || !s.bytes().all(|c| {
            c.is_ascii_digit() || matches!(c, b'+' | b'-' | b'.' | b'E' | b'e' | b'D' | b'd')
        })
    {
        return Err(format!("'{}' is not a number", clip(s)));
    }
    let x: f64 = s
        .replace(['D', 'd'], "E")
        .parse()
        .map_err(|_| format!("'{}' is not a number", clip(s)))?;
    if !x.is_finite() {
        return Err(format!("'{}' is not a finite number", clip(s)));
    }
    Ok(Some(x))
}

/// An integer (a real with an integral value is accepted). `None` for an
/// empty field.
pub(super) fn parse_int(s: &str) -> Result<Option<i64>, String> {
    if s.is_empty() {
        return Ok(None);
    }
    if let Ok(i) = s.parse::<i64>() {
        return Ok(Some(i));
    }
    match parse_real(s)? {
        Some(x) if x.fract() == 0.0 && x.abs() < 1e15 => Ok(Some(x as i64)),
        _ => Err(format!("'{}' is not an integer", clip(s))),
    }
}

pub(super) fn clip(s: &str) -> String {
    s.chars().take(24).collect()
}

pub(super) fn split_lines(bytes: &[u8]) -> Vec<Line<'_>> {
    let raw: Vec<&[u8]> = if bytes.contains(&b'\n') {
        bytes.split(|&c| c == b'\n').collect()
    } else {
        bytes.chunks(80).collect()
    };
    raw.into_iter()
        .enumerate()
        .map(|(i, l)| Line {
            text: l.strip_suffix(b"\r").unwrap_or(l),
            number: i + 1,
        })
        .filter(|l| !l.text.iter().all(u8::is_ascii_whitespace))
        .collect()
}

/// The G, D and P sections' lines, checked for the fixed layout.
#[allow(clippy::type_complexity)]
pub(super) fn sections<'a>(
    path: &Path,
    lines: &[Line<'a>],
) -> Result<(Vec<Line<'a>>, Vec<Line<'a>>, Vec<Line<'a>>), ReferenceError> {
    if lines.is_empty() {
        return Err(ReferenceError::whole(
            path,
            "the file is empty; export the reference again from the CAD system",
        ));
    }
    let (mut g, mut d, mut p) = (Vec::new(), Vec::new(), Vec::new());
    let mut last = 0usize;
    for l in lines {
        if l.text.len() < 73 {
            return Err(ReferenceError::at(
                path,
                l.number,
                l.text.len().max(1),
                format!(
                    "the line has {} columns; an IGES line has 80, its section letter (S, G, D, P or T) in column 73: the file's lines were wrapped, trimmed or changed, re-export it",
                    l.text.len()
                ),
            ));
        }
        let letter = l.text[72];
        let order = match letter {
            b'S' => 1,
            b'G' => 2,
            b'D' => 3,
            b'P' => 4,
            b'T' => 5,
            b'C' => {
                return Err(ReferenceError::at(
                    path,
                    l.number,
                    73,
                    "the file is compressed IGES (C in column 73), which is not read; export it as fixed-format ASCII IGES",
                ));
            }
            b'B' if l.number == 1 => {
                return Err(ReferenceError::at(
                    path,
                    l.number,
                    73,
                    "the file is binary IGES, which is not read; export it as fixed-format ASCII IGES",
                ));
            }
            c => {
                return Err(ReferenceError::at(
                    path,
                    l.number,
                    73,
                    format!(
                        "column 73 holds '{}', not a section letter (S, G, D, P or T); an IGES line has fixed columns: the file was changed (tabs or spaces added or removed), re-export it",
                        (c as char).escape_default()
                    ),
                ));
            }
        };
        if order < last {
            return Err(ReferenceError::at(
                path,
                l.number,
                73,
                format!(
                    "a {} line after the {} section; the sections come in the order S, G, D, P, T: {REEXPORT}",
                    letter as char,
                    ["", "S", "G", "D", "P", "T"][last]
                ),
            ));
        }
        last = order;
        match order {
            2 => g.push(*l),
            3 => d.push(*l),
            4 => p.push(*l),
            _ => {}
        }
    }
    let missing = if g.is_empty() {
        Some("global (G)")
    } else if d.is_empty() {
        Some("directory (D)")
    } else if p.is_empty() {
        Some("parameter (P)")
    } else {
        None
    };
    if let Some(m) = missing {
        return Err(ReferenceError::whole(
            path,
            format!("the file has no {m} section, so it holds no entity; {REEXPORT}"),
        ));
    }
    Ok((g, d, p))
}
