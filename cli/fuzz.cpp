#include "fuzz.hpp"

#include "exit_codes.hpp"
#include "trace.hpp"

#include "pge/generators.hpp"
#include "pge/invariants.hpp"
#include "pge/oracle.hpp"
#include "pge/scene_io.hpp"

#include <fmt/core.h>

#include <array>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <functional>

namespace pge::cli {
namespace {

using Clock = std::chrono::steady_clock;

// Shrinking stops after this many candidate evaluations: a shrink tree can be deep, and a
// failure that is already found is worth more written down than shrunk for minutes.
constexpr int kMaxShrinkEvaluations = 2000;

// rapidcheck's size parameter: cases cycle through sizes 0..100 as rapidcheck's own runs do, so
// both small and large scenes are made in every shard.
constexpr int kMaxSize = 100;
constexpr std::uint64_t kStackEvery = 16;  // cases that may hold stacks (fuzz_command)

std::uint64_t mix(std::uint64_t x) {  // splitmix64 finaliser: independent seeds per case
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

struct Outcome {
  std::optional<Failure> failure;
  std::uint64_t events = 0;
  bool storm = false;
};

// The run again, every event judged by the exact oracle: the first miss or phantom (any
// solver but fast, whose closed forms are the baseline that is expected to fail) and, for the
// certified solver, the first time that is not the exact time correctly rounded.
std::optional<Failure> judge_with_oracle(const Scene& s, SolverKind solver) {
  WorldOptions wo;
  wo.solver = solver;
  World<double> world(s, wo);
  oracle::Referee referee(oracle::exact_state(world));
  std::optional<Failure> failure;
  oracle::follow(world, referee, [&](const CollisionInfo<double>& info, const oracle::ExactEvent&,
                                     const oracle::Judgement& j) {
    if (failure) return;
    const std::string pair = fmt::format("bodies \"{}\" and \"{}\"", s.bodies[info.a].id, s.bodies[info.b].id);
    if (j.verdict == oracle::Verdict::Miss)
      failure = Failure{FailureKind::Miss, info.time, pair + ": another pair touches exactly earlier"};
    else if (j.verdict == oracle::Verdict::Phantom)
      failure = Failure{FailureKind::Phantom, info.time, pair + ": no exact contact at this time"};
    else if (solver == SolverKind::Certified && j.verdict != oracle::Verdict::Undecided && (!j.pair_time || j.ulps != 0))
      failure = Failure{FailureKind::Rounding, info.time, fmt::format("{}: {} ulps from the exact time", pair, j.ulps)};
    if (failure) world.stop();
  });
  world.run();
  if (!failure && referee.stats().misses_between_events > 0)
    failure = Failure{FailureKind::Miss, world.time(), "a contact before a body slid off a face was never processed"};
  if (!failure && world.stop_reason() == StopReason::ReachedUntil && referee.judge_end().miss)
    failure = Failure{FailureKind::Miss, s.run.until, "a contact before the horizon was never processed"};
  return failure;
}

// With --spin: the scene with its moving polygons and segments turning (see FuzzOptions::spin).
Scene spun(const Scene& scene, const FuzzOptions& o) {
  if (!(o.spin > 0)) return scene;
  Scene s = scene;
  for (BodyDesc& b : s.bodies) {
    if (b.fixed || b.shape == ShapeKind::Circle) continue;
    const std::uint64_t r = mix(o.seed ^ mix(std::hash<std::string>{}(b.id)));
    const double u = static_cast<double>(r >> 11) * 0x1p-53;  // [0, 1)
    b.rotates = true;
    b.angular_velocity = o.spin * (2 * u - 1);
  }
  return s;
}

Outcome judge(const Scene& generated, const FuzzOptions& o) {
  const Scene s = spun(generated, o);
  InvariantOptions io;
  io.solver = o.solver;
  io.storms_fail = o.storms_fail;
  const InvariantReport r = check_invariants(s, io);
  Outcome out{r.failure, r.events, r.stop == StopReason::EventStorm};
  // Storms (resting contact between moving bodies) are the engine's known limit, not the oracle's business.
  if (!out.failure && !out.storm && o.oracle && o.solver != SolverKind::Fast)
    out.failure = judge_with_oracle(s, o.solver);
  return out;
}

// Greedy descent through rapidcheck's shrink tree: take the first smaller scene that still
// fails the same way, until none does (or the evaluation budget is spent).
rc::Shrinkable<GeneratedScene> shrink(rc::Shrinkable<GeneratedScene> current, FailureKind kind, const FuzzOptions& o,
                                      Failure& failure, int& evaluations) {
  bool progressed = true;
  while (progressed && evaluations < kMaxShrinkEvaluations) {
    progressed = false;
    auto candidates = current.shrinks();
    while (auto candidate = candidates.next()) {
      if (++evaluations > kMaxShrinkEvaluations) break;
      const Outcome r = judge(candidate->value().scene, o);
      if (r.failure && r.failure->kind == kind) {
        current = *candidate;
        failure = *r.failure;
        progressed = true;
        break;
      }
    }
  }
  return current;
}

std::string write_failure(const GeneratedScene& g, const Failure& f, const FuzzOptions& o, std::uint64_t case_index) {
  Scene s = spun(g.scene, o);
  const std::string text = write_scene(s);
  const std::string name = fmt::format("{}-{:016x}", failure_kind_name(f.kind), mix(std::hash<std::string>{}(text)));
  s.name = name;
  // The note is a string, as `pge check` and the regression tests read it (fixtures/README.md):
  // an object here made every written scene a bad scene file (exit 3) until edited by hand.
  const std::string note = fmt::format(
      R"J({{"note": {}}})J",
      json_quoted(fmt::format("Found by pge fuzz --seed {} --shard {}/{}{} (case {}), solver {}: {} at t = {}: {}. "
                              "Replace this note with what the scene tests and where its expectations come from.",
                              o.seed, o.shard, o.shards, o.spin > 0 ? fmt::format(" --spin {}", o.spin) : std::string(),
                              case_index, solver_name(o.solver), failure_kind_name(f.kind), f.time, f.detail)));
  std::filesystem::create_directories(o.out);
  const std::string path = (std::filesystem::path(o.out) / (name + ".json")).string();
  write_scene_file(s, path, note);
  return path;
}

}  // namespace

int fuzz_command(const FuzzOptions& o) {
  GenOptions gen_options;
  gen_options.polygons = o.polygons;
  const rc::Gen<GeneratedScene> gen = gen_scene(gen_options);
  // Every kStackEvery-th case may hold the Stack motif too (off in the generators' default):
  // its storms, resting contact between moving bodies, are reported and counted, not failures
  // unless --storms-fail, and a pass-through in a stack fails like any other. Not in every
  // case: a storm runs to the storm detector, and with stacks in every case a third of the
  // cases stormed and the fuzzer ran ten times fewer cases a second.
  GenOptions stack_options = gen_options;
  stack_options.motif_mask |= motif_bit(Motif::Stack);
  const rc::Gen<GeneratedScene> stack_gen = gen_scene(stack_options);

  const auto start = Clock::now();
  auto next_progress = start + std::chrono::milliseconds(500);
  std::uint64_t cases = 0, events = 0, storms = 0;
  std::array<std::uint64_t, static_cast<std::size_t>(FailureKind::Count)> by_kind{};
  std::vector<std::string> written;
  const auto elapsed = [&] { return std::chrono::duration<double>(Clock::now() - start).count(); };

  // Case k of the whole campaign belongs to shard k mod shards: shards with one seed never
  // overlap, and together they run exactly the cases of one unsharded campaign.
  const std::uint64_t first_k = o.first + (o.shard + o.shards - o.first % o.shards) % o.shards;  // first k >= first in this shard
  for (std::uint64_t k = first_k;; k += o.shards) {
    if (o.cases > 0 && cases >= o.cases) break;
    if (o.time_limit > 0 && elapsed() >= o.time_limit) break;
    if (o.cases == 0 && o.time_limit == 0) break;
    const std::uint64_t case_seed = mix(o.seed ^ mix(k));
    const int size = static_cast<int>(k % (kMaxSize + 1));
    const rc::Shrinkable<GeneratedScene> generated =
        (k % kStackEvery == 0 ? stack_gen : gen)(rc::Random(case_seed), size);
    const Outcome r = judge(generated.value().scene, o);
    ++cases;
    events += r.events;
    storms += r.storm ? 1 : 0;
    if (r.failure) {
      ++by_kind[static_cast<std::size_t>(r.failure->kind)];
      Failure failure = *r.failure;
      int evaluations = 0;
      const auto small = shrink(generated, failure.kind, o, failure, evaluations);
      std::string path;
      try {
        path = write_failure(small.value(), failure, o, k);
      } catch (const std::exception& e) {
        fmt::print(stderr, "\npge fuzz: cannot write the failing scene to {}: {}\n", o.out, e.what());
        return kExitOutput;
      }
      written.push_back(path);
      if (!o.quiet)
        fmt::print(stderr, "{}pge fuzz: case {}: {} at t = {:.17g}: {}; shrunk in {} evaluations to {} bodies: {}\n",
                   o.progress ? "\r" : "", k, failure_kind_name(failure.kind), failure.time, failure.detail,
                   evaluations, small.value().scene.bodies.size(), path);
      if (written.size() >= o.max_failures) break;
    }
    if (o.progress && Clock::now() >= next_progress) {
      next_progress = Clock::now() + std::chrono::milliseconds(500);
      fmt::print(stderr, "\r{} cases, {} events, {} failures, {:.0f} cases/s   ", cases, events, written.size(),
                 static_cast<double>(cases) / elapsed());
    }
  }
  const double secs = elapsed();
  if (o.progress) fmt::print(stderr, "\r{:70}\r", "");
  if (!o.quiet) {
    fmt::print("fuzz: seed {}, shard {}/{}, solver {}, oracle {}{}\n", o.seed, o.shard, o.shards, solver_name(o.solver),
               o.oracle && o.solver != SolverKind::Fast ? "on" : "off",
               o.spin > 0 ? fmt::format(", spin up to {} rad/s", o.spin) : std::string());
    fmt::print("  cases: {} in {:.1f} s ({:.0f} cases/s), {} events ({:.0f} events/s)\n", cases, secs,
               secs > 0 ? static_cast<double>(cases) / secs : 0.0, events,
               secs > 0 ? static_cast<double>(events) / secs : 0.0);
    fmt::print("  failures: {}", written.size());
    for (std::size_t k = 0; k < by_kind.size(); ++k)
      if (by_kind[k] > 0) fmt::print(", {} {}", by_kind[k], failure_kind_name(static_cast<FailureKind>(k)));
    fmt::print("\n  event storms (resting between moving bodies, reported, {}): {}\n", o.storms_fail ? "failures" : "not failures",
               storms);
    for (const std::string& p : written) fmt::print("  written: {}\n", p);
  }
  return written.empty() ? kExitOk : kExitInvariant;
}

}  // namespace pge::cli
