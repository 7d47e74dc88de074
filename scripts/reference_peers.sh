#!/usr/bin/env bash
# Our fit of a reference beside OpenCascade's grid fitter, in one run
# (docs/fit.md, docs/benchmarks.md): for the three shipped faces
# (scenes/references/), our fit (`streamline-studio bench --filter
# reference-` for its time, `fit --json` for its net and deviation, `build
# --depth 5` for the mesh's size) and OpenCascade's
# GeomAPI_PointsToBSplineSurface (degree 3–8, C2, the same tolerance) on the
# face sampled on a grid as dense as that mesh (scripts/reference_peers.py).
# Uses the test virtual environment (scripts/venv.sh). With --json it prints
# only one JSON object a face and the bench rows (scripts/bench_tables.py
# reads them). STREAMLINE_STUDIO_BIN names a built binary to use instead of
# building one.
# Usage: bash scripts/reference_peers.sh [--json]
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/venv.sh
VENV="${STREAMLINE_VENV:-$HOME/.cache/streamline-venv}"
BIN="${STREAMLINE_STUDIO_BIN:-}"
if [ -z "$BIN" ]; then
  cargo build --release -q
  BIN="${CARGO_TARGET_DIR:-target}/release/streamline-studio"
fi
OUT="$(mktemp -d)"
trap 'rm -rf "$OUT"' EXIT
"$BIN" bench --json --filter reference- --millis 2000 > "$OUT/ours.jsonl"
for f in hood.step duct.igs roof.step; do
  s="${f%.*}"
  "$BIN" fit "scenes/references/$f" --out "$OUT/$s.ron" --json > "$OUT/$s.json"
  "$BIN" build "$OUT/$s.ron" --depth 5 --export "$OUT/$s-d5.obj" > "$OUT/$s-d5.json"
done
if [ "${1:-}" = "--json" ]; then
  cat "$OUT/ours.jsonl"
fi
"$VENV/bin/python" scripts/reference_peers.py "$OUT" "$@"
