#!/usr/bin/env bash
# Loop subdivision, ours beside the peers, in one run: installs trimesh and
# pymeshlab into a virtual environment (.venv-peers, ignored by git), times
# 1, 2 and 3 levels on a small, a medium and the largest test mesh with each,
# and prints a table with `streamline-studio bench`'s figures for the same
# work; with --json, one JSON object a row (scripts/bench_tables.py reads it).
# STREAMLINE_STUDIO_BIN names a built binary to time instead of building one.
# Usage: bash scripts/peers.sh [--json]
set -euo pipefail
cd "$(dirname "$0")/.."
VENV=.venv-peers
if [ ! -x "$VENV/bin/python" ]; then
  python3 -m venv "$VENV"
  "$VENV/bin/pip" install -q trimesh pymeshlab numpy
fi
BIN="${STREAMLINE_STUDIO_BIN:-}"
if [ -z "$BIN" ]; then
  cargo build --release -q
  BIN="${CARGO_TARGET_DIR:-target}/release/streamline-studio"
fi
"$BIN" bench --json --filter loop/subdivide --millis 1000 > "$VENV/ours.jsonl"
"$VENV/bin/python" scripts/peers.py "$VENV/ours.jsonl" "$@"
