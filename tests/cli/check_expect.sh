#!/usr/bin/env bash
# `pge check` and the expect block (fixtures/README.md, "Expectations") on the scenes of
# tests/cli/expect/, whose expected values are mathematics (each scene's note derives them):
# expectations that hold pass, a solver the block does not list is shown for contrast and never
# fails, a shorter run (--until) is judged by the oracle alone, "oracle": false still checks the
# rest, and --table / --table-out give one Markdown row per scene.
# Usage: check_expect.sh PGE EXPECT_SCENES_DIR
set -u
pge=$1; dir=$2
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
fail() { echo "FAIL: $*"; for f in "$out"/*; do echo "--- $f"; cat "$f"; done; exit 1; }

# Every expectation holds with robust and certified (17 of them: stop, events, oracle, ulps,
# 2 energy, momentum, overlap, 4 final components, 1 collision, 2 never_collide, 2 at_rest).
"$pge" check --all-solvers "$dir/head-on-holds.json" >"$out/holds" 2>"$out/holds.err" || fail "holds: exit $?"
[[ $(grep -c '^  expectations: 17 checked, all hold$' "$out/holds") -eq 2 ]] || fail "holds: robust and certified"
grep -q '^  expectations (contrast, not enforced: fast is not among the expect block.s solvers): 17 checked' \
  "$out/holds" || fail "holds: fast is not shown for contrast"
[[ ! -s "$out/holds.err" ]] || fail "holds: stderr is not empty"

# "oracle": false: the engine runs alone; the 7 other expectations are checked.
"$pge" check "$dir/head-on-no-oracle.json" >"$out/no-oracle" 2>&1 || fail "no-oracle: exit $?"
grep -q 'not judged' "$out/no-oracle" || fail "no-oracle: judged"
grep -q '^  expectations: 7 checked, all hold$' "$out/no-oracle" || fail "no-oracle: expectations"

# A wrong expectation on a solver the block does not list: shown, not a failure.
"$pge" check --solver fast "$dir/head-on-wrong-time.json" >"$out/contrast" 2>"$out/contrast.err" ||
  fail "contrast: exit $?"
grep -q '^  expectations (contrast, not enforced: .*1 would fail:$' "$out/contrast" || fail "contrast: no contrast line"
[[ ! -s "$out/contrast.err" ]] || fail "contrast: stderr is not empty"

# A shorter run than the block describes: judged by the oracle only.
"$pge" check --until 3 "$dir/head-on-wrong-time.json" >"$out/until" 2>&1 || fail "until: exit $?"
grep -q '^  expectations: not checked: --until 3 changes the run' "$out/until" || fail "until: no note"

# The table: one row per scene, three solvers; the wrong scene fails for robust and certified
# (one stderr line each) and is contrast for fast.
code=0
"$pge" check --table "$dir/head-on-holds.json" "$dir/head-on-wrong-time.json" >"$out/table" 2>"$out/table.err" || code=$?
[[ $code -eq 7 ]] || fail "table: exit $code, expected 7"
grep -q '^| family *| scene *| fast events |.*| certified result *|$' "$out/table" || fail "table: header"
grep -q '^| expect *| `head-on-holds` *| *1 | *0 | *0 | n/a (contrast: pass) *| *1 | *0 | *0 | pass *| *1 | *0 | *0 | pass *|$' \
  "$out/table" || fail "table: holds row"
grep -q '^| expect *| `head-on-wrong-time` *|.*| n/a (contrast: fails collisions\[0\]) *|.*| FAIL: collisions\[0\] *|.*| FAIL: collisions\[0\] *|$' \
  "$out/table" || fail "table: wrong-time row"
[[ $(grep -c '^scene ' "$out/table") -eq 0 ]] || fail "table: summaries printed with the table"
[[ $(wc -l <"$out/table.err") -eq 2 ]] || fail "table: expected 2 lines on stderr"

# --table-out: the same table in a file, the summaries on stdout.
code=0
"$pge" check --table-out "$out/table.md" "$dir/head-on-holds.json" "$dir/head-on-wrong-time.json" \
  >"$out/table-out" 2>/dev/null || code=$?
[[ $code -eq 7 ]] || fail "table-out: exit $code, expected 7"
cmp -s "$out/table" "$out/table.md" || fail "table-out: the file differs from the printed table"
[[ $(grep -c '^scene ' "$out/table-out") -eq 6 ]] || fail "table-out: expected 6 summaries (2 scenes, 3 solvers)"
echo "ok: expectations hold, contrast, --until, oracle off, --table and --table-out"
