// The one step loop: a World stepped to the end of its run, measured before and after, the
// stepping alone timed. What a caller adds (a progress line, energy samples, ...) runs after
// every event; what it measures is its own choice. `pge run`, `pge check`, `pge render`, the
// report's timed runs and the peers' PGE runs all step through here.
//
//   pge::World<double> world(scene);
//   const auto run = pge::step_to_end(world, [](const pge::World<double>& w) { return pge::world_totals(w); });
//   std::printf("%llu events in %.3f s; energy %g -> %g J\n", (unsigned long long)run.steps,
//               run.wall_seconds, run.start.energy(), run.end.energy());
//
// A whole program with its output: docs/api.md, "pge/world.hpp and pge/step_loop.hpp"
// (docs/examples/world.cpp). Header-only over pge::engine.
#pragma once

#include "pge/world.hpp"

#include <chrono>
#include <cstdint>
#include <type_traits>

namespace pge {

// What a world measures of itself at its current time, in its own scalar: energies in joules,
// momentum in kg m / s (World::kinetic_energy, potential_energy, momentum).
template <class T> struct WorldTotals {
  T kinetic{};
  T potential{};
  Vec2<T> momentum;

  T energy() const { return kinetic + potential; }
};

template <class T> WorldTotals<T> world_totals(const World<T>& w) {
  return {w.kinetic_energy(), w.potential_energy(), w.momentum()};
}

// Each total rounded to double on its own.
template <class T> WorldTotals<double> in_double(const WorldTotals<T>& t) {
  return {to_double(t.kinetic), to_double(t.potential), vec_cast<double>(t.momentum)};
}

// The measure that measures nothing, and the observer that does nothing.
struct NoMeasure {
  struct None {};
  template <class T> None operator()(const World<T>&) const { return {}; }
};
struct NoObserver {
  template <class T> void operator()(const World<T>&) const {}
};

// What step_to_end returns: the two measures, the events stepped, the time it took, why it stopped.
template <class M> struct SteppedRun {
  M start{};                  // measure(world) before the first event
  M end{};                    // and after the last
  std::uint64_t steps = 0;    // events processed: World::step() calls that returned true
  double wall_seconds = 0;    // wall-clock seconds (steady clock) of the stepping and the observer's work, not the two measures
  StopReason stop = StopReason::ReachedUntil;
};

// Steps `world` until its run is over (horizon, collision budget, storm, or stop() from a
// callback), calling `after_step(world)` after every event; `measure(world)` before and after.
// `measure` is any callable taking const World<T>& (its result type is SteppedRun::start's);
// `after_step` too, its result ignored. Exceptions from the world's callbacks, the measure or the
// observer pass through, leaving the world where it stopped.
template <class T, class Measure = NoMeasure, class AfterStep = NoObserver>
auto step_to_end(World<T>& world, Measure&& measure = {}, AfterStep&& after_step = {}) {
  using Clock = std::chrono::steady_clock;
  const World<T>& seen = world;
  SteppedRun<std::decay_t<std::invoke_result_t<Measure&, const World<T>&>>> run;
  run.start = measure(seen);
  const auto start = Clock::now();
  while (world.step()) {
    ++run.steps;
    after_step(seen);
  }
  run.wall_seconds = std::chrono::duration<double>(Clock::now() - start).count();
  run.end = measure(seen);
  run.stop = world.stop_reason();
  return run;
}

}  // namespace pge
