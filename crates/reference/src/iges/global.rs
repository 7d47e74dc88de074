//! The global section of an IGES file: its delimiters and length unit.

use super::records::{Line, REEXPORT, Text, clip, field_text, parse_real, tokenize};
use crate::error::ReferenceError;
use std::path::Path;

/// The global section's values this reader uses.
pub(super) struct Global {
    pub(super) pd: u8,
    pub(super) rd: u8,
    pub(super) unit: String,
    pub(super) metres_per_unit: f64,
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
