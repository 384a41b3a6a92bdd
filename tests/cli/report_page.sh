#!/usr/bin/env bash
# The report's index.html opens offline and cleanly (issue 8): made from two small scenes and two
# configurations, every part (the peers part on the head-on compare scene), it references nothing
# outside itself, its plots are well-formed SVG from gnuplot, the peers part has PGE's rows in every
# solver x scalar asked for, and headless Chromium loads it with no console error, exception or
# failed load (tests/tools/html_console_check.sh), and in Chromium's layout every chart is there
# and no label overlaps another or is cut off (tests/tools/report_layout_check.sh: the peers
# chart's settings of nearly the same speed and drift wrote their labels over one another). Exit
# 77, a skip, only where Chromium is not installed.
# Usage: report_page.sh PGE FIXTURES_DIR CHECKER [LAYOUT_CHECKER]
set -u
pge=$1; fixtures=$2; checker=$3; layout=${4:-$(dirname "$checker")/report_layout_check.sh}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
fail() { echo "FAIL: $*"; exit 1; }
"$pge" report --quick --scenes "$fixtures/scenes/basics/head-on.json" "$fixtures/scenes/simultaneous/cradle-5.json" \
  --random 1 --solvers robust,certified --scalars double --parts accuracy,scaling,drift,peers \
  --peer-scenes "$fixtures/scenes/peers/peers-head-on.json" --out "$out/r" -q || fail "pge report exited with $?"
# The peers part runs PGE in every solver x scalar asked for (here 2 x 2 on the head-on scene,
# where each is exact: energy drift and final-state error 0).
"$pge" report --parts peers --solvers robust,certified --scalars float,quad \
  --peer-scenes "$fixtures/scenes/peers/peers-head-on.json" --out "$out/p" -q || fail "pge report --parts peers exited with $?"
python3 - "$out/p/results.json" <<'PY' || fail "the peers part does not have PGE's rows in every solver x scalar"
import json, sys
rows = [r for r in json.load(open(sys.argv[1]))["rows"] if r["kind"] == "peer" and r["solver"] == "pge"]
got = sorted(r["scalar"] for r in rows)
want = ["certified/float", "certified/quad", "robust/float", "robust/quad"]
assert got == want, got
assert all(r["error"] == "" and r["energy_drift"] == 0 and r["final_error"] == 0 for r in rows), rows
PY
# Progress for a log (--progress-lines): the plan (with several workers, how many rows at once), a
# line as each part ends (its rows' time, "of work" when added up over workers; the time left but
# after the last part); then index.html's path and the headline numbers (a line per solver x
# scalar) on stdout.
"$pge" report --quick --scenes "$fixtures/scenes/basics/head-on.json" --random 0 --solvers robust --scalars double,quad \
  --parts accuracy,drift --out "$out/l" --progress-lines >"$out/l.out" 2>"$out/l.err" || fail "pge report --progress-lines exited with $?"
grep -Eq '^measuring: accuracy 2 rows, drift 2 rows( \([0-9]+ at once\))?$' "$out/l.err" || fail "no plan line in: $(cat "$out/l.err")"
grep -Eq '^accuracy: 2/2 rows in [0-9]+s( of work)?, [0-9]+s elapsed(, ~[0-9ms]+ left)?$' "$out/l.err" ||
  fail "no accuracy line in: $(cat "$out/l.err")"
grep -Eq '^drift: 2/2 rows in ' "$out/l.err" || fail "no drift line in: $(cat "$out/l.err")"
grep -q "open $out/l/index.html" "$out/l.out" || fail "index.html's path not said: $(cat "$out/l.out")"
grep -Eq '^robust/quad +0 ' "$out/l.out" || fail "no headline line for robust/quad: $(cat "$out/l.out")"
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
"$checker" "$page" || exit $?
"$layout" "$page"
