#!/usr/bin/env bash
# Installs what is missing, builds PGE and runs the main job on the bundled scenes:
# `pge run fixtures/scenes`, with traces in out/traces and summaries in out/run-summary.json.
# Extra arguments are passed to `pge run` (for example --scalar long-double).
set -euo pipefail
cd "$(dirname "$0")/.."
build=${PGE_BUILD_DIR:-build}
scripts/install-deps.sh
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build "$build" -j "$(nproc)" --target pge
"$build/cli/pge" run fixtures/scenes --trace-dir out/traces --json out/run-summary.json "$@"
