#!/usr/bin/env bash
# Installs what is missing, builds PGE and runs the main job on the bundled scenes:
# `pge run` on every scene of fixtures/scenes/ except the long family (fixtures/scenes/long:
# a million-event gas whose trace alone is hundreds of megabytes; run it by name), with traces
# in out/traces and summaries in out/run-summary.json.
# Extra arguments are passed to `pge run` (for example --scalar long-double).
set -euo pipefail
cd "$(dirname "$0")/.."
build=${PGE_BUILD_DIR:-build}
scripts/install-deps.sh
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build "$build" -j "$(nproc)" --target pge
scenes=()
for dir in fixtures/scenes/*/; do
  [[ $dir == fixtures/scenes/long/ ]] || scenes+=("$dir")
done
"$build/cli/pge" run "${scenes[@]}" --trace-dir out/traces --json out/run-summary.json "$@"
