//! STEP (ISO 10303-21) with AP214's schema (`AUTOMOTIVE_DESIGN`): what
//! every file we write holds around its faces (docs/math.md §10) — a product
//! with its definition and shape, the length unit (metres), plane and solid
//! angle units, the distance uncertainty — and the entities the faces are
//! made of: poles, B-spline curves and surfaces. The faces, their edges and
//! their shell are written by [`super::step_shell`], one face per patch (a
//! design of one patch is a shell of one face).
//!
//! The entity graph is the one OpenCascade writes for B-spline faces
//! (product → product definition → shape → manifold surface shape
//! representation → shell based surface model → open shell → faces), less
//! what a reader does not need.

use super::cad_text::step_string as string;
use super::numbers::real;
use std::fmt::Write as _;
use streamline_kernel::DVec3;
use streamline_kernel::nurbs::BSplineSurface;
use streamline_kernel::nurbs::curve::Curve;

/// What goes into the file besides the surface.
#[derive(Debug, Clone)]
pub struct StepInfo<'a> {
    /// The product's name (the scene's).
    pub name: &'a str,
    /// The file name written in the header.
    pub file_name: &'a str,
    /// The distance uncertainty (metres).
    pub uncertainty: f64,
    /// ISO 8601 time stamp for the header.
    pub timestamp: &'a str,
}

pub(super) struct Writer {
    pub(super) text: String,
    pub(super) next: usize,
}

impl Writer {
    pub(super) fn add(&mut self, entity: impl AsRef<str>) -> usize {
        let id = self.next;
        self.next += 1;
        let _ = writeln!(self.text, "#{id}={};", entity.as_ref());
        id
    }
}

fn list<T>(items: impl IntoIterator<Item = T>, f: impl Fn(T) -> String) -> String {
    let v: Vec<String> = items.into_iter().map(f).collect();
    format!("({})", v.join(","))
}

pub(super) fn refs(ids: &[usize]) -> String {
    list(ids.iter(), |i| format!("#{i}"))
}

/// Distinct knots and their multiplicities.
fn knots_and_multiplicities(k: &[f64]) -> (Vec<usize>, Vec<f64>) {
    let (mut mult, mut vals) = (Vec::new(), Vec::<f64>::new());
    for &x in k {
        if vals.last() == Some(&x) {
            *mult.last_mut().expect("one per value") += 1;
        } else {
            vals.push(x);
            mult.push(1);
        }
    }
    (mult, vals)
}

pub(super) fn point(w: &mut Writer, p: DVec3) -> usize {
    w.add(format!(
        "CARTESIAN_POINT('',({},{},{}))",
        real(p.x),
        real(p.y),
        real(p.z)
    ))
}

/// A `B_SPLINE_CURVE_WITH_KNOTS` with its poles; returns its id.
pub(super) fn curve(w: &mut Writer, c: &Curve) -> usize {
    let ids: Vec<usize> = c.poles.iter().map(|&p| point(w, p)).collect();
    let (mult, vals) = knots_and_multiplicities(&c.knots);
    w.add(format!(
        "B_SPLINE_CURVE_WITH_KNOTS('',{},{},.UNSPECIFIED.,.F.,.F.,{},{},.UNSPECIFIED.)",
        c.degree,
        refs(&ids),
        list(mult, |m| m.to_string()),
        list(vals, real),
    ))
}

/// The ids every file's shape hangs from: the product's shape, the
/// geometric context (units, uncertainty), and the quoted name.
pub(super) struct Frame {
    /// The name, as a STEP string.
    pub(super) name: String,
    /// `PRODUCT_DEFINITION_SHAPE`.
    pub(super) shape: usize,
    /// The geometric representation context (metres, radians, uncertainty).
    pub(super) ctx: usize,
}

/// The product, its definition and shape, the units and the uncertainty:
/// what comes before the geometry in every file we write (AP214).
pub(super) fn frame(w: &mut Writer, info: &StepInfo) -> Frame {
    let name = string(info.name);
    let app = w.add("APPLICATION_CONTEXT('core data for automotive mechanical design processes')");
    w.add(format!(
        "APPLICATION_PROTOCOL_DEFINITION('international standard','automotive_design',2000,#{app})"
    ));
    let pctx = w.add(format!("PRODUCT_CONTEXT('',#{app},'mechanical')"));
    let product = w.add(format!("PRODUCT({name},{name},'',(#{pctx}))"));
    w.add(format!(
        "PRODUCT_RELATED_PRODUCT_CATEGORY('part',$,(#{product}))"
    ));
    let formation = w.add(format!("PRODUCT_DEFINITION_FORMATION('','',#{product})"));
    let dctx = w.add(format!(
        "PRODUCT_DEFINITION_CONTEXT('part definition',#{app},'design')"
    ));
    let def = w.add(format!(
        "PRODUCT_DEFINITION('design','',#{formation},#{dctx})"
    ));
    let shape = w.add(format!("PRODUCT_DEFINITION_SHAPE('','',#{def})"));
    let metre = w.add("(LENGTH_UNIT()NAMED_UNIT(*)SI_UNIT($,.METRE.))");
    let radian = w.add("(NAMED_UNIT(*)PLANE_ANGLE_UNIT()SI_UNIT($,.RADIAN.))");
    let steradian = w.add("(NAMED_UNIT(*)SI_UNIT($,.STERADIAN.)SOLID_ANGLE_UNIT())");
    let unc = w.add(format!(
        "UNCERTAINTY_MEASURE_WITH_UNIT(LENGTH_MEASURE({}),#{metre},'distance_accuracy_value','confusion accuracy')",
        real(info.uncertainty)
    ));
    let ctx = w.add(format!(
        "(GEOMETRIC_REPRESENTATION_CONTEXT(3)GLOBAL_UNCERTAINTY_ASSIGNED_CONTEXT((#{unc}))GLOBAL_UNIT_ASSIGNED_CONTEXT((#{metre},#{radian},#{steradian}))REPRESENTATION_CONTEXT('Context #1','3D Context with UNIT and UNCERTAINTY'))"
    ));
    Frame { name, shape, ctx }
}

