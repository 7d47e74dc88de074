#!/usr/bin/env bash
# Drives the file browser with the keyboard on a virtual display (run inside
# `xvfb-run -a`): Ctrl+O, `/` (the path field), Ctrl+A, type a scene path,
# Enter (opens it); then Ctrl+Shift+S, clear the proposed name, type SAVE (a
# whole path), Enter (saves it there).
# Usage: files.sh BIN OUT.png REPORT.json OPEN.ron SAVE.ron
set -euo pipefail
BIN=$1; OUT=$2; REPORT=$3; OPEN=$4; SAVE=$5
STREAMLINE_STUDIO_SHOT_WAIT="$REPORT.done" STREAMLINE_STUDIO_SHOT_FRAMES=${FRAMES:-30} "$BIN" screenshot minimal --out "$OUT" \
  --select 0,0 --report "$REPORT" --size 900x600 2>"$REPORT.log" &
PID=$!
for _ in $(seq 1 600); do
  [ -s "$REPORT.at" ] && break
  sleep 0.2
done
# without a window manager the keyboard goes nowhere until the window is focused
WID=$(xdotool search --name "Streamline Studio" | tail -1)
xdotool windowfocus --sync "$WID"
xdotool mousemove 600 120; sleep 1
# modifiers are held across frames (llvmpipe draws a few frames a second)
chord() { xdotool keydown "$1"; sleep 0.6; xdotool key "$2"; sleep 0.6; xdotool keyup "$1"; sleep 1; }
chord ctrl o; sleep 1
xdotool key slash; sleep 1.2
chord ctrl a
# the browser reads Enter before the text of the same frame: let it land
xdotool type --delay 80 "$OPEN"; sleep 2
xdotool key Return; sleep 3
chord ctrl+shift s; sleep 1
# clear the proposed name (the name field has the focus)
xdotool key End; sleep 0.3; xdotool key --delay 40 --repeat 200 BackSpace; sleep 1
xdotool type --delay 80 "$SAVE"; sleep 1
xdotool key Return; sleep 3
# let the last frames land, then let the editor take its picture and exit
sleep 2
touch "$REPORT.done"
wait "$PID"
