//! The scan of a STEP text before `ruststep` parses it.
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
