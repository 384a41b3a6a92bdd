#!/usr/bin/env bash
# A scene past the engine's body limit (kMaxBodiesWithoutBroadPhase = 100,000) is refused at
# once with exit 5 and one clear line, not left to spend hours predicting every pair.
# Usage: too_many_bodies.sh PGE EXPECT_ERROR_SCRIPT
set -eu
pge=$1
expect_error=$2
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
"$pge" generate gas --bodies 100001 --seed 1 -o "$dir/gas.json"
"$expect_error" 5 "100005 bodies" "at most 100000" -- "$pge" run "$dir/gas.json" --max-events 10
