//! Damaged and hostile inputs give located errors (`FILE:LINE:COL: WHAT;
//! FIX`) and never a panic, a stack overflow or an unbounded allocation.

use proptest::prelude::*;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use streamline_reference::{ReferenceError, read};

fn fixture(name: &str) -> Vec<u8> {
    std::fs::read(
        Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("tests/data")
            .join(name),
    )
    .expect("fixture")
}

fn fixture_text(name: &str) -> String {
    String::from_utf8(fixture(name)).expect("ASCII fixture")
}

/// Writes `bytes` to a fresh file named `name` in this process's scratch
/// folder.
fn write(name: &str, bytes: impl AsRef<[u8]>) -> PathBuf {
    static N: AtomicUsize = AtomicUsize::new(0);
    let dir = std::env::temp_dir().join(format!(
        "streamline-reference-malformed-{}-{}",
        std::process::id(),
        N.fetch_add(1, Ordering::Relaxed)
    ));
    std::fs::create_dir_all(&dir).unwrap();
    let p = dir.join(name);
    std::fs::write(&p, bytes).unwrap();
    p
}

/// Reads `bytes` as file `name`; the error, which must name `line` (and a
/// column) in its Display, else the test fails.
fn located(name: &str, bytes: impl AsRef<[u8]>, line: usize) -> ReferenceError {
    let p = write(name, bytes);
    let e = match read(&p) {
        Ok(f) => panic!("{name} read with {} faces", f.faces.len()),
        Err(e) => e,
    };
    eprintln!("{e}");
    assert!(e.is_located(), "{e}");
    assert_eq!(e.line, line, "{e}");
    let prefix = format!("{}:{}:{}: ", p.display(), e.line, e.col);
    assert!(e.col >= 1);
    assert!(e.to_string().starts_with(&prefix), "{e}");
    assert!(e.message.contains("; "), "WHAT; FIX: {e}");
    e
}

/// `text` with the first `width` columns of line `index` (0-based) set to
/// `columns`, padded with blanks.
fn set_columns(text: &str, index: usize, width: usize, columns: &str) -> String {
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    assert!(columns.len() <= width);
    let rest = lines[index][width..].to_string();
    lines[index] = format!("{columns:<width$}{rest}");
    lines.join("\n")
}

#[test]
fn truncated_step() {
    let text = fixture_text("bicubic.step");
    // cut inside #38 = CARTESIAN_POINT('',(0.25,0.,9.63…
    let cut = text.find("0.25,0.,9.63").unwrap();
    let e = located("truncated.step", &text[..cut], 58);
    assert!(
        e.message
            .contains("the file ends inside #38 CARTESIAN_POINT"),
        "{e}"
    );
    assert_eq!(e.col, 1);
    // cut between two statements: the sections never end
    let cut = text.find("#38 =").unwrap();
    let e = located("truncated2.step", &text[..cut], 58);
    assert!(e.message.contains("re-export"), "{e}");
}

#[test]
fn a_missing_referenced_entity() {
    let text = fixture_text("bicubic.step");
    let gone = text.replace(
        "#38 = CARTESIAN_POINT('',(0.25,0.,9.635581854172E-02));\n",
        "",
    );
    assert_ne!(gone, text);
    let e = located("missing.step", gone, 46);
    assert!(
        e.message.starts_with("#33 B_SPLINE_SURFACE_WITH_KNOTS: its control point is #38, which the file does not define"),
        "{e}"
    );
}

#[test]
fn a_non_finite_pole() {
    // STEP has no NaN: a number too large for a double is infinite
    let text = fixture_text("bicubic.step");
    let bad = text.replace("(0.25,0.,9.635581854172E-02)", "(0.25,0.,9.6E999)");
    let e = located("inf.step", bad, 58);
    assert!(
        e.message
            .starts_with("#38 CARTESIAN_POINT: coordinate 3 is not a finite number"),
        "{e}"
    );
    // IGES: `NaN` where a coordinate should be, the columns kept
    let text = fixture_text("bicubic.igs");
    let bad = text.replacen("9.635581854E-02", "NaN            ", 1);
    assert_ne!(bad, text);
    let e = located("nan.igs", bad, 13);
    assert_eq!(e.col, 27);
    assert!(
        e.message.contains("DE 3 (128)") && e.message.contains("'NaN' is not a number"),
        "{e}"
    );
}

