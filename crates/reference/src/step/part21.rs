//! The exchange structure (ISO 10303-21, the text of a STEP file) through
//! `ruststep`'s parser, plus what that parser does not give: the line and
//! column of every `#N =` definition, so that each later error can name
//! them.
//!
//! Before the text reaches `ruststep`, one pass over it ([`scan`]) skips
//! strings `'…'` (with their `''` escapes) and comments `/* … */` and
//!
//! - records each statement (up to its `;`) with the 1-based line and
//!   column of its first character, and the instance number of a `#N =`;
//! - refuses lists nested deeper than [`MAX_NESTING`] (the parser is
//!   recursive), more than [`MAX_STEP_VALUES`] values (its syntax tree
//!   takes about 40 bytes a value), runs of more than
//!   [`MAX_INTEGER_DIGITS`] digits that can only be read as an integer
//!   (`ruststep` 0.4 panics on an integer that overflows `i64`), and an
//!   instance number defined twice;
//! - rewrites what `ruststep` 0.4 does not read, keeping every byte where
//!   it was: the `''` escape inside strings becomes `""` (it ends a string
//!   at any `'`; the strings this crate reads, unit names, never hold a
//!   quote), and an empty list `()` as a parameter becomes `$` (it reads
//!   no empty list; a `$` where a list is expected reads as an empty one).

use crate::error::{MAX_INTEGER_DIGITS, MAX_NESTING, MAX_STEP_VALUES, ReferenceError};
use ruststep::ast::{EntityInstance, Parameter, Record, SubSuperRecord};
use std::collections::HashMap;
use std::path::Path;

/// One statement of the file: the text up to and including its `;`.
#[derive(Debug, Clone)]
pub(crate) struct Statement {
    /// Byte offset of its first character.
    pub start: usize,
    /// Byte offset after its `;` (the end of the file when unterminated).
    pub end: usize,
    /// 1-based line of its first character.
    pub line: usize,
    /// 1-based column (in characters) of its first character.
    pub col: usize,
    /// `N` for an instance `#N = …`.
    pub id: Option<u64>,
    /// Whether a `;` ends it (false: the file ends inside it).
    pub terminated: bool,
    /// Whether its parentheses balance.
    pub balanced: bool,
}

/// The file's text as handed to `ruststep` and its statements.
#[derive(Debug)]
pub(crate) struct Scan {
    /// The text, `''` inside strings rewritten as `""`.
    pub text: String,
    /// Every statement, in file order.
    pub statements: Vec<Statement>,
    /// Byte offset of the start of every line (`line_starts[0] = 0`).
    pub line_starts: Vec<usize>,
}

impl Scan {
    /// 1-based line and character column of byte `offset`.
    pub fn position(&self, offset: usize) -> (usize, usize) {
        let offset = offset.min(self.text.len());
        let line = self.line_starts.partition_point(|&s| s <= offset).max(1);
        let start = self.line_starts[line - 1];
        let col = self
            .text
            .as_bytes()
            .get(start..offset)
            .map_or(0, |b| b.iter().filter(|&&c| c & 0xC0 != 0x80).count());
        (line, col + 1)
    }

    /// The statement holding byte `offset` (the last one starting at or
    /// before it).
    pub fn statement_at(&self, offset: usize) -> Option<&Statement> {
        let i = self.statements.partition_point(|s| s.start <= offset);
        i.checked_sub(1).map(|i| &self.statements[i])
    }

    /// The keyword after `#N =` of a statement (`(` for a complex one).
    pub fn keyword(&self, s: &Statement) -> String {
        let t = self.text.get(s.start..s.end).unwrap_or("");
        let after = t.find('=').map_or("", |i| t[i + 1..].trim_start());
        if after.starts_with('(') {
            return "(complex instance)".into();
        }
        after
            .chars()
            .take_while(|c| c.is_ascii_alphanumeric() || *c == '_' || *c == '!')
            .take(60)
            .collect()
    }
}

