//! Text in CAD files: the scene's name (and the file's) as a STEP string
//! literal (ISO 10303-21) and as an IGES Hollerith string. Names are labels
//! that every reader must take, whatever the scene is called: quotes,
//! semicolons, parentheses, backslashes, control characters, any Unicode,
//! any length.
//!
//! **STEP.** ISO 10303-21 writes a quote inside a string as `''`, but
//! OpenCascade's lexer (`StepFile/step.lex`, as in 8.0) ends a string at
//! any `'` that is followed, after optional spaces, `"` or line breaks, by
//! `,` or `)`: the name `a');b` written `'a'');b'` ends after `'a''` and the
//! file is refused ("Incorrect syntax: unexpected TYPE"). Tried on hand-made
//! files through OpenCascade 8.0 (`cadquery-ocp-novtk` 8.0.1), product name read
//! back from the `PRODUCT` entity and by XCAF:
//!
//! | written | OpenCascade |
//! |---|---|
//! | `''` followed by a letter, or by `'` | reads `'` |
//! | `''` followed by `)`, `,`, or spaces or `"` and then `)` or `,` | refuses the file |
//! | `\X2\0027\X0\` (a quote as ISO 10646 code) | reads `'`, anywhere |
//! | `\\` | reads `\` (also before a directive: `\\X2\\` reads `\X2\`) |
//! | `\X2\hhhh…\X0\` (BMP, 4 hex digits each) | reads the characters, control characters too |
//! | `\X4\hhhhhhhh…\X0\` (beyond the BMP) | reads them (`\X2\` with surrogate pairs too) |
//! | `\X\hh` | reads the Latin-1 character |
//! | `\X2\0000\X0\` | drops the NUL |
//! | raw UTF-8 | reads it, but ISO 10303-21 allows only printable ASCII |
//! | a string literal of 16 382 bytes or more | refuses the file ("input buffer overflow": flex's 16 KiB buffer) |
//!
//! So [`step_string`] writes printable ASCII as itself except `'` and `\`;
//! `\` as `\\`; every other character, the quote included, in
//! `\X2\…\X0\` runs (4 hex digits a character) or `\X4\…\X0\` runs for
//! characters beyond the BMP (8 digits). No `'` ever stands inside the
//! literal, so no reader's idea of where a string ends can go wrong; NUL,
//! which no C reader can hold, is left out.
//!
//! **IGES** strings are Hollerith, `nH` and `n` characters, counted, so `,`
//! `;` `'` `(` `)` `\` need no escape (OpenCascade reads them back). IGES is
//! ASCII and has no escape for anything else: [`iges_string`]
//! transliterates the Latin letters of Latin-1 and Latin Extended-A to ASCII
//! (`Ü` → `U`, `ß` → `ss`, `Ł` → `L`), writes whitespace as a space and
//! anything else as `?` (the STEP file keeps the whole name). The empty
//! string is written as an empty (defaulted) parameter: OpenCascade reads
//! `0H` back as the text `0H`.
//!
//! **Length.** Both take at most [`MAX_CHARS`] characters of a name: 1000
//! characters is far more than any label shows, and at most 16 bytes a
//! character (a lone `\X4\…\X0\`) keeps the STEP literal under
//! OpenCascade's 16 382 bytes whatever the characters.

use std::fmt::Write as _;

/// The most characters of a name written into a CAD file (see the module
/// documentation); the rest is left out.
pub const MAX_CHARS: usize = 1000;

/// The first [`MAX_CHARS`] characters of `text`.
pub fn capped(text: &str) -> &str {
    match text.char_indices().nth(MAX_CHARS) {
        Some((end, _)) => &text[..end],
        None => text,
    }
}

/// `text` (capped) as an ISO 10303-21 string literal, quotes included:
/// printable ASCII but `'` and `\` as itself, `\` as `\\`, everything else
/// in `\X2\…\X0\` (BMP) or `\X4\…\X0\` runs; NUL left out.
pub fn step_string(text: &str) -> String {
    let mut out = String::with_capacity(text.len() + 2);
    out.push('\'');
    // the open run's directive: 0 none, 2 `\X2\`, 4 `\X4\`
    let mut run = 0u8;
    for c in capped(text).chars() {
        if c == '\0' {
            continue;
        }
        if (' '..='~').contains(&c) && c != '\'' {
            if run != 0 {
                out.push_str("\\X0\\");
                run = 0;
            }
            if c == '\\' {
                out.push_str("\\\\");
            } else {
                out.push(c);
            }
            continue;
        }
        let code = u32::from(c);
        let want = if code > 0xFFFF { 4 } else { 2 };
        if run != want {
            if run != 0 {
                out.push_str("\\X0\\");
            }
            let _ = write!(out, "\\X{want}\\");
            run = want;
        }
        let _ = if want == 2 {
            write!(out, "{code:04X}")
        } else {
            write!(out, "{code:08X}")
        };
    }
    if run != 0 {
        out.push_str("\\X0\\");
    }
    out.push('\'');
    out
}

