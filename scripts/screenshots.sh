#!/usr/bin/env bash
# Regenerates the pictures in docs/img/ (the editor under Xvfb with Mesa's
# software Vulkan): one per panel section and one per curvature display.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
cargo build --release
BIN="${CARGO_TARGET_DIR:-target}/release/streamline-studio"
# --msaa 4: the pictures show the 3D views as a GPU draws them (on a
# software renderer the editor itself starts without multisampling)
shot() { local name=$1; shift; xvfb-run -a -s "-screen 0 1280x800x24" "$BIN" screenshot "$@" --msaa 4 --out "docs/img/$name.png" 2>/dev/null; echo "docs/img/$name.png"; }
mkdir -p docs/img
shot editor-car1 car1 --select 3,4
shot panel-file car1 --panel file
shot panel-subdivision car1 --panel subdivision
shot panel-selection car1 --panel selection --select 3,4
shot panel-display car1 --panel display
shot panel-stats car1 --panel stats
shot panel-initial car1 --panel initial --select i1
shot panel-curvature car1 --panel curvature --select 4,3
shot panel-tuning car1-tuned --panel tuning --select 2,4
shot analysis-tuned-mean car1-tuned --panel analysis --analysis mean
shot analysis-gaussian car1 --panel analysis --analysis gaussian
shot analysis-mean car1 --panel analysis --analysis mean
shot analysis-zebra car1 --panel analysis --analysis zebra
shot analysis-comb car1 --panel analysis --comb
shot editor-qi-side qi-side --select 1,2
for m in snail fertility camelhead; do
  shot "mesh-$m" car1 --mesh "tests/data/meshes/$m.obj" --panel mesh
done
# docs/authoring.md: the walk-through's scenes, step by step
T=$(mktemp -d)
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
# the dialog and the arrow's menu need a pointer (xdotool)
xvfb-run -a -s "-screen 0 1280x800x24" bash tests/gui/authoring.sh "$BIN" docs/img/dialog-new-design.png "$T/d.json" dialog -
cp "$T/2-insert.ron" "$T/menu.ron"
xvfb-run -a -s "-screen 0 1280x800x24" bash tests/gui/authoring.sh "$BIN" docs/img/menu-arrow.png "$T/m.json" menu "$T/menu.ron"
echo docs/img/dialog-new-design.png docs/img/menu-arrow.png
# the menu bar and the file browser (docs/editor.md): a folder of designs,
# opened from one of them so that it is a recent place too
mkdir -p "$T/designs/archive" "$T/work"
cp scenes/car1.ron scenes/car2.ron scenes/qi-side.ron "$T/designs/"
cp scenes/minimal.ron "$T/designs/body-v2.ron"
cp scenes/car1.ron "$T/designs/archive/car1-old.ron"
echo notes > "$T/designs/notes.txt"
for m in menu:menu-file browser:file-browser keys:help-keys; do
  (cd "$T/work" && SCENE="$T/designs/car2.ron" SHOT_ARGS="--msaa 4" xvfb-run -a -s "-screen 0 1280x800x24" \
    bash "$OLDPWD/tests/gui/browser.sh" "$OLDPWD/$BIN" "$OLDPWD/docs/img/${m#*:}.png" "$T/${m%%:*}.json" "${m%%:*}" "$T/designs" x.obj)
  echo "docs/img/${m#*:}.png"
done
rm -rf "$T"
