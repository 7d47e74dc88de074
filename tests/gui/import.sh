#!/usr/bin/env bash
# File ▸ Import surface… with a real pointer (xdotool) on a virtual display:
# run it inside `xvfb-run -a`. Window 900×600, the minimal scene.
#   dialog: File ▸ Import surface… (the menu bar); in the file browser `/`,
#           the file's path typed, Enter: the Import surface dialog lists its
#           faces; left open for the picture.
#   fit:    as dialog, then a click on Fit; the fit runs on its own thread
#           and the design it makes replaces the scene.
# Usage: import.sh BIN OUT.png REPORT.json MODE FILE
set -euo pipefail
BIN=$1; OUT=$2; REPORT=$3; MODE=$4; FILE=$5
STREAMLINE_STUDIO_SHOT_WAIT="$REPORT.done" STREAMLINE_STUDIO_SHOT_FRAMES=${FRAMES:-30} "$BIN" screenshot minimal ${SHOT_ARGS:-} --out "$OUT" \
  --select 0,0 --report "$REPORT" --size 900x600 2>"$REPORT.log" &
PID=$!
for _ in $(seq 1 600); do
  [ -s "$REPORT.at" ] && break
  sleep 0.2
done
# without a window manager the keyboard goes nowhere until the window is focused
WID=$(xdotool search --name "Streamline Studio" | tail -1)
xdotool windowfocus --sync "$WID"
# generous pauses: under load llvmpipe may draw only a few frames a second;
# arrive with a wiggle so that a frame sees the pointer where it stops
goto() { xdotool mousemove "$(($1 - 2))" "$2"; sleep 0.6; xdotool mousemove "$1" "$2"; sleep 0.9; }
click() { goto "$1" "$2"; xdotool click 1; sleep 1.5; }
chord() { xdotool keydown "$1"; sleep 0.6; xdotool key "$2"; sleep 0.6; xdotool keyup "$1"; sleep 1; }
# where things are in a 900×600 window (egui's default style)
FILE_MENU="18 11"; IMPORT_ENTRY="60 252"; FIT_BUTTON=${FIT_BUTTON:-"0 0"}
click $FILE_MENU; click $IMPORT_ENTRY; sleep 1
# the path field: `/`, the path typed over the folder, Enter picks the file
xdotool key slash; sleep 1.2
chord ctrl a
# the browser reads Enter before the text of the same frame: let it land
xdotool type --delay 60 "$FILE"; sleep 2
xdotool key Return; sleep 3
if [ "$MODE" = fit ]; then
  click $FIT_BUTTON
  # the fit runs off the frame: wait for it (hood.step takes well under a minute)
  sleep "${FIT_WAIT:-20}"
fi
# a pointer away from the dialog, the last frames, then the picture
goto 880 580
sleep 2
touch "$REPORT.done"
wait "$PID"
