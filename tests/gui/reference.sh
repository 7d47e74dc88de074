#!/usr/bin/env bash
# Analysis ▸ to reference with a real pointer (xdotool) on a virtual display:
# run it inside `xvfb-run -a`. Window 900×600, the minimal scene, the
# Analysis section open. Each step does what the ones before it do, then
# the picture is taken:
#   dialog:  File ▸ Import surface… (the menu bar); in the file browser `/`,
#            the file's path typed, Enter: the Import surface dialog lists
#            its faces.
#   fitted:  Fit clicked; the fit runs on its own thread and the design it
#            makes replaces the scene; the dialog closed, Frame all, and
#            "to reference" clicked in the Analysis section: the map, green.
#   dragged: the selected handle's arrow (where `REPORT.at` says, kept up to
#            date by STREAMLINE_STUDIO_SHOT_FOLLOW) pressed and dragged up:
#            the map, red where the surface left the face (measured when
#            the drag ends: the drag moves more points than a frame measures).
#   undone:  Ctrl+Z: green again.
# Usage: [SELECT=R,C] [FIT_BUTTON="X Y"] [CLOSE_BUTTON="X Y"] [REFERENCE_RADIO="X Y"] [HANDLE="X Y"]
#        reference.sh BIN OUT.png REPORT.json STEP FILE
set -euo pipefail
BIN=$1; OUT=$2; REPORT=$3; STEP=$4; FILE=$5
rm -f "$REPORT" "$REPORT.at" "$REPORT.done"
STREAMLINE_STUDIO_SHOT_FOLLOW=1 STREAMLINE_STUDIO_SHOT_WAIT="$REPORT.done" STREAMLINE_STUDIO_SHOT_FRAMES=${FRAMES:-30} "$BIN" screenshot minimal \
  --panel analysis --out "$OUT" --select "${SELECT:-0,0}" --report "$REPORT" --size 900x600 2>"$REPORT.log" &
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
FILE_MENU="18 11"; IMPORT_ENTRY="60 252"
FIT_BUTTON=${FIT_BUTTON:-"216 400"}; CLOSE_BUTTON=${CLOSE_BUTTON:-"255 417"}; FRAME_ALL="346 34"
REFERENCE_RADIO=${REFERENCE_RADIO:-"140 246"}
click $FILE_MENU; click $IMPORT_ENTRY; sleep 1
# the path field: `/`, the path typed over the folder, Enter picks the file
xdotool key slash; sleep 1.2
chord ctrl a
# the browser reads Enter before the text of the same frame: let it land
xdotool type --delay 60 "$FILE"; sleep 2
xdotool key Return; sleep 3
if [ "$STEP" != dialog ]; then
  click $FIT_BUTTON
  # the fit runs off the frame: wait for it (hood.step takes well under a minute)
  sleep "${FIT_WAIT:-20}"
  # the dialog says what it imported: closed; the view framed on the design
  click $CLOSE_BUTTON
  click $FRAME_ALL
  click $REFERENCE_RADIO
  sleep 2
fi
if [ "$STEP" = dragged ] || [ "$STEP" = undone ]; then
  # the selected handle's arrow (REPORT.at follows it), unless HANDLE says where
  if [ -n "${HANDLE:-}" ]; then read -r X Y <<<"$HANDLE"; else read -r X Y < <(sed -n 1p "$REPORT.at"); fi
  xdotool mousemove "$((X - 3))" "$Y"; sleep 0.7
  xdotool mousemove "$X" "$Y"; sleep 1.5
  xdotool mousedown 1; sleep 1.5
  for _ in $(seq 1 "${MOVES:-10}"); do xdotool mousemove_relative -- 0 "-${STEP_PX:-6}"; sleep 0.25; done
  sleep 1.5
  xdotool mouseup 1
  # the map is measured when the drag ends
  sleep 3
fi
if [ "$STEP" = undone ]; then
  chord ctrl z
  sleep 3
fi
# a pointer away from the dialog and the arrows, the last frames, then the picture
goto 880 580
sleep 2
touch "$REPORT.done"
wait "$PID"
