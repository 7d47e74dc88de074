//! Mesh mode (paper 002): open a triangle mesh (OBJ), see it as a wireframe
//! with its vertices, and the Loop surface that interpolates every vertex
//! (progressive interpolation, plain or fast) at a chosen subdivision depth,
//! with the iteration count and errors; export the surface or its control
//! mesh. While a mesh is open the editor is in [`EditorMode::Mesh`]: the
//! streamline surface is hidden on entering it and shown again on leaving,
//! and its handles step aside. The geometry comes from the kernel (`trimesh`, `loop_subdiv`,
//! `interpolate`); this plugin only shows it (its entities: `draw`).

use super::interaction::EditorMode;
use crate::scene::job::{Job, Poll, Progress};
use crate::scene::loop_mesh::obj;
use bevy::prelude::*;
use bevy_state::prelude::{OnEnter, OnExit};
use std::path::PathBuf;
use std::sync::Arc;
use std::time::Instant;
use streamline_kernel::DVec3;
use streamline_kernel::loop_subdiv::mesh_interpolation::{
    Method, Options, Report, interpolate_observed,
};
use streamline_kernel::loop_subdiv::subdivide::{BoundaryRule, subdivide};
use streamline_kernel::loop_subdiv::trimesh::{Topology, TriMesh};

mod draw;

/// The deepest subdivision shown (each level multiplies the faces by 4).
pub const MAX_DEPTH: u32 = 4;
/// Surfaces are not subdivided past this many faces.
const MAX_SHOWN_FACES: usize = 4_000_000;

/// A mesh with its topology, shared with the worker threads.
pub type Given = Arc<(TriMesh, Topology)>;

/// What a mesh job hands back: the mesh (when it opened one) and the
/// interpolation and subdivision of it.
pub struct Computed {
    /// The file and mesh opened, when the job opened one.
    pub opened: Option<(PathBuf, Given)>,
    /// The interpolating control mesh's positions.
    pub control: Vec<DVec3>,
    /// The subdivided control mesh.
    pub surface: TriMesh,
    /// What the interpolation did.
    pub report: Report,
    /// Seconds it took.
    pub seconds: f64,
}

/// Mesh mode's state, by what it holds: the mesh open and what was computed
/// from it, the settings of its interpolation, the work off the frame, and
/// the panel's text.
#[derive(Resource, Default)]
pub struct MeshView {
    /// The mesh open and its interpolation.
    pub doc: MeshDocument,
    /// How it is interpolated and shown.
    pub settings: MeshSettings,
    /// The job running off the frame and what the next frame must do.
    pub work: MeshWork,
    /// The path typed and the last failure.
    pub text: MeshText,
}

/// The mesh open and what was computed from it.
#[derive(Default)]
pub struct MeshDocument {
    /// The file opened.
    pub path: Option<PathBuf>,
    /// The given mesh and its topology.
    pub given: Option<Given>,
    /// The interpolating control mesh's positions (same faces as the given mesh).
    pub control: Vec<DVec3>,
    /// The subdivided control mesh shown.
    pub surface: Option<TriMesh>,
    /// What the interpolation did.
    pub report: Option<Report>,
    /// Seconds it took.
    pub seconds: f64,
}

/// How the mesh is interpolated and shown.
pub struct MeshSettings {
    /// Plain or fast.
    pub method: Method,
    /// The boundary rules of the Loop surface.
    pub boundary: BoundaryRule,
    /// Stop at this error (bounding box's largest side = 1).
    pub tolerance: f64,
    /// Subdivision depth shown.
    pub depth: u32,
    /// Show the given mesh's wireframe and vertices.
    pub show_given: bool,
}

impl Default for MeshSettings {
    fn default() -> Self {
        MeshSettings {
            method: Method::Fast,
            boundary: BoundaryRule::EdgeAndCorner,
            tolerance: 1e-3,
            depth: 3,
            show_given: true,
        }
    }
}

impl MeshSettings {
    fn options(&self) -> Options {
        Options {
            tolerance: self.tolerance,
            max_iterations: 10_000,
            method: self.method,
            boundary: self.boundary,
        }
    }
}

/// The work off the frame, and what the next frame must do.
#[derive(Default)]
pub struct MeshWork {
    /// The reading or interpolation running off the frame, if any.
    pub job: Option<Job<Result<Computed, String>>>,
    /// Interpolate and rebuild the view in the next frame.
    pub dirty: bool,
    /// Frame the camera on the mesh in the next frame.
    pub frame: bool,
}

impl MeshWork {
    /// Stops the running job (its result is dropped).
    pub fn cancel(&mut self) {
        if let Some(j) = self.job.take() {
            j.cancel();
        }
    }
}

/// The panel's text.
pub struct MeshText {
    /// The path typed in the panel.
    pub input: String,
    /// The last failure (open or export), shown in the panel.
    pub error: Option<String>,
}

impl Default for MeshText {
    fn default() -> Self {
        MeshText {
            input: "tests/data/meshes/snail.obj".into(),
            error: None,
        }
    }
}

impl MeshView {
    /// Whether a mesh is open (the streamline surface steps aside).
    pub fn active(&self) -> bool {
        self.doc.given.is_some()
    }

    /// Whether a job is running.
    pub fn busy(&self) -> bool {
        self.work.job.is_some()
    }

