#!/usr/bin/env bash
# The reference's ghost and File ▸ Reference… with a real pointer (xdotool)
# on a virtual display: run it inside `xvfb-run -a`. Window 900×600,
# scenes/references/hood.ron with a tangent turned (a script), so that the
# design leaves its reference.
#   ghost:  View ▸ Reference ticked (the menu bar): the face drawn as a
#           translucent ghost over the design; the menu closed.
#   dialog: File ▸ Reference… (the menu bar); in the file browser `/`, the
#           file's path typed, Enter: the Reference dialog lists its faces,
#           the chosen one drawn as the ghost in the preview colour; left
#           open for the picture.
# Usage: [ZOOM=N] [VIEW_MENU="X Y"] [GHOST_ENTRY="X Y [X Y…]"] [REFERENCE_ENTRY="X Y"]
#        ghost.sh BIN OUT.png REPORT.json MODE [FILE]
set -euo pipefail
BIN=$1; OUT=$2; REPORT=$3; MODE=$4; FILE=${5:-}
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
SCRIPT=$(mktemp --suffix=.ron)
trap 'rm -f "$SCRIPT"' EXIT
# a tangent turned about y: the surface leaves the face
echo '(steps: [Rotate(row: 2, col: 4, axis: (0.0, 1.0, 0.0), degrees: 25.0), Rotate(row: 5, col: 6, axis: (0.0, 1.0, 0.0), degrees: -20.0)])' > "$SCRIPT"
STREAMLINE_STUDIO_SHOT_WAIT="$REPORT.done" STREAMLINE_STUDIO_SHOT_FRAMES=${FRAMES:-30} "$BIN" screenshot \
  "$ROOT/scenes/references/hood.ron" ${SHOT_ARGS:-} --script "$SCRIPT" --out "$OUT" \
  --report "$REPORT" --size 900x600 2>"$REPORT.log" &
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
FILE_MENU="18 11"
VIEW_MENU=${VIEW_MENU:-"94 11"}
GHOST_ENTRY=${GHOST_ENTRY:-"0 0"}
REFERENCE_ENTRY=${REFERENCE_ENTRY:-"0 0"}
case "$MODE" in
  ghost)
    if [ "$GHOST_ENTRY" = "0 0" ]; then click $VIEW_MENU; fi
    # GHOST_ENTRY: one or more "X Y" entries of the View menu ticked in turn
    # (the menu opened for each; a click in it may close it)
    set -- $GHOST_ENTRY
    while [ "$GHOST_ENTRY" != "0 0" ] && [ $# -ge 2 ]; do
      click $VIEW_MENU; click "$1" "$2"; shift 2
      xdotool key Escape; sleep 1
    done
    # ZOOM: wheel steps in, over the 3D view
    for _ in $(seq 1 "${ZOOM:-0}"); do goto 620 330; xdotool click 4; sleep 0.5; done
    ;;
  dialog)
    click $FILE_MENU
    if [ "$REFERENCE_ENTRY" != "0 0" ]; then
      click $REFERENCE_ENTRY; sleep 1
      # the path field: `/`, the path typed over the folder, Enter picks the file
      xdotool key slash; sleep 1.2
      chord ctrl a
      xdotool type --delay 60 "$FILE"; sleep 2
      xdotool key Return; sleep 3
    fi
    ;;
esac
# a pointer away from the dialog, the last frames, then the picture
if [ "$GHOST_ENTRY" != "0 0" ] || [ "$REFERENCE_ENTRY" != "0 0" ]; then goto 880 580; fi
sleep 2
touch "$REPORT.done"
wait "$PID"
