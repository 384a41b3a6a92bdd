#!/usr/bin/env bash
# render.sh PGE_BINARY CHECKER
# `pge render` on two bundled scenes: the SVG is well-formed XML with one start shape per body
# (class "body") and at least one collision mark (class "hit"); the HTML page loads in headless
# Chromium without console errors, exceptions or failed loads (CHECKER is
# tests/tools/html_console_check.sh; its exit 77, Chromium missing, is passed on as a skip
# once everything else has been checked). A turning square is drawn at its angle. A bad extension
# exits 2, a missing scene 3.
set -eu
pge=$1; checker=$2
fixtures=$(cd "$(dirname "$0")/../../fixtures/scenes" && pwd)
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

fail() { echo "FAIL: $*"; exit 1; }

for scene in "$fixtures/basics/newtons-cradle.json" "$fixtures/games/snooker.json"; do
  name=$(basename "$scene" .json)
  "$pge" render "$scene" -o "$out/$name.svg" >"$out/$name.stdout" || fail "$name: pge render to SVG exited $?"
  grep -q "^render: .* -> $out/$name.svg: " "$out/$name.stdout" || fail "$name: no summary line: $(cat "$out/$name.stdout")"
  "$pge" render --quiet "$scene" -o "$out/$name.html" || fail "$name: pge render to HTML exited $?"
  [[ -s $out/$name.html ]] || fail "$name: no HTML page written"

  python3 - "$scene" "$out/$name.svg" <<'PY' || fail "$name: the SVG does not hold"
import json, sys, xml.dom.minidom

scene, svg = sys.argv[1], sys.argv[2]
bodies = len(json.load(open(scene))["bodies"])
doc = xml.dom.minidom.parse(svg)  # raises on malformed XML
def count(cls):
    return sum(1 for e in doc.getElementsByTagName("*") if cls in e.getAttribute("class").split())
shapes, marks = count("body"), count("hit")
print(f"{svg}: {shapes} body shapes for {bodies} bodies, {marks} collision marks")
sys.exit(0 if shapes == bodies and marks >= 1 else 1)
PY
done

# A turning body is drawn at its angle: fixtures/scenes/rotation/square-spins-into-a-wall.json's square
# ends at the position and angle its expect block derives in 50 digits (derive.py, independent of
# the engine), so the final outline's corners are position + R(angle) (+-0.5, +-0.5); the start
# outline is the square at angle 0. The picture's frame is recovered from the fixed wall (the
# line x = 0.6 from y = -5 to 5).
rotating=$(cd "$(dirname "$0")/../../fixtures/scenes/rotation" && pwd)/square-spins-into-a-wall.json
"$pge" render --quiet "$rotating" -o "$out/spin.svg" || fail "spin: pge render to SVG exited $?"
"$pge" render --quiet "$rotating" -o "$out/spin.html" || fail "spin: pge render to HTML exited $?"
python3 - "$rotating" "$out/spin.svg" <<'PY' || fail "spin: the turning square is not drawn at its angle"
import json, math, sys, xml.dom.minidom

scene, svg = json.load(open(sys.argv[1])), sys.argv[2]
final = {k: v for f in scene["expect"]["final"] if f["body"] == "box" for k, v in f.items()}
doc = xml.dom.minidom.parse(svg)
wall = [e for e in doc.getElementsByTagName("line") if "fixed" in e.getAttribute("class").split()][0]
ox, oy = 0.6 - float(wall.getAttribute("x1")), -5.0 - float(wall.getAttribute("y1"))
def corners(cls):
    e = [e for e in doc.getElementsByTagName("polygon") if cls in e.getAttribute("class").split()][0]
    return [(float(x) + ox, float(y) + oy) for x, y in (p.split(",") for p in e.getAttribute("points").split())]
def want(pos, angle):
    c, s = math.cos(angle), math.sin(angle)
    return [(pos[0] + c * x - s * y, pos[1] + s * x + c * y) for x, y in ((-0.5, -0.5), (0.5, -0.5), (0.5, 0.5), (-0.5, 0.5))]
worst = 0.0
for cls, pos, angle in (("body", (0.0, 0.0), 0.0), ("final", final["position"], final["angle"])):
    got, exp = corners(cls), want(pos, angle)
    worst = max([worst] + [math.hypot(g[0] - e[0], g[1] - e[1]) for g, e in zip(got, exp)])
print(f"{svg}: turning square's corners within {worst:.2g} of position + R(angle) corner")
# Written with 6 significant digits of a picture about 10 across (4 decimals), corners and the
# wall each rounded: within 2e-4. A square drawn a hundredth of a radian off is 0.007 off.
sys.exit(0 if worst < 1e-3 else 1)
PY

# Each error: its exit code, one line on stderr naming what is wrong (expect_error.sh).
expect_error=$(dirname "$0")/expect_error.sh
"$expect_error" 2 ".svg" -- "$pge" render "$fixtures/basics/newtons-cradle.json" -o "$out/picture.png" ||
  fail "a .png output: not exit 2 with a message naming the forms"
"$expect_error" 3 "no-such-scene.json" -- "$pge" render "$out/no-such-scene.json" -o "$out/missing.svg" ||
  fail "a missing scene: not exit 3 with a message naming the file"

set +e
"$checker" "$out/newtons-cradle.html" "$out/snooker.html" "$out/spin.html"
code=$?
set -e
[[ $code -eq 77 ]] && { echo "skip: the HTML pages were not loaded (Chromium missing)"; exit 77; }
[[ $code -eq 0 ]] || fail "the HTML pages log errors or fail to load (checker exit $code)"
echo "ok: SVG and HTML for newtons-cradle, snooker and a turning square (drawn at its angle); bad extension 2; missing scene 3"
