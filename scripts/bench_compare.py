#!/usr/bin/env python3
"""`streamline-studio bench` rows of two builds side by side, in one run.

Runs the two binaries' `bench --json` in turn, ROUNDS times each (old, new,
old, new, ...), so both see the same machine; a row's figure is its
smallest median over the rounds (on a shared machine the slow samples are
other programs' work). Prints each row's two figures and their ratio.

Build the old binary from a commit into a copy with the same target folder,
so Bevy is not built twice:

    git worktree add ../old COMMIT && (cd ../old && cargo build --release)
    cp "$CARGO_TARGET_DIR/release/streamline-studio" /tmp/ss-old
    cargo build --release
    python3 scripts/bench_compare.py /tmp/ss-old "$CARGO_TARGET_DIR/release/streamline-studio"

Usage: bench_compare.py OLD_BIN NEW_BIN [ROUNDS=3] [-- BENCH ARGS...]
"""

import json
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
    if len(argv) < 3:
        sys.exit(__doc__)
    old_bin, new_bin = argv[1], argv[2]
    rounds = int(argv[3]) if len(argv) > 3 else 3
    old, new = [], []
    for _ in range(rounds):
        old.append(run(old_bin, extra))
        new.append(run(new_bin, extra))
    print(f"{'row':<38} {'old':>13} {'new':>13} {'new/old':>8}")
    for name in old[0]:
        if not all(name in r for r in old + new):
            continue
        a = min(r[name] for r in old)
        b = min(r[name] for r in new)
        print(f"{name:<38} {a:>10.0f} ns {b:>10.0f} ns {b / a:>8.3f}")


if __name__ == "__main__":
    main(sys.argv)