#[derive(Clone, Copy, PartialEq)]
enum State {
    Code,
    Str,
    Comment,
}

/// The pass over the text described in the module's documentation.
pub(crate) fn scan(path: &Path, text: String) -> Result<Scan, ReferenceError> {
    let mut b = text.into_bytes();
    let n = b.len();
    let mut statements = Vec::new();
    let mut line_starts = vec![0usize];
    let (mut line, mut col) = (1usize, 1usize);
    let mut state = State::Code;
    let mut depth = 0usize;
    let mut values = 0usize;
    // (start, line, col) of the statement under way
    let mut current: Option<(usize, usize, usize)> = None;
    let mut defined: HashMap<u64, usize> = HashMap::new();
    // the last byte of code (not blank, not in a comment) before `i`
    let mut prev = b';';
    let mut i = 0usize;
    while i < n {
        let c = b[i];
        let mut step = 1usize;
        match state {
            State::Str => {
                if c == b'\'' {
                    if b.get(i + 1) == Some(&b'\'') {
                        b[i] = b'"';
                        b[i + 1] = b'"';
                        step = 2;
                    } else {
                        state = State::Code;
                    }
                }
            }
            State::Comment => {
                if c == b'*' && b.get(i + 1) == Some(&b'/') {
                    state = State::Code;
                    step = 2;
                }
            }
            State::Code => {
                if c == b'/' && b.get(i + 1) == Some(&b'*') {
                    state = State::Comment;
                    step = 2;
                } else if !c.is_ascii_whitespace() {
                    if current.is_none() {
                        current = Some((i, line, col));
                    }
                    match c {
                        b'\'' => state = State::Str,
                        b'(' => {
                            // an empty list `()` as a parameter (not the
                            // empty parameters of a record `NAME()`):
                            // ruststep 0.4 reads no empty list, so it
                            // becomes `$` and blanks, the same length
                            if matches!(prev, b'(' | b',') {
                                let close = b[i + 1..]
                                    .iter()
                                    .position(|c| !c.is_ascii_whitespace())
                                    .map(|k| i + 1 + k);
                                if let Some(k) = close.filter(|&k| b[k] == b')') {
                                    b[i] = b'$';
                                    for x in &mut b[i + 1..=k] {
                                        if !x.is_ascii_whitespace() {
                                            *x = b' ';
                                        }
                                    }
                                    prev = b'$';
                                    i += 1;
                                    col += 1;
                                    continue;
                                }
                            }
                            depth += 1;
                            values += 1;
                            if depth > MAX_NESTING {
                                return Err(ReferenceError::at(
                                    path,
                                    line,
                                    col,
                                    format!(
                                        "lists nest more than {MAX_NESTING} deep here (STEP data nests four deep at most); the file is damaged or not STEP: re-export it from the CAD system"
                                    ),
                                ));
                            }
                        }
                        b')' => depth = depth.saturating_sub(1),
                        b',' => values += 1,
                        // `;` ends a statement wherever it stands outside a
                        // string or comment: the parentheses before it
                        // must balance
                        b';' => {
                            let balanced = depth == 0;
                            depth = 0;
                            if let Some((start, l, k)) = current.take() {
                                let id = instance_number(&b[start..=i]);
                                if let Some(id) = id {
                                    if let Some(&first) = defined.get(&id) {
                                        return Err(ReferenceError::at(
                                            path,
                                            l,
                                            k,
                                            format!(
                                                "#{id} is defined a second time (first on line {first}); instance numbers must be unique: the file is damaged, re-export it"
                                            ),
                                        ));
                                    }
                                    defined.insert(id, l);
                                }
                                statements.push(Statement {
                                    start,
                                    end: i + 1,
                                    line: l,
                                    col: k,
                                    id,
                                    terminated: true,
                                    balanced,
                                });
                            }
                        }
                        b'0'..=b'9' if i == 0 || !b[i - 1].is_ascii_digit() => {
                            let run = b[i..].iter().take_while(|d| d.is_ascii_digit()).count();
                            let before = i.checked_sub(1).map(|j| b[j]);
                            let after = b.get(i + run).copied();
                            if run > MAX_INTEGER_DIGITS
                                && before != Some(b'.')
                                && after != Some(b'.')
                            {
                                return Err(ReferenceError::at(
                                    path,
                                    line,
                                    col,
                                    format!(
                                        "a number of {run} digits, more than the {MAX_INTEGER_DIGITS} an integer can hold; the file is damaged: re-export it"
                                    ),
                                ));
                            }
                        }
                        _ => {}
                    }
                    prev = c;
                    if values > MAX_STEP_VALUES {
                        return Err(ReferenceError::at(
                            path,
                            line,
                            col,
                            format!(
                                "the file holds more than {MAX_STEP_VALUES} values by here; export only the faces you need"
                            ),
                        ));
                    }
                }
            }
        }
        for (k, &c) in b.iter().enumerate().take((i + step).min(n)).skip(i) {
            if c == b'\n' {
                line += 1;
                col = 1;
                line_starts.push(k + 1);
            } else if c & 0xC0 != 0x80 {
                col += 1;
            }
        }
        i += step;
    }
    if let Some((start, l, k)) = current {
        statements.push(Statement {
            start,
            end: n,
            line: l,
            col: k,
            id: instance_number(&b[start..]),
            terminated: false,
            balanced: depth == 0,
        });
    }
    // Only ASCII bytes were replaced by ASCII bytes: the text is still UTF-8.
    let text = match String::from_utf8(b) {
        Ok(t) => t,
        Err(e) => String::from_utf8_lossy(e.as_bytes()).into_owned(),
    };
    Ok(Scan {
        text,
        statements,
        line_starts,
    })
}

