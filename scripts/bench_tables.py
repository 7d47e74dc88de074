#!/usr/bin/env python3
"""Regenerates the tables of docs/benchmarks.md from measured results.

Every table of docs/benchmarks.md sits between two marker comments,
`<!-- bench:AREA:begin -->` and `<!-- bench:AREA:end -->`; this script
rewrites what lies between them from the raw results in docs/bench/, one
JSON-lines file a source, whose first line is {"meta": {...}} (machine,
cores, date, commit, load, command) and whose other lines are the rows as
the source printed them:

    bench.jsonl     `streamline-studio bench --json`  (kernel, ecs, patches, export)
    peers.jsonl     `bash scripts/peers.sh --json`    (Loop vs pymeshlab, trimesh)
    osd.jsonl       `bash scripts/loop_vs_osd.sh --json` (Loop vs OpenSubdiv)
    cad.jsonl       `bash scripts/cad_peers.sh --json`   (the fit vs OpenCascade)
    reference.jsonl `bash scripts/reference_peers.sh --json` (a reference's fit and
                    deviation rows, the fit vs OpenCascade's grid fitter)
    drag.jsonl      `tests/gui/drag.sh` under xvfb + `scripts/drag_figures.py --json`
                    (the editor's drag; the reports are kept in docs/bench/drag/)
    versus.jsonl    an earlier binary (`--before PATH`) and this one side by side in
                    one run: the `ecs/` and three-patch export bench rows, taken in
                    turns, and the drags of the car at depths 5 and 6 and of
                    hood-screen-wing at depth 6 (measured only when named)

Ratios and verdicts are computed here from those rows; no figure is typed.

Usage:
    bench_tables.py [--measure SOURCES] [--from DIR] [--check] [--bin PATH]
                    [--before PATH] [--millis N] [--drag-runs N] [--doc FILE]

    (no option)         measure every source, save, rewrite the tables
    --measure a,b       measure only these sources (bench, peers, osd, cad,
                        reference, drag), read the others from DIR
    --from DIR          measure nothing: rewrite the tables from DIR's files
                        (default DIR: docs/bench)
    --check             rewrite nothing; exit 1 if the tables differ from DIR's files
    --bin PATH          the streamline-studio binary (default: the release
                        build in $CARGO_TARGET_DIR or target/, built if missing)
    --millis N          `bench --millis` (default 300)
    --drag-runs N       drags of the car at depth 6 (default 3)
    --before PATH       the earlier binary `versus` compares with (its commit is
                        read from PATH.commit when that file exists)
"""

import datetime
import json
import os
import platform
import re
import shutil
import statistics
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SOURCES = ["bench", "peers", "osd", "cad", "reference", "drag", "versus"]
# measured only when named with --measure (it needs --before)
OPTIONAL = ["versus"]


# ---------------------------------------------------------------- measuring


def git(*args):
    return subprocess.run(["git", *args], cwd=ROOT, capture_output=True, text=True).stdout.strip()


def machine():
    model, flags = platform.processor() or "unknown CPU", ""
    try:
        for line in open("/proc/cpuinfo"):
            key, _, value = line.partition(":")
            if key.strip() == "model name":
                model = value.strip()
            elif key.strip() == "flags":
                flags = f" {value.strip()} "
    except OSError:
        pass
    simd = "AVX-512" if " avx512f " in flags else "AVX2" if " avx2 " in flags else "SSE2"
    return f"{model} ({simd})", os.cpu_count()


def meta(source, command):
    cpu, cores = machine()
    # the binary is built from the working tree: say when it was not the commit
    dirty = git("diff", "--name-only", "HEAD", "--", "src", "crates", "benches", "Cargo.toml", "Cargo.lock").split()
    return {
        "meta": {
            "source": source,
            "machine": cpu,
            "cores": cores,
            "date": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d"),
            "commit": git("rev-parse", "--short", "HEAD"),
            "dirty": dirty,
            "load": round(os.getloadavg()[0], 1),
            "command": command,
        }
    }


def binary(path):
    if path:
        return os.path.abspath(path)
    target = os.environ.get("CARGO_TARGET_DIR", os.path.join(ROOT, "target"))
    b = os.path.join(target, "release", "streamline-studio")
    if not os.path.exists(b):
        subprocess.run(["cargo", "build", "--release", "-q"], cwd=ROOT, check=True)
    return b


def json_lines(text):
    return [json.loads(l) for l in text.splitlines() if l.strip().startswith("{")]


def run_lines(cmd, env=None):
    print("+", " ".join(cmd), file=sys.stderr, flush=True)
    out = subprocess.run(cmd, cwd=ROOT, env=env, check=True, stdout=subprocess.PIPE, text=True).stdout
    return json_lines(out)


def save(folder, source, head, rows):
    os.makedirs(folder, exist_ok=True)
    with open(os.path.join(folder, f"{source}.jsonl"), "w") as f:
        for r in [head, *rows]:
            f.write(json.dumps(r, ensure_ascii=False) + "\n")


