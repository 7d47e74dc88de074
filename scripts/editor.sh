#!/usr/bin/env bash
# The README's first command: set up, build (release) and open the editor on the
# built-in car scene. Extra arguments go to the binary (e.g. a scene file).
# The first build compiles Bevy: about 25 minutes on 2 cores with nothing cached
# (docs/benchmarks.md, "Building"); later runs start at once.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
if [ -z "${DISPLAY:-}" ] && [ -z "${WAYLAND_DISPLAY:-}" ]; then
  echo "editor: no display found; running on a virtual X display (xvfb-run)." >&2
  exec xvfb-run -a -s "-screen 0 1280x800x24" cargo run --release -- "$@"
fi
exec cargo run --release -- "$@"
