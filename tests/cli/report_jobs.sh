#!/usr/bin/env bash
# `pge report --jobs` (issue 27): rows measured by worker processes give the results of one at a
# time, and a worker that dies costs only its own row.
# - the same small sweep (two fixture families, 2 random scenes, every solver, the scaling, drift
#   and peers parts) with --jobs 1 and --jobs 2: the same rows in the same order, every field but
#   the timings identical (the timings: wall times, repeats, events/s, ns/prediction, cost);
#   meta.jobs says how each was made;
# - a worker killed mid-row (PGE_REPORT_TEST_CRASH: SIGABRT on the rows of one scene): exit 1,
#   the results written with each of that scene's rows a failed run naming the signal, every other
#   row as in the --jobs 1 run; the gate fails on them (exit 9, naming them);
# - the gate measures with the baseline's jobs unless told (meta.jobs of its report);
# - OUT/costs.json lists the rows' costs (those of 0.5 s or more), the next run into OUT reads it,
#   one of another sweep is left aside with a note, and --costs naming no file is exit 10.
# Usage: report_jobs.sh PGE FIXTURES_DIR
set -u
pge=$1; fixtures=$2
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
fail() { echo "FAIL: $*"; exit 1; }
sweep=(--quick --scenes "$fixtures/scenes/basics" "$fixtures/scenes/games" --random 2 --scalars float,double
       --parts accuracy,scaling,drift,peers --peer-scenes "$fixtures/scenes/peers/peers-head-on.json")

"$pge" report "${sweep[@]}" --jobs 1 --out "$out/j1" -q || fail "--jobs 1 exited with $?"
"$pge" report "${sweep[@]}" --jobs 2 --out "$out/j2" --progress-lines > "$out/j2.txt" 2>&1 ||
  { cat "$out/j2.txt"; fail "--jobs 2 exited with $?"; }
grep -q "2 at once" "$out/j2.txt" || { cat "$out/j2.txt"; fail "--jobs 2: the progress does not say 2 at once"; }

same_rows() {  # same_rows A B [SCENE]: B's rows are A's (but SCENE's, which must be failed runs)
  python3 - "$@" <<'PY'
import json, sys
timing = {"wall_seconds", "wall_min_seconds", "events_per_second", "ns_per_prediction", "repeats", "cost_seconds",
          "cost_cpu_seconds"}
a, b = (json.load(open(p)) for p in sys.argv[1:3])
crashed = sys.argv[3] if len(sys.argv) > 3 else None
ka = [(r["kind"], r["family"], r["scene"], r["solver"], r["scalar"]) for r in a["rows"]]
kb = [(r["kind"], r["family"], r["scene"], r["solver"], r["scalar"]) for r in b["rows"]]
assert ka == kb, "rows differ in number or order:\n%s\n%s" % (ka, kb)
assert len(ka) > 40, "only %d rows" % len(ka)
failed = 0
for ra, rb in zip(a["rows"], b["rows"]):
    if crashed and rb["scene"] == crashed:
        assert "worker process measuring it killed by signal 6" in rb["error"], rb["error"]
        failed += 1
        continue
    for f in ra:
        if f not in timing:
            assert ra[f] == rb[f], "%s: %s is %r with --jobs 1, %r with --jobs 2" % (ka[a["rows"].index(ra)], f, ra[f], rb[f])
assert not crashed or failed > 0, "no row of %s failed" % crashed
kinds = {k[0] for k in ka}
assert kinds == {"accuracy", "scaling", "drift", "peer"}, kinds
PY
}
same_rows "$out/j1/results.json" "$out/j2/results.json" || fail "--jobs 2 does not give the rows of --jobs 1"
python3 -c 'import json,sys; m=[json.load(open(p))["meta"]["jobs"] for p in sys.argv[1:]]; assert m == [1, 2], m' \
  "$out/j1/results.json" "$out/j2/results.json" || fail "meta.jobs is not 1 and 2"