def measure(source, folder, opts):
    b = binary(opts["bin"])
    env = dict(os.environ, STREAMLINE_STUDIO_BIN=b)
    start = meta(source, {
        "bench": f"streamline-studio bench --json --millis {opts['millis']}",
        "peers": "bash scripts/peers.sh --json",
        "osd": "bash scripts/loop_vs_osd.sh --json",
        "cad": "bash scripts/cad_peers.sh --json",
        "reference": "bash scripts/reference_peers.sh --json",
        "drag": f"tests/gui/drag.sh ×{opts['drag_runs']} + scripts/drag_figures.py --json",
        "versus": "bench --json (ecs/, export/hood-screen-wing) ×2 in turns + tests/gui/drag.sh, before and after",
    }[source])
    if source == "bench":
        rows = run_lines([b, "bench", "--json", "--millis", str(opts["millis"])])
    elif source == "peers":
        rows = run_lines(["bash", "scripts/peers.sh", "--json"], env)
    elif source == "osd":
        rows = run_lines(["bash", "scripts/loop_vs_osd.sh", "--json"], env)
    elif source == "cad":
        rows = run_lines(["bash", "scripts/cad_peers.sh", "--json"], env)
    elif source == "reference":
        rows = run_lines(["bash", "scripts/reference_peers.sh", "--json"], env)
    elif source == "versus":
        if not opts["before"]:
            sys.exit("versus: give the earlier binary with --before PATH")
        before = os.path.abspath(opts["before"])
        tag = before + ".commit"
        start["meta"]["before"] = open(tag).read().strip() if os.path.exists(tag) else before
        rows = measure_versus(before, b, opts["millis"])
    else:
        rows = measure_drag(b, folder, opts["drag_runs"])
    save(folder, source, start, rows)


# The side-by-side drags: (name, scene, display depth, handle).
VERSUS_DRAGS = [
    ("car/d5", "scenes/car1.ron", 5, "2,4"),
    ("car/d6", "scenes/car1.ron", 6, "2,4"),
    ("hood-screen-wing/d6", "scenes/hood-screen-wing.ron", 6, "2,4"),
]


def measure_versus(before, after, millis):
    """The bench rows of `ecs/` and the three-patch export, each binary twice
    in turns (the smaller median of each kept, so that a burst of other work
    on the machine weighs on neither alone), then each drag once with each
    binary, one after the other."""
    medians = {}
    for who in ("before", "after", "before", "after"):
        b = before if who == "before" else after
        for f in ("ecs/", "export/hood-screen-wing"):
            for r in run_lines([b, "bench", "--json", "--millis", str(millis), "--filter", f]):
                key = (r["name"], who)
                medians[key] = min(medians.get(key, r["median_ns"]), r["median_ns"])
    names = sorted({n for n, _ in medians}, key=lambda n: (not n.startswith("ecs/"), n))
    rows = [{"name": n, "before_ns": medians.get((n, "before")), "after_ns": medians.get((n, "after"))}
            for n in names]
    tmp = tempfile.mkdtemp()
    fig = os.path.join(ROOT, "scripts/drag_figures.py")
    for name, scene, depth, handle in VERSUS_DRAGS:
        path = os.path.join(tmp, name.replace("/", "-") + ".ron")
        text = open(os.path.join(ROOT, scene)).read()
        open(path, "w").write(re.sub(r"display_depth: *\d+", f"display_depth: {depth}", text))
        row = {"drag": name}
        for who, b in (("before", before), ("after", after)):
            report = os.path.join(tmp, f"{name.replace('/', '-')}-{who}.json")
            env = dict(os.environ, SCENE=path, **dict(DRAG_ENV, SELECT=handle))
            cmd = ["xvfb-run", "-a", "-s", "-screen 0 1280x800x24", "bash", "tests/gui/drag.sh", b,
                   report + ".png", report]
            print("+", " ".join(cmd), file=sys.stderr, flush=True)
            subprocess.run(cmd, cwd=ROOT, env=env, check=True, stdout=subprocess.DEVNULL)
            row[who] = run_lines([sys.executable, fig, "--json", report])[0]
        rows.append(row)
    shutil.rmtree(tmp, ignore_errors=True)
    return rows


# The drag of the method section: handle (2, 4) of the car at display depth 6.
DRAG_ENV = {
    "STREAMLINE_STUDIO_METER_DETAIL": "1",
    "MOVES": "60",
    "STEP_PX": "3",
    "PAUSE": "0.12",
    "SELECT": "2,4",
}


