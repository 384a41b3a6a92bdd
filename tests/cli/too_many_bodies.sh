#!/usr/bin/env bash
# Body limits (engine/include/pge/constants.hpp). Without the broad phase a scene past
# kMaxBodiesWithoutBroadPhase = 100,000 is refused at once with exit 5 and one clear line, not
# left to spend hours predicting every pair; with the grid (the default for such a scene) the
# same scene runs.
# Usage: too_many_bodies.sh PGE EXPECT_ERROR_SCRIPT
set -eu
pge=$1
expect_error=$2
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
"$pge" generate gas --bodies 100001 --seed 1 -o "$dir/gas.json"
"$expect_error" 5 "100005 bodies" "at most 100000" -- "$pge" run "$dir/gas.json" --max-events 10 --broad-phase all-pairs
"$pge" run "$dir/gas.json" --max-events 10 --json "$dir/summary.json" -q
grep -q '"broad_phase": *"grid"' "$dir/summary.json" || { echo "expected the grid in $dir/summary.json"; cat "$dir/summary.json"; exit 1; }
grep -q '"collisions": *10\b' "$dir/summary.json" || { echo "expected 10 collisions"; cat "$dir/summary.json"; exit 1; }
echo "ok: refused without the broad phase, ran with the grid"
