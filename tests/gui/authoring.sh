#!/usr/bin/env bash
# Drives the authoring tools with a real pointer (xdotool) on a virtual
# display: run it inside `xvfb-run -a`. Window 900×600, the File section open.
#   new:    File ▸ New design… (the menu bar), rows 4, columns 7, width 3, Create, then
#           Ctrl+S and a typed path (a new design has no file yet), Enter.
#   insert: opens SCENE with arrow (1, 3) selected, right-clicks that arrow,
#           picks "Insert row after" from its menu, saves (Ctrl+S).
#   menu:   as insert, but leaves the menu open for the picture.
#   dialog: opens the New design dialog, picks Cylinder, leaves it open.
# Usage: authoring.sh BIN OUT.png REPORT.json new SAVE.ron
#        authoring.sh BIN OUT.png REPORT.json insert SCENE.ron
set -euo pipefail
BIN=$1; OUT=$2; REPORT=$3; MODE=$4; FILE=$5
case "$MODE" in new|dialog) SCENE=minimal ;; *) SCENE=$FILE ;; esac
STREAMLINE_STUDIO_SHOT_WAIT="$REPORT.done" STREAMLINE_STUDIO_SHOT_FRAMES=${FRAMES:-30} "$BIN" screenshot "$SCENE" --out "$OUT" \
  --select 1,3 --panel file --report "$REPORT" --size 900x600 2>"$REPORT.log" &
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
# a DragValue clicked becomes a text field: clear it, type, Enter
field() {
  click "$1" "$2"
  xdotool key --delay 60 End; xdotool key --delay 60 --repeat 8 BackSpace; sleep 0.4
  xdotool type --delay 80 "$3"; sleep 0.4; xdotool key Return; sleep 1
}
chord() { xdotool keydown "$1"; sleep 0.6; xdotool key "$2"; sleep 0.6; xdotool keyup "$1"; sleep 1; }
if [ "$MODE" = dialog ]; then
  click 18 11; click 55 36; click 467 290
elif [ "$MODE" = new ]; then
  click 18 11     # File (the menu bar)
  click 55 36     # New design…
  field 431 242 4 # rows
  field 431 266 7 # columns
  field 431 314 3 # width
  click 310 392   # Create
  sleep 2
  chord ctrl s; sleep 1
  # clear the proposed name in the file browser (End: past its extension), type the file
  xdotool key End; sleep 0.3; xdotool key --delay 40 --repeat 200 BackSpace; sleep 1
  xdotool type --delay 80 "$FILE"; sleep 1
  xdotool key Return; sleep 3
else
  read -r X Y < <(sed -n 1p "$REPORT.at")
  goto "$X" "$Y"
  # a right click (press and release in place) opens the arrow's menu
  xdotool mousedown 3; sleep 0.8; xdotool mouseup 3; sleep 1.5
  if [ "$MODE" = menu ]; then sleep 2; touch "$REPORT.done"; wait "$PID"; exit; fi
  # its entries start just below and right of the pointer: a label, then
  # "Insert row before", "Insert row after"
  click "$((X + 40))" "$((Y + ${AFTER_DY:-52}))"
  sleep 2
  chord ctrl s; sleep 2
fi
# let the last frames land, then let the editor take its picture and exit
sleep 2
touch "$REPORT.done"
wait "$PID"
