//! The fixed-column layer of an IGES file (5.3, ASCII): its lines and
//! sections, the free-format fields of the global and parameter sections
//! (delimiters, Hollerith strings, numbers with located errors) and the
//! directory entries. What the entities mean is the parent module's.

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

/// The global section's values this reader uses.
pub(super) struct Global {
    pub(super) pd: u8,
    pub(super) rd: u8,
    pub(super) unit: String,
    pub(super) metres_per_unit: f64,
}

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

/// The parameters of one entity, read with located errors.
pub(super) struct Params<'a> {
    pub(super) path: &'a Path,
    pub(super) t: Text<'a>,
    pub(super) toks: Vec<Tok>,
    pub(super) end: usize,
    pub(super) who: String,
}

impl Params<'_> {
    pub(super) fn len(&self) -> usize {
        self.toks.len()
    }

    pub(super) fn err(&self, k: usize, msg: impl AsRef<str>) -> ReferenceError {
        let off = self.toks.get(k).map_or(self.end, |t| t.start);
        let (l, c) = self.t.pos(off);
        ReferenceError::at(self.path, l, c, format!("{}: {}", self.who, msg.as_ref()))
    }

    pub(super) fn text(&self, k: usize, what: &str) -> Result<String, ReferenceError> {
        let tok = self.toks.get(k).ok_or_else(|| {
            self.err(
                k,
                format!(
                    "it has {} parameters, its {what} (parameter {k}) is missing; {REEXPORT}",
                    self.toks.len().saturating_sub(1)
                ),
            )
        })?;
        if tok.hollerith {
            return Err(self.err(
                k,
                format!("its {what} (parameter {k}) is a string, not a number; {REEXPORT}"),
            ));
        }
        Ok(field_text(&self.t, tok))
    }

    pub(super) fn int(&self, k: usize, what: &str) -> Result<i64, ReferenceError> {
        let s = self.text(k, what)?;
        parse_int(&s)
            .map(|v| v.unwrap_or(0))
            .map_err(|e| self.err(k, format!("its {what} (parameter {k}): {e}; {REEXPORT}")))
    }

    /// An integer from `lo` to `hi`.
    pub(super) fn count(
        &self,
        k: usize,
        what: &str,
        lo: i64,
        hi: usize,
    ) -> Result<usize, ReferenceError> {
        let v = self.int(k, what)?;
        if v < lo || v > hi as i64 {
            return Err(self.err(
                k,
                format!("its {what} (parameter {k}) is {v}, outside {lo} to {hi}; {REEXPORT}"),
            ));
        }
        Ok(v as usize)
    }

    pub(super) fn real(&self, k: usize, what: &str) -> Result<f64, ReferenceError> {
        let s = self.text(k, what)?;
        match parse_real(&s) {
            Ok(Some(x)) => Ok(x),
            Ok(None) => Err(self.err(
                k,
                format!("its {what} (parameter {k}) is empty; {REEXPORT}"),
            )),
            Err(e) => Err(self.err(k, format!("its {what} (parameter {k}): {e}; {REEXPORT}"))),
        }
    }

    /// That parameters `k..k + n` exist.
    pub(super) fn need(&self, k: usize, n: usize, what: &str) -> Result<(), ReferenceError> {
        if k.saturating_add(n) > self.toks.len() {
            return Err(self.err(
                self.toks.len(),
                format!(
                    "it has {} parameters, its counts need {} ({what}); {REEXPORT}",
                    self.toks.len().saturating_sub(1),
                    k.saturating_add(n).saturating_sub(1)
                ),
            ));
        }
        Ok(())
    }
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

