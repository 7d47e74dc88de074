#!/usr/bin/env python3
"""Figures of drag runs (issue 4, item 9) from `screenshot --report` files.

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

Usage: drag_figures.py REPORT.json [REPORT.json ...]
"""

import json
import statistics
import sys

BUDGET_MS = 4.0
STEADY = 1.5
QUIET = 1.1


def pct(sorted_values, p):
    return sorted_values[int(p * (len(sorted_values) - 1))]


def line(name, values):
    s = sorted(values)
    over = sum(v > BUDGET_MS for v in s)
    return (
        f"{name}: {len(s)} frames, median {statistics.median(s):.2f} ms, "
        f"p90 {pct(s, 0.9):.2f}, p99 {pct(s, 0.99):.2f}, largest {s[-1]:.2f}, "
        f"over {BUDGET_MS:g} ms: {over}"
    )


def main(paths):
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
