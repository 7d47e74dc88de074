//! Reading JSON from stdin and writing JSON to stdout, with errors that name the place.

use serde::Serialize;
use serde::de::DeserializeOwned;
use std::fmt;
use std::io::{Read, Write};
use streamline_kernel::KernelError;

/// Why a command failed. Every variant but `Io` is the user's input: exit code 2.
#[derive(Debug)]
pub enum CliError {
    /// The JSON on stdin is malformed or of the wrong shape.
    Json(serde_json::Error),
    /// The input is well-formed but geometrically invalid.
    Kernel(KernelError),
    /// A command-line value is unusable.
    Usage(String),
    /// Reading stdin or writing stdout failed.
    Io(std::io::Error),
    /// A scene or script file is invalid (the message names file, line and column).
    Scene(crate::scene::SceneError),
    /// A script ran and some expectations failed (exit code 1).
    Failed(String),
}

impl CliError {
    /// 2 for bad input, 1 for I/O failures.
    pub fn exit_code(&self) -> i32 {
        match self {
            CliError::Io(_) | CliError::Failed(_) => 1,
            _ => 2,
        }
    }
}

impl fmt::Display for CliError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            CliError::Json(e) => write!(
                f,
                "stdin:{}:{}: {e}; fix the JSON input",
                e.line(),
                e.column()
            ),
            CliError::Kernel(e) => write!(f, "stdin: {e}"),
            CliError::Usage(m) => write!(f, "{m}"),
            CliError::Io(e) => write!(f, "I/O error: {e}"),
            CliError::Scene(e) => write!(f, "{e}"),
            CliError::Failed(m) => write!(f, "{m}"),
        }
    }
}

impl From<KernelError> for CliError {
    fn from(e: KernelError) -> Self {
        CliError::Kernel(e)
    }
}

impl From<std::io::Error> for CliError {
    fn from(e: std::io::Error) -> Self {
        CliError::Io(e)
    }
}

/// The most bytes read from stdin (larger input is refused, not read into memory).
pub const MAX_STDIN_BYTES: u64 = 256 << 20;

/// All of stdin as text (at most [`MAX_STDIN_BYTES`]).
pub fn read_stdin_text() -> Result<String, CliError> {
    let mut bytes = Vec::new();
    std::io::stdin()
        .lock()
        .take(MAX_STDIN_BYTES + 1)
        .read_to_end(&mut bytes)?;
    if bytes.len() as u64 > MAX_STDIN_BYTES {
        return Err(CliError::Usage(format!(
            "stdin: the input is over {MAX_STDIN_BYTES} bytes; split it into smaller inputs"
        )));
    }
    String::from_utf8(bytes).map_err(|e| {
        CliError::Usage(format!(
            "stdin: byte {} is not UTF-8 text; the input is JSON",
            e.utf8_error().valid_up_to()
        ))
    })
}

/// Parses a JSON document as `T`.
pub fn parse<T: DeserializeOwned>(s: &str) -> Result<T, CliError> {
    serde_json::from_str(s).map_err(CliError::Json)
}

/// Writes `value` as one line of JSON to stdout.
pub fn write_stdout<T: Serialize>(value: &T) -> Result<(), CliError> {
    let mut out = std::io::stdout().lock();
    serde_json::to_writer(&mut out, value).map_err(|e| CliError::Io(e.into()))?;
    writeln!(out)?;
    Ok(())
}

impl From<crate::scene::SceneError> for CliError {
    fn from(e: crate::scene::SceneError) -> Self {
        CliError::Scene(e)
    }
}

/// A scene argument: a `.ron` file, or the name of a built-in scene.
pub fn scene_arg(arg: &str) -> Result<crate::scene::Scene, CliError> {
    use crate::scene::design::{builtin, document_io};
    let path = std::path::Path::new(arg);
    if arg.ends_with(".ron") || path.is_file() {
        return Ok(document_io::load_scene(path)?);
    }
    builtin::scene(arg).map_err(|_| {
        CliError::Usage(format!(
            "'{arg}' is neither a .ron scene file nor a built-in scene; built-in scenes: {}",
            builtin::names()
        ))
    })
}

/// A design argument: a .ron file of any version (1 and 2 as one patch
/// named `main`, 3 as its patches) or a built-in scene's name (one patch).
pub fn document_arg(arg: &str) -> Result<crate::scene::Document, CliError> {
    use crate::scene::{Document, design::document_io};
    let path = std::path::Path::new(arg);
    if arg.ends_with(".ron") || path.is_file() {
        return Ok(document_io::load(path)?);
    }
    scene_arg(arg).map(Document::from_scene)
}
