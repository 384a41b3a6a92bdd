#!/usr/bin/env bash
# Final state hashes of every bundled scene and fixture (fixtures/scenes/**, fixtures/regressions/**;
# not fixtures/known-failures) in every scalar and solver, one line each: file, scalar, solver,
# stop reason, collisions, grazes, final time, state hash. A change that must not move any event
# (a speed-up, a refactoring) compares the lines of two binaries:
#
#   scripts/state-hashes.sh OLD/pge > /tmp/old.txt
#   scripts/state-hashes.sh NEW/pge > /tmp/new.txt
#   diff /tmp/old.txt /tmp/new.txt && echo identical
#
# Options (environment): JOBS (parallel runs, default 2), SCALARS, SOLVERS (space-separated lists),
# SCENES (files or directories, default the two fixture folders). Runs scenes one per process, so
# that a scene the engine rejects or that crashes prints its own line (an error line) and the
# others still run. About 10 minutes on 2 idle cores, most of it quad.
set -euo pipefail
pge=${1:?usage: scripts/state-hashes.sh PATH/TO/pge}
root=$(cd "$(dirname "$0")/.." && pwd)
scalars=${SCALARS:-float double long-double quad}
solvers=${SOLVERS:-fast robust certified}
scenes=${SCENES:-$root/fixtures/scenes $root/fixtures/regressions}
jobs=${JOBS:-2}

one() {  # pge file scalar solver
  local out
  if out=$("$1" run --quiet --json - --scalar "$3" --solver "$4" "$2" 2>/dev/null) || [ -n "$out" ]; then
    printf '%s\n' "$out" | jq -r --arg f "$2" --arg sc "$3" --arg so "$4" \
      '.[] | [$f, $sc, $so, .stop, .collisions, .grazes, .time, .state_hash] | @tsv' 2>/dev/null ||
      printf '%s\t%s\t%s\terror\n' "$2" "$3" "$4"
  else
    printf '%s\t%s\t%s\terror\n' "$2" "$3" "$4"
  fi
}
export -f one

find $scenes -name '*.json' | sort | while read -r f; do
  for sc in $scalars; do
    for so in $solvers; do printf '%s\0%s\0%s\0%s\0' "$pge" "${f#"$root"/}" "$sc" "$so"; done
  done
done | (cd "$root" && xargs -0 -n 4 -P "$jobs" bash -c 'one "$@"' _) | sort