def measure_drag(b, folder, runs):
    keep = os.path.join(folder, "drag")
    shutil.rmtree(keep, ignore_errors=True)
    os.makedirs(keep)
    tmp = tempfile.mkdtemp()
    scene = os.path.join(tmp, "car1-d6.ron")
    text = open(os.path.join(ROOT, "scenes/car1.ron")).read()
    open(scene, "w").write(re.sub(r"display_depth: *\d+", "display_depth: 6", text))
    env = dict(os.environ, SCENE=scene, **DRAG_ENV)
    reports = []
    for k in range(1, runs + 1):
        report = os.path.join(tmp, f"report-{k}.json")
        cmd = ["xvfb-run", "-a", "-s", "-screen 0 1280x800x24", "bash", "tests/gui/drag.sh", b,
               os.path.join(tmp, f"out-{k}.png"), report]
        print("+", " ".join(cmd), file=sys.stderr, flush=True)
        subprocess.run(cmd, cwd=ROOT, env=env, check=True, stdout=subprocess.DEVNULL)
        r = json.load(open(report))
        kept = {key: r[key] for key in ("ours_frames", "frame_probe", "detail") if key in r}
        path = os.path.join(keep, f"run-{k}.json")
        with open(path, "w") as f:
            json.dump(kept, f)
        reports.append(path)
    shutil.rmtree(tmp, ignore_errors=True)
    fig = os.path.join(ROOT, "scripts/drag_figures.py")
    rows = []
    for k, path in enumerate(reports, 1):
        rows.append({"run": k, **run_lines([sys.executable, fig, "--json", path])[0]})
    rows.append({"run": "all", **run_lines([sys.executable, fig, "--json", *reports])[0]})
    return rows


# ---------------------------------------------------------------- reading


def load(folder, source):
    path = os.path.join(folder, f"{source}.jsonl")
    if not os.path.exists(path):
        return None, []
    lines = [json.loads(l) for l in open(path) if l.strip()]
    head = lines[0].get("meta", {}) if lines and "meta" in lines[0] else {}
    return head, [l for l in lines if "meta" not in l]


# ---------------------------------------------------------------- formatting


def t(ns):
    """A time in ns, in the unit that suits it, three significant figures."""
    if ns is None:
        return "–"
    for unit, scale in (("s", 1e9), ("ms", 1e6), ("µs", 1e3)):
        if ns >= scale:
            v = ns / scale
            break
    else:
        unit, v = "ns", ns
    digits = 0 if v >= 100 else 1 if v >= 10 else 2
    return f"{v:,.{digits}f} {unit}"


def ms(v):
    return "–" if v is None else f"{v:.2f}"


def r2(x, digits=2):
    return "–" if x is None else f"{x:.{digits}f}"


def table(head, rows, align=None):
    """A Markdown table; a column of figures (every cell starting with a
    digit, or empty) is aligned right."""
    if align is None:
        def figures(k):
            cells = [str(r[k]) for r in rows if str(r[k]) not in ("", "–")]
            return bool(cells) and all(c[0].isdigit() for c in cells)
        align = ["---"] + ["---:" if figures(k) else "---" for k in range(1, len(head))]
    out = ["| " + " | ".join(head) + " |", "|" + "|".join(align) + "|"]
    out += ["| " + " | ".join(str(c) for c in r) + " |" for r in rows]
    return out


def provenance(m, extra=""):
    if not m:
        return ["*(not measured yet: run the command below)*"]
    dirty = m.get("dirty") or []
    tree = f"`{m['commit']}`"
    if dirty:
        tree = f"the working tree on {tree} ({len(dirty)} source files changed and not yet committed)"
    line = (f"Measured {m['date']} on {m['machine']}, {m['cores']} cores, load average {m['load']} "
            f"at the start; built from {tree}; raw results in `docs/bench/{m['source']}.jsonl`.")
    return [line + extra]


def command(*cmds):
    return ["", "```sh", *cmds, "```"]


class Rows:
    def __init__(self, rows):
        self.ns = {r["name"]: r["median_ns"] for r in rows}

    def __call__(self, name):
        return self.ns.get(name)

    def ratio(self, a, b):
        x, y = self(a), self(b)
        return None if x is None or y is None or y == 0 else x / y

    def named(self, prefix):
        return [n for n in self.ns if n.startswith(prefix)]


# ---------------------------------------------------------------- the areas

# Table 1 of the paper (milliseconds on 2001 hardware), quoted for the ratios.
PAPER_MS = {
    "curve/chaikin/d7": 0.31,
    "curve/cubic-bspline/d7": 0.63,
    "curve/four-point/d6": 1.09,
    "curve/qi-k3/257": 4.69,
    "curve/qi-k4/257": 4.84,
}
TABLE1 = [
    ("curve/chaikin/d7", "Chaikin, depth 7 (386 tangents)"),
    ("curve/cubic-bspline/d7", "cubic B-spline, depth 7 (259 tangents)"),
    ("curve/four-point/d6", "4-point (ω = 1), depth 6 (257 tangents)"),
    ("curve/qi-k3/257", "QI curve k = 3, 257 samples"),
    ("curve/qi-k4/257", "QI curve k = 4, 257 samples"),
    ("curve/qi-k5/257", "QI curve k = 5, 257 samples"),
]
BENCH_CMD = "python3 scripts/bench_tables.py --measure bench"


