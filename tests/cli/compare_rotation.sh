#!/bin/sh
# pge compare on the spinning boxes (issues 25 and 26: the peers with rotation on, their contacts
# judged): PGE robust and certified and every installed peer setting run to the horizon; PGE
# certified, the reference, is elastic to rounding (1e-12, as the scene's expect block); peers'
# step traces carry each body's turn, and the exact referee judges every peer row, following
# each box between steps from its recorded angle at its recorded angular velocity. What can be
# derived of the verdicts:
#  - Chipmunk reports the arbiters it found overlapping after moving the bodies, i.e. at the
#    step's end positions, so a report of a pair that stays apart through the step (a phantom)
#    cannot happen: 0 phantoms at every setting.
#  - Box2D reports a pair once its shapes come within their skins (b2_polygonRadius 0.01 each, at
#    the scene's length scale 4, peer_sim.hpp: 2.5 mm each, 5 mm together) and bounces them off
#    there; it has no path without a contact that a free flight from the step's start would not
#    follow, so an exact contact in a step always has its report: 0 missed. Its phantoms are
#    those skin contacts: apart at the step's start and end (checked here from the trace in
#    Python floats, apart from the referee's code), and at 1000 Hz the gap at the step's start is
#    at most the 5 mm of skin plus what the pair can close in the 1 ms step before Box2D's
#    contact acts, each body's points moving at most |v| + |w| r (r its half diagonal, the reach
#    from its centroid) at the step's start, plus 0.1 mm for Box2D's float coordinates (about 1e-6
#    m at 8 m).
#  - pge judge on a peer's written trace gives the row's counts.
# Usage: compare_rotation.sh PGE SCENE
set -u
pge=$1
scene=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "compare_rotation.sh: $*" >&2; exit 1; }
. "$(dirname "$0")/peer_rows.sh"

"$pge" compare "$scene" --json "$tmp/rows.json" --trace-dir "$tmp/traces" >"$tmp/out.md" 2>"$tmp/err.txt" ||
  fail "exit $? on $scene; stderr: $(cat "$tmp/err.txt")"
[ "$(grep -c '^| pge | pge ' "$tmp/out.md")" -eq 2 ] || fail "expected 2 pge rows"
grep -q '^| pge | pge certified/double | [0-9.]* | [-0-9.e]* | [-0-9.e]* | [-0-9.e]* | 0 | 0 | - | - | - | - |$' "$tmp/out.md" ||
  fail "pge certified row: not run, tunnelled, or not the reference"
grep -q 'not run' "$tmp/out.md" && fail "a setting did not run: $(grep 'not run' "$tmp/out.md")"
grep -q 'not judged' "$tmp/out.md" && fail "a note says the peers are not judged: $(grep 'not judged' "$tmp/out.md")"
grep -q 'refused' "$tmp/err.txt" && fail "the referee refused a trace: $(cat "$tmp/err.txt")"
peers=$(installed_peers "$tmp/out.md" "$tmp/err.txt") || exit 1
for peer in $peers; do
  [ "$(grep "^| $peer | $peer " "$tmp/out.md" | grep -c ' | [0-9][0-9]* | [0-9][0-9]* | [0-9][0-9]* | [0-9][0-9]* |$')" -eq 6 ] ||
    fail "$peer rows without the referee's verdicts: $(grep "^| $peer | $peer " "$tmp/out.md")"
  # Every moving body's [angle, angular velocity] on each step line (12 boxes).
  trace=$(ls "$tmp/traces/$peer"-*.jsonl | head -n 1)
  sed -n 2p "$trace" | grep -q '"turns":\[\[[-0-9.e]*,[-0-9.e]*\]\(,\[[-0-9.e]*,[-0-9.e]*\]\)\{11\}\]' ||
    fail "$trace: a step without the 12 boxes' turns: $(sed -n 2p "$trace" | cut -c1-300)"
done
python3 - "$tmp/rows.json" <<'PY' || fail "JSON rows"
import json, sys
rows = json.load(open(sys.argv[1]))
for r in rows:
    if r["engine"] == "pge":
        assert r["referee"] is None, r["label"]
        continue
    j = r["referee"]
    assert j is not None, r
    assert j["contacts"] == j["on_time"] + j["late"] + j["missed"], r
    assert j["contacts"] + j["phantom"] > 0, r  # the boxes do hit the walls and each other
    assert j["undecided"] >= 0, r
    if r["engine"] == "chipmunk":
        assert j["phantom"] == 0, r
    if r["engine"] == "box2d":
        assert j["missed"] == 0, r
