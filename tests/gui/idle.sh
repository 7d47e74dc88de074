#!/usr/bin/env bash
# The editor rests when nobody touches it and wakes on input (run inside
# `xvfb-run -a`): opens the interactive editor (not `screenshot`, which draws
# every frame) on SCENE, lets the start settle, counts the CPU it takes over
# five idle seconds, then saves the scene to SAVE with Ctrl+Shift+S, a path
# typed into the file browser's name field and Enter, and counts the CPU of
# that too.
# Prints "idle TICKS" and "busy TICKS" (1/100 s); the caller checks SAVE.
# Usage: idle.sh BIN SCENE.ron SAVE.ron
set -euo pipefail
BIN=$1; SCENE=$2; SAVE=$3
STREAMLINE_STUDIO_HOME=$(mktemp -d)
export STREAMLINE_STUDIO_HOME
"$BIN" "$SCENE" 2>"$SAVE.log" &
PID=$!
trap 'kill $PID 2>/dev/null || true' EXIT
ticks() { awk '{print $14 + $15}' "/proc/$PID/stat"; }
WID=""
for _ in $(seq 1 300); do
  WID=$(xdotool search --name "Streamline Studio" 2>/dev/null | tail -1 || true)
  [ -n "$WID" ] && break
  sleep 0.2
done
[ -n "$WID" ] || { echo "no editor window" >&2; cat "$SAVE.log" >&2; exit 1; }
xdotool windowfocus --sync "$WID"
xdotool mousemove 640 400
# the first pipelines compile while the editor draws for its first seconds
sleep 12
a=$(ticks); sleep 5; b=$(ticks)
echo "idle $((b - a))"
chord() { xdotool keydown "$1"; sleep 0.6; xdotool key "$2"; sleep 0.6; xdotool keyup "$1"; sleep 1; }
a=$(ticks)
chord ctrl+shift s; sleep 1
xdotool key End; sleep 0.3; xdotool key --delay 40 --repeat 200 BackSpace; sleep 1
xdotool type --delay 80 "$SAVE"; sleep 1
xdotool key Return
for _ in $(seq 1 50); do
  [ -s "$SAVE" ] && break
  sleep 0.2
done
b=$(ticks)
echo "busy $((b - a))"
