#!/usr/bin/env bash
# Installs what is missing, builds PGE and runs the main job on the bundled scenes: the accuracy
# report (`pge report`): every solver x scalar over the fixture families (fixtures/scenes/* but
# long) and random scenes, speed against error, written to out/report/ (open
# out/report/index.html; report.md, results.json and results.csv beside it).
# The full report takes about 20 minutes on 2 cores; pass --quick for the 2-minute sweep CI gates
# on. Other arguments are passed to `pge report` too (for example --solvers robust,certified).
# Exit code: pge report's (0 when the report was written; README.md, "Exit codes").
set -euo pipefail
cd "$(dirname "$0")/.."
build=${PGE_BUILD_DIR:-build}
scripts/install-deps.sh
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build "$build" -j "$(nproc)" --target pge
"$build/cli/pge" report --out out/report "$@"
