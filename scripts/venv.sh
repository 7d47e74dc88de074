#!/usr/bin/env bash
# The test virtual environment: a Python 3 venv holding the outside readers the
# tests check our files with (tests/python/requirements.txt: OpenCascade's OCP,
# Pixar's usd-core). It lives outside the clone, so fresh clones share it:
# $STREAMLINE_VENV, default ~/.cache/streamline-venv. Installs only what is missing
# (a stamp file holds the hash of the requirements it was made from).
# Prints nothing when it is already up to date.
set -euo pipefail
cd "$(dirname "$0")/.."
venv="${STREAMLINE_VENV:-$HOME/.cache/streamline-venv}"
req=tests/python/requirements.txt
want="$(sha256sum "$req" | cut -d' ' -f1)"
if [ -x "$venv/bin/python" ] && [ "$(cat "$venv/.requirements-sha256" 2>/dev/null)" = "$want" ]; then
  exit 0
fi
py="$(command -v python3 || true)"
[ -n "$py" ] || { echo "setup: python3 not found; install Python 3.11 (Debian: python3 python3-venv)" >&2; exit 1; }
echo "setup: making the test virtual environment in $venv (OpenCascade, USD: ~100 MB)" >&2
"$py" -m venv "$venv"
"$venv/bin/python" -m pip install -q --disable-pip-version-check -r "$req"
echo "$want" > "$venv/.requirements-sha256"
