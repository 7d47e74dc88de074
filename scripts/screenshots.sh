#!/usr/bin/env bash
# Regenerates every picture in docs/img/ from the current build (the editor
# under Xvfb with Mesa's software Vulkan): the panel sections, the curvature
# displays, the walk-throughs' steps, several patches, and the dialogs and
# menus that need a real pointer (xdotool).
#
# Usage: scripts/screenshots.sh [NAME…]   (NAME: a picture without .png;
#                                          none: every picture)
#   STREAMLINE_BIN=path  use this binary: no scripts/setup.sh, no cargo build
#                        (xvfb-run, xdotool and Mesa's Vulkan must be there)
#   SHOTS_DIR=dir        write the pictures there instead of docs/img
# Each picture is drawn into a temporary folder and moved into place only
# once it was written, so a failed one keeps the old file. Exits non-zero if
# any picture was not written, if docs/img holds a picture this script does
# not make, or if a picture is linked from no doc (README.md, docs/*.md);
# prints how many pictures were written.
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD
START=$SECONDS
if [ -n "${STREAMLINE_BIN:-}" ]; then
  BIN=$(realpath "$STREAMLINE_BIN")
  for tool in xvfb-run xdotool awk; do
    command -v "$tool" >/dev/null || { echo "screenshots: $tool not found (scripts/setup.sh installs it)" >&2; exit 1; }
  done
else
  bash scripts/setup.sh
  cargo build --release
  BIN=$(realpath "${CARGO_TARGET_DIR:-target}/release/streamline-studio")
fi
[ -x "$BIN" ] || { echo "screenshots: no binary at $BIN" >&2; exit 1; }
OUT=${SHOTS_DIR:-docs/img}
mkdir -p "$OUT"
OUT=$(realpath "$OUT")
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
mkdir -p "$T/new"
ONLY=" $* "
made=()   # every picture this script makes (asked for or not)
written=()
failed=()
XVFB=(xvfb-run -a -s "-screen 0 1280x800x24")

# asked NAME: whether NAME is asked for (no arguments: every picture)
asked() { [ "$ONLY" = "  " ] || [[ "$ONLY" == *" $1 "* ]]; }
# want NAME: the same, NAME counted among the pictures this script makes
want() { made+=("$1"); asked "$1"; }
# finish NAME LOG: moves $T/new/NAME.png into place, or records the failure
finish() {
  local name=$1 log=$2
  if [ -s "$T/new/$name.png" ]; then
    mv -f "$T/new/$name.png" "$OUT/$name.png"
    written+=("$name")
    echo "$OUT/$name.png"
  else
    failed+=("$name")
    echo "screenshots: $name.png was not written" >&2
    if [ -f "$log" ]; then tail -n 15 "$log" >&2; fi
  fi
}
# gui NAME COMMAND…: runs COMMAND, which writes $T/new/NAME.png, and once
# more if it failed (a virtual display that did not start, a pointer that
# missed on a busy machine); a picture of a failed run is not kept
gui() {
  local name=$1; shift
  want "$name" || return 0
  if ! "$@" >"$T/$name.log" 2>&1; then
    rm -f "$T/new/$name.png"
    "$@" >>"$T/$name.log" 2>&1 || rm -f "$T/new/$name.png"
  fi
  finish "$name" "$T/$name.log"
}
# shot NAME ARGS…: `screenshot ARGS…` on a virtual display.
# --msaa 4: the pictures show the 3D views as a GPU draws them (on a
# software renderer the editor itself starts without multisampling)
shot() {
  local name=$1; shift
  gui "$name" "${XVFB[@]}" "$BIN" screenshot "$@" --msaa 4 --out "$T/new/$name.png"
}

