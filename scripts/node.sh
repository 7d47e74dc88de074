#!/usr/bin/env bash
# The test node folder: the Khronos glTF validator (npm `gltf-validator`, the
# version pinned in tests/node/package.json) that tests/cad_document.rs checks
# our .glb files with. It lives outside the clone, so fresh clones share it:
# $STREAMLINE_NODE, default ~/.cache/streamline-node. Installs only what is
# missing (a stamp file holds the hash of the package.json it was made from).
# Prints nothing when it is already up to date.
set -euo pipefail
cd "$(dirname "$0")/.."
dir="${STREAMLINE_NODE:-$HOME/.cache/streamline-node}"
pkg=tests/node/package.json
want="$(sha256sum "$pkg" | cut -d' ' -f1)"
if [ -f "$dir/node_modules/gltf-validator/package.json" ] && [ "$(cat "$dir/.package-sha256" 2>/dev/null)" = "$want" ]; then
  exit 0
fi
command -v node >/dev/null && command -v npm >/dev/null || {
  echo "setup: node and npm not found; install Node.js 18 or later (Debian: nodejs npm)" >&2; exit 1; }
echo "setup: installing the Khronos glTF validator into $dir (npm gltf-validator, ~3 MB)" >&2
mkdir -p "$dir"
cp "$pkg" "$dir/package.json"
if ! (cd "$dir" && npm install --no-audit --no-fund --silent >/dev/null); then
  echo "setup: npm could not install gltf-validator into $dir (offline? npm's registry unreachable?); connect and run 'bash scripts/setup.sh --tests' again" >&2
  exit 1
fi
echo "$want" > "$dir/.package-sha256"
