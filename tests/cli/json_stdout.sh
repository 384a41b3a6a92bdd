#!/usr/bin/env bash
# `--json -` writes the JSON to standard output, alone (run, check, judge, compare). Before, run,
# check and judge wrote it to a file named "-" in the working directory and printed their text
# summaries on stdout.
# Usage: json_stdout.sh PGE SCENE
set -u
pge=$(realpath "$1"); scene=$(realpath "$2")
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
cd "$dir" || exit 1
fail() { echo "FAIL: $*"; exit 1; }
is_json() {  # FILE FORMAT-CHECK (a Python expression over d)
  python3 -c 'import json, sys; d = json.load(open(sys.argv[1])); sys.exit(0 if eval(sys.argv[2]) else 1)' "$1" "$2"
}
"$pge" run "$scene" --json - > out 2> err || fail "pge run --json - exited with $?: $(cat err)"
is_json out 'isinstance(d, list) and len(d) == 1 and "state_hash" in d[0]' || fail "pge run: stdout is not the summaries' JSON alone: $(head -c 300 out)"
"$pge" check "$scene" --json - > out 2> err || fail "pge check --json - exited with $?: $(cat err)"
is_json out 'd["format"] == "pge-check/1" and len(d["scenes"]) >= 1' || fail "pge check: stdout is not the JSON alone: $(head -c 300 out)"
"$pge" run "$scene" --trace t.jsonl -q || fail "pge run --trace exited with $?"
"$pge" judge t.jsonl --scene "$scene" --json - > out 2> err || fail "pge judge --json - exited with $?: $(cat err)"
is_json out 'd["format"] == "pge-judge/1"' || fail "pge judge: stdout is not the JSON alone: $(head -c 300 out)"
[[ -e ./- ]] && fail "a file named - was written"
code=0
"$pge" check "$scene" --json - --table > out 2> err || code=$?
[[ $code == 2 ]] || fail "pge check --json - --table: exit $code, expected 2 (both on stdout)"
grep -q -- "--table-out" err || fail "pge check --json - --table: the error does not name --table-out: $(cat err)"
echo "ok: run, check and judge write --json - to stdout alone; check --json - --table is refused"
