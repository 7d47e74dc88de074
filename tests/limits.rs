//! Resource limits (docs/math.md §8, docs/reliability.md): what would need more
//! than the memory cap is refused with a message before it is allocated; a 1 GB
//! OBJ and a million-step script are read off the frame, with progress, and can
//! be cancelled. No test here asserts a speed: the time bounds only turn a hang
//! into a failure.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};
use streamline_studio::ecs::runner::{MAX_BATCH, RunState, ScriptRun, ScriptRunPlugin};
use streamline_studio::ecs::{self, Edit, headless_app};
use streamline_studio::scene::job::{Job, Poll};
use streamline_studio::scene::{design::builtin, loop_mesh::obj};

/// A long time: a job that has not finished by then is hung.
const HANG: Duration = Duration::from_secs(120);

fn tmp(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("streamline-limits-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d.join(name)
}

/// A 1 GiB OBJ: a grid of vertices, then its faces (never all read: the
/// memory cap stops the reader first).
fn one_gib_obj(path: &Path) {
    let f = std::fs::File::create(path).unwrap();
    let mut w = std::io::BufWriter::with_capacity(1 << 22, f);
    let target = 1u64 << 30;
    let mut written = 0u64;
    let side = 20_000u64;
    let mut i = 0u64;
    let mut block = String::with_capacity(1 << 20);
    while written < target {
        block.clear();
        for _ in 0..20_000 {
            let (x, y) = (i % side, i / side);
            block.push_str(&format!("v {x}.25 {y}.75 0.125\n"));
            i += 1;
        }
        w.write_all(block.as_bytes()).unwrap();
        written += block.len() as u64;
    }
    w.flush().unwrap();
}

#[test]
fn a_1gib_obj_is_read_off_the_frame_refused_at_the_cap_and_can_be_cancelled() {
    let path = tmp("huge.obj");
    one_gib_obj(&path);
    let len = std::fs::metadata(&path).unwrap().len();
    assert!(len >= 1 << 30);

    // read to the end of what the cap allows: progress moves, then a refusal
    let p = path.clone();
    let job = Job::spawn("open", move |pr| obj::read_with(&p, pr).map(|_| ()));
    let start = Instant::now();
    let mut seen = Vec::new();
    let result = loop {
        match job.poll() {
            Poll::Running => {
                let (done, total) = job.progress.counts();
                if seen.last() != Some(&done) {
                    seen.push(done);
                }
                assert!(total == 0 || total == len, "{total} bytes to read");
                assert!(start.elapsed() < HANG, "reading hangs");
                std::thread::sleep(Duration::from_millis(5));
            }
            Poll::Done(r) => break r,
            Poll::Lost => panic!("the reader died"),
        }
    };
    assert!(seen.len() >= 3, "progress was reported: {seen:?}");
    let e = result
        .expect_err("a 1 GiB mesh is over the cap")
        .to_string();
    assert!(
        e.starts_with(&format!("{}:", path.display()))
            && e.contains("over the memory cap of 2048 MB")
            && e.contains("simplify the mesh"),
        "{e}"
    );
    // refused before the end: the reader stopped early
    let (done, total) = job.progress.counts();
    assert!(done < total / 2, "stopped at {done} of {total} bytes");
    eprintln!(
        "1 GiB OBJ: refused after {} MB of {} MB in {:.2} s, {} progress reports seen: {e}",
        done >> 20,
        total >> 20,
        start.elapsed().as_secs_f64(),
        seen.len()
    );

    // cancelled part-way: the job ends soon with "cancelled"
    let p = path.clone();
    let job = Job::spawn("open", move |pr| obj::read_with(&p, pr).map(|_| ()));
    while job.progress.counts().0 == 0 {
        std::thread::sleep(Duration::from_millis(1));
    }
    job.cancel();
    let t = Instant::now();
    let r = job.wait().expect("a result");
    let e = r.expect_err("cancelled").to_string();
    assert!(e.contains("cancelled; nothing was opened"), "{e}");
    assert!(t.elapsed() < HANG);
    eprintln!(
        "1 GiB OBJ: cancelled, the job ended {:.1} ms later",
        t.elapsed().as_secs_f64() * 1e3
    );
    let _ = std::fs::remove_file(&path);
}

#[test]
fn a_million_step_script_runs_a_batch_a_frame_and_cancels() {
    let path = tmp("million.ron");
    let mut text = String::from("(steps: [\n");
    for i in 0..1_000_000 {
        text.push_str(match i % 4 {
            0 => "SetDirection(row: 2, col: 3, dir: (1.0, 0.2, 0.1)),\n",
            1 => "Undo,\n",
            2 => "Redo,\n",
            _ => "ExpectScene(streamlines: Some(6)),\n",
        });
    }
    text.push_str("])\n");
    std::fs::write(&path, &text).unwrap();

    let mut app = headless_app(builtin::scene("car1").unwrap());
    app.add_plugins(ScriptRunPlugin);
    app.world_mut()
        .resource_mut::<ScriptRun>()
        .start(path.clone());
    // parsing happens off the frame: frames keep coming meanwhile
    let start = Instant::now();
    let mut frames_while_parsing = 0;
    while matches!(
        app.world().resource::<ScriptRun>().state,
        RunState::Parsing(..)
    ) {
        app.update();
        frames_while_parsing += 1;
        assert!(start.elapsed() < HANG, "parsing hangs");
        std::thread::sleep(Duration::from_millis(2));
    }
    assert!(
        frames_while_parsing > 1,
        "frames ran while the script was parsed"
    );
    eprintln!(
        "million-step script: read and parsed in {:.2} s off the frame, {frames_while_parsing} frames meanwhile",
        start.elapsed().as_secs_f64()
    );
    let mut last = 0;
    for frame in 0..200 {
        app.update();
        let run = app.world().resource::<ScriptRun>();
        let (done, all) = run.progress().expect("running");
        assert_eq!(all, 1_000_000);
        assert!(done > last || frame == 0, "progress moves");
        assert!(done - last <= MAX_BATCH, "at most a batch a frame");
        last = done;
    }
    assert!(last > 200, "batches grew past one step a frame: {last}");
    eprintln!("million-step script: {last} steps in 200 frames");
    app.world_mut().resource_mut::<ScriptRun>().cancel();
    app.update();
    match &app.world().resource::<ScriptRun>().state {
        RunState::Done(line) => assert!(
            line.contains(&format!("cancelled after step {last} of 1000000")),
            "{line}"
        ),
        _ => panic!("not stopped"),
    }
    // the edits went through the model: the last ones are undoable
    let log = app.world().resource::<ecs::History>();
    assert!(log.undo_len() > 0);
    let _ = std::fs::remove_file(&path);
}

#[test]
fn depths_past_the_memory_cap_are_refused_before_building() {
    let mut app = headless_app(builtin::scene("car1").unwrap());
    let e = ecs::apply(&mut app, Edit::SetDisplayDepth(12))
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("depth 12 would produce") && e.contains("2048 MB memory cap"),
        "{e}"
    );
    // the model is as it was
    assert_eq!(
        ecs::patch::scene(app.world()).display_depth,
        builtin::scene("car1").unwrap().display_depth
    );
}