def kernel(m, b):
    out = provenance(m) + command(BENCH_CMD) + [""]
    qi3 = "curve/qi-k3/257"
    rows = []
    for name, what in TABLE1:
        paper = PAPER_MS.get(name)
        pr = PAPER_MS[qi3] / paper if paper else None
        rows.append([f"`{name}`", what, t(b(name)), r2(b.ratio(qi3, name)),
                     "–" if paper is None else f"{paper:g}", r2(pr)])
    out += ["**Table 1 of the paper: subdivision against QI curves** (5 control tangents):", ""]
    out += table(["row", "what", "median", "QI k = 3 ÷ row", "paper (ms, 2001)", "paper: QI k = 3 ÷ row"], rows)
    chaikin = b("curve/chaikin/d7")
    if chaikin is not None:
        out += ["", f"Target: Chaikin at depth 7 in at most 5 µs — **{'met' if chaikin <= 5e3 else 'not met'}** ({chaikin / 1e3:.2f} µs)."]
    car = [
        ("surface/kobbelt/9x6/d3/full", "`Design::build` at depth 3 (65 × 41 tangents), fresh buffers"),
        ("surface/kobbelt/9x6/d5/full", "`Design::build` at depth 5 (257 × 161), fresh buffers"),
        ("surface/kobbelt/9x6/d5/builder-1t", "a kept `Builder`, one thread, the widest vector path"),
        ("surface/kobbelt/9x6/d5/builder-1t-avx2", "the same, AVX2 at most"),
        ("surface/kobbelt/9x6/d5/builder-1t-scalar", "the same, vector paths off"),
        ("surface/kobbelt/9x6-mirrored/d5/full", "the mirrored car (11 × 9 net, 321 × 258 points)"),
    ]
    out += ["", "**The car's full build** (the 9 × 6 Kobbelt net: blend, integrate, mesh):", ""]
    out += table(["row", "what", "median"], [[f"`{n}`", w, t(b(n))] for n, w in car if b(n) is not None])
    kept = b("surface/kobbelt/9x6/d5/builder-1t")
    if kept is not None:
        out += ["", f"Target: the car at depth 5 built in at most 0.5 ms on one thread — "
                f"**{'met' if kept <= 5e5 else 'not met'}** on this machine ({kept / 1e3:.1f} µs, kept `Builder`)."]
    return out


def ecs(m, b):
    out = provenance(m) + command(BENCH_CMD) + [""]
    out += ["**One edit against a full rebuild** (message → blend → integrate → mesh through the "
            "headless app; the interior tangent is (2, 4) on the car, (10, 9) on the 20 × 20 net):", ""]
    rows = []
    for net, label in (("car", "car 9 × 6"), ("grid20", "20 × 20")):
        for d in (3, 5):
            p = f"ecs/{net}/d{d}/"
            if b(p + "full") is None:
                continue
            rows.append([f"`{p}…`", f"{label}, depth {d}", t(b(p + "edit-interior")), t(b(p + "edit-corner")),
                         t(b(p + "full")), r2(b.ratio(p + "edit-interior", p + "full"), 3),
                         r2(b.ratio(p + "edit-corner", p + "full"), 3)])
    out += table(["rows", "net", "interior edit", "corner edit", "full rebuild", "interior / full", "corner / full"], rows)
    loc = b.ratio("ecs/grid20/d5/edit-interior", "ecs/grid20/d5/full")
    if loc is not None:
        out += ["", f"Target: an interior edit on `ecs/grid20/d5` costs at most 0.12 of a full rebuild — "
                f"**{'met' if loc <= 0.12 else 'not met'}** ({loc:.3f}, from the two rows of this run)."]
    other = [
        ("ecs/car/d6/drag", "the editor's drag frame at depth 6, headless, with the `f32` staging pair"),
        ("ecs/car/d6/drag-deferred", "the same with the `f64` normals left for the drag's end, as the editor runs it"),
        ("ecs/car/d6/drag-cold", "`drag-deferred` after 48 MB of other writes (caches cold, as in the editor)"),
        ("ecs/car/d6/release", "the frame after the drag: the deferred normals made"),
        ("tune/car/d3/free", "one fine-tuning value of the car at depth 3, free"),
        ("tune/car/d3/keep-ends", "the same, every streamline's ends kept"),
        ("ecs/car/d5/insert-row", "a row inserted, then deleted, in turn (a full rebuild each)"),
        ("ecs/car/d5/initial-curve", "an initial-curve tangent turned: every streamline placed again, nothing re-blended"),
        ("ecs/car-mirrored/d5/edit-interior", "a tangent edit on the mirrored car (both copies of the cell)"),
    ]
    base = "ecs/car/d5/edit-interior"
    rows = [[f"`{n}`", w, t(b(n)), r2(b.ratio(n, base))] for n, w in other if b(n) is not None]
    out += ["", f"**Drag frames, fine tuning and authoring** (the last column against `{base}` of the same run):", ""]
    out += table(["row", "what", "median", f"÷ `{base}`"], rows)
    return out


