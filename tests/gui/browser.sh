#!/usr/bin/env bash
# The menu bar and the file browser with a real pointer (xdotool) on a virtual
# display: run it inside `xvfb-run -a`. Window 900×600, the minimal scene,
# started in a folder of its own.
#   run:     File ▸ Open…; in the browser, `/` and a typed folder (the scene's,
#            elsewhere), Enter; a click on the scene's entry, a click on Open.
#            Then File ▸ Export ▸ OBJ mesh…; the browser starts in the scene's
#            folder: the name typed over the proposed one, a click on Save.
#   menu:    File ▸ Export open, for the picture.
#   browser: File ▸ Open… with the scene's folder listed, for the picture.
#   keys:    Help ▸ Keys, for the picture.
# Usage: browser.sh BIN OUT.png REPORT.json MODE FOLDER NAME.obj
set -euo pipefail
BIN=$1; OUT=$2; REPORT=$3; MODE=$4; FOLDER=$5; NAME=$6
STREAMLINE_STUDIO_SHOT_WAIT="$REPORT.done" STREAMLINE_STUDIO_SHOT_FRAMES=${FRAMES:-30} "$BIN" screenshot "${SCENE:-minimal}" ${SHOT_ARGS:-} --out "$OUT" \
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
FILE_MENU="18 11"; HELP_MENU="130 11"
OPEN_ENTRY="50 87"; EXPORT_ENTRY="50 180"; OBJ_ENTRY="240 180"; KEYS_ENTRY="150 36"
FIRST_ENTRY="360 200"; OPEN_BUTTON="735 468"
finish() { sleep 2; touch "$REPORT.done"; wait "$PID"; exit; }
# File ▸ Open…, then `/`, the folder typed over the current one, Enter
open_folder() {
  click $FILE_MENU; click $OPEN_ENTRY; sleep 1
  xdotool key slash; sleep 1.2
  chord ctrl a
  # the browser reads Enter before the text of the same frame: let the
  # typing land first
  xdotool type --delay 60 "$FOLDER"; sleep 2
  xdotool key Return; sleep 2.5
}
case "$MODE" in
  menu) click $FILE_MENU; [ -n "${JUST_CLICK:-}" ] && finish; goto $EXPORT_ENTRY; sleep 1.5; finish ;;
  keys) click $HELP_MENU; click $KEYS_ENTRY; sleep 1; goto 880 580; finish ;;
  browser) open_folder; click $FIRST_ENTRY; finish ;;
esac
open_folder
click $FIRST_ENTRY
click $OPEN_BUTTON
sleep 3
# File ▸ Export ▸ OBJ mesh…: the name field has the focus
click $FILE_MENU; goto $EXPORT_ENTRY; sleep 1; click $OBJ_ENTRY; sleep 1.5
chord ctrl a
xdotool type --delay 60 "$NAME"; sleep 2
click $OPEN_BUTTON
sleep 3
finish
