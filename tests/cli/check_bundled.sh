#!/usr/bin/env bash
# `pge check` on every bundled scene over a short horizon: exit 0 (no miss, no phantom), one
# summary per scene with its verdict counts, and a JSON document with every event's verdict.
# Usage: check_bundled.sh PGE SCENES_DIR [pge check options...]
set -eu
pge=$1; scenes=$2; shift 2
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
"$pge" check "$scenes" "$@" --json "$out/check.json" >"$out/stdout" || {
  code=$?; cat "$out/stdout"; echo "FAIL: pge check exited with $code"; exit 1; }
count=$(find "$scenes" -name '*.json' | wc -l)
summaries=$(grep -c '^scene ' "$out/stdout")
[[ $summaries -eq $count ]] || { echo "FAIL: $summaries summaries for $count scenes"; exit 1; }
verdict_lines=$(grep -c '^  verdicts: agree [0-9]*, tie [0-9]*, time_error [0-9]*, misorder [0-9]*, miss 0, phantom 0, undecided 0$' "$out/stdout")
[[ $verdict_lines -eq $count ]] || { cat "$out/stdout"; echo "FAIL: $verdict_lines scenes without miss or phantom of $count"; exit 1; }
grep -q '"format":"pge-check/1"' "$out/check.json" || { echo "FAIL: no pge-check/1 JSON"; exit 1; }
events=$(grep -c '"verdict":' "$out/check.json" || true)
[[ $events -gt 0 ]] || { echo "FAIL: no per-event verdicts in the JSON"; exit 1; }
echo "ok: $count scenes checked, $events events judged, no miss and no phantom"
