//! The length unit of a STEP file's geometric contexts: an `SI_UNIT` with
//! its prefix, or a `CONVERSION_BASED_UNIT` (the inch, the foot) through its
//! measure of another unit; every length read is multiplied by its metres.

use super::args::{as_ref, describe};
use super::part21::{Instance, params};
use super::{FIX, Mapper};
use crate::error::ReferenceError;
use ruststep::ast::Parameter;

impl<'a> Mapper<'a> {
    /// The length unit of the file's geometric contexts: its name and
    /// metres per unit.
    pub(super) fn length_unit(&self) -> Result<(String, f64), ReferenceError> {
        let mut found: Option<(String, f64, &Instance)> = None;
        for ctx in &self.data.instances {
            if !ctx.has("GLOBAL_UNIT_ASSIGNED_CONTEXT") {
                continue;
            }
            let a = self.args(ctx, "GLOBAL_UNIT_ASSIGNED_CONTEXT", 1)?;
            let mut unit = None;
            for id in a.refs(0, "units")? {
                let u = self.get(id, ctx, "unit")?;
                if let Some(x) = self.unit(u, 0)? {
                    unit = Some(x);
                    break;
                }
            }
            let Some((name, metres)) = unit else {
                continue;
            };
            match &found {
                None => found = Some((name, metres, ctx)),
                Some((n0, m0, c0)) => {
                    if (metres - m0).abs() > 1e-12 * m0.abs() {
                        return Err(self.err(
                            ctx,
                            format!(
                                "its length unit is {name}, the context #{} on line {} has {n0}; a reference must use one length unit: re-export it in one unit",
                                c0.id, c0.line
                            ),
                        ));
                    }
                }
            }
        }
        found.map(|(n, m, _)| (n, m)).ok_or_else(|| {
            ReferenceError::whole(
                self.path,
                "the file names no length unit (no GLOBAL_UNIT_ASSIGNED_CONTEXT with a LENGTH_UNIT); re-export it from the CAD system with its units",
            )
        })
    }

    /// A length unit's name and metres, `None` for a unit that is not a
    /// length (an angle, a solid angle).
    pub(super) fn unit(
        &self,
        u: &'a Instance,
        depth: usize,
    ) -> Result<Option<(String, f64)>, ReferenceError> {
        if depth > 8 {
            return Err(self.err(
                u,
                format!("its unit is defined through more than 8 conversions; {FIX}"),
            ));
        }
        if let Some(rec) = u.record("SI_UNIT") {
            let p = params(rec);
            // complex: (prefix, name); a simple instance: (*, prefix, name)
            let [.., prefix, name] = p else {
                return Err(self.err(
                    u,
                    format!(
                        "its SI_UNIT has {} parameters, 2 are needed; {FIX}",
                        p.len()
                    ),
                ));
            };
            if !matches!(name, Parameter::Enumeration(n) if n == "METRE") {
                return Ok(None);
            }
            let (word, factor) = match prefix {
                Parameter::Enumeration(e) => si_prefix(e).ok_or_else(|| {
                    self.err(
                        u,
                        format!("its SI prefix .{e}. is not one of ISO 10303-41's; {FIX}"),
                    )
                })?,
                _ => ("", 1.0),
            };
            return Ok(Some((format!("{word}metre"), factor)));
        }
        if let Some(rec) = u.record("CONVERSION_BASED_UNIT") {
            if !u.has("LENGTH_UNIT") && u.complex {
                return Ok(None);
            }
            let p = params(rec);
            let [.., name, factor] = p else {
                return Err(self.err(
                    u,
                    format!(
                        "its CONVERSION_BASED_UNIT has {} parameters, 2 are needed; {FIX}",
                        p.len()
                    ),
                ));
            };
            let name = match name {
                Parameter::String(s) => s.trim().to_lowercase(),
                _ => "unnamed unit".into(),
            };
            let fid = as_ref(factor).ok_or_else(|| {
                self.err(
                    u,
                    format!(
                        "its conversion_factor is {}, not a reference; {FIX}",
                        describe(factor)
                    ),
                )
            })?;
            let f = self.get(fid, u, "conversion_factor")?;
            let rec = ["LENGTH_MEASURE_WITH_UNIT", "MEASURE_WITH_UNIT"]
                .into_iter()
                .find(|n| f.record(n).is_some_and(|r| params(r).len() >= 2))
                .ok_or_else(|| {
                    self.err(
                        f,
                        format!(
                            "it is not a LENGTH_MEASURE_WITH_UNIT with a value and a unit; {FIX}"
                        ),
                    )
                })?;
            let a = self.args(f, rec, 2)?;
            let value = a.real(0, "value_component")?;
            let base = self.get(a.reference(1, "unit_component")?, f, "unit_component")?;
            let Some((_, metres)) = self.unit(base, depth + 1)? else {
                return Err(self.err(
                    f,
                    format!(
                        "its unit_component #{} is not a length unit; {FIX}",
                        base.id
                    ),
                ));
            };
            let m = value * metres;
            if !(m.is_finite() && m > 0.0) {
                return Err(self.err(
                    f,
                    format!(
                        "the length unit it defines is {m} metres, not a positive length; {FIX}"
                    ),
                ));
            }
            return Ok(Some((name, m)));
        }
        Ok(None)
    }
}

/// An SI prefix's word and factor.
fn si_prefix(e: &str) -> Option<(&'static str, f64)> {
    Some(match e {
        "EXA" => ("exa", 1e18),
        "PETA" => ("peta", 1e15),
        "TERA" => ("tera", 1e12),
        "GIGA" => ("giga", 1e9),
        "MEGA" => ("mega", 1e6),
        "KILO" => ("kilo", 1e3),
        "HECTO" => ("hecto", 1e2),
        "DECA" => ("deca", 1e1),
        "DECI" => ("deci", 1e-1),
        "CENTI" => ("centi", 1e-2),
        "MILLI" => ("milli", 1e-3),
        "MICRO" => ("micro", 1e-6),
        "NANO" => ("nano", 1e-9),
        "PICO" => ("pico", 1e-12),
        "FEMTO" => ("femto", 1e-15),
        "ATTO" => ("atto", 1e-18),
        _ => return None,
    })
}
