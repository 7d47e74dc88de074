#!/usr/bin/env bash
# Loop subdivision, ours beside OpenSubdiv's (issue 22): compiles the OpenSubdiv
# oracle (tests/oracle/osd_loop.cpp, Debian's libosd-dev: `bash scripts/setup.sh
# --tests`) and prints a Markdown table of the best of 15 runs (3 rounds of 5, alternating), one thread, at
# levels 1–3, building the topology from the face list included, for each
# boundary rule, on meshes of 10k–35k vertices (docs/loop.md "Speed").
# Usage: bash scripts/loop_vs_osd.sh [MESH.obj[:k] …]
set -euo pipefail
cd "$(dirname "$0")/.."
TARGET="${CARGO_TARGET_DIR:-target}"
mkdir -p "$TARGET/oracle"
BIN="$TARGET/oracle/osd_loop"
if [ ! -x "$BIN" ] || [ tests/oracle/osd_loop.cpp -nt "$BIN" ]; then
  g++ -O2 -std=c++14 tests/oracle/osd_loop.cpp -o "$BIN" -losdCPU
fi
D=tests/data/meshes
if [ $# -eq 0 ]; then
  set -- $D/camelhead.obj $D/spot.obj:1 $D/fertility.obj:1 $D/fairing-cross.obj:1 $D/max-planck.obj:1
fi
cargo run -q -p streamline-kernel --release --example loop_timing -- --osd "$BIN" "$@"