def patches(m, b):
    out = provenance(m) + command(BENCH_CMD) + [""]
    rows = [
        ("ecs/patches/car-x1/d5/edit-first", "the car alone as a one-patch document, tangent (2, 4) turned"),
        ("ecs/patches/car-x3/d5/edit-first", "the same edit, two more cars G1-chained on its end"),
        ("ecs/patches/car-x3/d5/edit-middle", "the same three cars, the middle car's (2, 4) turned"),
        ("ecs/patches/car-x3/d5/edit-last", "the same three cars, the last car's (2, 4) turned"),
        ("ecs/patches/car-g2x3/d5/edit-first", "three cars G2-chained (one merged run), the first edited"),
        ("ecs/patches/car-g2x3/d5/edit-last", "the same run, the last car edited"),
        ("ecs/patches/hood-screen-wing/d6/edit-hood", "`scenes/hood-screen-wing.ron` at depth 6, the hood's (2, 4) turned"),
        ("joins/car-g2x3/d5/whole", "the kernel's G2 run built whole (`g2_run`)"),
        ("joins/car-g2x3/d5/update", "the same run updated in its window (`G2State::update`)"),
    ]
    out += table(["row", "what", "median"], [[f"`{n}`", w, t(b(n))] for n, w in rows if b(n) is not None])
    ratios = [
        ("ecs/patches/car-x3/d5/edit-first", "ecs/patches/car-x1/d5/edit-first", "three G1-chained cars ÷ one car"),
        ("ecs/patches/car-x3/d5/edit-last", "ecs/patches/car-x3/d5/edit-first", "three G1-chained cars: last car edited ÷ first car edited"),
        ("ecs/patches/car-g2x3/d5/edit-last", "ecs/patches/car-g2x3/d5/edit-first", "G2 run: last car edited ÷ first car edited"),
        ("joins/car-g2x3/d5/update", "joins/car-g2x3/d5/whole", "G2 run: update ÷ whole build"),
    ]
    out += [""] + table(["ratio", "value"], [[w, r2(b.ratio(x, y))] for x, y, w in ratios if b.ratio(x, y) is not None])
    return out


def export(m, b):
    out = provenance(m) + command(BENCH_CMD) + [""]
    rows = [
        ("fit/car/d4", "the car's B-spline fit from its depth-4 grid (builds outside)"),
        ("fit/car/d5", "the same from depth 5"),
        ("fit/car2/d5", "car2 from depth 5"),
        ("export-fit/car/d3", "the car shown at depth 3 fitted within 1e-4 of its diagonal, builds included"),
        ("export-fit/car/d3/edited", "the same after every control tangent was turned (fixed seed)"),
        ("export/hood-screen-wing/d4/step", "three patches to a STEP shell: build, fit, text, write, read-back check"),
        ("export/hood-screen-wing/d4/shell-fit", "the shell's fit alone"),
        ("export/hood-screen-wing/d4/iges", "IGES (the shell's faces, each an entity), build included"),
        ("export/hood-screen-wing/d4/glb", "`.glb`, one mesh a patch (no fit)"),
    ]
    out += table(["row", "what", "median"], [[f"`{n}`", w, t(b(n))] for n, w in rows if b(n) is not None])
    return out


def loop_ours(m, b):
    out = provenance(m) + command(BENCH_CMD) + [""]
    rows = []
    for prefix in ("loop/subdivide/", "loop/20k/", "pi/1m/"):
        rows += [[f"`{n}`", t(b(n))] for n in b.named(prefix)]
    out += table(["row", "median"], rows)
    return out


def osd(m, rows):
    out = provenance(m, " Each figure is the best of 15 runs (3 rounds of 5, ours and "
                         "OpenSubdiv's alternating), one thread, the topology built from the face list included.")
    out += command("python3 scripts/bench_tables.py --measure osd") + [""]
    if not rows:
        return out
    rules = list(dict.fromkeys(r["rule"] for r in rows))
    body, ratios = {}, []
    for r in rows:
        key = (r["mesh"], r["vertices"], r["level"], r["vertices_out"])
        body.setdefault(key, {})[r["rule"]] = r
        ratios.append(r["ours_ms"] / r["osd_ms"])
    lines = []
    for (mesh, v, level, vout), by in body.items():
        cells = []
        for rule in rules:
            x = by.get(rule)
            cells.append("–" if x is None else f"{x['ours_ms']:.2f} / {x['osd_ms']:.2f} ({x['ours_ms'] / x['osd_ms']:.2f})")
        lines.append([mesh, f"{v:,}", level, f"{vout:,}", *cells])
    out += table(["mesh", "vertices", "level", "vertices out", *[f"{r}: ours / OSD ms (÷)" for r in rules]], lines)
    out += ["", f"Ours ÷ OpenSubdiv over all {len(ratios)} rows: median {statistics.median(ratios):.2f}, "
            f"from {min(ratios):.2f} to {max(ratios):.2f}."]
    return out