/// `N` when `statement` is `#N = …`.
fn instance_number(statement: &[u8]) -> Option<u64> {
    let rest = statement.strip_prefix(b"#")?;
    let digits = rest.iter().take_while(|c| c.is_ascii_digit()).count();
    if digits == 0 {
        return None;
    }
    let after = rest[digits..].iter().find(|c| !c.is_ascii_whitespace());
    if after != Some(&b'=') {
        return None;
    }
    std::str::from_utf8(&rest[..digits]).ok()?.parse().ok()
}

/// One entity instance: a simple one has one record, a complex one
/// `(A(…) B(…))` several.
#[derive(Debug, Clone)]
pub(crate) struct Instance {
    /// `N` of `#N`.
    pub id: u64,
    /// Its records.
    pub records: Vec<Record>,
    /// Whether it is a complex instance.
    pub complex: bool,
    /// 1-based line of its `#N`.
    pub line: usize,
    /// 1-based column of its `#N`.
    pub col: usize,
}

impl Instance {
    /// The record named `name`.
    pub fn record(&self, name: &str) -> Option<&Record> {
        self.records.iter().find(|r| r.name == name)
    }

    /// Whether it has a record named `name`.
    pub fn has(&self, name: &str) -> bool {
        self.record(name).is_some()
    }

    /// Its entity type for messages: the record's name, or the names of a
    /// complex instance's records that say what it is (the abstract
    /// supertypes every such instance carries left out).
    pub fn type_name(&self) -> String {
        if !self.complex {
            return self
                .records
                .first()
                .map_or_else(String::new, |r| r.name.clone());
        }
        const GENERIC: [&str; 8] = [
            "BOUNDED_SURFACE",
            "B_SPLINE_SURFACE",
            "GEOMETRIC_REPRESENTATION_ITEM",
            "REPRESENTATION_ITEM",
            "SURFACE",
            "BOUNDED_CURVE",
            "B_SPLINE_CURVE",
            "CURVE",
        ];
        let names: Vec<&str> = self
            .records
            .iter()
            .map(|r| r.name.as_str())
            .filter(|n| !GENERIC.contains(n))
            .collect();
        if names.is_empty() {
            let all: Vec<&str> = self.records.iter().map(|r| r.name.as_str()).collect();
            format!("({})", all.join(" "))
        } else {
            format!("({})", names.join(" "))
        }
    }

