// Scale benchmarks (issue "Scale"): events per second and ns per event of whole worlds, robust
// solver in double, for the scene families of properties/include/pge/families.hpp:
//   gas/N         elastic discs, area fraction 0.3, no gravity (N = 1e3, 1e4, 1e5)
//   pegs/N        discs raining through a lattice of fixed pegs under gravity 1, elastic
//   polygons/N    moving squares and triangles among fixed pentagons, no gravity
//   gas_quartic/N the gas with a distinct small acceleration per disc (every pair's contact is a
//                 quartic instead of a quadratic): what a scene pays for what it uses
//   gas_all_pairs/N  the gas without the broad phase (every body predicted against every body)
//   gas_interleaved  the gas at 1e3 and at 1e5 in one process, timed in alternating batches: the
//                 ratio of their costs per event with the machine's noise falling on both alike
// An event is a collision (or a graze); cell crossings are counted apart (crossings_per_event).
// The world is built and run for a warm-up of 10 events per body before timing, so that every
// size is measured at the same point of its run (the same simulated time, for the gas: its
// collision rate per body does not depend on N); each iteration then processes 10,000 events.
// That matters: robust and certified re-derive every event time exactly, by a walk over the
// doubles around the predicted time whose length grows with the prediction's error in ulps of
// the clock, large early in a run (a clock near 0 has tiny ulps) and larger in a larger box
// (each step's sign is filtered in floating point, exact only where the filter cannot decide).
// Counters: ns_per_event, events_per_second,
// bytes_per_body (World::memory_bytes() / bodies, after the warm-up), peak_rss_mb (the process's
// peak so far: run one benchmark per process to read it for that scene).
// Usage: bench_scale [google benchmark flags], e.g. --benchmark_filter='gas/' ; PGE_BENCH_SEED
// changes the scenes.
#include "pge/families.hpp"
#include "pge/world.hpp"

#include <benchmark/benchmark.h>
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

namespace {

using pge::BroadPhase;
using pge::GasParams;
using pge::Scene;
using pge::World;

constexpr std::uint64_t kEventsPerIteration = 10000;

std::uint64_t seed() {
  const char* s = std::getenv("PGE_BENCH_SEED");
  return s && *s ? std::strtoull(s, nullptr, 10) : 1;
}

GasParams params(std::uint32_t n) {
  GasParams p;
  p.bodies = n;
  p.radius = 0.01;
  p.area_fraction = 0.3;
  p.speed = 1;
  p.until = 1e9;
  p.max_events = 1ull << 60;
  p.seed = seed();
  return p;
}

double peak_rss_mb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_maxrss) / 1024.0;  // Linux: kilobytes
}

// The world of `scene`, run for the warm-up of 10 events per body.
std::unique_ptr<World<double>> warm_world(const Scene& scene, BroadPhase broad_phase) {
  pge::WorldOptions options;
  options.broad_phase = broad_phase;
  auto world = std::make_unique<World<double>>(scene, options);
  const std::uint64_t warmup = 10 * scene.bodies.size();
  for (std::uint64_t k = 0; k < warmup && world->step(); ++k) {
  }
  return world;
}