#[test]
fn decreasing_knots() {
    let text = fixture_text("bicubic.step");
    let bad = text.replace("(0.,0.4,1.),(0.,2.)", "(0.,1.4,1.),(0.,2.)");
    assert_ne!(bad, text);
    let e = located("knots.step", bad, 46);
    assert!(e.message.contains("the u knots decrease"), "{e}");
    // IGES: the fifth u knot, 0.4 → 1.4, same columns
    let text = fixture_text("bicubic.igs");
    let bad = text.replacen("0.,0.4,1.,", "0.,1.4,1.,", 1);
    assert_ne!(bad, text);
    let e = located("knots.igs", bad, 11);
    // the knot after it (1.) is the first that is smaller
    assert_eq!(e.col, 39);
    assert!(
        e.message.contains("DE 3 (128): the u knots decrease"),
        "{e}"
    );
}

#[test]
fn wrong_pole_counts() {
    let text = fixture_text("bicubic.step");
    // one u multiplicity less: 8 knots for 5 poles of degree 3
    let bad = text.replace("(4,1,4),(4,4)", "(4,1,3),(4,4)");
    let e = located("count.step", bad, 46);
    assert!(
        e.message
            .contains("poles in u but 8 knots of degree 3 need 4"),
        "{e}"
    );
    // a ragged control point list
    let bad = text.replace("(#38,#39,#40,#41)", "(#38,#39,#40)");
    let e = located("ragged.step", bad, 46);
    assert!(
        e.message.contains("row 1 of its control_points_list"),
        "{e}"
    );
    // IGES: K1 says 6 poles in u, the data holds 5
    let text = fixture_text("bicubic.igs");
    let bad = text.replacen("128,4,3,3,3,", "128,5,3,3,3,", 1);
    // the parameters end (`;`, line 21 column 9) before the data does
    let e = located("count.igs", bad, 21);
    assert_eq!(e.col, 9);
    assert!(
        e.message
            .contains("DE 3 (128): it has 110 parameters, its counts need 127"),
        "{e}"
    );
}

#[test]
fn bad_iges_column_layout() {
    let text = fixture_text("bicubic.igs");
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    lines[7] = format!(" {}", lines[7]); // the 128's first directory line
    let e = located("columns.igs", lines.join("\n"), 8);
    assert_eq!(e.col, 73);
    assert!(e.message.contains("column 73 holds"), "{e}");
    // a line cut short
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    lines[10].truncate(40);
    let e = located("short.igs", lines.join("\n"), 11);
    assert!(e.message.contains("the line has 40 columns"), "{e}");
    // a letter in a directory field
    let bad = text.replacen("     128       2", "     1x8       2", 1);
    let e = located("field.igs", bad, 8);
    assert_eq!(e.col, 1);
    assert!(e.message.contains("entity type"), "{e}");
}

#[test]
fn empty_and_foreign_files() {
    for name in ["empty.step", "empty.igs", "blank.stp"] {
        let p = write(
            name,
            if name.starts_with("blank") {
                "\n  \n"
            } else {
                ""
            },
        );
        let e = read(&p).unwrap_err();
        assert_eq!(
            e.to_string(),
            format!(
                "{}: the file is empty; export the reference again from the CAD system",
                p.display()
            )
        );
    }
    // IGES text named .step
    let e = located("iges.step", fixture("bicubic.igs"), 1);
    assert!(
        e.message.contains("does not start with ISO-10303-21"),
        "{e}"
    );
    // STEP text named .igs
    let e = located("step.igs", fixture("bicubic.step"), 1);
    assert!(e.message.contains("column"), "{e}");
    // no faces
    let text = fixture_text("bicubic.step");
    let none = text.replace("#17 = ADVANCED_FACE(", "#17 = SOMETHING_ELSE(");
    let e = read(&write("none.step", none)).unwrap_err();
    assert!(
        e.message
            .starts_with("the file has no face: no ADVANCED_FACE or FACE_SURFACE"),
        "{e}"
    );
    let e = read(&write("none.txt", "x")).unwrap_err();
    assert!(e.message.contains(".step, .stp, .p21"), "{e}");
}

#[test]
fn step_syntax_errors_name_the_entity() {
    let text = fixture_text("bicubic.step");
    let bad = text.replace(
        "#39 = CARTESIAN_POINT('',(0.25,0.3,",
        "#39 = CARTESIAN_POINT('',(0.25,,0.3,",
    );
    assert_ne!(bad, text);
    let e = located("syntax.step", bad, 59);
    assert_eq!(e.col, 1);
    assert!(e.message.starts_with("#39 CARTESIAN_POINT does not follow the ISO 10303-21 syntax: the parser cannot read on from line 59, column"), "{e}");
    // in a complex instance
    let cylinder = fixture_text("cylinder.step");
    let bad = cylinder.replace(
        "RATIONAL_B_SPLINE_SURFACE((",
        "RATIONAL_B_SPLINE_SURFACE(((",
    );
    assert_ne!(bad, cylinder);
    let e = located("complex.step", bad, 44);
    assert!(
        e.message
            .starts_with("#31 (complex instance) does not follow the ISO 10303-21 syntax"),
        "{e}"
    );
    assert!(e.message.contains("its parentheses do not balance"), "{e}");
    let bad = text.replace("#39 =", "FOO(1);\n#39 =");
    let e = located("stray.step", bad, 59);
    assert!(
        e.message
            .starts_with("`FOO(1)` in the data section is not an entity instance"),
        "{e}"
    );
    let bad = text.replace("#39 =", "#38 =");
    let e = located("twice.step", bad, 59);
    assert!(
        e.message
            .contains("#38 is defined a second time (first on line 58)"),
        "{e}"
    );
}

