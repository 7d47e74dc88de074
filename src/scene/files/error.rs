//! Errors of scene and script files: the file, the line and column, what is
//! wrong and what to do.

use std::fmt;
use std::path::{Path, PathBuf};

/// An error located in a file.
#[derive(Debug, Clone, PartialEq)]
pub struct SceneError {
    /// The file (or `<memory>`).
    pub file: PathBuf,
    /// 1-based line, 0 when unknown.
    pub line: usize,
    /// 1-based column, 0 when unknown.
    pub col: usize,
    /// What is wrong and how to fix it.
    pub message: String,
}

impl SceneError {
    /// An error at a place.
    pub fn at(file: &Path, line: usize, col: usize, message: impl Into<String>) -> Self {
        SceneError {
            file: file.to_path_buf(),
            line,
            col,
            message: message.into(),
        }
    }

    /// An error about a whole file (I/O).
    pub fn file(file: &Path, message: impl Into<String>) -> Self {
        Self::at(file, 0, 0, message)
    }

    /// From a RON parse error of `text`: keeps its position; an error at the
    /// very end of the text is reported as a truncated file.
    pub fn ron(file: &Path, text: &str, e: &ron::error::SpannedError) -> Self {
        let mut msg = explain(&e.code);
        let (line, col) = (e.span.start.line, e.span.start.col);
        let trimmed = text.trim_end();
        let last_line = trimmed.lines().count().max(1);
        let last_col = trimmed.lines().last().map_or(0, |l| l.chars().count());
        let at_end = line > last_line || (line == last_line && col >= last_col);
        let about_content = matches!(
            e.code,
            ron::Error::Eof | ron::Error::MissingStructField { .. }
        );
        if at_end && !about_content {
            msg = format!(
                "the file ends too early ({msg}); it looks truncated — check that every bracket is closed"
            );
        }
        Self::at(file, line, col, msg)
    }

    /// The place of the first `key:` in `text` (for errors that span fields).
    pub fn locate(file: &Path, text: &str, key: &str, message: impl Into<String>) -> Self {
        let (line, col) = find_key(text, key).unwrap_or((0, 0));
        Self::at(file, line, col, message)
    }
}

/// Line and column (1-based) of the first `key` followed by `:`, as a field name.
pub fn find_key(text: &str, key: &str) -> Option<(usize, usize)> {
    for (i, line) in text.lines().enumerate() {
        let mut from = 0;
        while let Some(p) = line[from..].find(key) {
            let at = from + p;
            let before_ok = at == 0
                || !line[..at]
                    .chars()
                    .next_back()
                    .is_some_and(|c| c.is_alphanumeric() || c == '_');
            let after = line[at + key.len()..].trim_start();
            if before_ok && after.starts_with(':') {
                return Some((i + 1, line[..at].chars().count() + 1));
            }
            from = at + key.len();
        }
    }
    None
}

fn explain(code: &ron::Error) -> String {
    use ron::Error as E;
    match code {
        E::Message(m) => m.clone(),
        E::NoSuchStructField {
            expected, found, ..
        } => format!(
            "unknown field `{found}`; remove it or use one of: {}",
            expected.join(", ")
        ),
        E::MissingStructField { field, .. } => {
            format!(
                "the record that ends here has no field `{field}`; add it (see scenes/car1.ron for an example)"
            )
        }
        E::NoSuchEnumVariant {
            expected, found, ..
        } => format!(
            "unknown variant `{found}`; use one of: {}",
            expected.join(", ")
        ),
        E::Eof => "the file ends too early; it looks truncated — check the closing brackets".into(),
        other => format!("{other}; fix the RON syntax here"),
    }
}

impl fmt::Display for SceneError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.line > 0 {
            write!(
                f,
                "{}:{}:{}: {}",
                self.file.display(),
                self.line,
                self.col,
                self.message
            )
        } else {
            write!(f, "{}: {}", self.file.display(), self.message)
        }
    }
}

impl std::error::Error for SceneError {}
