//! The located error for a STEP text `ruststep` cannot read: the
//! statement at fault and where in it the parser stops.

use super::scan::{Scan, Statement};
use crate::error::ReferenceError;
use ruststep::ast::{EntityInstance, Record, SubSuperRecord};
use std::path::Path;

/// The located error for a text `ruststep` could not tokenize: the line
/// (and column) its rendered message gives (nom's `convert_error` says `at
/// line N` over a caret under the column), else the first statement that
/// does not parse on its own; the statement there is named, and parsed on
/// its own for the precise place.
pub(super) fn syntax_error(
    path: &Path,
    scan: &Scan,
    skip: usize,
    rendered: &str,
) -> ReferenceError {
    let fix = "the file is damaged or truncated: re-export it from the CAD system";
    // an instance whose text does not parse (or that the file ends inside)
    let at_fault = |s: &Statement| -> ReferenceError {
        let what = format!("#{} {}", s.id.unwrap_or(0), scan.keyword(s));
        if !s.terminated {
            return ReferenceError::at(
                path,
                s.line,
                s.col,
                format!("the file ends inside {what} (no `;` closes it); {fix}"),
            );
        }
        match statement_error(scan, s) {
            Some((at, reason)) => {
                let (line, col) = scan.position(at);
                let reason = if s.balanced {
                    reason
                } else {
                    "its parentheses do not balance".into()
                };
                ReferenceError::at(
                    path,
                    s.line,
                    s.col,
                    format!(
                        "{what} does not follow the ISO 10303-21 syntax: the parser cannot read on from line {line}, column {col} ({reason}); {fix}"
                    ),
                )
            }
            None => ReferenceError::at(
                path,
                s.line,
                s.col,
                format!("the STEP text cannot be read from {what} on; {fix}"),
            ),
        }
    };
    let offset = rendered_offset(scan, skip, rendered);
    if let Some(s) = offset
        .and_then(|o| scan.statement_at(o).filter(|s| o < s.end))
        .filter(|s| s.id.is_some())
    {
        return at_fault(s);
    }
    // ruststep stops at the start of a section when anything in it fails:
    // the first instance that does not parse on its own
    let instances = || scan.statements.iter().filter(|s| s.id.is_some());
    if let Some(s) = instances().find(|s| !s.terminated || statement_error(scan, s).is_some()) {
        return at_fault(s);
    }
    // every instance parses: a statement in a data section that is not an
    // instance, or the sections around them
    let mut in_data = false;
    for s in &scan.statements {
        let t = scan
            .text
            .get(s.start..s.end)
            .unwrap_or("")
            .trim_end_matches(';')
            .trim();
        if s.id.is_none() && in_data && t != "ENDSEC" {
            let shown: String = t.chars().take(40).collect();
            return ReferenceError::at(
                path,
                s.line,
                s.col,
                format!("`{shown}` in the data section is not an entity instance `#N = …;`; {fix}"),
            );
        }
        if s.id.is_none() {
            in_data = t.starts_with("DATA");
        }
    }
    if let Some(last) = scan.statements.last().filter(|s| s.id.is_some()) {
        let (line, col) = scan.position(scan.text.len());
        return ReferenceError::at(
            path,
            line,
            col,
            format!(
                "the file ends after #{} without `ENDSEC;` and `END-ISO-10303-21;`; {fix}",
                last.id.unwrap_or(0)
            ),
        );
    }
    let (line, col) = offset.map_or((1, 1), |o| scan.position(o));
    ReferenceError::at(
        path,
        line,
        col,
        format!(
            "the file's ISO 10303-21 structure (ISO-10303-21; HEADER; … ENDSEC; DATA; … ENDSEC; END-ISO-10303-21;) cannot be read here ({}); {fix}",
            first_reason(rendered)
        ),
    )
}

/// The byte offset of the first place `rendered` (nom's `convert_error`
/// output for the text from byte `skip`) names.
fn rendered_offset(scan: &Scan, skip: usize, rendered: &str) -> Option<usize> {
    let at = rendered.find("at line ")?;
    let rest = &rendered[at + 8..];
    let digits: String = rest.chars().take_while(char::is_ascii_digit).collect();
    let rel_line: usize = digits.parse().ok()?;
    // the caret line: the first line after the quoted source line that is
    // only spaces and one `^`; its length is the byte column
    let byte_col = rest
        .lines()
        .nth(2)
        .filter(|l| l.trim_start() == "^")
        .map_or(1, |l| l.len());
    let (skip_line, _) = scan.position(skip);
    let line = skip_line + rel_line - 1;
    let line_start = if rel_line == 1 {
        skip
    } else {
        *scan.line_starts.get(line.checked_sub(1)?)?
    };
    Some((line_start + byte_col.saturating_sub(1)).min(scan.text.len()))
}

/// Where (byte offset) and why statement `s` does not parse on its own, or
/// `None` when it does. The place is where `ruststep` stops reading its
/// record (nom reports the last alternative it tried, so the record is
/// parsed on its own, simple or complex, rather than the whole instance):
/// the start of the parameter at fault, or past it.
fn statement_error(scan: &Scan, s: &Statement) -> Option<(usize, String)> {
    let text = scan.text.get(s.start..s.end)?;
    text.parse::<EntityInstance>().err()?;
    let body_at = text.find('=').map_or(0, |i| {
        i + 1 + (text[i + 1..].len() - text[i + 1..].trim_start().len())
    });
    let body = text[body_at..].trim_end();
    let body = body.strip_suffix(';').unwrap_or(body).trim_end();
    let rendered = if body.starts_with('(') {
        body.parse::<SubSuperRecord>().err()
    } else {
        body.parse::<Record>().err()
    };
    let Some(rendered) = rendered.map(|e| e.to_string()) else {
        return Some((s.start, "the text around its record".into()));
    };
    let sub = Scan {
        text: body.to_string(),
        statements: Vec::new(),
        line_starts: std::iter::once(0)
            .chain(body.match_indices('\n').map(|(i, _)| i + 1))
            .collect(),
    };
    let at = rendered_offset(&sub, 0, &rendered).unwrap_or(0);
    Some((s.start + body_at + at, first_reason(&rendered)))
}

/// The first `expected …` line of a rendered error, else a short excerpt.
fn first_reason(rendered: &str) -> String {
    if let Some(l) = rendered
        .lines()
        .find(|l| l.starts_with("expected ") || l.contains("got empty input"))
    {
        let l = l.trim();
        return l
            .split_once(": ")
            .map_or(l, |(_, r)| r)
            .chars()
            .take(120)
            .collect();
    }
    if rendered.contains("u64-overflow") {
        return "an instance number too large".into();
    }
    "ruststep cannot tokenize it".into()
}
