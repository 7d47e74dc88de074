//! The exchange structure (ISO 10303-21, the text of a STEP file) through
//! `ruststep`'s parser, plus what that parser does not give: the line and
//! column of every `#N =` definition, so that each later error can name
//! them.
//!
//! The text is scanned first ([`scan`]); a text the parser cannot read
//! is reported where it goes wrong ([`syntax_error`]).

use super::scan::scan;
use super::syntax_error::syntax_error;
use crate::error::ReferenceError;
use ruststep::ast::{EntityInstance, Parameter, Record};
use std::collections::HashMap;
use std::path::Path;

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
