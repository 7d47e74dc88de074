#!/usr/bin/env bash
# Pictures of scenes/hood-screen-wing.ron that need a real pointer (xdotool)
# on a virtual display, for scripts/screenshots.sh: run it inside
# `xvfb-run -a`. Window 1280×800.
#   new:         the Patches section open; a click on `wing` in its list,
#                a click on "New patch on an edge of `wing`…": the form.
#   right-click: the default sections open; a right click on the hood's End
#                edge (the G2 seam, between two of its arrows) opens the
#                Patches section's form on that edge.
# Usage: patches-pointer.sh BIN OUT.png REPORT.json new|right-click
# (RIGHT_CLICK="X Y" moves the right click.)
set -euo pipefail
BIN=$1; OUT=$2; REPORT=$3; MODE=$4
SCENE=$(dirname "$0")/../scenes/hood-screen-wing.ron
case "$MODE" in
  new) PANEL=(--panel patches) ;;
  right-click) PANEL=() ;;
  *) echo "patches-pointer: MODE is new or right-click, not $MODE" >&2; exit 2 ;;
esac
rm -f "$REPORT" "$REPORT.patches" "$REPORT.done"
STREAMLINE_STUDIO_SHOT_WAIT="$REPORT.done" "$BIN" screenshot "$SCENE" --out "$OUT" \
  "${PANEL[@]}" --report "$REPORT" --msaa 4 2>"$REPORT.log" &
PID=$!
trap 'kill $PID 2>/dev/null || true' EXIT
# the run writes REPORT.patches once the patches are drawn
for _ in $(seq 1 600); do
  [ -s "$REPORT.patches" ] && break
  sleep 0.2
done
[ -s "$REPORT.patches" ] || { echo "no patch positions were written" >&2; cat "$REPORT.log" >&2; exit 1; }
# without a window manager the keyboard and pointer go nowhere until focused
WID=$(xdotool search --name "Streamline Studio" | tail -1)
xdotool windowfocus --sync "$WID"
# generous pauses: under load llvmpipe may draw only a few frames a second;
# arrive with a wiggle so that a frame sees the pointer where it stops
goto() { xdotool mousemove "$(($1 - 2))" "$2"; sleep 0.6; xdotool mousemove "$1" "$2"; sleep 0.9; }
click() { goto "$1" "$2"; xdotool click "${3:-1}"; sleep 1.5; }
sleep 2
if [ "$MODE" = new ]; then
  click 44 139    # `wing` in the Patches section's list
  click 100 212   # New patch on an edge of `wing`…
else
  # a right click (press and release in place) on the hood's End edge
  read -r X Y <<<"${RIGHT_CLICK:-763 451}"
  goto "$X" "$Y"
  xdotool mousedown 3; sleep 0.8; xdotool mouseup 3; sleep 1.5
fi
# the pointer away from the surface and the panel for the picture
xdotool mousemove 1100 110; sleep 2
touch "$REPORT.done"
wait $PID
trap - EXIT
# the report: the patch the picture should show chosen, no arrow picked
# instead (a right click on an arrow opens the arrow's menu)
case "$MODE" in new) WANT=wing ;; *) WANT=hood ;; esac
grep -Eq "\"active_patch\": *\"$WANT\"" "$REPORT" || { echo "patches-pointer: $WANT is not the chosen patch" >&2; exit 1; }
grep -Eq '"selection": *null' "$REPORT" || { echo "patches-pointer: an arrow was picked" >&2; exit 1; }
