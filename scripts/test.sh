#!/usr/bin/env bash
# Installs what is missing, builds PGE and runs every test (CTest).
# Environment:
#   PGE_BUILD_DIR   build directory (default: build)
#   PGE_CMAKE_ARGS  extra CMake arguments, e.g. "-DPGE_SANITIZE=ON" (default: none)
#   PGE_JOBS        parallel build jobs (default: number of cores)
#   PGE_CTEST_EXCLUDE  CTest labels left out, a regular expression (default: long)
# Exit code: 0 when every test passes; non-zero otherwise (the failing step says why).
set -euo pipefail
cd "$(dirname "$0")/.."
build=${PGE_BUILD_DIR:-build}
jobs=${PGE_JOBS:-$(nproc)}
scripts/install-deps.sh
# shellcheck disable=SC2086
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo ${PGE_CMAKE_ARGS:-}
cmake --build "$build" -j "$jobs"
# The "long" label (fixture_expectations_long: judged runs of up to 1,000,000 events, about 2.5 minutes) is
# left out by default; run it with: ctest --test-dir build -L long
ctest --test-dir "$build" --output-on-failure -j "$jobs" -LE "${PGE_CTEST_EXCLUDE:-long}"