void run(benchmark::State& state, const Scene& scene, BroadPhase broad_phase) {
  auto world = warm_world(scene, broad_phase);
  const auto start = world->counts();
  std::uint64_t events = 0;
  for (auto _ : state) {
    for (std::uint64_t k = 0; k < kEventsPerIteration; ++k) {
      if (!world->step()) {
        state.SkipWithError("the run ended (horizon, storm or budget) before the benchmark did");
        return;
      }
    }
    events += kEventsPerIteration;
  }
  const auto& end = world->counts();
  state.counters["events_per_second"] = benchmark::Counter(static_cast<double>(events), benchmark::Counter::kIsRate);
  state.counters["ns_per_event"] =
      benchmark::Counter(static_cast<double>(events) * 1e-9, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["crossings_per_event"] =
      events ? static_cast<double>(end.crossings - start.crossings) / static_cast<double>(events) : 0.0;
  state.counters["predictions_per_event"] =
      events ? static_cast<double>(end.predictions - start.predictions) / static_cast<double>(events) : 0.0;
  state.counters["bodies"] = static_cast<double>(scene.bodies.size());
  state.counters["bytes_per_body"] = static_cast<double>(world->memory_bytes()) / static_cast<double>(scene.bodies.size());
  state.counters["global_bodies"] = static_cast<double>(end.global_bodies);
  state.counters["peak_rss_mb"] = peak_rss_mb();
  state.SetLabel(std::string(pge::broad_phase_name(world->broad_phase())));
}

void BM_Gas(benchmark::State& state) {
  run(state, pge::make_gas(params(static_cast<std::uint32_t>(state.range(0)))), BroadPhase::Auto);
}
void BM_GasAllPairs(benchmark::State& state) {
  run(state, pge::make_gas(params(static_cast<std::uint32_t>(state.range(0)))), BroadPhase::AllPairs);
}
void BM_GasGrid(benchmark::State& state) {
  run(state, pge::make_gas(params(static_cast<std::uint32_t>(state.range(0)))), BroadPhase::Grid);
}
void BM_GasQuartic(benchmark::State& state) {
  Scene s = pge::make_gas(params(static_cast<std::uint32_t>(state.range(0))));
  pge::SplitMix64 rng(seed() + 1);
  for (auto& b : s.bodies)
    if (!b.fixed) b.acceleration = {rng.uniform(-1e-3, 1e-3), rng.uniform(-1e-3, 1e-3)};
  run(state, s, BroadPhase::Auto);
}
void BM_Pegs(benchmark::State& state) {
  run(state, pge::make_pegs(params(static_cast<std::uint32_t>(state.range(0)))), BroadPhase::Auto);
}
void BM_Polygons(benchmark::State& state) {
  run(state, pge::make_polygons(params(static_cast<std::uint32_t>(state.range(0)))), BroadPhase::Auto);
}
// The same polygons turning at up to 10 rad/s (docs/rotation.md): every pair with a turning body
// is predicted by the rotating search, with rigorous sin/cos enclosures.
void BM_SpinningPolygons(benchmark::State& state) {
  GasParams p = params(static_cast<std::uint32_t>(state.range(0)));
  p.spin = 10;
  run(state, pge::make_polygons(p), BroadPhase::Auto);
}

// The ratio (ns per event at 1e5 over 1e3) as one figure: run one after the other,
// gas/1000 and gas/100000 meet the machine's noise at different moments, and on a shared
// machine that moved the ratio by a few tenths from run to run. Here both gases are built and
// warmed in one process; each iteration runs a batch of 20,000 events on the 1e3 gas, then one
// on the 1e5 gas, each timed on its own. Counters: the median over the batches of each size's ns
// per event, and their ratio (ratio_1e5_to_1e3). 40 iterations (40 batches of each size).
void BM_GasInterleaved(benchmark::State& state) {
  constexpr std::uint64_t kBatch = 20000;
  auto small = warm_world(pge::make_gas(params(1000)), BroadPhase::Auto);
  auto large = warm_world(pge::make_gas(params(100000)), BroadPhase::Auto);
  std::vector<double> ns_small, ns_large;
  for (auto _ : state) {
    for (auto* w : {small.get(), large.get()}) {
      const auto t0 = std::chrono::steady_clock::now();
      for (std::uint64_t k = 0; k < kBatch; ++k) {
        if (!w->step()) {
          state.SkipWithError("the run ended (horizon, storm or budget) before the benchmark did");
          return;
        }
      }
      const double ns = std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - t0).count();
      (w == small.get() ? ns_small : ns_large).push_back(ns / static_cast<double>(kBatch));
    }
  }
  const auto median = [](std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.empty() ? 0.0 : v[v.size() / 2];
  };
  state.counters["ns_per_event_1e3"] = median(ns_small);
  state.counters["ns_per_event_1e5"] = median(ns_large);
  state.counters["ratio_1e5_to_1e3"] = median(ns_small) > 0 ? median(ns_large) / median(ns_small) : 0.0;
  state.counters["peak_rss_mb"] = peak_rss_mb();
}

// Unit(kMillisecond) per iteration of 10,000 events; ns_per_event is the figure to read.
BENCHMARK(BM_Gas)->Name("gas")->Arg(1000)->Arg(10000)->Arg(100000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_GasQuartic)->Name("gas_quartic")->Arg(1000)->Arg(10000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Pegs)->Name("pegs")->Arg(1000)->Arg(10000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Polygons)->Name("polygons")->Arg(1000)->Arg(10000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SpinningPolygons)->Name("spinning_polygons")->Arg(1000)->Arg(10000)->Unit(benchmark::kMillisecond);
// Where the grid starts to pay (kGridMinMovingBodies): the small gas both ways.
BENCHMARK(BM_GasAllPairs)->Name("gas_all_pairs")->Arg(16)->Arg(32)->Arg(64)->Arg(128)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_GasGrid)->Name("gas_grid")->Arg(16)->Arg(32)->Arg(64)->Arg(128)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_GasInterleaved)->Name("gas_interleaved")->Iterations(40)->Unit(benchmark::kMillisecond);

}  // namespace

// The build's kind in the context block: a PGE_VALIDATE build (CI's) runs an O(n^2) overlap scan
// every 1,024 events on scenes of up to 5,000 bodies, which is most of the translating gases' time
// and turns a ratio between families into a ratio of scans (spinning polygons against polygons at
// 1,000 bodies: about 23 times in CI's build, about 100 in a release build). Figures are read from
// a build configured with -DPGE_VALIDATE=OFF (the default).
int main(int argc, char** argv) {
#ifdef PGE_VALIDATE
  benchmark::AddCustomContext("pge_validate", "ON: timings include the validation scans; do not quote them");
  std::fprintf(stderr, "bench_scale: this is a PGE_VALIDATE build; its timings include the validation scans "
                       "(configure with -DPGE_VALIDATE=OFF to measure)\n");
#else
  benchmark::AddCustomContext("pge_validate", "OFF");
#endif
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
