#!/usr/bin/env bash
# A libFuzzer campaign on both targets (fuzz/README.md): configures and builds them with clang,
# seeds the corpora from the fixtures, runs fuzz_engine then fuzz_reader for S seconds each
# under nice, and prints per target the executions, exec/s, coverage (cov: and ft:) and crashes.
# Logs, corpora and crash/timeout/OOM artifacts go to out/fuzz/.
# Exit code: 0 when nothing was found, 1 when a target found a crash, timeout or OOM,
# 2 on a usage or build error.
set -uo pipefail

usage() {
  cat <<'USAGE'
Usage: scripts/fuzz-campaign.sh [--seconds S] [--timeout S] [--build-dir DIR] [--jobs N] [--no-build] [--parallel]
  --seconds S      seconds per target (default: 120)
  --timeout S      wall seconds one input may take before it counts as a hang (default: 60; libFuzzer's
                   clock is wall time, so on a loaded machine a slow input can pass a short limit)
  --build-dir DIR  clang build directory (default: build-fuzz); configured if needed
  --jobs N         parallel build jobs (default: 1)
  --no-build       use the targets already built in DIR
  --parallel       run the two targets at the same time (one core each) instead of one after the other
Writes out/fuzz/<target>.log, corpora in out/fuzz/corpus/{engine,reader}, and artifacts
(crash-*, timeout-*, oom-*, slow-unit-*) in out/fuzz/artifacts/<target>/.
Reproduce an artifact: DIR/fuzz/fuzz_engine out/fuzz/artifacts/fuzz_engine/crash-...
USAGE
}

die() { echo "fuzz-campaign.sh: $*" >&2; exit 2; }

root=$(cd "$(dirname "$0")/.." && pwd)
seconds=120
timeout=60
parallel=0
build="$root/build-fuzz"
jobs=1
do_build=1
while [[ $# -gt 0 ]]; do
  case "$1" in
    --seconds) [[ $# -ge 2 && "$2" =~ ^[1-9][0-9]*$ ]] || die "--seconds needs a positive integer"; seconds=$2; shift 2 ;;
    --build-dir) [[ $# -ge 2 ]] || die "--build-dir needs a value"
                 case "$2" in /*) build=$2 ;; *) build="$PWD/$2" ;; esac; shift 2 ;;
    --timeout) [[ $# -ge 2 && "$2" =~ ^[1-9][0-9]*$ ]] || die "--timeout needs a positive integer"; timeout=$2; shift 2 ;;
    --jobs) [[ $# -ge 2 && "$2" =~ ^[1-9][0-9]*$ ]] || die "--jobs needs a positive integer"; jobs=$2; shift 2 ;;
    --no-build) do_build=0; shift ;;
    --parallel) parallel=1; shift ;;
    -h|--help) usage; exit 0 ;;
    *) die "unknown argument: $1 (see --help)" ;;
  esac
done

out="$root/out/fuzz"
mkdir -p "$out" || die "cannot create $out"

if [[ $do_build -eq 1 ]]; then
  command -v clang++ >/dev/null || die "clang++ not found (libFuzzer ships with clang; Debian: apt-get install clang)"
  echo "== building fuzz targets in $build"
  nice -n 10 cmake -S "$root" -B "$build" -DCMAKE_CXX_COMPILER=clang++ -DPGE_LIBFUZZER=ON -DPGE_BUILD_TESTS=OFF \
      -DCMAKE_BUILD_TYPE=RelWithDebInfo >"$out/configure.log" 2>&1 \
    || die "configure failed, see $out/configure.log"
  nice -n 10 cmake --build "$build" -j "$jobs" --target fuzz_engine fuzz_reader pge_fuzz_encode >"$out/build.log" 2>&1 \
    || die "build failed, see $out/build.log"
fi
for t in fuzz_engine fuzz_reader pge_fuzz_encode; do
  [[ -x "$build/fuzz/$t" ]] || die "$build/fuzz/$t not found (build it, or drop --no-build)"
done

echo "== seeding corpora"
"$root/scripts/fuzz-corpus.sh" --build-dir "$build" --out "$out/corpus" || die "seeding the corpora failed"

# One target: run it for $seconds into its log (its exit code in $out/<target>.exit).
run_target() {
  local target=$1
  local corpus="$out/corpus/${target#fuzz_}"
  local artifacts="$out/artifacts/$target"
  local log="$out/$target.log"
  mkdir -p "$artifacts"
  local extra=()
  [[ $target == fuzz_reader ]] && extra+=("-dict=$root/fuzz/reader.dict")
  echo "== $target for ${seconds}s (log: $log)"
  # -timeout: one input running longer is a hang; -rss_limit_mb: memory blow-up is a failure;
  # -report_slow_units: inputs over 10 s are kept as slow-unit-* (reported, not failures).
  nice -n 10 "$build/fuzz/$target" "$corpus" -max_total_time="$seconds" -timeout="$timeout" -rss_limit_mb=4096 \
      -report_slow_units=10 \
      -print_final_stats=1 -artifact_prefix="$artifacts/" "${extra[@]}" >"$log" 2>&1
  echo $? >"$out/$target.exit"
}

if [[ $parallel -eq 1 ]]; then
  run_target fuzz_engine &
  run_target fuzz_reader &
  wait
else
  run_target fuzz_engine
  run_target fuzz_reader
fi

found=0
summary=()
for target in fuzz_engine fuzz_reader; do
  artifacts="$out/artifacts/$target"
  log="$out/$target.log"
  code=$(cat "$out/$target.exit")
  execs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$')
  rate=$(grep -o 'stat::average_exec_per_sec: *[0-9]*' "$log" | grep -o '[0-9]*$')
  last=$(grep -E '^#[0-9]+' "$log" | grep -E 'cov: ' | tail -1)
  cov=$(grep -o 'cov: [0-9]*' <<<"$last" | grep -o '[0-9]*')
  ft=$(grep -o 'ft: [0-9]*' <<<"$last" | grep -o '[0-9]*')
  crashes=$(find "$artifacts" -maxdepth 1 -type f \( -name 'crash-*' -o -name 'timeout-*' -o -name 'oom-*' -o -name 'leak-*' \) | wc -l)
  # libFuzzer exits 0 when the time ran out with nothing found; anything else is a finding.
  if [[ $code -ne 0 || $crashes -gt 0 ]]; then found=1; fi
  summary+=("$(printf '%-12s executions %-10s exec/s %-7s cov %-6s ft %-7s crashes/timeouts/OOMs %s (exit %s)' \
      "$target" "${execs:-?}" "${rate:-?}" "${cov:-?}" "${ft:-?}" "$crashes" "$code")")
done

echo "== summary (${seconds}s per target)"
printf '%s\n' "${summary[@]}"
if [[ $found -ne 0 ]]; then
  echo "FOUND: see the logs in $out and the artifacts in $out/artifacts/"
  exit 1
fi
echo "nothing found"