/// `text` (capped) as an IGES Hollerith string `nH…` of ASCII (Latin
/// letters transliterated, whitespace a space, anything else `?`); the
/// empty string as an empty parameter.
pub fn iges_string(text: &str) -> String {
    let mut ascii = String::with_capacity(text.len());
    for c in capped(text).chars() {
        match c {
            ' '..='~' => ascii.push(c),
            c if c.is_whitespace() => ascii.push(' '),
            c => ascii.push_str(ascii_letter(c).unwrap_or("?")),
        }
    }
    if ascii.is_empty() {
        ascii
    } else {
        format!("{}H{ascii}", ascii.len())
    }
}

/// One ASCII letter a character of U+00C0..=U+017F (Latin-1's letters and
/// Latin Extended-A) stands for, from its canonical decomposition or, for
/// letters without one (`Ø`, `Ł`, `Đ`, `ı`), its base letter; `×` is `x`
/// and `÷` `/`. The ligatures and letters written with two (`Æ`, `ß`, `Þ`,
/// `Œ`, `Ĳ`) are in [`ascii_letter`].
const LATIN: &str = concat!(
    "AAAAAA?CEEEEIIIIDNOOOOOxOUUUUY??aaaaaa?ceeeeiiiidnooooo/ouuuuy?y",
    "AaAaAaCcCcCcCcDdDdEeEeEeEeEeGgGgGgGgHhHhIiIiIiIiIi??JjKkkLlLlLlL",
    "lLlNnNnNnnNnOoOoOo??RrRrRrSsSsSsSsTtTtTtUuUuUuUuUuUuWwYyYZzZzZzs",
);