#[test]
fn hostile_step_is_refused_before_parsing() {
    let text = fixture_text("bicubic.step");
    let head = &text[..text.find("#1 =").unwrap()];
    // lists nested a hundred thousand deep: no stack overflow
    let deep = format!(
        "{head}#1 = A({}1{});\nENDSEC;\nEND-ISO-10303-21;\n",
        "(".repeat(100_000),
        ")".repeat(100_000)
    );
    let e = located("deep.step", deep, 10);
    assert!(e.message.contains("nest more than 32 deep"), "{e}");
    // 32 deep (the record's own parentheses included) is still read
    let nested = text.replacen(
        "#1 =",
        &format!("#999 = A({}1{});\n#1 =", "(".repeat(31), ")".repeat(31)),
        1,
    );
    let f = read(&write("nested.step", nested)).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(f.faces.len(), 1);
    // an integer of 30 digits (ruststep 0.4 would panic on it)
    let long = text.replace(
        "#17 = ADVANCED_FACE('',(#18),#33,.T.);",
        "#17 = ADVANCED_FACE('',(#18),#33,123456789012345678901234567890);",
    );
    let e = located("long.step", long, 29);
    assert!(e.message.contains("30 digits"), "{e}");
    // a knot multiplicity of four hundred million
    let big = text.replace("(4,1,4),(4,4)", "(4,1,400000000),(4,4)");
    let e = located("mult.step", big, 46);
    assert!(
        e.message
            .contains("u multiplicity 3 is the integer 400000000"),
        "{e}"
    );
    // but long fractions and exponents of reals are fine
    let fine = text.replace(
        "(0.,0.4,1.),(0.,2.)",
        "(0.,0.4000000000000000000000000001,1.),(0.,2.)",
    );
    assert!(read(&write("fraction.step", fine)).is_ok());
}

#[test]
fn step_strings_and_comments_do_not_confuse_the_index() {
    let text = fixture_text("bicubic.step");
    let odd = text
        .replace(
            "#7 = PRODUCT('Open CASCADE STEP translator 8.0 1',",
            "#7 = PRODUCT('it''s; #99 = (''',",
        )
        .replace("#33 = B_SPLINE", "/* #33 = ; ( */ #33 = B_SPLINE")
        // empty lists, which ruststep 0.4 does not read by itself
        .replace("'part',$,(#7)", "'part',$,( \n )")
        .replace("'Open CASCADE 8.0'\n  ,'Unknown'", "()\n  ,'Unknown'");
    assert_ne!(odd, text);
    let f = read(&write("odd.step", &odd)).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(f.faces[0].info.line, 46);
    // and an error after them is still on its line
    let bad = odd.replace(
        "#38 = CARTESIAN_POINT('',(0.25,0.,9.635581854172E-02));\n",
        "",
    );
    let e = located("odd-missing.step", bad, 46);
    assert!(
        e.message.starts_with("#33 B_SPLINE_SURFACE_WITH_KNOTS"),
        "{e}"
    );
}

#[test]
fn hostile_iges_counts_are_refused() {
    let text = fixture_text("bicubic.igs");
    // K1 = 999 999 999 poles in u, the columns kept
    let bad = set_columns(
        &text,
        10,
        64,
        "128,999999999,3,3,3,0,0,1,0,0,0.,0.,0.,0.,0.4,1.,1.,1.,1.,0.,",
    );
    let e = located("huge.igs", bad, 11);
    assert_eq!(e.col, 5);
    assert!(e.message.contains("K1"), "{e}");
    // a Hollerith string longer than the section
    let bad = text.replacen(",,31HO", ",,999H", 1);
    let e = located("hollerith.igs", bad, 2);
    assert_eq!(e.col, 3);
    assert!(
        e.message
            .contains("a string of 999 characters runs past the end of the global section"),
        "{e}"
    );
    // a parameter pointer past the parameter section
    let bad = text.replacen("     128       2       0", "     128   99999       0", 1);
    let e = located("pointer.igs", bad, 8);
    assert!(
        e.message.contains("lies outside the parameter section"),
        "{e}"
    );
}