/// The shape's representation around `model` (a `SHELL_BASED_SURFACE_MODEL`),
/// then the file: header (`what` describes the contents), data, end.
pub(super) fn finish(
    mut w: Writer,
    model: usize,
    frame: Frame,
    info: &StepInfo,
    what: &str,
) -> String {
    let Frame { name, shape, ctx } = frame;
    let origin = point(&mut w, DVec3::ZERO);
    let z = w.add("DIRECTION('',(0.,0.,1.))");
    let x = w.add("DIRECTION('',(1.,0.,0.))");
    let axes = w.add(format!("AXIS2_PLACEMENT_3D('',#{origin},#{z},#{x})"));
    let rep = w.add(format!(
        "MANIFOLD_SURFACE_SHAPE_REPRESENTATION({name},(#{axes},#{model}),#{ctx})"
    ));
    w.add(format!("SHAPE_DEFINITION_REPRESENTATION(#{shape},#{rep})"));
    format!(
        "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION(('Streamline Studio surface: {what}'),'2;1');\nFILE_NAME({},{},(''),(''),'Streamline Studio {}','Streamline Studio','');\nFILE_SCHEMA(('AUTOMOTIVE_DESIGN {{ 1 0 10303 214 1 1 1 1 }}'));\nENDSEC;\nDATA;\n{}ENDSEC;\nEND-ISO-10303-21;\n",
        string(info.file_name),
        string(info.timestamp),
        env!("CARGO_PKG_VERSION"),
        w.text
    )
}

/// The surface itself: its poles column by column (`u`), then the
/// `B_SPLINE_SURFACE_WITH_KNOTS` entity; returns its id.
pub(super) fn surface_entity(w: &mut Writer, surface: &BSplineSurface) -> usize {
    let (nu, nv) = surface.pole_counts();
    let (p, q) = surface.degree();
    let mut columns = Vec::with_capacity(nu);
    for i in 0..nu {
        let col: Vec<usize> = (0..nv).map(|j| point(w, surface.poles.get(j, i))).collect();
        columns.push(refs(&col));
    }
    let (mu, ku) = knots_and_multiplicities(surface.knots_u.knots());
    let (mv, kv) = knots_and_multiplicities(surface.knots_v.knots());
    w.add(format!(
        "B_SPLINE_SURFACE_WITH_KNOTS('',{p},{q},({}),.UNSPECIFIED.,.F.,.F.,.F.,{},{},{},{},.UNSPECIFIED.)",
        columns.join(","),
        list(mu, |m| m.to_string()),
        list(mv, |m| m.to_string()),
        list(ku, real),
        list(kv, real),
    ))
}

/// A check of what was written: ASCII, the envelope, `faces` faces, each
/// on its own B-spline surface, and every `#n` referenced is defined (all
/// outside string literals, which may hold anything a name does but a `'`:
/// cad_text.rs).
pub fn verify(bytes: &[u8], faces: usize) -> Result<(), String> {
    if !bytes.is_ascii() {
        return Err("not ASCII".into());
    }
    let text = std::str::from_utf8(bytes).map_err(|_| "not ASCII".to_string())?;
    if !(text.starts_with("ISO-10303-21;") && text.trim_end().ends_with("END-ISO-10303-21;")) {
        return Err("no ISO-10303-21 envelope".into());
    }
    let code: String = text.split('\'').step_by(2).collect();
    let count = |what: &str| code.matches(what).count();
    if count("ADVANCED_FACE(") != faces || count("B_SPLINE_SURFACE_WITH_KNOTS(") != faces {
        return Err(format!(
            "not exactly {faces} face(s), each on one B-spline surface"
        ));
    }
    let defined = code.lines().filter(|l| l.starts_with('#')).count();
    for l in code.lines().filter(|l| l.starts_with('#')) {
        for r in l.split('#').skip(2) {
            let n: usize = r
                .chars()
                .take_while(char::is_ascii_digit)
                .collect::<String>()
                .parse()
                .map_err(|_| format!("a bad reference in {l}"))?;
            if n == 0 || n > defined {
                return Err(format!("#{n} is referenced but not defined"));
            }
        }
    }
    Ok(())
}
