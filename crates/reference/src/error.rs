//! Errors of reference files: the file, the line and column, what is wrong
//! and, after a `;`, what to do.

use std::fmt;
use std::path::{Path, PathBuf};

/// An error located in a reference file.
///
/// Displayed as `FILE:LINE:COL: WHAT; FIX`, or `FILE: WHAT; FIX` when no
/// line is at fault (the file is empty, cannot be read, or lacks something
/// that would sit on no line).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ReferenceError {
    /// The file as it was named.
    pub file: PathBuf,
    /// 1-based line, 0 when the whole file is at fault.
    pub line: usize,
    /// 1-based column, 0 when the whole file is at fault.
    pub col: usize,
    /// What is wrong and, after `; `, what to do.
    pub message: String,
}

impl ReferenceError {
    /// An error at `line`, `col` (1-based).
    pub fn at(file: &Path, line: usize, col: usize, message: impl Into<String>) -> Self {
        ReferenceError {
            file: file.to_path_buf(),
            line,
            col,
            message: message.into(),
        }
    }

    /// An error about the whole file.
    pub fn whole(file: &Path, message: impl Into<String>) -> Self {
        Self::at(file, 0, 0, message)
    }

    /// Whether the error names a line.
    pub fn is_located(&self) -> bool {
        self.line > 0
    }
}

impl fmt::Display for ReferenceError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.line > 0 {
            write!(
                f,
                "{}:{}:{}: {}",
                self.file.display(),
                self.line,
                self.col.max(1),
                self.message
            )
        } else {
            write!(f, "{}: {}", self.file.display(), self.message)
        }
    }
}

impl std::error::Error for ReferenceError {}

/// The largest reference file read (bytes): 512 MiB, far above any single
/// face or scan a designer brings, well below the memory cap.
pub const MAX_FILE_BYTES: u64 = 512 << 20;

/// The most poles one surface may have (a million: 24 MB of coordinates;
/// CAD faces have thousands at most).
pub const MAX_POLES: usize = 1_000_000;

/// The most poles the faces of one file may have together (8 million,
/// about 450 MB of surfaces): faces that share one large surface cannot
/// make the reader copy it without end.
pub const MAX_FILE_POLES: usize = 8_000_000;

/// The most points a grid or vertices a mesh may have (16 million).
pub const MAX_POINTS: usize = 16_000_000;

/// The most triangles a mesh may have (32 million, about 400 MB with its
/// index; a binary STL of the largest size read holds 10.7 million).
pub const MAX_TRIANGLES: usize = 32_000_000;

/// The whole file as bytes, refused when it cannot be read or is larger
/// than [`MAX_FILE_BYTES`].
pub fn read_file(path: &Path) -> Result<Vec<u8>, ReferenceError> {
    let meta = std::fs::metadata(path).map_err(|e| {
        ReferenceError::whole(path, format!("cannot read the file ({e}); check the path"))
    })?;
    if meta.is_dir() {
        return Err(ReferenceError::whole(
            path,
            "is a folder, not a file; name the reference file itself",
        ));
    }
    if meta.len() > MAX_FILE_BYTES {
        return Err(ReferenceError::whole(
            path,
            format!(
                "the file is {} bytes, more than the {MAX_FILE_BYTES} read as a reference; export only the faces you need",
                meta.len()
            ),
        ));
    }
    std::fs::read(path).map_err(|e| {
        ReferenceError::whole(
            path,
            format!("cannot read the file ({e}); check the permissions"),
        )
    })
}

/// The deepest nesting of lists, typed values and complex instances read in
/// a STEP file (its data nests four deep at most: the weights of a complex
/// rational instance). Deeper text is refused before it is parsed, so no
/// input can exhaust the stack of the recursive Part 21 parser.
pub const MAX_NESTING: usize = 32;

/// The most values (parameters, list items and records) a STEP file may
/// hold: 24 million, about a gigabyte once parsed; a STEP file of the
/// largest size read holds fewer unless it is mostly tiny numbers.
pub const MAX_STEP_VALUES: usize = 24_000_000;

/// The longest run of digits read as one integer in a STEP file (an `i64`
/// holds 18 digits); longer runs are refused before they are parsed.
pub const MAX_INTEGER_DIGITS: usize = 18;
