#!/usr/bin/env bash
# `pge run` on every bundled scene: exit 0, a summary per scene, and a trace per scene whose
# first line is the trace header and last line the end record.
set -eu
pge=$1; scenes=$2
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
"$pge" run "$scenes" --until 1 --trace-dir "$out/traces" --json "$out/summary.json" >"$out/stdout"
count=$(find "$scenes" -name '*.json' | wc -l)
summaries=$(grep -c '^scene ' "$out/stdout")
[[ $summaries -eq $count ]] || { echo "FAIL: $summaries summaries for $count scenes"; exit 1; }
for f in "$out"/traces/*.jsonl; do
  head -n1 "$f" | grep -q '"format":"pge-trace/2"' || { echo "FAIL: $f has no trace header"; exit 1; }
  tail -n1 "$f" | grep -q '"event":"end"' || { echo "FAIL: $f has no end record"; exit 1; }
done
traces=$(ls "$out"/traces/*.jsonl | wc -l)
[[ $traces -eq $count ]] || { echo "FAIL: $traces traces for $count scenes"; exit 1; }
echo "ok: $count scenes, $traces traces"
