#!/usr/bin/env bash
# The B-spline fit of CAD export beside OpenCascade's, in one run
# (docs/cad.md): for car1 and car2 at depth 5 (161 × 258 points), our fit
# (`streamline-studio bench --filter fit/` for its time, `build --export
# .step` for its net) and OpenCascade's GeomAPI_PointsToBSplineSurface
# (degree 3–8, C2, the same tolerance) on the same grid; both surfaces'
# deviations measured the same way, by OpenCascade's projection of the
# depth-5 and depth-6 points. Uses the test virtual environment
# (scripts/venv.sh). With --json it prints only one JSON object a scene
# (scripts/bench_tables.py reads them). STREAMLINE_STUDIO_BIN names a built
# binary to use instead of building one.
# Usage: bash scripts/cad_peers.sh [--json]
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
"$BIN" bench --json --filter fit/ --millis 2000 > "$OUT/ours.jsonl"
for s in car1 car2; do
  "$BIN" build "$s" --depth 5 --export "$OUT/$s.step" > "$OUT/$s.json"
  "$BIN" build "$s" --depth 5 --export "$OUT/$s-d5.obj" > "$OUT/$s-d5.json"
  "$BIN" build "$s" --depth 6 --export "$OUT/$s-d6.obj" > /dev/null
done
"$VENV/bin/python" scripts/cad_peers.py "$OUT" "$@"
