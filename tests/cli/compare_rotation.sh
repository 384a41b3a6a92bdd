#!/bin/sh
# pge compare on the spinning boxes (issue 25: the peers with rotation on): PGE robust and
# certified and every installed peer setting run to the horizon; the peers' contacts are not
# judged (the exact referee does not judge rotating bodies yet, issue 26), and the table and the
# JSON say so; PGE certified, the reference, is elastic to rounding (1e-12, as the scene's expect
# block); peers' step traces carry each body's turn.
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
grep -q '^Peer rows: - (not judged: the scene has rotating bodies, and the referee judges their contacts in PGE' "$tmp/out.md" ||
  fail "no note that the peers' contacts are not judged"
grep -q 'refused' "$tmp/err.txt" && fail "the referee was asked: $(cat "$tmp/err.txt")"
peers=$(installed_peers "$tmp/out.md" "$tmp/err.txt") || exit 1
for peer in $peers; do
  [ "$(grep "^| $peer | $peer " "$tmp/out.md" | grep -c ' | - | - | - | - |$')" -eq 6 ] || fail "$peer rows have referee verdicts"
  # Every moving body's [angle, angular velocity] on each step line (12 boxes).
  trace=$(ls "$tmp/traces/$peer"-*.jsonl | head -n 1)
  sed -n 2p "$trace" | grep -q '"turns":\[\[[-0-9.e]*,[-0-9.e]*\]\(,\[[-0-9.e]*,[-0-9.e]*\]\)\{11\}\]' ||
    fail "$trace: a step without the 12 boxes' turns: $(sed -n 2p "$trace" | cut -c1-300)"
done
python3 - "$tmp/rows.json" <<'PY' || fail "JSON rows"
import json, sys
rows = json.load(open(sys.argv[1]))
for r in rows:
    assert r["referee"] is None, r["label"]
    if r["engine"] != "pge":
        assert "rotating bodies" in r["referee_note"], r
    if r["label"] == "pge certified/double":
        assert abs(r["energy_drift"]) <= 1e-12, r
        assert r["final_error"] == 0, r
PY
echo "compare_rotation.sh: ok"