    /// Opens an OBJ file off the frame: read, checked, interpolated and
    /// subdivided on a worker thread; on failure or cancel the current state
    /// stays and the error is kept.
    pub fn open(&mut self, path: PathBuf) {
        self.cancel();
        let (opts, depth) = (self.settings.options(), self.settings.depth);
        let label = format!("opening {}", path.display());
        self.work.job = Some(Job::spawn(&label, move |p| {
            let given: Given = Arc::new(
                obj::read_with(&path, p).map_err(|e| format!("{e} (nothing was opened)"))?,
            );
            let mut c = compute(&given, &opts, depth, p)?;
            c.opened = Some((path, given));
            Ok(c)
        }));
    }

    /// Stops the running job (its result is dropped).
    pub fn cancel(&mut self) {
        self.work.cancel();
    }

    /// Leaves mesh mode.
    pub fn close(&mut self) {
        self.cancel();
        self.doc.given = None;
        self.doc.surface = None;
        self.doc.report = None;
        self.doc.control.clear();
        self.work.dirty = true;
    }

    /// Writes the control mesh as USD text (`.usda`, with the boundary rule it
    /// was interpolated for; refused for 002's rule, which USD cannot say).
    pub fn export_usd(&mut self, to: PathBuf) {
        let result = match &self.doc.given {
            Some(g) => crate::scene::loop_mesh::usd::write(
                &to,
                &self.doc.control,
                &g.0.faces,
                self.settings.boundary,
                "control mesh of an interpolating Loop surface",
            ),
            None => {
                self.text.error = Some("nothing to export: open a mesh first".into());
                return;
            }
        };
        self.text.error = result.err().map(|e| e.to_string());
    }

    /// Writes the shown surface (`control == false`) or the control mesh as OBJ.
    pub fn export(&mut self, to: PathBuf, control: bool) {
        let doc = &self.doc;
        let result = match (&doc.given, &doc.surface) {
            (Some(g), _) if control => obj::write(
                &to,
                &doc.control,
                &g.0.faces,
                "control mesh of an interpolating Loop surface",
            ),
            (_, Some(s)) => obj::write(&to, &s.positions, &s.faces, "Loop surface"),
            _ => {
                self.text.error = Some("nothing to export: open a mesh first".into());
                return;
            }
        };
        self.text.error = result.err().map(|e| e.to_string());
    }
}

/// Interpolates `given` and subdivides the control mesh `depth` times,
/// reporting to `p` and stopping when it is cancelled.
fn compute(given: &Given, opts: &Options, depth: u32, p: &Progress) -> Result<Computed, String> {
    let (mesh, topo) = (&given.0, &given.1);
    let cancelled = || Err("cancelled; the mesh shown is unchanged".to_string());
    p.stage("interpolating", opts.max_iterations as u64);
    let t0 = Instant::now();
    let (control, report) = interpolate_observed(mesh, topo, opts, &|k| {
        p.set(k as u64);
        !p.cancelled()
    });
    if p.cancelled() {
        return cancelled();
    }
    let seconds = t0.elapsed().as_secs_f64();
    p.stage("subdividing", u64::from(depth));
    let mut s = TriMesh {
        positions: control.clone(),
        faces: mesh.faces.clone(),
    };
    for level in 0..depth {
        if s.faces.len() * 4 > MAX_SHOWN_FACES {
            break;
        }
        let Ok(t) = s.topology() else { break };
        match subdivide(&s, &t, opts.boundary) {
            Ok(next) => s = next,
            Err(_) => break,
        }
        p.set(u64::from(level) + 1);
        if p.cancelled() {
            return cancelled();
        }
    }
    Ok(Computed {
        opened: None,
        control,
        surface: s,
        report,
        seconds,
    })
}

pub struct MeshModePlugin;

impl Plugin for MeshModePlugin {
    fn build(&self, app: &mut App) {
        app.init_resource::<MeshView>()
            .add_systems(Startup, draw::setup)
            .add_systems(Update, (recompute, draw::follow_mode, draw::show).chain())
            .add_systems(OnEnter(EditorMode::Mesh), draw::hide_streamline_surface)
            .add_systems(OnExit(EditorMode::Mesh), draw::show_streamline_surface);
    }
}

/// Starts a job when a setting changed, and takes a finished job's result.
fn recompute(meter: Res<crate::ecs::meter::CpuMeter>, mut view: ResMut<MeshView>) {
    let _meter = meter.start();
    if view.work.dirty {
        let view = &mut *view;
        view.work.dirty = false;
        if let Some(given) = view.doc.given.clone() {
            // a newer setting replaces a running interpolation
            view.work.cancel();
            let (opts, depth) = (view.settings.options(), view.settings.depth);
            view.work.job = Some(Job::spawn("interpolating", move |p| {
                compute(&given, &opts, depth, p)
            }));
        }
    }
    let Some(job) = &view.work.job else {
        return;
    };
    let result = match job.poll() {
        Poll::Running => return,
        Poll::Done(r) => r,
        Poll::Lost => Err("the worker stopped without a result (a bug; please report it)".into()),
    };
    let view = &mut *view;
    view.work.job = None;
    match result {
        Ok(c) => {
            let doc = &mut view.doc;
            if let Some((path, given)) = c.opened {
                doc.path = Some(path);
                doc.given = Some(given);
                view.work.frame = true;
            }
            view.text.error = None;
            doc.control = c.control;
            doc.report = Some(c.report);
            doc.seconds = c.seconds;
            doc.surface = Some(c.surface);
        }
        Err(e) => view.text.error = Some(e),
    }
}
