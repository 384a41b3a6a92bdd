#!/usr/bin/env bash
# The scale figures of docs/scale.md (bench_scale, every benchmark): builds bench_scale and pge, then
#   1. the three gas sizes in one bench_scale run, 3 repetitions (the cost of an event across N),
#      then gas_interleaved (the 1e3 and 1e5 gases in alternating batches: the same ratio with
#      the machine's noise falling on both sizes alike);
#   2. every bench_scale benchmark in a process of its own (so that peak_rss_mb is that scene's);
#   3. pge run on fixtures/scenes/basics/gas-1000.json with each solver, 3 times.
# Writes JSON and text to DIR (default out/scale) and prints a Markdown table of step 2, the
# medians of steps 1 and 3 and step 1's interleaved ratio. Takes about 6 minutes on an idle
# 2-core machine; run it idle, since the figures are timings. Exit code: 0, or non-zero if a
# build or a run failed.
# Usage: scripts/bench-scale.sh [--out DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
out=out/scale
while [[ $# -gt 0 ]]; do
  case "$1" in
    --out) [[ $# -ge 2 ]] || { echo "bench-scale.sh: --out needs a directory" >&2; exit 2; }; out=$2; shift 2 ;;
    -h|--help) sed -n '2,12p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "bench-scale.sh: unknown argument: $1 (see --help)" >&2; exit 2 ;;
  esac
done
build=${PGE_BUILD_DIR:-build}
scripts/install-deps.sh
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build "$build" -j "$(nproc)" --target bench_scale pge
mkdir -p "$out"
bench="$build/bench/bench_scale"

echo "== 1/3: the gas at 1e3, 1e4, 1e5 in one run" >&2
"$bench" --benchmark_filter='^gas/' --benchmark_repetitions=3 --benchmark_report_aggregates_only=true \
  --benchmark_out="$out/gas-one-run.json" --benchmark_out_format=json >"$out/gas-one-run.txt"
"$bench" --benchmark_filter='^gas_interleaved' \
  --benchmark_out="$out/gas-interleaved.json" --benchmark_out_format=json >"$out/gas-interleaved.txt"

names=(gas/1000 gas/10000 gas/100000 pegs/1000 pegs/10000 polygons/1000 polygons/10000 gas_quartic/1000
       gas_quartic/10000 gas_all_pairs/16 gas_all_pairs/32 gas_all_pairs/64 gas_all_pairs/128 gas_all_pairs/1000
       gas_grid/16 gas_grid/32 gas_grid/64 gas_grid/128)
for name in "${names[@]}"; do
  echo "== 2/3: $name" >&2
  "$bench" --benchmark_filter="^$name\$" --benchmark_min_time=2 \
    --benchmark_out="$out/${name//\//-}.json" --benchmark_out_format=json >"$out/${name//\//-}.txt"
done

for solver in robust fast certified; do
  for k in 1 2 3; do
    echo "== 3/3: gas-1000 with $solver, run $k" >&2
    "$build/cli/pge" run fixtures/scenes/basics/gas-1000.json --solver "$solver" -q --json "$out/gas1000-$solver-$k.json"
  done
done

python3 - "$out" "${names[@]}" <<'EOF'
import json, statistics, sys
out, names = sys.argv[1], sys.argv[2:]
print("| benchmark | bodies | events/s | ns/event | crossings/event | predictions/event | bytes/body | peak RSS |")
print("| --- | --- | --- | --- | --- | --- | --- | --- |")
for name in names:
    b = json.load(open(f"{out}/{name.replace('/', '-')}.json"))["benchmarks"][0]
    if b.get("error_occurred"):
        print(f"| `{name}` | error: {b.get('error_message')} |")
        continue
    ns = b["ns_per_event"] * (1e9 if b["ns_per_event"] < 1 else 1)
    print(f"| `{name}` | {b['bodies']:,.0f} | {b['events_per_second']:,.0f} | {ns:,.0f} | {b['crossings_per_event']:.2f} "
          f"| {b['predictions_per_event']:,.1f} | {b['bytes_per_body']:,.0f} | {b['peak_rss_mb']:.1f} MB |")
print()
for b in json.load(open(f"{out}/gas-one-run.json"))["benchmarks"]:
    if b.get("aggregate_name") == "median":
        ns = b["ns_per_event"] * (1e9 if b["ns_per_event"] < 1 else 1)
        print(f"one run, median of 3: {b['run_name']}: {ns:,.0f} ns per event")
b = json.load(open(f"{out}/gas-interleaved.json"))["benchmarks"][0]
if b.get("error_occurred"):
    print(f"gas_interleaved: error: {b.get('error_message')}")
else:
    print(f"interleaved batches, medians: {b['ns_per_event_1e3']:,.0f} ns per event at 1e3, "
          f"{b['ns_per_event_1e5']:,.0f} at 1e5: {b['ratio_1e5_to_1e3']:.2f} times")
print()
for solver in ("robust", "fast", "certified"):
    runs = [json.load(open(f"{out}/gas1000-{solver}-{k}.json"))[0] for k in (1, 2, 3)]
    print(f"gas-1000, {solver}: {statistics.median(r['events_per_second'] for r in runs):,.0f} events/s "
          f"(median of 3), state hash {runs[0]['state_hash']}")
EOF
