#!/usr/bin/env bash
# Drives the editor with a real pointer (xdotool) on a virtual display: run it
# inside `xvfb-run -a`. Starts a screenshot run that selects handle (0, 8) and
# reports where its arrow is, drags that arrow upwards, optionally presses Esc
# before letting go, and waits for the run to end.
# With `sphere` it drags the handle's point on the Gaussian sphere view instead.
# SHOT_ARGS adds options to the screenshot run (`--panel analysis --analysis
# reference`: the map to the reference shown while dragging).
# Usage: [SCENE=FILE.ron] [SELECT=ROW,COL] [MOVES=10 STEP_PX=9 PAUSE=0.25] [MSAA=N] [SHOT_ARGS=…] drag.sh BIN OUT.png REPORT.json [esc|sphere]
set -euo pipefail
BIN=$1; OUT=$2; REPORT=$3; ESC=${4:-}
STREAMLINE_STUDIO_SHOT_WAIT="$REPORT.done" STREAMLINE_STUDIO_SHOT_FRAMES=${FRAMES:-30} "$BIN" screenshot "${SCENE:-car1}" --out "$OUT" \
  --select "${SELECT:-0,8}" --report "$REPORT" --size "${SIZE:-900x600}" ${MSAA:+--msaa "$MSAA"} ${SHOT_ARGS:-} 2>"$REPORT.log" &
PID=$!
for _ in $(seq 1 600); do
  [ -s "$REPORT.at" ] && break
  sleep 0.2
done
if [ "$ESC" = sphere ]; then
  read -r X Y < <(sed -n 2p "$REPORT.at")
else
  read -r X Y < <(sed -n 1p "$REPORT.at")
fi
# without a window manager the keyboard goes nowhere until the window is focused
WID=$(xdotool search --name "Streamline Studio" | tail -1)
xdotool windowfocus --sync "$WID"
# generous pauses: under load llvmpipe may draw only a few frames a second, and
# the press must land in a frame where the pointer is still on the arrow
# arrive with a small wiggle so that a frame sees the pointer on the arrow
xdotool mousemove "$((X - 3))" "$Y"; sleep 0.7
xdotool mousemove "$X" "$Y"; sleep 1.5
xdotool mousedown 1; sleep 1.5
for _ in $(seq 1 "${MOVES:-10}"); do xdotool mousemove_relative -- 0 "-${STEP_PX:-9}"; sleep "${PAUSE:-0.25}"; done
sleep 1.5
if [ "$ESC" = esc ]; then xdotool key Escape; sleep 1.5; fi
xdotool mouseup 1
# let the last frames land, then let the editor take its picture and exit
sleep 2
touch "$REPORT.done"
wait "$PID"
