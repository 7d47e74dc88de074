//! IGES 5.3 with one entity 128 per patch (a design of one patch is one
//! entity), the rational B-spline surface, written polynomial (`PROP3 = 1`,
//! all weights 1) (docs/math.md §10). Fixed 80-column records: Start,
//! Global, Directory Entry, Parameter Data and Terminate sections; the
//! global section declares metres (units flag 6) and the model's resolution.

use super::cad_text::iges_string as hollerith;
use super::numbers::real;
use streamline_kernel::nurbs::BSplineSurface;

/// What goes into the global section besides the surface.
#[derive(Debug, Clone)]
pub struct IgesInfo<'a> {
    /// The product's name (the scene's).
    pub name: &'a str,
    /// The file name.
    pub file_name: &'a str,
    /// The minimum resolution (metres).
    pub resolution: f64,
    /// `YYYYMMDD.HHNNSS`.
    pub timestamp: &'a str,
}

/// Lays `params` (already delimited, ending in `;`) into records of
/// `width` columns of data, then the section letter and sequence number;
/// `de` is the directory entry pointer written into columns 66–72 of
/// parameter records. Parameters are never split across records.
fn records(
    params: &[String],
    width: usize,
    letter: char,
    de: Option<usize>,
    out: &mut Vec<String>,
) -> usize {
    let mut line = String::new();
    let mut count = 0;
    let mut flush = |line: &mut String, out: &mut Vec<String>| {
        count += 1;
        let seq = out
            .iter()
            .filter(|l: &&String| l.as_bytes()[72] == letter as u8)
            .count()
            + 1;
        let body = match de {
            Some(d) => format!("{:<64}{:>8}", line, d),
            None => format!("{line:<72}"),
        };
        out.push(format!("{body}{letter}{seq:>7}"));
        line.clear();
    };
    for p in params {
        if !line.is_empty() && line.len() + p.len() > width {
            flush(&mut line, out);
        }
        // a single parameter longer than a record is split (only long strings)
        let mut rest = p.as_str();
        while rest.len() > width {
            let (a, b) = rest.split_at(width - line.len());
            line.push_str(a);
            flush(&mut line, out);
            rest = b;
        }
        line.push_str(rest);
    }
    if !line.is_empty() {
        flush(&mut line, out);
    }
    count
}

/// The parameter data of one entity 128.
fn surface_params(surface: &BSplineSurface) -> Vec<String> {
    let (nu, nv) = surface.pole_counts();
    let (p, q) = surface.degree();
    let mut pd: Vec<String> = [128, nu - 1, nv - 1, p, q, 0, 0, 1, 0, 0]
        .iter()
        .map(|v| v.to_string())
        .collect();
    pd.extend(surface.knots_u.knots().iter().map(|&k| real(k)));
    pd.extend(surface.knots_v.knots().iter().map(|&k| real(k)));
    pd.extend(std::iter::repeat_n("1.".to_string(), nu * nv));
    for j in 0..nv {
        for i in 0..nu {
            let c = surface.poles.get(j, i);
            pd.extend([c.x, c.y, c.z].map(real));
        }
    }
    pd.extend(["0.", "1.", "0.", "1."].map(String::from));
    let n = pd.len();
    pd.into_iter()
        .enumerate()
        .map(|(i, s)| format!("{s}{}", if i + 1 == n { ";" } else { "," }))
        .collect()
}

