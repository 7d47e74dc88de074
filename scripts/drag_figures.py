#!/usr/bin/env python3
"""Figures of drag runs from `screenshot --report` files.

Each report comes from `tests/gui/drag.sh` run with
`STREAMLINE_STUDIO_METER_DETAIL=1`, e.g. (the car at display depth 5):

    STREAMLINE_STUDIO_METER_DETAIL=1 MOVES=80 STEP_PX=3 PAUSE=0.12 SELECT=2,4 \\
      SCENE=car1-d5.ron xvfb-run -a -s "-screen 0 1280x800x24" \\
      bash tests/gui/drag.sh BIN out.png report.json

Prints, over all frames with an edit: the CPU time of our systems (median,
90th and 99th percentile, largest, frames over 4 ms), each system's mean, and
the speed probe's verdict: a frame is "steady" when the fixed piece of work
run at four points of it took at most 1.5 times its usual time (the median
over all frames of each frame's fastest probe). Two more lines help judge
the frames the machine slowed: the "quiet" frames (every probe within 1.1
times its usual time), and every frame divided by its probes' mean slowdown.

With `--json` it prints the same figures as one JSON object instead
(`scripts/bench_tables.py` keeps it in docs/bench/drag.jsonl): "all",
"steady", "quiet" and "scaled" each hold frames, median, p90, p99, largest
and over_budget (ms); "usual_probe_us", "systems" (the ten dearest
systems' means, ms a frame) and "slow_frames" (each frame over the budget
with its probes' slowdowns).

Usage: drag_figures.py [--json] REPORT.json [REPORT.json ...]
"""

import json
import statistics
import sys

BUDGET_MS = 4.0
STEADY = 1.5
QUIET = 1.1


def pct(sorted_values, p):
    return sorted_values[int(p * (len(sorted_values) - 1))]


def figures(values):
    s = sorted(values)
    return {
        "frames": len(s),
        "median": statistics.median(s),
        "p90": pct(s, 0.9),
        "p99": pct(s, 0.99),
        "largest": s[-1],
        "over_budget": sum(v > BUDGET_MS for v in s),
    }


def line(name, values):
    f = figures(values)
    return (
        f"{name}: {f['frames']} frames, median {f['median']:.2f} ms, "
        f"p90 {f['p90']:.2f}, p99 {f['p99']:.2f}, largest {f['largest']:.2f}, "
        f"over {BUDGET_MS:g} ms: {f['over_budget']}"
    )


def as_json(frames, probes, systems):
    out = {"budget_ms": BUDGET_MS, "steady_within": STEADY, "quiet_within": QUIET}
    out["all"] = figures(frames)
    top = sorted(systems.items(), key=lambda kv: -kv[1][0])[:10]
    out["systems"] = {name.split("src/")[-1]: total / max(n, 1) for name, (total, n) in top}
    known = [(ms, p) for ms, p in zip(frames, probes) if p]
    if known:
        usual = statistics.median(min(p) for _, p in known)
        out["usual_probe_us"] = usual
        steady = [ms for ms, p in known if max(p) <= STEADY * usual]
        quiet = [ms for ms, p in known if max(p) <= QUIET * usual]
        out["steady"] = figures(steady) if steady else None
        out["quiet"] = figures(quiet) if quiet else None
        out["scaled"] = figures([ms * usual * len(p) / sum(p) for ms, p in known])
        out["slow_frames"] = [
            {"ms": ms, "probes": [x / usual for x in p]}
            for ms, p in sorted(known, key=lambda x: -x[0])
            if ms > BUDGET_MS
        ]
    print(json.dumps(out))


def main(paths):
    want_json = "--json" in paths
    paths = [p for p in paths if p != "--json"]
    if not paths:
        sys.exit(__doc__)
    frames, probes, systems = [], [], {}
    for path in paths:
        with open(path) as f:
            r = json.load(f)
        ms = r["ours_frames"]
        frames += ms
        p = r.get("frame_probe") or []
        probes += p if len(p) == len(ms) else [None] * len(ms)
        for name, total, _largest, n in r.get("detail", []):
            t = systems.setdefault(name, [0.0, 0])
            t[0] += total
            t[1] += n
    if not frames:
        sys.exit("no frames with an edit in these reports")
    if want_json:
        as_json(frames, probes, systems)
        return
    print(line("all frames", frames))
    for name, (total, n) in sorted(systems.items(), key=lambda kv: -kv[1][0])[:10]:
        print(f"  {name.split('src/')[-1]:34s} mean {total / max(n, 1):.3f} ms")
    known = [(ms, p) for ms, p in zip(frames, probes) if p]
    if not known:
        return
    usual = statistics.median(min(p) for _, p in known)
    steady = [ms for ms, p in known if max(p) <= STEADY * usual]
    print(f"speed probe: usual {usual:.0f} µs")
    print(line(f"steady frames (every probe within {STEADY}x)", steady))
    quiet = [ms for ms, p in known if max(p) <= QUIET * usual]
    if quiet:
        print(line(f"quiet frames (every probe within {QUIET}x)", quiet))
    scaled = [ms * usual * len(p) / sum(p) for ms, p in known]
    print(line("all frames divided by their probes' mean slowdown", scaled))
    for ms, p in sorted(known, key=lambda x: -x[0]):
        if ms <= BUDGET_MS:
            break
        slow = " ".join(f"{x / usual:.2f}" for x in p)
        print(f"  {ms:.2f} ms: probes at {slow} times their usual time")


if __name__ == "__main__":
    main(sys.argv[1:] or sys.exit(__doc__))
