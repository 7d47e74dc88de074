//! The parameters of one STEP entity instance, read with errors that name
//! the instance, its line and the parameter.

use super::{Args, FIX};
use crate::error::{MAX_POLES, ReferenceError};
use ruststep::ast::{Name, Parameter};
use streamline_kernel::nurbs::rational::MAX_DEGREE;

/// How a parameter reads in a message.
pub(super) fn describe(p: &Parameter) -> String {
    match p {
        Parameter::Typed { keyword, .. } => format!("the typed value {keyword}(…)"),
        Parameter::Integer(i) => format!("the integer {i}"),
        Parameter::Real(x) => format!("the number {x}"),
        Parameter::String(s) => {
            let s: String = s.chars().take(24).collect();
            format!("the string '{s}'")
        }
        Parameter::Enumeration(e) => format!("the enumeration .{e}."),
        Parameter::List(l) => format!("a list of {}", l.len()),
        Parameter::Ref(Name::Entity(n)) => format!("the reference #{n}"),
        Parameter::Ref(_) => "a constant or value reference".into(),
        Parameter::NotProvided => "`$` (no value)".into(),
        Parameter::Omitted => "`*`".into(),
    }
}

pub(super) fn as_real(p: &Parameter) -> Option<f64> {
    match p {
        Parameter::Real(x) => Some(*x),
        Parameter::Integer(i) => Some(*i as f64),
        Parameter::Typed { parameter, .. } => match parameter.as_ref() {
            Parameter::Real(x) => Some(*x),
            Parameter::Integer(i) => Some(*i as f64),
            _ => None,
        },
        _ => None,
    }
}

pub(super) fn as_ref(p: &Parameter) -> Option<u64> {
    match p {
        Parameter::Ref(Name::Entity(n)) => Some(*n),
        _ => None,
    }
}

/// A list; `$` reads as an empty one (the scan turns an empty list `()`
/// into `$`, which `ruststep` can read).
pub(super) fn as_list(p: &Parameter) -> Option<&[Parameter]> {
    match p {
        Parameter::List(l) => Some(l),
        Parameter::NotProvided => Some(&[]),
        _ => None,
    }
}

impl<'a> Args<'a> {
    pub(super) fn at(&self, i: usize, what: &str) -> Result<&'a Parameter, ReferenceError> {
        self.params.get(i).ok_or_else(|| {
            self.m.err(
                self.inst,
                format!("its {what} (parameter {}) is missing; {FIX}", i + 1),
            )
        })
    }

    pub(super) fn wrong(&self, i: usize, what: &str, want: &str, p: &Parameter) -> ReferenceError {
        self.m.err(
            self.inst,
            format!(
                "its {what} (parameter {}) should be {want}, it is {}; {FIX}",
                i + 1,
                describe(p)
            ),
        )
    }

    pub(super) fn reference(&self, i: usize, what: &str) -> Result<u64, ReferenceError> {
        let p = self.at(i, what)?;
        as_ref(p).ok_or_else(|| self.wrong(i, what, "a reference #N", p))
    }

    pub(super) fn list(&self, i: usize, what: &str) -> Result<&'a [Parameter], ReferenceError> {
        let p = self.at(i, what)?;
        as_list(p).ok_or_else(|| self.wrong(i, what, "a list", p))
    }

    pub(super) fn refs(&self, i: usize, what: &str) -> Result<Vec<u64>, ReferenceError> {
        let l = self.list(i, what)?;
        l.iter()
            .map(|p| as_ref(p).ok_or_else(|| self.wrong(i, what, "a list of references #N", p)))
            .collect()
    }

    pub(super) fn real(&self, i: usize, what: &str) -> Result<f64, ReferenceError> {
        let p = self.at(i, what)?;
        let x = as_real(p).ok_or_else(|| self.wrong(i, what, "a number", p))?;
        if x.is_finite() {
            Ok(x)
        } else {
            Err(self.wrong(i, what, "a finite number", p))
        }
    }

    pub(super) fn degree(&self, i: usize, what: &str) -> Result<usize, ReferenceError> {
        let p = self.at(i, what)?;
        match p {
            Parameter::Integer(d) if (1..=MAX_DEGREE as i64).contains(d) => Ok(*d as usize),
            _ => Err(self.wrong(i, what, &format!("an integer from 1 to {MAX_DEGREE}"), p)),
        }
    }

    /// `.T.` → true, `.F.` → false, anything else (`.U.`) → `None`.
    pub(super) fn logical(&self, i: usize) -> Option<bool> {
        match self.params.get(i) {
            Some(Parameter::Enumeration(e)) if e == "T" => Some(true),
            Some(Parameter::Enumeration(e)) if e == "F" => Some(false),
            _ => None,
        }
    }

    /// The full knot vector from multiplicities (parameter `mi`) and
    /// distinct knots (parameter `ki`).
    pub(super) fn knots(
        &self,
        mi: usize,
        ki: usize,
        dir: char,
    ) -> Result<Vec<f64>, ReferenceError> {
        let mname = format!("{dir}_multiplicities");
        let kname = format!("{dir}_knots");
        let mults = self.list(mi, &mname)?;
        let knots = self.list(ki, &kname)?;
        if mults.len() != knots.len() {
            return Err(self.m.err(
                self.inst,
                format!(
                    "it has {} {dir} multiplicities for {} {dir} knots; there must be one per knot: {FIX}",
                    mults.len(),
                    knots.len()
                ),
            ));
        }
        let mut out = Vec::new();
        for (k, (mp, kp)) in mults.iter().zip(knots).enumerate() {
            let m = match mp {
                Parameter::Integer(m) if (1..=(MAX_DEGREE as i64 + 1)).contains(m) => *m as usize,
                _ => {
                    return Err(self.m.err(
                        self.inst,
                        format!(
                            "{dir} multiplicity {} is {}, not an integer from 1 to {}; {FIX}",
                            k + 1,
                            describe(mp),
                            MAX_DEGREE + 1
                        ),
                    ));
                }
            };
            let x = as_real(kp).filter(|x| x.is_finite()).ok_or_else(|| {
                self.m.err(
                    self.inst,
                    format!(
                        "{dir} knot {} is {}, not a finite number; {FIX}",
                        k + 1,
                        describe(kp)
                    ),
                )
            })?;
            if out.len() + m > MAX_POLES + MAX_DEGREE + 1 {
                return Err(self.m.err(
                    self.inst,
                    format!("its {dir} knots number more than {MAX_POLES}; simplify the face or export a smaller one"),
                ));
            }
            out.extend(std::iter::repeat_n(x, m));
        }
        Ok(out)
    }
}
