#!/usr/bin/env bash
# `pge check` on every bundled scene over a short horizon: exit 0 (no miss, no phantom), one
# summary per scene with its verdict counts, and a JSON document with every event's verdict.
# Usage: check_bundled.sh PGE SCENES_DIR [--skip FOLDER]... [--allow-undecided] [pge check options...]
#   --skip FOLDER      leave SCENES_DIR/FOLDER out (another test checks it with other options)
#   --allow-undecided  accept undecided verdicts (the referee for rotation's exact tangencies),
#                      counted and printed; without it a scene with one fails
set -eu
pge=$1; scenes=$2; shift 2
skip=(); undecided='0'
while [[ $# -gt 0 ]]; do
  case $1 in
    --skip) skip+=("$2"); shift 2 ;;
    --allow-undecided) undecided='[0-9]*'; shift ;;
    *) break ;;
  esac
done
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
targets=()
if [[ ${#skip[@]} -eq 0 ]]; then
  targets=("$scenes")
else
  for entry in "$scenes"/*; do
    name=$(basename "$entry")
    for s in "${skip[@]}"; do [[ $name == "$s" ]] && continue 2; done
    [[ -d $entry || $entry == *.json ]] && targets+=("$entry")
  done
fi
"$pge" check "${targets[@]}" "$@" --json "$out/check.json" >"$out/stdout" || {
  code=$?; cat "$out/stdout"; echo "FAIL: pge check exited with $code"; exit 1; }
count=$(find "${targets[@]}" -name '*.json' | wc -l)
summaries=$(grep -c '^scene ' "$out/stdout")
[[ $summaries -eq $count ]] || { echo "FAIL: $summaries summaries for $count scenes"; exit 1; }
verdict_lines=$(grep -c "^  verdicts: agree [0-9]*, tie [0-9]*, time_error [0-9]*, misorder [0-9]*, miss 0, phantom 0, undecided $undecided\$" "$out/stdout")
[[ $verdict_lines -eq $count ]] || { cat "$out/stdout"; echo "FAIL: $verdict_lines scenes without miss or phantom (undecided $undecided) of $count"; exit 1; }
grep -q '"format":"pge-check/1"' "$out/check.json" || { echo "FAIL: no pge-check/1 JSON"; exit 1; }
events=$(grep -c '"verdict":' "$out/check.json" || true)
[[ $events -gt 0 ]] || { echo "FAIL: no per-event verdicts in the JSON"; exit 1; }
undecided_total=$(grep -o 'undecided [0-9]*$' "$out/stdout" | awk '{s += $2} END {print s + 0}')
echo "ok: $count scenes checked, $events events judged, no miss and no phantom, $undecided_total undecided"