# the car and the panel sections (README.md, docs/editor.md)
shot editor-car1 car1 --select 3,4
# a design fitted to a shipped reference, and its zebra stripes (docs/fit.md)
shot fit-hood scenes/references/hood.ron --select 4,4
shot fit-hood-zebra scenes/references/hood.ron --panel analysis --analysis zebra
shot editor-qi-side qi-side --select 1,2
shot panel-file car1 --panel file
shot panel-subdivision car1 --panel subdivision
shot panel-selection car1 --panel selection --select 3,4
shot panel-display car1 --panel display
shot panel-stats car1 --panel stats
shot panel-initial car1 --panel initial --select i1
shot panel-curvature car1 --panel curvature --select 4,3
shot panel-tuning car1-tuned --panel tuning --select 2,4
# the curvature displays
shot analysis-tuned-mean car1-tuned --panel analysis --analysis mean
shot analysis-gaussian car1 --panel analysis --analysis gaussian
shot analysis-mean car1 --panel analysis --analysis mean
shot analysis-zebra car1 --panel analysis --analysis zebra
shot analysis-comb car1 --panel analysis --comb
# docs/cad.md: the deviation map, and File ▸ CAD export after a script's
# Export (run from a folder of its own: the section proposes a path there)
shot analysis-deviation car1 --panel analysis --analysis deviation
# docs/editor.md, docs/fit.md: the map to the reference of a fitted design
shot analysis-reference scenes/references/hood.ron --panel analysis --analysis reference
mkdir -p "$T/cad"
echo '(steps: [Export("car1.step")])' > "$T/cad/export.ron"
cd "$T/cad"
shot panel-cad-export car1 --panel file --script "$T/cad/export.ron"
# and of a design of several patches: one line per face
echo '(steps: [Export("hood-screen-wing.step")])' > "$T/cad/export-patches.ron"
shot panel-cad-export-patches "$ROOT/scenes/hood-screen-wing.ron" --panel file --script "$T/cad/export-patches.ron"
cd "$ROOT"
# docs/editor.md: Run script with a million steps, in progress
asked panel-file-script && awk 'BEGIN { print "(steps: ["; for (i = 0; i < 250000; i++) {
  print "SetDirection(row: 2, col: 4, dir: (1.0, 0.55, 0.06)),";
  print "SetDirection(row: 2, col: 3, dir: (1.0, 0.2, 0.1)),"; print "Undo,"; print "Redo," }
  print "])" }' > "$T/million-steps.ron"
shot panel-file-script car1 --panel file --script "$T/million-steps.ron"
rm -f "$T/million-steps.ron"
# docs/editor.md: Stats and the status line warn of an antipodal pair
cat > "$T/antipodal-steps.ron" <<'RON'
(steps: [
    Load("builtin:car1"),
    SetDirection(row: 2, col: 4, dir: (1.0, 0.0, 0.5)),
    SetDirection(row: 2, col: 5, dir: (-1.0, 0.0, -0.5)),
    Save("antipodal.ron"),
])
RON
"$BIN" play "$T/antipodal-steps.ron" >/dev/null
shot warning-antipodal "$T/antipodal.ron" --panel stats --size 1100x700
# ... and on a later patch: Stats of the active patch, the warning naming it
echo '(steps: [SetPatch("wing"), SetDirection(row: 2, col: 2, dir: (1.0, 0.0, 0.5)), SetDirection(row: 2, col: 3, dir: (-1.0, 0.0, -0.5))])' > "$T/wing-antipodal.ron"
shot warning-antipodal-patches "$ROOT/scenes/hood-screen-wing.ron" --script "$T/wing-antipodal.ron" --panel stats --size 1100x700
# the Loop meshes (docs/editor.md, docs/loop.md)
for m in snail fertility camelhead; do
  shot "mesh-$m" car1 --mesh "tests/data/meshes/$m.obj" --panel mesh
done
# docs/reliability.md: an OBJ over the memory cap, refused (the reader stops
# at line 3579904, as it does in the 1 GiB file of tests/editor_gui_files.rs)
asked mesh-refused && awk 'BEGIN { for (i = 0; i < 3600000; i++)
  printf "v %d.5 %d.5 0.25\n", i % 20000, int(i / 20000) }' > "$T/huge.obj"