def peers(m, rows):
    out = provenance(m, " Ours: `bench --millis 1000` medians; the peers: best of 3 runs (of 1 at level 3).")
    out += command("python3 scripts/bench_tables.py --measure peers") + [""]
    lines = [[r["mesh"], r["levels"], f"{r['vertices_out']:,}", t(r["ours_s"] * 1e9), t(r["pymeshlab_s"] * 1e9),
              t(r["trimesh_s"] * 1e9), f"{r['pymeshlab_s'] / r['ours_s']:.0f}×", f"{r['trimesh_s'] / r['ours_s']:.0f}×"]
             for r in rows]
    if lines:
        out += table(["mesh", "levels", "vertices out", "ours", "pymeshlab", "trimesh", "pymeshlab ÷ ours",
                      "trimesh ÷ ours"], lines)
    return out


def cad(m, rows):
    out = provenance(m, " Our time is the `fit/…/d5` row's median (`bench --millis 2000`), "
                        "OpenCascade's `GeomAPI_PointsToBSplineSurface` (degree 3–8, C2, the same tolerance) "
                        "the best of 5; both surfaces' distances from the depth-5 and depth-6 points measured "
                        "by OpenCascade's projection.")
    out += command("python3 scripts/bench_tables.py --measure cad") + [""]
    lines = []
    for r in rows:
        for who, name in (("ours", "ours"), ("occ", "OpenCascade")):
            x = r[who]
            ok = "yes" if max(x["d5"][0], x["d6"][0]) <= r["tolerance"] else "no"
            lines.append([r["scene"], name, t(x["seconds"] * 1e9), f"{x['degree'][0]} × {x['degree'][1]}",
                          f"{x['poles'][0]} × {x['poles'][1]}", f"{x['d5'][0]:.2e} / {x['d6'][0]:.2e}",
                          f"{x['d6'][1]:.2e}", f"{r['tolerance']:.2e}", ok])
        lines.append([r["scene"], "OpenCascade ÷ ours", f"{r['occ']['seconds'] / r['ours']['seconds']:.1f}×",
                      "", "", "", "", "", ""])
    if lines:
        out += table(["scene", "fitter", "time", "degree", "poles", "largest distance d5 / d6", "mean d6",
                      "tolerance", "within"], lines)
    return out


# The rows of a reference (src/cli/bench/reference_rows.rs), as
# scripts/reference_peers.sh measures them beside OpenCascade.
REFERENCE_ROWS = [
    ("reference-fit/hood/d5", "hood.step's face fitted at the default options, the kernel's helper thread on"),
    ("reference-fit/duct/d5", "duct.igs's face, likewise"),
    ("reference-fit/roof/d5", "roof.step's face, likewise"),
    ("reference-fit/hood/d5/1t", "hood.step's face on one thread"),
    ("reference-fit/duct/d5/1t", "duct.igs's face on one thread"),
    ("reference-fit/roof/d5/1t", "roof.step's face on one thread"),
    ("reference-deviation/hood/d5", "every point of `scenes/references/hood.ron` at depth 5 to its face"),
    ("reference-deviation/hood/d5/drag-row", "the editor's map in a frame of a drag of tangent (4, 3), a handle of the "
     "net: the 189 × 223 points the drag moves (42,147 of 58,082) measured again, the others kept"),
    ("reference-deviation/hood/d5/drag-frame", "that drag's whole frame headless, one thread: the edit, the "
     "streamlines, the mesh and the map"),
    ("reference-deviation/car/d5", "every point of the car at depth 5 to the car's depth-4 B-spline export"),
    ("reference-deviation/car/index", "the export's closest-point index made (its dense sample, a k-d tree)"),
]
# Points of the deviation rows' meshes: the hood's comes with its face's row.
CAR_D5_POINTS = 161 * 258


