#!/usr/bin/env bash
# The engine's cache-line prefetches survive compilation (engine/src/aligned.hpp, prefetch_line).
# GCC treats __builtin_prefetch as free of side effects and deleted loops that only prefetch as
# empty loops: in 62d1855 World<double>::step() had no prefetch left, and prefetch helpers
# written after it compiled to a bare `ret`; with the prefetches kept, an event with 1e5 bodies
# takes about a quarter less time (docs/scale.md).
# Reads the disassembly of the engine library and checks, for the double world:
#   1. every function named *prefetch* issues a prefetch or calls something (not a bare ret);
#   2. World<double>::step() issues prefetches (the next events' bodies and this one's cells),
#      or calls a prefetching function.
# Optimised x86-64 builds without sanitizers only (exit 77, skipped, otherwise: at -O0 nothing is
# deleted, and a sanitizer build inlines differently, so a helper may sit out of line under
# another name).
# Usage: prefetch_kept.sh LIBRARY BUILD_TYPE [SANITIZED: 1 or 0]
set -euo pipefail
lib=$1
build_type=${2:-}
sanitized=${3:-0}
if [[ "$(uname -m)" != x86_64 || "$build_type" == Debug || -z "$build_type" || "$sanitized" == 1 ]] ||
  ! command -v objdump >/dev/null; then
  echo "skipped: needs an optimised x86-64 build without sanitizers, and objdump (build type '${build_type}', sanitized ${sanitized})"
  exit 77
fi
dis=$(mktemp)
trap 'rm -f "$dis"' EXIT
objdump -d --no-show-raw-insn -C "$lib" >"$dis"
awk '
  /^[0-9a-f]+ <.*>:$/ { fn = $0; sub(/^[0-9a-f]+ </, "", fn); sub(/>:$/, "", fn); next }
  fn ~ /^pge::World<double>::/ || fn ~ /^pge::EventHeap<double>::/ {
    if ($0 ~ /prefetch/) pf[fn]++
    if ($0 ~ /call/) { calls[fn]++; if ($0 ~ /prefetch/) pfcall[fn]++ }
    seen[fn] = 1
  }
  END {
    bad = 0; helpers = 0
    for (f in seen) {
      if (f ~ /prefetch/) {
        helpers++
        if (!pf[f] && !calls[f]) { print "no prefetch left in " f; bad = 1 }
      }
      if (f == "pge::World<double>::step()") {
        step = 1
        if (!pf[f] && !pfcall[f]) { print "no prefetch left in " f; bad = 1 }
        else print "ok: " f ": " pf[f] + 0 " prefetch instructions, " pfcall[f] + 0 " calls to prefetching functions"
      }
    }
    if (!step) { print "World<double>::step() not found in the disassembly"; bad = 1 }
    if (!bad) print "ok: " helpers " out-of-line prefetch helpers, each issuing prefetches or calling"
    exit bad
  }' "$dis"