/// The whole file of several surfaces: one entity 128 each, in order
/// (directory entries `1, 3, 5, …`; docs/cad.md, "Several patches").
pub fn iges_faces_text(surfaces: &[&BSplineSurface], info: &IgesInfo) -> String {
    let mut out: Vec<String> = Vec::new();
    // start section
    let what = if surfaces.len() == 1 {
        "one B-spline surface (entity 128)".to_string()
    } else {
        format!("{} B-spline surfaces (entity 128)", surfaces.len())
    };
    out.push(format!(
        "{:<72}S{:>7}",
        format!("Streamline Studio surface: {what}"),
        1
    ));
    // global section
    let max_coord = surfaces
        .iter()
        .flat_map(|s| s.poles.data().iter())
        .map(|p| p.abs().max_element())
        .fold(0.0f64, f64::max);
    let g = [
        "1H,".to_string(),
        "1H;".to_string(),
        hollerith(info.name),
        hollerith(info.file_name),
        hollerith("Streamline Studio"),
        hollerith(env!("CARGO_PKG_VERSION")),
        "32".into(),
        "38".into(),
        "6".into(),
        "308".into(),
        "15".into(),
        hollerith(info.name),
        "1.".into(),
        "6".into(),
        "1HM".into(),
        "1".into(),
        "0.001".into(),
        hollerith(info.timestamp),
        real(info.resolution),
        real(max_coord),
        hollerith(""),
        hollerith(""),
        "11".into(),
        "0".into(),
        hollerith(info.timestamp),
    ];
    let g: Vec<String> = g
        .iter()
        .enumerate()
        .map(|(i, s)| format!("{s}{}", if i + 1 == g.len() { ";" } else { "," }))
        .collect();
    records(&g, 72, 'G', None, &mut out);
    // parameter data and directory entries (two records) of each entity
    let mut params = Vec::new();
    let mut entries = Vec::new();
    for (k, surface) in surfaces.iter().enumerate() {
        let de = 2 * k + 1;
        let first = params.len() + 1;
        let lines = records(&surface_params(surface), 64, 'P', Some(de), &mut params);
        let d1 = format!(
            "{:>8}{:>8}{:>8}{:>8}{:>8}{:>8}{:>8}{:>8}{:>8}",
            128, first, 0, 0, 0, 0, 0, 0, "00000000"
        );
        let d2 = format!(
            "{:>8}{:>8}{:>8}{:>8}{:>8}{:>8}{:>8}{:>8}{:>8}",
            128,
            0,
            0,
            lines,
            0,
            "",
            "",
            "BSPLSURF",
            if surfaces.len() == 1 { 0 } else { k + 1 }
        );
        entries.push(format!("{d1}D{:>7}", de));
        entries.push(format!("{d2}D{:>7}", de + 1));
    }
    out.extend(entries);
    out.extend(params);
    let count = |c: u8| out.iter().filter(|l| l.as_bytes()[72] == c).count();
    let t = format!(
        "S{:>7}G{:>7}D{:>7}P{:>7}",
        count(b'S'),
        count(b'G'),
        count(b'D'),
        count(b'P')
    );
    out.push(format!("{t:<72}T{:>7}", 1));
    let mut text = out.join("\n");
    text.push('\n');
    text
}

/// A check of what was written: every record 80 columns, the sections in
/// order, the terminate counts right, `faces` entities 128.
pub fn verify(bytes: &[u8], faces: usize) -> Result<(), String> {
    if !bytes.is_ascii() {
        return Err("not ASCII".into());
    }
    let text = std::str::from_utf8(bytes).map_err(|_| "not ASCII".to_string())?;
    let lines: Vec<&str> = text.lines().collect();
    if let Some(l) = lines.iter().find(|l| l.len() != 80) {
        return Err(format!("a record is {} columns, not 80", l.len()));
    }
    let letters: String = lines.iter().map(|l| l.as_bytes()[72] as char).collect();
    let mut order: Vec<char> = letters.chars().collect();
    order.dedup();
    let order: String = order.into_iter().collect();
    if order != "SGDPT" {
        return Err(format!("sections {order}, not SGDPT"));
    }
    let count = |c: char| letters.chars().filter(|x| *x == c).count();
    let last = lines.last().expect("T");
    let want = format!(
        "S{:>7}G{:>7}D{:>7}P{:>7}",
        count('S'),
        count('G'),
        count('D'),
        count('P')
    );
    if !last.starts_with(&want) {
        return Err("terminate section counts do not match".into());
    }
    let entities = lines
        .iter()
        .filter(|l| l.as_bytes()[72] == b'D')
        .step_by(2)
        .filter(|l| l.starts_with("     128"))
        .count();
    if count('D') != 2 * faces || entities != faces {
        return Err(format!("not {faces} entities 128"));
    }
    Ok(())
}
