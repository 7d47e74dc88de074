//! docs/math.md §11.5, "A start that moves": hood-screen-wing with every
//! patch on Catmull–Clark and on Doo–Sabin exports as one STEP shell and as
//! IGES faces. The screen is the hood's G2 chain (one net); the wing starts
//! on the hood's first streamline, which moves between depths, and is
//! measured from where it starts. OpenCascade reads one valid shell (and
//! three IGES faces, the shell's), every face within its tolerance of the
//! points it was fitted to, the G2 seam's normals within 0.1°. The
//! negative control: the wing measured as it lies, at the depth the export
//! sampled, is refused.

mod common;

use common::documents::{shipped, tmpdir};
use common::shell_read::{point_file, seam_angle, shell_as_it_lies, valid_within};
use streamline_kernel::SurfaceScheme;
use streamline_studio::scene::design::document_io::load;
use streamline_studio::scene::export::document::{DocumentExportSettings, export_document};

#[test]
fn hood_screen_wing_on_the_approximating_schemes_exports_its_wing_from_where_it_starts() {
    let dir = tmpdir("approximating");
    let settings = DocumentExportSettings::default();
    let (mut manifest, mut outs) = (Vec::new(), Vec::new());
    for (name, scheme) in [
        ("catmull-clark", SurfaceScheme::CatmullClark),
        ("doo-sabin", SurfaceScheme::DooSabin),
    ] {
        let mut doc = load(&shipped("hood-screen-wing")).unwrap();
        for p in &mut doc.patches {
            p.design.set_scheme(scheme).unwrap();
        }
        let built = doc.build(doc.display_depth).unwrap();
        for ext in ["step", "igs"] {
            let tag = format!("{name}.{ext}");
            let path = dir.join(&tag);
            let out = export_document(&doc, &built, &path, &settings)
                .unwrap_or_else(|e| panic!("{tag}: {e}"));
            let fit = out.fit.as_ref().unwrap();
            eprintln!(
                "{tag}: sampled at depth {}, poles {:?}, deviations {:?} within {:?}, {:.1} s",
                out.depth,
                (out.faces.iter())
                    .map(|f| f.surface.pole_counts())
                    .collect::<Vec<_>>(),
                (out.faces.iter())
                    .map(|f| format!("{:.2e}", f.deviation.max))
                    .collect::<Vec<_>>(),
                (out.faces.iter())
                    .map(|f| format!("{:.2e}", f.tolerance))
                    .collect::<Vec<_>>(),
                fit.seconds
            );
            // the points fitted (the check grid one depth finer is the
            // shell's to measure: a G2 chain's later patch's starts a strip
            // on the earlier face, docs/math.md §11.5)
            let files: Vec<String> = (fit.grids.iter().enumerate())
                .map(|(i, g)| point_file(&dir, &format!("{name}-{ext}"), i, g.data.points.data()))
                .collect();
            manifest.push(serde_json::json!({
                "file": path.display().to_string(),
                "points": files,
                "tolerance": out.faces.iter().map(|f| f.tolerance).fold(f64::INFINITY, f64::min),
                "samples": 40,
            }));
            outs.push((tag.clone(), out.faces.clone()));
            if ext == "step" {
                // the negative control: the wing as it lies is refused
                let e = shell_as_it_lies(&doc, out.depth)
                    .map(|_| ())
                    .expect_err("the wing as it lies was fitted");
                eprintln!("{tag}, the wing as it lies: {e}");
                assert!(e.to_string().contains("\"wing\""), "{tag}: {e}");
            }
        }
    }
    let results = common::opencascade_manifest("check_shell.py", &dir, &manifest);
    for ((tag, faces), r) in outs.iter().zip(&results) {
        eprintln!("{tag}: {r}");
        valid_within(tag, faces, r);
        if tag.contains(".step") {
            assert_eq!(r["shells"], 1, "{tag}: {r}");
            assert_eq!(r["shared_edges"], 2, "{tag}: {r}");
            assert!(seam_angle(r, [0, 1]) < 0.1, "{tag}: {r}");
            assert!(seam_angle(r, [0, 2]) < 90.0, "{tag}: {r}");
        } else {
            assert_eq!(r["shared_edges"], 0, "{tag}: {r}");
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}