# A worker that dies.
PGE_REPORT_TEST_CRASH=basics/head-on "$pge" report "${sweep[@]}" --jobs 2 --out "$out/crash" -q > "$out/crash.txt" 2>&1
code=$?
[[ $code -eq 1 ]] || { cat "$out/crash.txt"; fail "a worker killed: exit $code, expected 1"; }
grep -q "worker process(es) died" "$out/crash.txt" || { cat "$out/crash.txt"; fail "no line saying workers died"; }
same_rows "$out/j1/results.json" "$out/crash/results.json" head-on || fail "a worker killed: the other rows are not kept"
# The gate fails on the lost rows (a run that failed).
"$pge" gate --baseline "$out/j1/results.json" --results "$out/crash" --out "$out/g" > /dev/null 2>&1
[[ $? -eq 9 ]] || fail "the gate did not fail on the crashed rows"
grep -q "head-on: ran .*the run failed: the worker process measuring it killed by signal 6" "$out/g/gate.md" ||
  { cat "$out/g/gate.md"; fail "the gate's summary does not name the crashed rows"; }

# The gate measures as its baseline was measured: --jobs 2's baseline, 2 workers.
small=(--scenes "$fixtures/scenes/basics/head-on.json" --random 0 --solvers robust,certified --scalars double --parts accuracy)
"$pge" report --quick "${small[@]}" --jobs 2 --out "$out/b2" -q || fail "the small baseline"
"$pge" gate --baseline "$out/b2/results.json" "${small[@]}" --speed-factor 100 --calibrated-factor 100 --out "$out/g2" \
  > /dev/null 2>&1 || fail "the gate failed its own small sweep"
python3 -c 'import json,sys; j=json.load(open(sys.argv[1]))["meta"]["jobs"]; assert j == 2, j' "$out/g2/report/results.json" ||
  fail "the gate did not measure with its baseline's 2 jobs"
"$pge" gate --baseline "$out/b2/results.json" "${small[@]}" --jobs 1 --speed-factor 100 --calibrated-factor 100 \
  --out "$out/g1" > /dev/null 2>&1 || fail "the gate with --jobs 1 failed its own small sweep"
python3 -c 'import json,sys; j=json.load(open(sys.argv[1]))["meta"]["jobs"]; assert j == 1, j' "$out/g1/report/results.json" ||
  fail "the gate's --jobs 1 was not followed"
# What each row cost (OUT/costs.json): written by every unsharded run, read by the next run into
# the same directory (the order of work), refused by name when --costs names what is not one.
python3 - "$out/j2/costs.json" "$out/j2/results.json" <<'PY' || fail "costs.json is not the rows' costs of the quick sweep"
import json, sys
c, r = (json.load(open(p)) for p in sys.argv[1:3])
assert c["format"] == "pge-report-costs/1" and c["quick"] is True and c["max_events"] == 500, c
cost = {"%s/%s/%s/%s/%s" % (x["kind"], x["family"], x["scene"], x["solver"], x["scalar"]): x["cost_cpu_seconds"] for x in r["rows"]}
for key, seconds in c["rows"].items():
    assert key in cost and seconds >= 0.5 and abs(seconds - cost[key]) <= 5e-4, (key, seconds, cost.get(key))
assert all(key in c["rows"] for key, seconds in cost.items() if seconds >= 0.5005), "a costly row is not listed"
PY
"$pge" report --quick "${small[@]}" --jobs 2 --out "$out/b2" > "$out/again.txt" 2>&1 || fail "the second run into one directory"
grep -q "the longest first by $out/b2/costs.json" "$out/again.txt" || { cat "$out/again.txt"; fail "the second run did not read its directory's costs"; }
printf '{"format": "pge-report-costs/1", "quick": false, "max_events": 2000, "rows": {}}\n' > "$out/full-costs.json"
"$pge" report --quick "${small[@]}" --jobs 1 --costs "$out/full-costs.json" --out "$out/c1" > "$out/other.txt" 2>&1 ||
  fail "the costs of another sweep made the report fail"
grep -q "holds the costs of another sweep" "$out/other.txt" || { cat "$out/other.txt"; fail "no note on the costs of another sweep"; }
"$pge" report --quick "${small[@]}" --costs "$out/none.json" --out "$out/c2" > "$out/none.txt" 2>&1
code=$?
[[ $code -eq 10 ]] || { cat "$out/none.txt"; fail "--costs naming no file: exit $code, expected 10"; }
grep -q "cannot read $out/none.json" "$out/none.txt" || { cat "$out/none.txt"; fail "--costs naming no file: no message naming it"; }
echo "ok: --jobs 2 gives the rows of --jobs 1; a killed worker costs its rows only (exit 1); the gate follows the baseline; costs.json written, read back, refused by name"
