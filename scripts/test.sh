#!/usr/bin/env bash
# The README's second command: set up and run every test (kernel property tests,
# command-line tests, playback and editor tests) in the release profile, the same
# profile the editor runs in, so a newcomer compiles Bevy once.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh --tests
cargo test --release --workspace
