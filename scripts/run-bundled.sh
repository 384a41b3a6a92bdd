#!/usr/bin/env bash
# scripts/run-bundled.sh [--full] [--out DIR] [--no-deps] [--no-screenshot] [--] [pge report options...]
#
# The main job on the bundled scenes: installs what is missing (scripts/install-deps.sh), builds
# `pge` (in $PGE_BUILD_DIR, default build/: RelWithDebInfo, or the type the build directory was
# configured with), and writes the accuracy report, speed
# against error for every solver x scalar over the bundled fixture families (fixtures/scenes/*
# but long and peers) and random scenes, to out/report/: index.html (open it in a browser),
# report.md, results.json, results.csv and plots/.
#
# The default sweep is `pge report --quick` with the peers part on the small compare scenes:
# every fixture, solver and scalar judged by the exact oracle (500 contact events per scene, 12
# random scenes), the gas at 100 and 1,000 bodies, a 20,000-event drift run, and PGE against
# Box2D and Chipmunk on the head-on, Newton's cradle, bullet and snooker scenes of
# fixtures/scenes/peers. About 1 minute of CPU (the first build aside). --full runs the full sweep
# instead: 2,000 events per scene, 100 random scenes, the gas up to 10,000, a 200,000-event drift
# run, and the peers part on every compare scene (the two 1,000-ball gases too): about 22 minutes
# of CPU, most of it the quad rows and the peers part on the two gases. Rows are measured on every
# core at once (pge report --jobs, default one per core; pass --jobs 1 for one at a time), the
# longest first (reports/costs-full.json, then each run's own costs.json), so the wall time is about
# the CPU time over the cores, but never less than the longest single row (fast in quad on the
# 1000-turn near miss, about 4 minutes): 11 to 13 minutes on 2 cores; the line at the end says
# how long it took.
#
# While it measures: on a terminal, one line redrawn in place (rows done, the part, time elapsed
# and left); otherwise (a log, CI) a line per part every 30 s and when the part ends, e.g.
#   accuracy: 120/780 rows, 1m10s elapsed, ~2m40s left
# At the end: the path of index.html and the headline numbers, one line per solver x scalar
# (misses, p99 and worst relative time error, worst error in ulps, events/s, Pareto front); and,
# when Chromium is installed, a screenshot of the page (out/report/screenshot.png) and a check
# that the five charts are there (with --parts: whichever were drawn), load, and no label overlaps
# another or is cut off (tests/tools/report_layout_check.sh, its output in
# out/report/layout-check.log; a finding is printed as a warning and does not change the exit
# code; CHROMIUM names another Chromium than /usr/bin/chromium).
#
# Options:
#   --full           the full sweep (see above) instead of the quick one
#   --quick          the default sweep (the last of --quick and --full counts)
#   --out DIR        write the report to DIR (default out/report)
#   --no-deps        do not run scripts/install-deps.sh
#   --no-screenshot  no screenshot or layout check at the end
#   -h, --help       this text
# Anything else (or everything after --) goes to `pge report`, after the sweep's own options:
# for example --solvers robust,certified, --scalars double, --parts accuracy, --random 0.
#
# Exit codes: 0 the report was written; 2 bad command line (this script's); otherwise the code of
# the step that failed: scripts/install-deps.sh (1 a package could not be installed, 2 not
# Debian), the build (cmake's, usually 1 or 2), or `pge report` (docs/commands.md, "Exit codes": 2 bad
# command line, 3 bad scene file, 6 cannot write the output, ...).
set -euo pipefail
cd "$(dirname "$0")/.."

usage() { sed -n '2,/^set -euo/p' "$0" | sed -e '$d' -e 's/^# \{0,1\}//'; }
quick=(--quick --parts accuracy,scaling,drift,peers --peer-scenes fixtures/scenes/peers/peers-head-on.json
       fixtures/scenes/peers/peers-newtons-cradle-5.json fixtures/scenes/peers/peers-bullet-thin-wall.json
       fixtures/scenes/peers/peers-snooker-break.json)