/// The global section's delimiters and length unit.
pub(super) fn global(path: &Path, lines: &[Line]) -> Result<Global, ReferenceError> {
    let t = Text::new(lines, 72);
    let b = &t.bytes;
    let at = |i: usize, msg: String| {
        let (l, c) = t.pos(i);
        ReferenceError::at(path, l, c, msg)
    };
    // fields 1 and 2: `1Hx` or empty (`,` and `;`)
    let mut i = 0usize;
    let skip = |mut i: usize| {
        while i < b.len() && b[i] == b' ' {
            i += 1;
        }
        i
    };
    let delim = |i: &mut usize, default: u8, pd: u8| -> Result<(u8, bool), ReferenceError> {
        *i = skip(*i);
        if b.get(*i..*i + 2) == Some(b"1H") || b.get(*i..*i + 2) == Some(b"1h") {
            let Some(&c) = b.get(*i + 2) else {
                return Err(at(
                    *i,
                    format!("the global section ends inside a delimiter; {REEXPORT}"),
                ));
            };
            *i = skip(*i + 3);
            Ok((c, false))
        } else if b.get(*i) == Some(&pd) || b.get(*i) == Some(&b';') {
            Ok((default, false))
        } else {
            Err(at(
                *i,
                format!(
                    "the global section starts with neither a delimiter `1Hx` nor an empty field; {REEXPORT}"
                ),
            ))
        }
    };
    let (pd, _) = delim(&mut i, b',', b',')?;
    // after field 1: the parameter delimiter (or the record delimiter)
    if b.get(i) == Some(&b';') && pd != b';' {
        return Ok(Global {
            pd,
            rd: b';',
            unit: "inch".into(),
            metres_per_unit: 0.0254,
        });
    }
    if b.get(i) != Some(&pd) {
        return Err(at(
            i,
            format!(
                "the parameter delimiter '{}' should follow the global section's first field; {REEXPORT}",
                pd as char
            ),
        ));
    }
    i += 1;
    let (rd, _) = delim(&mut i, b';', pd)?;
    if pd == rd || pd == b' ' || rd == b' ' {
        return Err(at(
            0,
            format!(
                "the global section's delimiters are '{}' and '{}'; they must differ and not be blanks: {REEXPORT}",
                pd as char, rd as char
            ),
        ));
    }
    let toks = if b.get(i) == Some(&rd) {
        Vec::new()
    } else if b.get(i) == Some(&pd) {
        tokenize(path, &t, i + 1, pd, rd, "the global section")?.0
    } else {
        return Err(at(
            i,
            format!(
                "the parameter delimiter '{}' should follow the global section's second field; {REEXPORT}",
                pd as char
            ),
        ));
    };
    // field k (1-based) is toks[k - 3]
    let field = |k: usize| toks.get(k - 3);
    let number = |k: usize, what: &str| -> Result<Option<f64>, ReferenceError> {
        match field(k) {
            None => Ok(None),
            Some(tok) if tok.hollerith => Err(at(
                tok.start,
                format!(
                    "the global section's {what} (field {k}) is a string, not a number; {REEXPORT}"
                ),
            )),
            Some(tok) => parse_real(&field_text(&t, tok)).map_err(|e| {
                at(
                    tok.start,
                    format!("the global section's {what} (field {k}): {e}; {REEXPORT}"),
                )
            }),
        }
    };
    let scale = number(13, "model space scale")?.unwrap_or(1.0);
    if scale <= 0.0 {
        let off = field(13).map_or(0, |t| t.start);
        return Err(at(
            off,
            format!("the model space scale (global field 13) is {scale}, not positive; {REEXPORT}"),
        ));
    }
    let flag = number(14, "unit flag")?.unwrap_or(1.0);
    let name = field(15)
        .filter(|t| t.hollerith)
        .map(|tok| {
            String::from_utf8_lossy(&b[tok.start..tok.end])
                .trim()
                .to_uppercase()
        })
        .unwrap_or_default();
    let flag_at = field(14).map_or(0, |t| t.start);
    let by_flag = |f: f64| -> Option<(&'static str, f64)> {
        Some(match f as i64 {
            1 => ("inch", 0.0254),
            2 => ("millimetre", 0.001),
            4 => ("foot", 0.3048),
            5 => ("mile", 1609.344),
            6 => ("metre", 1.0),
            7 => ("kilometre", 1000.0),
            8 => ("mil", 2.54e-5),
            9 => ("micrometre", 1e-6),
            10 => ("centimetre", 0.01),
            11 => ("microinch", 2.54e-8),
            _ => return None,
        })
    };
    let (unit, metres) = if flag == 3.0 {
        let f = match name.as_str() {
            "IN" | "INCH" => 1.0,
            "MM" => 2.0,
            "FT" => 4.0,
            "MI" => 5.0,
            "M" => 6.0,
            "KM" => 7.0,
            "MIL" => 8.0,
            "UM" => 9.0,
            "CM" => 10.0,
            "UIN" => 11.0,
            _ => {
                let off = field(15).map_or(flag_at, |t| t.start);
                return Err(at(
                    off,
                    format!(
                        "the unit flag is 3 (named unit) but the unit name '{}' is none of IGES's (IN, MM, FT, MI, M, KM, MIL, UM, CM, UIN); re-export the file in millimetres or metres",
                        clip(&name)
                    ),
                ));
            }
        };
        by_flag(f).unwrap_or(("inch", 0.0254))
    } else if flag.fract() != 0.0 {
        return Err(at(
            flag_at,
            format!("the unit flag (global field 14) is {flag}, not an integer; {REEXPORT}"),
        ));
    } else {
        by_flag(flag).ok_or_else(|| {
            at(flag_at, format!("the unit flag (global field 14) is {flag}, not one of IGES's 1 to 11; re-export the file in millimetres or metres"))
        })?
    };
    Ok(Global {
        pd,
        rd,
        unit: unit.to_string(),
        metres_per_unit: metres / scale,
    })
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
