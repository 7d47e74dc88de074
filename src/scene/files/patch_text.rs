//! Where each patch of a version-3 file sits in its text, so that an error
//! found after reading (a shape, a join, a depth) points at the field of the
//! patch at fault, not at the first patch's. The scan skips strings and
//! comments; a file it cannot follow (truncated) places errors at the
//! first occurrence of the key, as version 2 does.

use super::error::find_key;
use std::ops::Range;

/// A version-3 file's text (comments blanked, [`code_only`]) and the byte
/// range of each record in its `patches: [ … ]`.
#[derive(Debug, Clone)]
pub struct PatchText {
    text: String,
    spans: Vec<Range<usize>>,
}

#[derive(Clone, Copy, PartialEq)]
enum Lex {
    Code,
    LineComment,
    BlockComment(usize),
    Str,
    Escape,
}

impl PatchText {
    /// Scans `text`.
    pub fn new(text: &str) -> Self {
        let text = code_only(text);
        let spans = patch_spans(&text);
        PatchText { text, spans }
    }

    /// The byte ranges of the patches' records, in order.
    pub fn spans(&self) -> &[Range<usize>] {
        &self.spans
    }

    /// Line and column (1-based) of `key:` inside patch `i`, else of the
    /// first `key:` of the file, else of the patch's start; `(0, 0)` when
    /// none is found.
    pub fn in_patch(&self, i: usize, key: &str) -> (usize, usize) {
        let Some(span) = self.spans.get(i) else {
            return self.top(key);
        };
        let inside = find_key(&self.text[span.clone()], key)
            .map(|(l, c)| self.shift(span.start, l, c))
            .or_else(|| find_key(&self.text, key));
        inside.unwrap_or_else(|| self.shift(span.start, 1, 1))
    }

    /// Line and column of the first `key:` of the file (a design-level
    /// field); `(0, 0)` when there is none.
    pub fn top(&self, key: &str) -> (usize, usize) {
        find_key(&self.text, key).unwrap_or((0, 0))
    }

    /// `(line, col)` of a slice starting at byte `start` as a place in the text.
    fn shift(&self, start: usize, line: usize, col: usize) -> (usize, usize) {
        let before = &self.text[..start];
        let lines_before = before.matches('\n').count();
        let col_before = before.rsplit('\n').next().map_or(0, |l| l.chars().count());
        let col = if line == 1 { col_before + col } else { col };
        (lines_before + line, col)
    }
}

/// `text` with every comment character replaced by spaces (as many as its
/// UTF-8 bytes: lines and byte offsets kept), so that a key in a comment is
/// not taken for a field.
pub fn code_only(text: &str) -> String {
    let is_comment = |l: Lex| matches!(l, Lex::LineComment | Lex::BlockComment(_));
    let mut out = String::with_capacity(text.len());
    let mut lex = Lex::Code;
    let mut chars = text.chars().peekable();
    while let Some(c) = chars.next() {
        let (take, to) = step(lex, c, chars.peek().copied());
        let comment = is_comment(lex) || is_comment(to);
        if comment && c != '\n' {
            out.extend(std::iter::repeat_n(' ', c.len_utf8()));
        } else {
            out.push(c);
        }
        if take == 2
            && let Some(n) = chars.next()
        {
            out.push(if comment { ' ' } else { n });
        }
        lex = to;
    }
    out
}

/// One step of the lexer at `c` (with `next` after it): how many characters
/// it takes (1, or 2 for `//`, `/*`, `*/`) and the state after them.
fn step(lex: Lex, c: char, next: Option<char>) -> (u8, Lex) {
    match lex {
        Lex::Code => match (c, next) {
            ('/', Some('/')) => (2, Lex::LineComment),
            ('/', Some('*')) => (2, Lex::BlockComment(1)),
            ('"', _) => (1, Lex::Str),
            _ => (1, Lex::Code),
        },
        Lex::LineComment if c == '\n' => (1, Lex::Code),
        Lex::LineComment => (1, Lex::LineComment),
        Lex::BlockComment(n) => match (c, next) {
            ('*', Some('/')) if n == 1 => (2, Lex::Code),
            ('*', Some('/')) => (2, Lex::BlockComment(n - 1)),
            ('/', Some('*')) => (2, Lex::BlockComment(n + 1)),
            _ => (1, lex),
        },
        Lex::Str => match c {
            '\\' => (1, Lex::Escape),
            '"' => (1, Lex::Code),
            _ => (1, Lex::Str),
        },
        Lex::Escape => (1, Lex::Str),
    }
}