def reference(m, rows):
    out = provenance(m, " Our times are the rows' medians (`bench --millis 2000`); OpenCascade's "
                        "`GeomAPI_PointsToBSplineSurface` (degree 3–8, C2, our tolerance) the best of 5, "
                        "one thread.")
    out += command("python3 scripts/bench_tables.py --measure reference") + [""]
    b = Rows([r for r in rows if "name" in r])
    faces = [r for r in rows if "face" in r]
    if b.ns:
        out += table(["row", "what", "median"], [[f"`{n}`", w, t(b(n))] for n, w in REFERENCE_ROWS
                                                 if b(n) is not None])
    hood = next((r for r in faces if r["face"] == "hood"), None)
    dev = []
    if hood and b("reference-deviation/hood/d5") is not None:
        dev.append(("the hood", hood["points"][0] * hood["points"][1], b("reference-deviation/hood/d5")))
    if b("reference-deviation/car/d5") is not None:
        dev.append(("the car", CAR_D5_POINTS, b("reference-deviation/car/d5")))
    if dev:
        ok = all(ns / n * 5e4 <= 5e7 for _, n, ns in dev)
        out += ["", "Target: the deviation of 50,000 points in under 50 ms (1 µs a point), the face's index "
                "already made — "
                f"**{'met' if ok else 'not met'}** on this machine ("
                + "; ".join(f"{w}: {n:,} points in {t(ns)}, {ns / n / 1e3:.2f} µs a point" for w, n, ns in dev)
                + ")."]
    row, frame, whole = (b("reference-deviation/hood/d5/drag-row"), b("reference-deviation/hood/d5/drag-frame"),
                         b("reference-deviation/hood/d5"))
    if row is not None and frame is not None and whole is not None:
        ok = frame <= 4e6
        out += ["", "A drag's frame: the map measures again only the points the drag moved and keeps the "
                f"others' distances (bit for bit a full measure): {t(row)} for a handle of the hood's net, "
                f"which moves most of the surface, against {t(whole)} for every point; the frame whole, "
                f"{t(frame)} on one thread. Target: our systems under 4 ms a frame during a drag with the map "
                f"measured live — **{'met' if ok else 'not met'}** for a drag this large, which the editor "
                "therefore measures when it ends (a drag that moves fewer points than a frame's budget, "
                "`reference_map::LIVE_POINTS`, is measured live). While it waits the map keeps its colours "
                "and costs the frame nothing, so the drag itself stays within 4 ms "
                "([fit.md](fit.md#how-fast) has that drag's frames under the editor)."]
    lines = []
    for r in faces:
        o, c = r["ours"], r["occ"]
        lines.append([r["face"], f"{r['points'][0]} × {r['points'][1]}", f"{r['tolerance']:.2e}",
                      t(o["seconds"] * 1e9), t(o["seconds_1t"] * 1e9), f"{o['net'][0]} × {o['net'][1]}",
                      f"{o['to_face']:.2e} / {o['from_face']:.2e}", t(c["seconds"] * 1e9),
                      f"{c['degree'][1]} × {c['degree'][0]}", f"{c['poles'][1]} × {c['poles'][0]}",
                      f"{c['to_face']:.2e} / {c['from_face']:.2e}", f"{c['seconds'] / o['seconds_1t']:.2f}×"])
    if lines:
        out += ["", "**Beside OpenCascade** (grids, nets, degrees and poles across × along the streamlines; "
                "largest distances in metres, to the face / from the face):", ""]
        out += table(["face", "grid (depth 5)", "tolerance", "ours", "ours, one thread", "net", "largest distance",
                      "OpenCascade", "degree", "poles", "largest distance", "OpenCascade ÷ ours (one thread)"],
                     lines)
        gap = max(abs(r["ours"]["to_face_by_occ"] - r["ours"]["to_face"]) / r["ours"]["to_face"] for r in faces)
        out += ["", f"OpenCascade's projection of our depth-5 points puts their largest distance to the face "
                f"within {gap:.1e} of our own measure (relative) on every face."]
    return out


def drag(m, rows):
    if m and m.get("transcribed"):
        out = [f"Measured {m['date']} at `{m['commit']}` on {m['machine']}, {m['cores']} cores. "
               f"{m['transcribed']} The figures are kept in `docs/bench/drag.jsonl`."]
    else:
        out = provenance(m, " Each run's `screenshot --report` is kept in `docs/bench/drag/`.")
    out += command("python3 scripts/bench_tables.py --measure drag") + [""]
    runs = [r for r in rows if r.get("run") != "all"]
    lines = []
    for r in runs:
        st, q = r.get("steady") or {}, r.get("quiet") or {}
        a = r.get("all") or {}
        lines.append([r["run"], a.get("frames", "–"), st.get("frames", "–"), ms(st.get("median")), ms(st.get("p99")),
                      ms(st.get("largest")), st.get("over_budget", "–"), q.get("frames", "–"), ms(q.get("largest"))])
    if lines:
        out += table(["run", "frames with an edit", "steady", "steady median", "steady p99", "largest steady",
                      "steady over 4 ms", "quiet", "largest quiet"], lines)
        out += ["", "(ms, our systems' CPU time a frame.)"]
    pooled = next((r for r in rows if r.get("run") == "all"), None)
    if pooled and pooled.get("scaled"):
        s, st = pooled["scaled"], pooled.get("steady") or {}
        out += ["", f"All {s['frames']} frames with an edit of {pooled.get('runs_pooled', 'these runs')}, each divided "
                f"by its probes' mean slowdown: median {s['median']:.2f} ms, p99 {s['p99']:.2f} ms, largest "
                f"{s['largest']:.2f} ms."]
        if st:
            out += ["", f"Target: every steady frame under 4 ms — **{'met' if st['over_budget'] == 0 else 'not met'}** "
                    f"in these runs ({st['over_budget']} of {st['frames']} steady frames over 4 ms, "
                    f"largest {st['largest']:.2f} ms)."]
    sysm = (pooled or {}).get("systems") or {}
    if sysm:
        def label(k):
            path = k.split(":")[0]
            return f"{SYSTEMS[path]} (`{path}`)" if path in SYSTEMS else f"`{path}`"
        out += ["", "Systems' means over those frames (ms a frame): "
                + ", ".join(f"{label(k)} {v:.2f}" for k, v in list(sysm.items())[:6]) + "."]
    return out