shot mesh-refused car1 --mesh "$T/huge.obj" --panel mesh
rm -f "$T/huge.obj"

# docs/authoring.md: the walk-through's scenes, step by step
cp scripts/authoring-shots.ron "$T/steps.ron"
"$BIN" play "$T/steps.ron" >/dev/null
shot authoring-1-new "$T/1-new.ron" --panel structure
shot panel-structure "$T/2-insert.ron" --panel structure --select 2,3
shot authoring-3-shaped "$T/3-shaped.ron" --panel subdivision
shot panel-lengths "$T/4-lengths.ron" --panel selection --select 4,2
shot authoring-5-mirror "$T/5-mirror.ron" --panel structure --select 1,2
shot authoring-6-curvature "$T/5-mirror.ron" --panel analysis --analysis gaussian
shot authoring-7-save "$T/5-mirror.ron" --panel file

# docs/patches.md: the several-patch walk-through's scenes
cp scripts/patches-shots.ron "$T/patches.ron"
cp scenes/hood-screen-wing.ron "$T/"
"$BIN" play "$T/patches.ron" >/dev/null
shot patches-walk-1-open scenes/hood-screen-wing.ron --panel patches
shot patches-walk-3-turned "$T/3-turned.ron" --panel selection --select 2,3
# the wing chosen and turned in the running editor (a script's SetPatch)
echo '(steps: [SetPatch("wing"), Rotate(row: 1, col: 2, axis: (1.0, 0.0, 0.0), degrees: -15.0)])' > "$T/wing.ron"
shot patches-walk-4-wing "$T/3-turned.ron" --script "$T/wing.ron" --panel patches
shot patches-walk-5-tail "$T/5-tail.ron" --panel patches
shot patches-walk-6-seams "$T/5-tail.ron" --panel analysis
shot patches-walk-7-save "$T/5-tail.ron" --panel file

# docs/editor.md (several patches): hood-screen-wing as shipped ...
HSW=scenes/hood-screen-wing.ron
shot handles-several-patches "$HSW" --select 2,4 --size 1100x700
echo '(steps: [SetPatch("screen")])' > "$T/screen.ron"
shot handles-joined-active "$HSW" --script "$T/screen.ron" --size 1100x700
shot patches-seams "$HSW" --panel analysis
shot patches-deviation "$HSW" --panel analysis --analysis deviation
echo '(steps: [HidePatch("wing", true)])' > "$T/hide.ron"
shot patches-hidden "$HSW" --script "$T/hide.ron" --panel patches
# ... and seen closer, from the side of the hood's first streamline (a copy
# with another camera: the maps and combs across the seams)
mkdir -p "$T/close"
awk '/^    view: \(/ { print; print "        yaw: -75.0,"; print "        pitch: 34.0,";
  print "        distance: 3.7,"; print "        target: (1.4, 0.3, 0.45),"; skip = 1; next }
  skip && /^    \),/ { skip = 0 } !skip' "$HSW" > "$T/close/hood-screen-wing.ron"
shot patches-zebra "$T/close/hood-screen-wing.ron" --panel analysis --analysis zebra
shot patches-gaussian "$T/close/hood-screen-wing.ron" --panel analysis --analysis gaussian
shot patches-comb "$T/close/hood-screen-wing.ron" --panel analysis --comb
# a click on the wing's surface (tests/gui/patches.sh, which checks the
# report too), then the new-patch form and a right click on the hood's End
gui patches-section env PANEL=patches "${XVFB[@]}" bash tests/gui/patches.sh "$BIN" "$T/new/patches-section.png" "$T/section.json"
gui patches-new "${XVFB[@]}" bash scripts/patches-pointer.sh "$BIN" "$T/new/patches-new.png" "$T/new.json" new
gui patches-right-click "${XVFB[@]}" bash scripts/patches-pointer.sh "$BIN" "$T/new/patches-right-click.png" "$T/right.json" right-click

