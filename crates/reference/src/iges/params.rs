//! The parameters of one entity (free-format fields of the parameter
//! section), read as integers, counts and reals with located errors.

use super::records::{REEXPORT, Text, Tok, field_text, parse_int, parse_real};
use crate::error::ReferenceError;
use std::path::Path;

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
