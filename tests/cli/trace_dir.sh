#!/usr/bin/env bash
# pge run --trace-dir names each trace after its scene file, and scenes whose file names are the
# same get their folder's name before it, so no trace overwrites another (regression: two
# scene.json files in two folders wrote one scene.jsonl, the second run's).
# Usage: trace_dir.sh PGE SCENES_DIR
set -eu
pge=$1; scenes=$2
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
mkdir -p "$dir/first" "$dir/second"
cp "$scenes/basics/head-on.json" "$dir/first/scene.json"
cp "$scenes/basics/head-on.json" "$dir/second/scene.json"
cp "$scenes/basics/head-on.json" "$dir/alone.json"
"$pge" run "$dir/first" "$dir/second" "$dir/alone.json" --trace-dir "$dir/traces" -q
for name in first-scene second-scene alone; do
  [[ -s $dir/traces/$name.jsonl ]] || { echo "FAIL: no trace $name.jsonl; have: $(ls "$dir/traces")"; exit 1; }
done
[[ $(ls "$dir/traces" | wc -l) -eq 3 ]] || { echo "FAIL: expected 3 traces, have: $(ls "$dir/traces")"; exit 1; }
echo "ok: three traces, none overwritten"