# the New design dialog and the arrow's menu (docs/authoring.md)
gui dialog-new-design "${XVFB[@]}" bash tests/gui/authoring.sh "$BIN" "$T/new/dialog-new-design.png" "$T/d.json" dialog -
# File ▸ Import surface… with hood.step picked in the file browser
# (docs/editor.md, docs/fit.md)
gui dialog-import-surface env SHOT_ARGS="--msaa 4" "${XVFB[@]}" bash tests/gui/import.sh "$BIN" "$T/new/dialog-import-surface.png" "$T/i.json" dialog "$ROOT/scenes/references/hood.step"
# the walk-through of docs/fit.md (tests/gui/reference.sh, which
# tests/editor_gui_reference.rs checks): the import dialog, the fitted hood
# with its map to the reference, a handle dragged (red), undone (green)
walk() { gui "fit-walk-$1" "${XVFB[@]}" bash tests/gui/reference.sh "$BIN" "$T/new/fit-walk-$1.png" "$T/w$1.json" "$2" "$ROOT/scenes/references/hood.step"; }
walk 1-import dialog
walk 2-fitted fitted
walk 3-dragged dragged
walk 4-undone undone
# View ▸ Reference: the reference as a ghost over the hood with two tangents
# turned (streamlines and sphere view off); File ▸ Reference… with
# roof.step picked, its face drawn in the preview colour (docs/editor.md)
gui reference-ghost env SHOT_ARGS="--msaa 4" ZOOM=2 GHOST_ENTRY="95 298 95 340 95 361" "${XVFB[@]}" bash tests/gui/ghost.sh "$BIN" "$T/new/reference-ghost.png" "$T/g.json" ghost
gui dialog-reference env SHOT_ARGS="--msaa 4" REFERENCE_ENTRY="52 273" "${XVFB[@]}" bash tests/gui/ghost.sh "$BIN" "$T/new/dialog-reference.png" "$T/r.json" dialog "$ROOT/scenes/references/roof.step"
cp "$T/2-insert.ron" "$T/menu.ron"
gui menu-arrow "${XVFB[@]}" bash tests/gui/authoring.sh "$BIN" "$T/new/menu-arrow.png" "$T/m.json" menu "$T/menu.ron"
# the menu bar and the file browser (docs/editor.md): a folder of designs,
# opened from one of them so that it is a recent place too
mkdir -p "$T/designs/archive" "$T/work"
cp scenes/car1.ron scenes/car2.ron scenes/qi-side.ron "$T/designs/"
cp scenes/minimal.ron "$T/designs/body-v2.ron"
cp scenes/car1.ron "$T/designs/archive/car1-old.ron"
echo notes > "$T/designs/notes.txt"
browser() {
  (cd "$T/work" && SCENE="$T/designs/car2.ron" SHOT_ARGS="--msaa 4" "${XVFB[@]}" \
    bash "$ROOT/tests/gui/browser.sh" "$BIN" "$T/new/$2.png" "$T/$1.json" "$1" "$T/designs" x.obj)
}
gui menu-file browser menu menu-file
gui file-browser browser browser file-browser
gui help-keys browser keys help-keys

# what was written, and what is missing
status=0
echo "screenshots: ${#written[@]} pictures written to $OUT in $((SECONDS - START)) s"
if ((${#failed[@]})); then
  echo "screenshots: ${#failed[@]} not written: ${failed[*]}" >&2
  status=1
fi
for n in "$@"; do
  [[ " ${made[*]} " == *" $n "* ]] || { echo "screenshots: no picture is called $n" >&2; status=1; }
done
for f in docs/img/*.png; do
  n=$(basename "$f" .png)
  [[ " ${made[*]} " == *" $n "* ]] || { echo "screenshots: docs/img/$n.png is not made by this script" >&2; status=1; }
done
for n in "${made[@]}"; do
  grep -qF "img/$n.png" README.md docs/*.md || { echo "screenshots: img/$n.png is linked from no doc" >&2; status=1; }
done
exit "$status"