def versus(m, rows):
    if not m:
        return provenance(m) + command("python3 scripts/bench_tables.py --measure versus --before OLD_BINARY")
    out = provenance(m, f" Before: `{m.get('before', '?')}`, the same machine, in turns.")
    out += command("python3 scripts/bench_tables.py --measure versus --before OLD_BINARY") + [""]
    bench = [r for r in rows if "name" in r and r.get("before_ns") and r.get("after_ns")]
    lines = [[f"`{r['name']}`", t(r["before_ns"]), t(r["after_ns"]), r2(r["after_ns"] / r["before_ns"])]
             for r in bench]
    if lines:
        out += table(["row", "before", "after", "after ÷ before"], lines)
        worst = max(bench, key=lambda r: r["after_ns"] / r["before_ns"])
        out += ["", f"Largest ratio: `{worst['name']}`, {worst['after_ns'] / worst['before_ns']:.2f}."]
    drags = [r for r in rows if "drag" in r]
    if drags:
        def fig(d, key, k):
            v = (d.get(key) or {}).get(k)
            return "–" if v is None else (f"{v:.2f}" if isinstance(v, float) else str(v))
        dl = []
        for r in drags:
            b, a = r.get("before") or {}, r.get("after") or {}
            dl.append([f"`{r['drag']}`", fig(b, "quiet", "frames"), fig(b, "quiet", "median"),
                       fig(b, "quiet", "largest"), fig(a, "quiet", "frames"), fig(a, "quiet", "median"),
                       fig(a, "quiet", "largest"), fig(a, "all", "over_budget")])
        out += [""] + table(["drag", "quiet frames before", "median before", "largest before", "quiet frames after",
                             "median after", "largest after", "frames over 4 ms after"], dl)
        out += ["", "(ms, our systems' CPU time a frame, over the frames whose speed probes ran within 1.1 times "
                "their usual time; `scripts/drag_figures.py`.)"]
    return out


SYSTEMS = {
    "ecs/mesh.rs": "mesh stage",
    "ecs/blend.rs": "blend",
    "ecs/integrate.rs": "integrate",
    "ecs/edit.rs": "edit",
    "ecs/warnings.rs": "build warnings",
    "editor/panels/mod.rs": "panels",
    "editor/view/overlay.rs": "overlay",
    "editor/handles/sphere_view.rs": "sphere view",
    "editor/handles/arrows.rs": "arrows",
    "editor/handles/sphere_dots.rs": "sphere dots",
}

AREAS = {
    "kernel": ("bench", kernel, True),
    "ecs": ("bench", ecs, True),
    "patches": ("bench", patches, True),
    "export": ("bench", export, True),
    "loop": ("bench", loop_ours, True),
    "osd": ("osd", osd, False),
    "peers": ("peers", peers, False),
    "cad": ("cad", cad, False),
    "reference": ("reference", reference, False),
    "drag": ("drag", drag, False),
    "versus": ("versus", versus, False),
}


def render(folder):
    data = {s: load(folder, s) for s in SOURCES}
    out = {}
    for area, (source, fn, named) in AREAS.items():
        m, rows = data[source]
        out[area] = "\n".join(fn(m, Rows(rows) if named else rows))
    return out


def rewrite(doc, tables):
    text = open(doc).read()
    for area, body in tables.items():
        pat = re.compile(rf"(<!-- bench:{area}:begin -->\n).*?(<!-- bench:{area}:end -->)", re.S)
        if not pat.search(text):
            print(f"bench_tables: no markers for {area} in {doc}", file=sys.stderr)
            continue
        text = pat.sub(lambda mo: mo.group(1) + body + "\n" + mo.group(2), text)
    return text


def main(argv):
    opts = {"bin": None, "millis": 300, "drag_runs": 3, "before": None}
    folder, doc, check = os.path.join(ROOT, "docs/bench"), os.path.join(ROOT, "docs/benchmarks.md"), False
    todo = [s for s in SOURCES if s not in OPTIONAL]
    args = list(argv)
    while args:
        a = args.pop(0)
        if a in ("-h", "--help"):
            sys.exit(__doc__)
        elif a == "--from":
            folder, todo = os.path.abspath(args.pop(0)), []
        elif a == "--measure":
            todo = [s for s in args.pop(0).split(",") if s]
        elif a == "--check":
            todo, check = [], True
        elif a == "--bin":
            opts["bin"] = args.pop(0)
        elif a == "--before":
            opts["before"] = args.pop(0)
        elif a == "--millis":
            opts["millis"] = int(args.pop(0))
        elif a == "--drag-runs":
            opts["drag_runs"] = int(args.pop(0))
        elif a == "--doc":
            doc = os.path.abspath(args.pop(0))
        else:
            sys.exit(f"unknown argument {a}\n{__doc__}")
    for s in todo:
        if s not in SOURCES:
            sys.exit(f"unknown source {s}: one of {', '.join(SOURCES)}")
        measure(s, folder, opts)
    text = rewrite(doc, render(folder))
    if check:
        if text != open(doc).read():
            sys.exit(f"{doc}: the tables differ from {folder}; run scripts/bench_tables.py --from {folder}")
        return
    with open(doc, "w") as f:
        f.write(text)


if __name__ == "__main__":
    main(sys.argv[1:])