sweep=("${quick[@]}") out=out/report deps=1 screenshot=1 pass=()
while [[ $# -gt 0 ]]; do
  case $1 in
    --full) sweep=(); shift ;;
    --quick) sweep=("${quick[@]}"); shift ;;
    --out|-o)
      [[ $# -ge 2 ]] || { echo "run-bundled: $1 needs a directory (see --help)" >&2; exit 2; }
      out=$2; shift 2 ;;
    --out=*) out=${1#--out=}; shift ;;
    --no-deps) deps=0; shift ;;
    --no-screenshot) screenshot=0; shift ;;
    -h|--help) usage; exit 0 ;;
    --) shift; pass+=("$@"); break ;;
    *) pass+=("$1"); shift ;;
  esac
done

# --parts or --peer-scenes given for pge report replace the quick sweep's own; with --parts, the
# layout check asks for no chart in particular (else: all five).
name="the quick sweep"
[[ ${#sweep[@]} -gt 0 ]] || name="the full sweep"
given=" ${pass[*]-} " charts=()
if [[ $given == *" --parts"* ]]; then
  charts=(--charts "")
  [[ ${#sweep[@]} -eq 0 ]] || sweep=(--quick)
elif [[ $given == *" --peer-scenes"* && ${#sweep[@]} -gt 0 ]]; then
  sweep=(--quick --parts accuracy,scaling,drift,peers)
fi
build=${PGE_BUILD_DIR:-build}
if [[ $deps -eq 1 ]]; then scripts/install-deps.sh; fi
# A build directory already configured keeps its type (a Release build measured by measure.sh
# --no-build stays one); a new one, or one configured without a type, is RelWithDebInfo.
type=$(sed -n 's/^CMAKE_BUILD_TYPE:[A-Z]*=//p' "$build/CMakeCache.txt" 2>/dev/null || true)
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE="${type:-RelWithDebInfo}" >/dev/null
cmake --build "$build" -j "$(nproc)" --target pge

# Progress: redrawn in place on a terminal, a line now and then in a log.
if [[ -t 2 ]]; then progress=--progress; else progress=--progress-lines; fi
echo "run-bundled: $name${pass[*]:+ with ${pass[*]}} into $out, on $(nproc) cores (load" \
     "$(cut -d' ' -f1-3 /proc/loadavg 2>/dev/null || echo '?'))"
start=$SECONDS
code=0
"$build/cli/pge" report ${sweep[@]+"${sweep[@]}"} --out "$out" "$progress" ${pass[@]+"${pass[@]}"} || code=$?
if [[ $code -ne 0 ]]; then
  echo "run-bundled: pge report failed (exit $code)" >&2
  exit "$code"
fi
elapsed=$((SECONDS - start))
echo "run-bundled: the report took $((elapsed / 60))m$(printf %02d $((elapsed % 60)))s"

if [[ $screenshot -eq 1 && -f $out/index.html ]]; then
  check=0
  tests/tools/report_layout_check.sh ${charts[@]+"${charts[@]}"} --screenshot "$out/screenshot.png" "$out/index.html" \
    >"$out/layout-check.log" 2>&1 || check=$?
  case $check in
    0) echo "run-bundled: screenshot $out/screenshot.png (every chart loads, no label overlaps another)" ;;
    77) echo "run-bundled: no screenshot: Chromium is not installed (/usr/bin/chromium, or set CHROMIUM)" ;;
    *) echo "run-bundled: warning: the page's layout check found problems ($out/layout-check.log):" >&2
       grep -E '^  ' "$out/layout-check.log" >&2 || tail -5 "$out/layout-check.log" >&2
       [[ -f $out/screenshot.png ]] && echo "run-bundled: screenshot $out/screenshot.png" ;;
  esac
fi
echo "run-bundled: open $out/index.html"
