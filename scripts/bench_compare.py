#!/usr/bin/env python3
"""`streamline-studio bench` rows of two (or more) builds side by side, in one run.

Runs the binaries' `bench --json` in turn, ROUNDS times each (old, new,
old, new, ...), so all see the same machine; a row's figure is its
smallest median over the rounds (on a shared machine the slow samples are
other programs' work), or with `--median` the median of the rounds'
medians. Prints each row's figures and their ratios to the first binary's.
`--raw FILE` writes every round's figures as JSON ({binary: [{row: ns}]}).

Build the old binary from a commit into a copy with the same target folder,
so Bevy is not built twice:

    git worktree add ../old COMMIT && (cd ../old && cargo build --release)
    cp "$CARGO_TARGET_DIR/release/streamline-studio" /tmp/ss-old
    cargo build --release
    python3 scripts/bench_compare.py /tmp/ss-old "$CARGO_TARGET_DIR/release/streamline-studio"

Usage: bench_compare.py [--median] [--raw FILE] OLD_BIN NEW_BIN [MORE_BINS...] [ROUNDS=3] [-- BENCH ARGS...]
"""

import json
import statistics
import subprocess
import sys


def run(binary, extra):
    out = subprocess.run(
        [binary, "bench", "--json", *extra], check=True, capture_output=True, text=True
    ).stdout
    return {r["name"]: r["median_ns"] for r in map(json.loads, out.splitlines())}


def main(argv):
    extra = []
    if "--" in argv:
        i = argv.index("--")
        argv, extra = argv[:i], argv[i + 1 :]
    args = argv[1:]
    median = "--median" in args
    args = [a for a in args if a != "--median"]
    raw = None
    if "--raw" in args:
        i = args.index("--raw")
        raw = args[i + 1]
        del args[i : i + 2]
    rounds = 3
    if args and args[-1].isdigit():
        rounds = int(args.pop())
    if len(args) < 2:
        sys.exit(__doc__)
    bins = args
    runs = {b: [] for b in bins}
    for _ in range(rounds):
        for b in bins:
            runs[b].append(run(b, extra))
    if raw:
        with open(raw, "w") as f:
            json.dump(runs, f, indent=1)
    pick = statistics.median if median else min
    names = [f"#{k}" for k in range(len(bins))]
    head = "".join(f" {n:>13}" for n in names)
    head += "".join(f" {n + '/#0':>8}" for n in names[1:])
    print(f"{'row':<38}{head}")
    for name in runs[bins[0]][0]:
        if not all(name in r for b in bins for r in runs[b]):
            continue
        v = [pick([r[name] for r in runs[b]]) for b in bins]
        line = "".join(f" {x:>10.0f} ns" for x in v)
        line += "".join(f" {x / v[0]:>8.3f}" for x in v[1:])
        print(f"{name:<38}{line}")
    for n, b in zip(names, bins):
        print(f"{n}: {b}")


if __name__ == "__main__":
    main(sys.argv)