/// The ASCII a Latin letter is written with in IGES, if it is one.
fn ascii_letter(c: char) -> Option<&'static str> {
    Some(match c {
        'Æ' => "AE",
        'æ' => "ae",
        'Þ' => "TH",
        'þ' => "th",
        'ß' => "ss",
        'Ĳ' => "IJ",
        'ĳ' => "ij",
        'Œ' => "OE",
        'œ' => "oe",
        '\u{C0}'..='\u{17F}' => {
            let i = (u32::from(c) - 0xC0) as usize;
            LATIN.get(i..=i)?
        }
        _ => return None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An ISO 10303-21 string literal read back: `''`, `\\`, `\X2\` and
    /// `\X4\` runs (what [`step_string`] writes, and nothing else).
    fn decode(lit: &str) -> Option<String> {
        let body = lit.strip_prefix('\'')?.strip_suffix('\'')?;
        let (mut out, mut rest) = (String::new(), body);
        while let Some(c) = rest.chars().next() {
            if let Some(r) = rest.strip_prefix("''") {
                out.push('\'');
                rest = r;
            } else if let Some(r) = rest.strip_prefix("\\\\") {
                out.push('\\');
                rest = r;
            } else if let Some((digits, r)) = [("\\X2\\", 4), ("\\X4\\", 8)]
                .iter()
                .find_map(|&(d, n)| rest.strip_prefix(d).map(|r| (n, r)))
            {
                let (hex, r) = r.split_once("\\X0\\")?;
                if hex.is_empty() || hex.len() % digits != 0 {
                    return None;
                }
                for k in (0..hex.len()).step_by(digits) {
                    out.push(char::from_u32(
                        u32::from_str_radix(&hex[k..k + digits], 16).ok()?,
                    )?);
                }
                rest = r;
            } else if c == '\'' || c == '\\' || !(' '..='~').contains(&c) {
                return None;
            } else {
                out.push(c);
                rest = &rest[1..];
            }
        }
        Some(out)
    }

    #[test]
    fn step_strings_are_exact() {
        for (name, want) in [
            ("car1", "'car1'"),
            ("", "''"),
            ("a');b", "'a\\X2\\0027\\X0\\);b'"),
            ("'", "'\\X2\\0027\\X0\\'"),
            ("''", "'\\X2\\00270027\\X0\\'"),
            ("\\", "'\\\\'"),
            ("a\\b", "'a\\\\b'"),
            (";()#,\"", "';()#,\"'"),
            (
                "Ünïcødé 車",
                "'\\X2\\00DC\\X0\\n\\X2\\00EF\\X0\\c\\X2\\00F8\\X0\\d\\X2\\00E9\\X0\\ \\X2\\8ECA\\X0\\'",
            ),
            ("emoji 🚗", "'emoji \\X4\\0001F697\\X0\\'"),
            ("é🚗", "'\\X2\\00E9\\X0\\\\X4\\0001F697\\X0\\'"),
            ("a\nb\0c", "'a\\X2\\000A\\X0\\bc'"),
            ("\\X2\\0041\\X0\\", "'\\\\X2\\\\0041\\\\X0\\\\'"),
        ] {
            assert_eq!(step_string(name), want, "{name:?}");
        }
    }

    #[test]
    fn step_strings_read_back_and_hold_no_quote_and_only_ascii() {
        let names = [
            "a');b",
            "'",
            "''",
            "\\",
            "a\\b",
            ";",
            "(",
            ")",
            "Ünïcødé 車",
            "emoji 🚗",
            "🚗🚗a🚗é",
            "\\é\\",
            "x'\" ,)",
            "\\X0\\ \\S\\A \\N\\",
            "\u{7F}\u{85}\u{FFFF}\u{10FFFF}",
        ];
        for name in names {
            let lit = step_string(name);
            assert!(lit.is_ascii(), "{lit}");
            assert!(!lit[1..lit.len() - 1].contains('\''), "{lit}");
            assert_eq!(decode(&lit).as_deref(), Some(name), "{lit}");
        }
    }

    #[test]
    fn long_names_are_capped_within_opencascades_buffer() {
        let long: String = "x".repeat(1500);
        assert_eq!(decode(&step_string(&long)).unwrap(), "x".repeat(MAX_CHARS));
        // the longest literal: every character alone in its own \X4\ run
        let worst: String = "🚗é".repeat(MAX_CHARS);
        let lit = step_string(&worst);
        assert!(lit.len() < 16_382, "{}", lit.len());
        assert_eq!(decode(&lit).unwrap(), "🚗é".repeat(MAX_CHARS / 2));
        assert_eq!(capped("ab"), "ab");
        assert_eq!(capped(&"é".repeat(2000)).chars().count(), MAX_CHARS);
    }

    #[test]
    fn iges_strings_are_counted_ascii() {
        for (name, want) in [
            ("car1", "4Hcar1"),
            ("", ""),
            ("a');b", "5Ha');b"),
            ("a,b;c\\", "6Ha,b;c\\"),
            ("Ünïcødé 車", "9HUnicode ?"),
            ("emoji 🚗", "7Hemoji ?"),
            ("Straße Łódź Œuvre", "19HStrasse Lodz OEuvre"),
            ("tab\there\n", "9Htab here "),
            ("\0", "1H?"),
        ] {
            assert_eq!(iges_string(name), want, "{name:?}");
        }
        assert_eq!(iges_string(&"y".repeat(1500)).len(), 5 + MAX_CHARS);
    }

    #[test]
    fn the_latin_table_is_ascii_letters_in_place() {
        assert_eq!(LATIN.len(), 0x180 - 0xC0);
        assert!(LATIN.is_ascii());
        for (c, want) in [
            ('À', "A"),
            ('ÿ', "y"),
            ('Ā', "A"),
            ('ſ', "s"),
            ('ž', "z"),
            ('ı', "i"),
        ] {
            assert_eq!(ascii_letter(c), Some(want), "{c}");
        }
        assert_eq!(ascii_letter('車'), None);
    }

    proptest::proptest! {
        #[test]
        fn any_text_reads_back(text in "\\PC{0,40}|.{0,1200}") {
            let lit = step_string(&text);
            proptest::prop_assert!(lit.is_ascii() && lit.len() < 16_382);
            proptest::prop_assert!(!lit[1..lit.len() - 1].contains('\''));
            let kept: String = capped(&text).chars().filter(|&c| c != '\0').collect();
            proptest::prop_assert_eq!(decode(&lit), Some(kept));
            let h = iges_string(&text);
            proptest::prop_assert!(h.is_ascii());
            if let Some((n, body)) = h.split_once('H') {
                proptest::prop_assert_eq!(n.parse::<usize>().ok(), Some(body.len()));
            } else {
                proptest::prop_assert!(h.is_empty() && text.is_empty());
            }
        }
    }
}