/// The byte ranges of the records in the top-level `patches: [ … ]`.
fn patch_spans(text: &str) -> Vec<Range<usize>> {
    let mut out = Vec::new();
    let mut lex = Lex::Code;
    let mut depth = 0usize;
    // the depth inside the patches list, once `patches: [` is open
    let mut list: Option<usize> = None;
    let mut want_list = false;
    let mut start: Option<usize> = None;
    let (mut word, mut last_word) = (String::new(), String::new());
    let mut chars = text.char_indices().peekable();
    while let Some((i, c)) = chars.next() {
        let next = chars.peek().map(|&(_, n)| n);
        let (take, to) = step(lex, c, next);
        let was_code = lex == Lex::Code && to == Lex::Code;
        lex = to;
        if take == 2 {
            chars.next();
        }
        if !was_code {
            if !word.is_empty() {
                last_word = std::mem::take(&mut word);
            }
            continue;
        }
        if c.is_alphanumeric() || c == '_' {
            word.push(c);
            continue;
        }
        if !word.is_empty() {
            last_word = std::mem::take(&mut word);
        }
        match c {
            ':' if depth == 1 && last_word == "patches" => want_list = true,
            '(' | '[' | '{' => {
                if c == '[' && want_list && depth == 1 {
                    list = Some(2);
                    want_list = false;
                } else if c == '(' && list == Some(depth) && start.is_none() {
                    start = Some(i);
                }
                depth += 1;
            }
            ')' | ']' | '}' => {
                depth = depth.saturating_sub(1);
                if c == ')' && list == Some(depth) {
                    if let Some(s) = start.take() {
                        out.push(s..i + 1);
                    }
                } else if c == ']' && list.is_some() && depth == 1 {
                    list = None;
                }
            }
            _ => {}
        }
        if !c.is_whitespace() {
            last_word.clear();
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    const TEXT: &str = "(\n    version: 3, // patches: [ (name: \"x\") ]\n    name: \"d\",\n    patches: [\n        (name: \"a\", t: [0.0], s: /* ) */ [[0.0]]),\n        (\n            name: \"b(\",\n            t: [1.0],\n        ),\n    ],\n)\n";

    #[test]
    fn finds_each_patch_and_its_keys() {
        let p = PatchText::new(TEXT);
        assert_eq!(p.spans().len(), 2, "{:?}", p.spans());
        assert!(TEXT[p.spans()[0].clone()].starts_with("(name: \"a\""));
        assert!(TEXT[p.spans()[1].clone()].trim_end().ends_with(')'));
        assert_eq!(p.in_patch(0, "t"), (5, 21));
        assert_eq!(p.in_patch(1, "t"), (8, 13));
        assert_eq!(p.in_patch(1, "name"), (7, 13));
        // a key the patch lacks: the file's first, then the patch's start
        assert_eq!(p.in_patch(1, "version"), (2, 5));
        assert_eq!(p.in_patch(1, "nothing"), (6, 9));
        assert_eq!(p.top("patches"), (4, 5));
    }

    #[test]
    fn comments_are_blanked_keeping_places() {
        let c = code_only(TEXT);
        assert_eq!(c.lines().count(), TEXT.lines().count());
        assert_eq!(c.len(), TEXT.len());
        assert!(!c.contains("patches: [ (name"));
        assert!(c.contains(&format!("s: {} [[0.0]]", " ".repeat(7))));
        assert!(c.contains("\"b(\""));
    }
}
