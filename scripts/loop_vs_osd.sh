#!/usr/bin/env bash
# Loop subdivision, ours beside OpenSubdiv's: compiles the OpenSubdiv
# oracle (tests/oracle/osd_loop.cpp, Debian's libosd-dev: `bash scripts/setup.sh
# --tests`) and prints a Markdown table of the best of 15 runs (3 rounds of 5, alternating), one thread, at
# levels 1–3, building the topology from the face list included, for each
# boundary rule, on meshes of 10k–35k vertices (docs/loop.md "Speed"). With
# --json, one JSON object a row of that table instead (mesh, vertices, rule,
# level, vertices_out, ours_ms, osd_ms; scripts/bench_tables.py reads them).
# Usage: bash scripts/loop_vs_osd.sh [--json] [MESH.obj[:k] …]
set -euo pipefail
cd "$(dirname "$0")/.."
TARGET="${CARGO_TARGET_DIR:-target}"
mkdir -p "$TARGET/oracle"
BIN="$TARGET/oracle/osd_loop"
if [ ! -x "$BIN" ] || [ tests/oracle/osd_loop.cpp -nt "$BIN" ]; then
  g++ -O2 -std=c++14 tests/oracle/osd_loop.cpp -o "$BIN" -losdCPU
fi
JSON=
if [ "${1:-}" = --json ]; then
  JSON=1
  shift
fi
D=tests/data/meshes
if [ $# -eq 0 ]; then
  set -- $D/camelhead.obj $D/spot.obj:1 $D/fertility.obj:1 $D/fairing-cross.obj:1 $D/max-planck.obj:1
fi
if [ -z "$JSON" ]; then
  cargo run -q -p streamline-kernel --release --example loop_timing -- --osd "$BIN" "$@"
  exit
fi
# the example's Markdown rows, one JSON object each
cargo run -q -p streamline-kernel --release --example loop_timing -- --osd "$BIN" "$@" | python3 -c '
import json, sys
for line in sys.stdin:
    c = [x.strip() for x in line.strip().strip("|").split("|")]
    if len(c) != 8 or not c[1].isdigit():
        continue
    print(json.dumps({"mesh": c[0], "vertices": int(c[1]), "rule": c[2], "level": int(c[3]),
                      "vertices_out": int(c[4]), "ours_ms": float(c[5].split()[0]),
                      "osd_ms": float(c[6].split()[0])}), flush=True)
'

