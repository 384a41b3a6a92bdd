#!/usr/bin/env bash
# The report's index.html opens offline and cleanly (issue 8): made from two small scenes and two
# configurations, every part (the peers part on the head-on compare scene), it references nothing outside itself, its plots are well-formed SVG from
# gnuplot, and headless Chromium loads it with no console error, exception or failed load
# (tests/tools/html_console_check.sh; exit 77, a skip, only where Chromium is not installed).
# Usage: report_page.sh PGE FIXTURES_DIR CHECKER
set -u
pge=$1; fixtures=$2; checker=$3
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
fail() { echo "FAIL: $*"; exit 1; }
"$pge" report --quick --scenes "$fixtures/scenes/basics/head-on.json" "$fixtures/scenes/simultaneous/cradle-5.json" \
  --random 1 --solvers robust,certified --scalars double --parts accuracy,scaling,drift,peers \
  --peer-scenes "$fixtures/scenes/peers/peers-head-on.json" --out "$out/r" -q || fail "pge report exited with $?"
page=$out/r/index.html
[[ -s $page ]] || fail "no index.html"
if grep -Eq '(src|href)="(https?:|//|file:)' "$page"; then fail "index.html references an outside resource"; fi
grep -q 'data:image/svg+xml;base64,' "$page" || fail "index.html has no inline plot"
grep -q 'Pareto' "$page" || fail "index.html does not explain the Pareto front"
for plot in speed_error error_cdf drift scaling peers; do
  svg=$out/r/plots/$plot.svg
  python3 -c 'import sys, xml.dom.minidom; xml.dom.minidom.parse(sys.argv[1])' "$svg" || fail "$svg is not well-formed"
  grep -q -i 'gnuplot' "$svg" || fail "$svg was not drawn by gnuplot"
done
for svg in "$out"/r/plots/family-*.svg; do  # pge render's pictures of the fixture families
  python3 -c 'import sys, xml.dom.minidom; xml.dom.minidom.parse(sys.argv[1])' "$svg" || fail "$svg is not well-formed"
done
[[ -e $out/r/plots/family-basics.svg && -e $out/r/plots/family-random.svg ]] || fail "a family has no picture"
"$checker" "$page"
