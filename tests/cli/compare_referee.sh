#!/bin/sh
# pge compare's referee columns (issue 28, item 3): each peer setting's run recorded as a step
# trace and judged by the exact referee, on the bullet against a thin wall.
#
# What the scene does (fixtures/scenes/peers/peers-bullet-thin-wall.json), worked out by hand:
# a ball of radius 0.5 at x = -2 moving at 1e4 m/s towards a fixed wall x in [0, 1e-4], run to
# t = 1e-3. A peer makes max(1, round(1e-3 hz)) steps: 1 step of 1e-3 s at 60, 240 and 1000 Hz
# alike. On the step's start-state path the ball's front (x = -1.5) reaches the wall at exactly
# t = 1.5 / 1e4 = 1.5e-4, inside that step: one exact contact per setting, and no other pair.
#  - Chipmunk (no continuous collision) moves the ball 10 m in the step, to x = 8, clear of the
#    wall: it reports nothing and the pair is apart at the step's end: missed (pass-through).
#  - Box2D scales the scene by 64 (peer_sim.hpp box2d_length_scale: the wall's 1e-4 side must
#    be at least b2_linearSlop 0.005, so 2^ceil(log2 50)), and b2_maxTranslation (2 units a step)
#    caps the ball at 2 / 64 m per step: it ends at x = -1.96875, 1.47 m short of the wall, and
#    reports nothing either: the exact contact is missed (apart at the step's end: pass-through).
# So every peer row: steps 1, contacts 1, on time 0, late 0, missed 1 (pass-through 1), phantom 0.
# PGE rows: no step verdicts ("-", referee null with a note). Plus: on every row the verdicts add
# up (on time + late + missed = contacts), `--json -` gives JSON alone on stdout (Chipmunk's
# greeting kept off it), --trace-dir writes traces that `pge judge` reads and fails (exit 7),
# and --no-judge leaves the columns out.
# Usage: compare_referee.sh PGE SCENE_DIR
set -u
pge=$1
scene=$2/peers-bullet-thin-wall.json
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "compare_referee.sh: $*" >&2; exit 1; }

"$pge" compare "$scene" --json "$tmp/rows.json" --trace-dir "$tmp/traces" >"$tmp/out.md" 2>"$tmp/err.txt" ||
  fail "exit $?; stderr: $(cat "$tmp/err.txt")"
grep -q '| contacts on time | late | missed | phantom |$' "$tmp/out.md" || fail "no referee columns in the table header"
grep -q '^| pge | pge robust/double | .* | - | - | - | - |$' "$tmp/out.md" || fail "pge robust row has no '-' referee cells"
for peer in box2d chipmunk; do
  grep -q "$peer is not installed" "$tmp/err.txt" && continue
  n=$(grep -c "^| $peer | $peer .* | 0 | 0 | 1 | 0 |\$" "$tmp/out.md")
  [ "$n" -eq 6 ] || fail "expected 6 $peer rows with on time 0, late 0, missed 1, phantom 0; got $n: $(grep "^| $peer" "$tmp/out.md")"
done

python3 - "$tmp/rows.json" "$tmp/err.txt" <<'PY' || exit 1
import json, sys
rows = json.load(open(sys.argv[1]))
skipped = open(sys.argv[2]).read()
def fail(msg):
    print("compare_referee.sh:", msg, file=sys.stderr); sys.exit(1)
peers = [r for r in rows if r["engine"] != "pge"]
for r in rows:
    if r["engine"] == "pge":
        if r["referee"] is not None or not r.get("referee_note"): fail(f"{r['label']}: a PGE row with step verdicts or no note")
        continue
    j = r["referee"]
    if j is None: fail(f"{r['label']}: no verdicts: {r.get('referee_note')}")
    if j["on_time"] + j["late"] + j["missed"] != j["contacts"]: fail(f"{r['label']}: verdicts do not add up: {j}")
    want = {"steps": 1, "contacts": 1, "on_time": 0, "late": 0, "missed": 1, "pass_through": 1, "phantom": 0}
    got = {k: j[k] for k in want}
    if got != want: fail(f"{r['label']}: {got}, expected {want}")
    if not r.get("trace"): fail(f"{r['label']}: no trace file named")
for peer in ("box2d", "chipmunk"):
    n = sum(r["engine"] == peer for r in peers)
    if n != (0 if f"{peer} is not installed" in skipped else 6): fail(f"{n} {peer} rows")
PY

# The traces on disk are the ones judged: pge judge gives the same miss, and fails (exit 7).
for f in "$tmp"/traces/*.jsonl; do
  [ -e "$f" ] || break
  "$pge" judge "$f" --scene "$scene" >"$tmp/judge.txt" 2>&1
  [ $? -eq 7 ] || fail "pge judge $f: expected exit 7 (a miss); $(cat "$tmp/judge.txt")"
  grep -q 'contacts: 1 exact: on time 0, late 0 (at most 0 steps), missed 1 (1 pass-through), phantom 0' "$tmp/judge.txt" ||
    fail "pge judge $f: $(cat "$tmp/judge.txt")"
done

# --json -: the JSON alone on stdout (no table, no library greeting).
"$pge" compare "$scene" --json - >"$tmp/stdout.json" 2>"$tmp/err2.txt" || fail "--json -: exit $?"
python3 -c 'import json, sys; json.load(open(sys.argv[1]))' "$tmp/stdout.json" ||
  fail "--json -: stdout is not the JSON alone: $(head -c 300 "$tmp/stdout.json")"
# --no-judge: no verdicts, the reason given.
"$pge" compare "$scene" --no-judge --json "$tmp/nojudge.json" >/dev/null 2>&1 || fail "--no-judge: exit $?"
python3 -c '
import json, sys
rows = json.load(open(sys.argv[1]))
assert all(r["referee"] is None and r["referee_note"] for r in rows), rows' "$tmp/nojudge.json" || fail "--no-judge gave verdicts"
echo "compare_referee.sh: ok"