for r in rows:
    if r["label"] == "pge certified/double":
        assert abs(r["energy_drift"]) <= 1e-12, r
        assert r["final_error"] == 0, r
PY

case " $(echo $peers) " in *" box2d "*) ;; *) echo "compare_rotation.sh: ok (box2d not installed)"; exit 0 ;; esac
# Box2D at 1000 Hz: pge judge gives the row's counts, and each phantom is a skin contact.
trace=$tmp/traces/box2d-1000hz-8+3.jsonl
"$pge" judge "$trace" --scene "$scene" --json "$tmp/judge.json" -q 2>/dev/null
python3 - "$tmp/rows.json" "$tmp/judge.json" "$trace" "$scene" <<'PY' || fail "Box2D 1000 Hz verdicts"
import json, math, sys
row = next(r for r in json.load(open(sys.argv[1])) if r["label"] == "box2d 1000 Hz, 8+3 iterations")
judged = json.load(open(sys.argv[2]))["result"]
for k in ("contacts", "on_time", "late", "missed", "phantom", "undecided"):
    assert judged["summary"][k] == row["referee"][k], (k, judged["summary"], row["referee"])
lines = [json.loads(l) for l in open(sys.argv[3])]
ids, steps = lines[0]["bodies"], lines[1:]
bodies = {b["id"]: b for b in json.load(open(sys.argv[4]))["bodies"]}

def outline(body_id, step):  # world vertices; a step of None is the scene's start
    b = bodies[body_id]
    if b.get("fixed"):
        return [b["segment"]["a"], b["segment"]["b"]]
    if step is None:
        (x, y), angle = b["position"], b["angle"]
    else:
        k = ids.index(body_id)
        x, y, angle = step["bodies"][k][0], step["bodies"][k][1], step["turns"][k][0]
    c, s = math.cos(angle), math.sin(angle)
    return [(x + c * u - s * v, y + s * u + c * v) for u, v in b["polygon"]["vertices"]]

def closing(body_id, step):  # the fastest a point of the body moves at the step's start, m/s
    b = bodies[body_id]
    if b.get("fixed"):
        return 0.0
    if step is None:
        (vx, vy), w = b["velocity"], b["angular_velocity"]
    else:
        k = ids.index(body_id)
        vx, vy, w = step["bodies"][k][2], step["bodies"][k][3], step["turns"][k][1]
    v = b["polygon"]["vertices"]
    cx, cy = sum(x for x, _ in v) / len(v), sum(y for _, y in v) / len(v)
    return math.hypot(vx, vy) + abs(w) * max(math.hypot(x - cx, y - cy) for x, y in v)

def gap(p, q):  # separating-axis gap (> 0: apart), over both outlines' edge normals
    best = -math.inf
    for shape in (p, q):
        for i in range(len(shape) if len(shape) > 2 else 1):
            (ax, ay), (bx, by) = shape[i], shape[(i + 1) % len(shape)]
            nx, ny = by - ay, ax - bx
            n = math.hypot(nx, ny)
            pp = [(x * nx + y * ny) / n for x, y in p]
            qq = [(x * nx + y * ny) / n for x, y in q]
            best = max(best, min(qq) - max(pp), min(pp) - max(qq))
    return best

phantoms = [c for c in judged["contacts"] if c["verdict"] == "phantom"]
assert phantoms, "Box2D's skin contacts at 1000 Hz are phantoms"
for c in phantoms:
    k = c["step"]
    before = steps[k - 1] if k > 0 else None
    start = gap(outline(c["a"], before), outline(c["b"], before))
    end = gap(outline(c["a"], steps[k]), outline(c["b"], steps[k]))
    bound = 0.005 + 0.001 * (closing(c["a"], before) + closing(c["b"], before)) + 1e-4
    assert 0 < start <= bound and end > 0, (c, start, bound, end)
print(f"ok: box2d 1000 Hz: {len(phantoms)} phantoms, each apart through its step at the skin")
PY
echo "compare_rotation.sh: ok"
