#!/usr/bin/env bash
# The editor's view of several patches (run inside `xvfb-run -a`): opens
# scenes/hood-screen-wing.ron (three patches: hood, screen on hood's End
# with G2, wing on hood's Last streamline with G1) in a screenshot run with
# the Patches section open, clicks the surface of patch CLICK (default
# wing) at its middle vertex (from REPORT.patches, written by the run),
# lets the run take its picture and checks the JSON report: three patches,
# each joined one drawn with a mesh, two seams with their continuities and
# measured figures, and the clicked patch active.
# Usage: [CLICK=wing] [PANEL=patches] patches.sh BIN OUT.png REPORT.json
set -euo pipefail
BIN=$1; OUT=$2; REPORT=$3
CLICK=${CLICK:-wing}
SCENE=$(dirname "$0")/../../scenes/hood-screen-wing.ron
rm -f "$REPORT" "$REPORT.patches" "$REPORT.done"
STREAMLINE_STUDIO_SHOT_WAIT="$REPORT.done" "$BIN" screenshot "$SCENE" --out "$OUT" \
  --panel "${PANEL:-patches}" --report "$REPORT" --size "${SIZE:-1280x800}" 2>"$REPORT.log" &
PID=$!
trap 'kill $PID 2>/dev/null || true' EXIT
for _ in $(seq 1 600); do
  [ -s "$REPORT.patches" ] && break
  sleep 0.2
done
[ -s "$REPORT.patches" ] || { echo "no patch positions were written" >&2; cat "$REPORT.log" >&2; exit 1; }
read -r X Y < <(awk -v n="$CLICK" '$1 == n { print $2, $3 }' "$REPORT.patches")
[ -n "${X:-}" ] || { echo "patch $CLICK is not drawn: $(cat "$REPORT.patches")" >&2; exit 1; }
WID=$(xdotool search --name "Streamline Studio" | tail -1)
xdotool windowfocus --sync "$WID"
# arrive with a small wiggle so that a frame sees the pointer there, then click
xdotool mousemove "$((X - 3))" "$Y"; sleep 0.7
xdotool mousemove "$X" "$Y"; sleep 1.0
xdotool click 1; sleep 1.5
# the pointer away from the surface for the picture
xdotool mousemove 1100 110; sleep 1.0
touch "$REPORT.done"
wait $PID
trap - EXIT
# the report's checks (the Rust test makes the same with serde_json)
command -v python3 >/dev/null || { echo "no python3: report not checked here"; exit 0; }
python3 - "$REPORT" "$CLICK" <<'PY'
import json, math, sys
r = json.load(open(sys.argv[1]))
click = sys.argv[2]
names = [p[0] for p in r["patches"]]
assert names == ["hood", "screen", "wing"], names
for name, shown, vertices in r["patches"][1:]:
    assert shown and vertices > 0, (name, shown, vertices)
seams = {(s[0], s[1]): s for s in r["seams"]}
assert set(seams) == {("hood", "screen"), ("hood", "wing")}, seams
a, b, edge, cont, verdict, gap, angle, dev = seams[("hood", "screen")]
assert (edge, cont) == ("End", "G2"), seams
assert gap == 0.0 and angle < 1e-6 and abs(dev) < 1.0, seams
a, b, edge, cont, verdict, gap, angle, dev = seams[("hood", "wing")]
assert (edge, cont) == ("Last", "G1"), seams
assert gap < 1e-9 and 0.0 <= angle < 5.0, seams
assert verdict in ("meets", "near", "fails"), verdict
assert r["active_patch"] == click, r["active_patch"]
print("patches", names, "active", r["active_patch"])
for s in r["seams"]:
    print("seam", *s)
PY
