#!/usr/bin/env bash
# `pge judge` end to end (issue 28):
#  - PGE's own traces (pge run --trace, events mode) get the verdicts pge check gives the same
#    run, event by event (verdict and ulps): head-on (all agree: exit 0) and the fast solver's pool
#    break (misorders and phantoms: exit 7; pge check shows fast there for contrast only, the
#    scene's expect block being for robust and certified), and scenes of rotating bodies;
#  - hand-made step traces of a bullet and a thin wall (tests/cli/judge/: the bullet meets the
#    wall at t = (2 - 1/4 - 1/2) / 32 = 5/128 in the first step): passing through without a
#    report is a miss (exit 7, one line on stderr naming the pass-through), a bounce reported in
#    that step passes (exit 0); bad traces exit 12 with one line naming the line and the field.
# Usage: judge.sh PGE EXPECT_ERROR SCENES_DIR HERE
set -eu
pge=$1; expect_error=$2; scenes=$3; here=$4
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT

same_as_check() {  # scene solver max_events judge's_exit_code
  local scene=$1 solver=$2 max=$3 code=$4 judge_code=0
  "$pge" run "$scene" --solver "$solver" --max-events "$max" --trace "$dir/t.jsonl" -q
  "$pge" judge "$dir/t.jsonl" --scene "$scene" --json "$dir/j.json" -q 2>/dev/null || judge_code=$?
  "$pge" check "$scene" --solver "$solver" --max-events "$max" --json "$dir/c.json" -q 2>/dev/null || true
  [[ $judge_code -eq $code ]] || { echo "FAIL: $scene $solver: judge exits $judge_code, expected $code"; exit 1; }
  python3 - "$dir/j.json" "$dir/c.json" "$scene $solver" <<'PY'
import json, sys
judged = json.load(open(sys.argv[1]))["result"]["events"]
checked = json.load(open(sys.argv[2]))["scenes"][0]["events"]
# Every event's exact time too: pge check writes it for every event of its JSON (and only there
# and in a failure's line: make_record's decimals).
key = lambda e: (e["index"], e["a"], e["b"], e["verdict"], e.get("ulps"), e.get("exact_time"))
if any("ulps" in e and not e.get("exact_time") for e in checked):
    sys.exit(f"FAIL: {sys.argv[3]}: pge check's JSON has a timed event without its exact time")
if [key(e) for e in judged] != [key(e) for e in checked]:
    for j, c in zip(judged, checked):
        if key(j) != key(c): print("first difference:", key(j), key(c)); break
    sys.exit(f"FAIL: {sys.argv[3]}: {len(judged)} judged events differ from pge check's {len(checked)}")
print(f"ok: {sys.argv[3]}: {len(judged)} events, verdicts as pge check's:",
      sorted({e['verdict'] for e in judged}))
PY
}
same_as_check "$scenes/basics/head-on.json" robust 100 0
same_as_check "$scenes/simultaneous/pool-break.json" fast 300 7
# A failure's line names the pair's exact time in 20 decimals (make_record writes them for
# failures even without --json): fast's pool break has a phantom whose pair touches later.
"$pge" check "$scenes/simultaneous/pool-break.json" --solver fast --max-events 300 > "$dir/failures" 2>&1 || true
grep -Eq 'FAILED: phantom .*touches only at [0-9]+\.[0-9]{20}$' "$dir/failures" ||
  { echo "FAIL: pge check prints no failure line with the exact time in decimals: $(grep FAILED "$dir/failures")"; exit 1; }
# Rotating bodies (issue 26): the trace's reference points, angles and angular velocities give the
# referee pge check's paths. A spinning box sliding into a wall and back; the twelve spinning
# boxes, two of them with their reference point at a corner (not the pivot they turn about).
same_as_check "$here/rotating-box.json" robust 50 0
same_as_check "$scenes/peers/peers-spinning-boxes.json" certified 1000 0

j=$here/judge
"$expect_error" 7 "bullet-tunnels.jsonl" "\"bullet\"-\"wall\"" "exact t = 0.0390625" "pass-through" -- \
  "$pge" judge "$j/bullet-tunnels.jsonl" --scene "$j/bullet-thin-wall.json" --quiet
"$pge" judge "$j/bullet-tunnels.jsonl" --scene "$j/bullet-thin-wall.json" --json "$dir/tunnels.json" -q 2>/dev/null || true
python3 - "$dir/tunnels.json" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
assert r["format"] == "pge-judge/1" and r["mode"] == "steps", r
c = r["result"]["contacts"]
want = [{"a": "bullet", "b": "wall", "step": 1, "t_step": 0.0625, "verdict": "missed", "exact_time": 0.0390625,
         "off_path": False, "reported_step": None, "miss": "pass_through", "depth": 0.0, "relative_depth": 0.0}]
assert c == want, c
s = r["result"]["summary"]
assert (s["contacts"], s["missed"], s["tunnelled"], s["failed"]) == (1, 1, 1, True), s
assert [x["t"] for x in r["result"]["steps"]] == [0, 0.0625, 0.125], r["result"]["steps"]
print("ok: the tunnelling trace's JSON")
PY
"$pge" judge "$j/bullet-bounces.jsonl" --scene "$j/bullet-thin-wall.json" | grep -q "on time 1, late 0" ||
  { echo "FAIL: the reported bounce is not on time"; exit 1; }
# A square turning in place at 1 rad/s next to a wall (square-spins-next-to-a-wall.json): its
# corner reaches the wall at t = pi/4 - acos((5/8) sqrt 2) = 0.29870320832267516 (in double), in
# the step (1/4, 3/8]. Skipped by one step from 1/4 to 3/2 (every corner behind the wall's line
# again there): missed, pass-through (exit 7); struck and reported in its step: on time.
"$expect_error" 7 "square-skips-the-wall.jsonl" "\"box\"-\"wall\"" "exact t = 0.298703208322675" "pass-through" -- \
  "$pge" judge "$j/square-skips-the-wall.jsonl" --scene "$j/square-spins-next-to-a-wall.json" --quiet
"$pge" judge "$j/square-strikes-the-wall.jsonl" --scene "$j/square-spins-next-to-a-wall.json" | grep -q "on time 1, late 0" ||
  { echo "FAIL: the reported corner strike is not on time"; exit 1; }
"$expect_error" 12 "bullet-bad-nan.jsonl:2:" "field \"bodies[0][2]\"" "NaN" -- \
  "$pge" judge "$j/bullet-bad-nan.jsonl" --scene "$j/bullet-thin-wall.json"
"$expect_error" 12 "bullet-bad-body.jsonl:2:" "field \"contacts[0][1]\"" "no body \"wal\"" -- \
  "$pge" judge "$j/bullet-bad-body.jsonl" --scene "$j/bullet-thin-wall.json"
"$expect_error" 12 "no-such.jsonl" "cannot open" -- "$pge" judge "$dir/no-such.jsonl" --scene "$j/bullet-thin-wall.json"
"$expect_error" 3 "no-such.json" -- "$pge" judge "$j/bullet-bounces.jsonl" --scene "$dir/no-such.json"
echo "ok: pge judge"
