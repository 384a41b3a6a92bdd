#!/bin/sh
# pge compare (issue 11): a row per setting (PGE's 2, and 6 per installed peer), the JSON file,
# exit 0; --solvers x --scalars rows (exact on head-on in float and quad); a bad scene exits 3;
# an unwritable --json exits 6.
# Usage: compare.sh COMPARE_COMMAND... -- SCENE_DIR   (e.g. `pge compare` or `pge_compare_dev`)
set -u
cmd=""
while [ $# -gt 0 ] && [ "$1" != "--" ]; do cmd="$cmd $1"; shift; done
shift
scenes=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "compare.sh: $*" >&2; exit 1; }
. "$(dirname "$0")/peer_rows.sh"

$cmd "$scenes/peers-head-on.json" --json "$tmp/rows.json" >"$tmp/out.md" 2>"$tmp/err.txt" ||
  fail "exit $? on head-on; stderr: $(cat "$tmp/err.txt")"
grep -q '^| engine | setting | wall time (s) | energy drift | momentum drift | penetration | tunnelled | final-state error | contacts on time | late | missed | phantom |$' "$tmp/out.md" ||
  fail "no table header"
[ "$(grep -c '^| pge | pge ' "$tmp/out.md")" -eq 2 ] || fail "expected 2 pge rows"
# PGE certified is exact on a head-on collision: energy drift 0 and final-state error 0.
# PGE rows have no step verdicts (-): pge check judges their events.
grep -q '^| pge | pge certified/double | [0-9.]* | 0 | 0 | 0 | 0 | 0 | - | - | - | - |$' "$tmp/out.md" || fail "pge certified row not exact"
installed_peers "$tmp/out.md" "$tmp/err.txt" >/dev/null || exit 1
# --solvers and --scalars: a PGE row for each pair, exact on head-on in every scalar.
$cmd "$scenes/peers-head-on.json" --peers chipmunk --solvers robust,certified --scalars float,quad >"$tmp/scalars.md" 2>"$tmp/err2.txt" ||
  fail "exit $? with --scalars; stderr: $(cat "$tmp/err2.txt")"
[ "$(grep -c '^| pge | pge ' "$tmp/scalars.md")" -eq 4 ] || fail "expected 4 pge rows with --scalars float,quad"
for config in robust/float robust/quad certified/float certified/quad; do
  grep -q "^| pge | pge $config | [0-9.]* | 0 | 0 | 0 | 0 | 0 | - | - | - | - |\$" "$tmp/scalars.md" || fail "pge $config row not exact"
done
$cmd "$scenes/peers-head-on.json" --scalars half >/dev/null 2>&1
[ $? -eq 2 ] || fail "an unknown scalar should exit 2"
[ -s "$tmp/rows.json" ] || fail "--json wrote nothing"
grep -q '"engine": "pge"' "$tmp/rows.json" || fail "--json has no pge row"

echo '{"format": "pge-scene/1", "bodies": [' > "$tmp/bad.json"
$cmd "$tmp/bad.json" >/dev/null 2>&1
[ $? -eq 3 ] || fail "a malformed scene should exit 3"
$cmd "$scenes/peers-head-on.json" --peers box2d --json "$tmp/no-such-dir/rows.json" >/dev/null 2>&1
[ $? -eq 6 ] || fail "an unwritable --json should exit 6"
$cmd "$scenes/peers-head-on.json" --peers bullet >/dev/null 2>&1
[ $? -eq 2 ] || fail "an unknown peer should exit 2"
echo "compare.sh: ok"