    /// `#N TYPE`, as messages and face descriptions name it.
    pub fn describe(&self) -> String {
        format!("#{} {}", self.id, self.type_name())
    }
}

/// The parameters of a record.
pub(crate) fn params(r: &Record) -> &[Parameter] {
    match &r.parameter {
        Parameter::List(v) => v,
        p => std::slice::from_ref(p),
    }
}

/// The data section(s) of a file: every instance, in file order.
#[derive(Debug)]
pub(crate) struct Data {
    /// The instances in file order.
    pub instances: Vec<Instance>,
    /// Index into `instances` by instance number.
    pub by_id: HashMap<u64, usize>,
}

impl Data {
    /// The instance `#id`.
    pub fn get(&self, id: u64) -> Option<&Instance> {
        self.by_id.get(&id).map(|&i| &self.instances[i])
    }
}

/// Reads the exchange structure of `text` (the whole file): scanned, then
/// parsed by `ruststep::parser::parse`.
pub(crate) fn read(path: &Path, text: String) -> Result<Data, ReferenceError> {
    let scan = scan(path, text)?;
    // ruststep wants `ISO-10303-21;` first: skip a byte order mark and
    // leading blank lines, and say so plainly when the file is not STEP.
    let skip = scan.text.len()
        - scan
            .text
            .trim_start_matches(['\u{feff}', ' ', '\t', '\r', '\n'])
            .len();
    let input = &scan.text[skip..];
    if input.is_empty() {
        return Err(ReferenceError::whole(
            path,
            "the file is empty; export the reference again from the CAD system",
        ));
    }
    if !input.starts_with("ISO-10303-21") {
        let (line, col) = scan.position(skip);
        return Err(ReferenceError::at(
            path,
            line,
            col,
            "the file does not start with ISO-10303-21; (it is not a STEP Part 21 text file); export the reference as STEP (AP203, AP214 or AP242)",
        ));
    }
    let exchange = match ruststep::parser::parse(input) {
        Ok(ex) => ex,
        Err(e) => return Err(syntax_error(path, &scan, skip, &e.to_string())),
    };
    let positions: HashMap<u64, (usize, usize)> = scan
        .statements
        .iter()
        .filter_map(|s| s.id.map(|id| (id, (s.line, s.col))))
        .collect();
    let mut instances = Vec::new();
    let mut by_id = HashMap::new();
    for section in exchange.data {
        for inst in section.entities {
            let (id, records, complex) = match inst {
                EntityInstance::Simple { id, record } => (id, vec![record], false),
                EntityInstance::Complex { id, subsuper } => (id, subsuper.0, true),
            };
            let (line, col) = positions.get(&id).copied().unwrap_or((0, 0));
            if by_id.insert(id, instances.len()).is_some() {
                // the scan refuses duplicates; this is only a safeguard
                return Err(ReferenceError::at(
                    path,
                    line,
                    col,
                    format!(
                        "#{id} is defined twice; instance numbers must be unique: the file is damaged, re-export it"
                    ),
                ));
            }
            instances.push(Instance {
                id,
                records,
                complex,
                line,
                col,
            });
        }
    }
    Ok(Data { instances, by_id })
}

/// The located error for a text `ruststep` could not tokenize: the line
/// (and column) its rendered message gives (nom's `convert_error` says `at
/// line N` over a caret under the column), else the first statement that
/// does not parse on its own; the statement there is named, and parsed on
/// its own for the precise place.
fn syntax_error(path: &Path, scan: &Scan, skip: usize, rendered: &str) -> ReferenceError {
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
