#!/usr/bin/env bash
# render.sh PGE_BINARY CHECKER
# `pge render` on two bundled scenes: the SVG is well-formed XML with one start shape per body
# (class "body") and at least one collision mark (class "hit"); the HTML page loads in headless
# Chromium without console errors, exceptions or failed loads (CHECKER is
# tests/tools/html_console_check.sh; its exit 77, Chromium missing, is passed on as a skip
# once everything else has been checked). A bad extension exits 2, a missing scene 3.
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

# Each error: its exit code, one line on stderr naming what is wrong (expect_error.sh).
expect_error=$(dirname "$0")/expect_error.sh
"$expect_error" 2 ".svg" -- "$pge" render "$fixtures/basics/newtons-cradle.json" -o "$out/picture.png" ||
  fail "a .png output: not exit 2 with a message naming the forms"
"$expect_error" 3 "no-such-scene.json" -- "$pge" render "$out/no-such-scene.json" -o "$out/missing.svg" ||
  fail "a missing scene: not exit 3 with a message naming the file"

set +e
"$checker" "$out/newtons-cradle.html" "$out/snooker.html"
code=$?
set -e
[[ $code -eq 77 ]] && { echo "skip: the HTML pages were not loaded (Chromium missing)"; exit 77; }
[[ $code -eq 0 ]] || fail "the HTML pages log errors or fail to load (checker exit $code)"
echo "ok: SVG and HTML for newtons-cradle and snooker; bad extension 2; missing scene 3"