#[test]
fn iges_units_and_transforms() {
    let text = fixture_text("bicubic.igs");
    // unit flag 3: the unit named in field 15
    let named = text.replacen(",1.,6,1HM,1,", ",1.,3,2HMM,1", 1);
    assert_ne!(named, text);
    let f = read(&write("named.igs", named)).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!((f.unit.as_str(), f.metres_per_unit), ("millimetre", 0.001));
    // model space scale 2: model units are half a real one
    let scaled = text.replacen(",1.,6,1HM,1,", ",2.,6,1HM,1,", 1);
    let f = read(&write("scaled.igs", scaled)).unwrap();
    assert_eq!(f.metres_per_unit, 0.5);
    // an unknown unit flag
    let bad = text.replacen(",1.,6,1HM,1,", ",1.,0,1HM,1,", 1);
    let e = located("unit.igs", bad, 4);
    assert!(e.message.contains("unit flag"), "{e}");
}

/// One way to damage a file.
#[derive(Debug, Clone)]
enum Damage {
    Truncate(usize),
    Set(usize, u8),
    Insert(usize, Vec<u8>),
    Remove(usize, usize),
    Repeat(usize, usize, usize),
}

fn damage() -> impl Strategy<Value = Damage> {
    let byte = prop_oneof![
        Just(b'('),
        Just(b')'),
        Just(b','),
        Just(b';'),
        Just(b'\''),
        Just(b'#'),
        Just(b'.'),
        Just(b'9'),
        Just(b'E'),
        Just(b'H'),
        Just(b'\n'),
        Just(b' '),
        Just(b'-'),
        any::<u8>(),
    ];
    prop_oneof![
        any::<usize>().prop_map(Damage::Truncate),
        (any::<usize>(), byte.clone()).prop_map(|(i, b)| Damage::Set(i, b)),
        (any::<usize>(), proptest::collection::vec(byte, 1..12))
            .prop_map(|(i, b)| Damage::Insert(i, b)),
        (any::<usize>(), 1usize..200).prop_map(|(i, n)| Damage::Remove(i, n)),
        (any::<usize>(), 1usize..40, 1usize..50).prop_map(|(i, n, k)| Damage::Repeat(i, n, k)),
    ]
}

fn apply(bytes: &mut Vec<u8>, d: &Damage) {
    let at = |i: usize, len: usize| if len == 0 { 0 } else { i % (len + 1) };
    match d {
        Damage::Truncate(i) => {
            let n = at(*i, bytes.len());
            bytes.truncate(n);
        }
        Damage::Set(i, b) => {
            if !bytes.is_empty() {
                let n = i % bytes.len();
                bytes[n] = *b;
            }
        }
        Damage::Insert(i, b) => {
            let n = at(*i, bytes.len());
            bytes.splice(n..n, b.iter().copied());
        }
        Damage::Remove(i, k) => {
            let n = at(*i, bytes.len());
            let e = (n + k).min(bytes.len());
            bytes.drain(n..e);
        }
        Damage::Repeat(i, k, times) => {
            let n = at(*i, bytes.len());
            let e = (n + k).min(bytes.len());
            let piece = bytes[n..e].to_vec();
            for _ in 0..*times {
                bytes.splice(e..e, piece.iter().copied());
            }
        }
    }
}

const FIXTURES: [&str; 13] = [
    "bicubic.step",
    "bicubic-mm.step",
    "bicubic-inch.step",
    "cylinder.step",
    "two-faces.step",
    "trimmed.step",
    "bicubic.igs",
    "bicubic-mm.igs",
    "bicubic-inch.igs",
    "cylinder.igs",
    "trimmed.igs",
    "car1-streamline.step",
    "car1-streamline.igs",
];

proptest! {
    // 400 cases (about a second); PROPTEST_CASES=N runs more
    #![proptest_config(ProptestConfig {
        cases: std::env::var("PROPTEST_CASES").ok().and_then(|n| n.parse().ok()).unwrap_or(400),
        ..ProptestConfig::default()
    })]

    /// Random truncations and byte mutations of every fixture: `read`
    /// returns (a file or an error) and never panics.
    #[test]
    fn damaged_fixtures_never_panic(
        which in 0..FIXTURES.len(),
        damages in proptest::collection::vec(damage(), 1..6),
    ) {
        let name = FIXTURES[which];
        let mut bytes = fixture(name);
        for d in &damages {
            apply(&mut bytes, d);
        }
        let p = write(name, &bytes);
        match read(&p) {
            Ok(f) => {
                for face in &f.faces {
                    prop_assert!(face.info.area.is_finite() || face.surface.is_some());
                }
            }
            Err(e) => {
                prop_assert!(!e.message.is_empty());
            }
        }
        let _ = std::fs::remove_dir_all(p.parent().unwrap());
    }
}
