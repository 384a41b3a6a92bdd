// Deterministic scene families: the same parameters and seed give the same scene, bit for bit,
// on every machine (integer PRNG, exactly rounded arithmetic only).
#pragma once

#include "pge/scene.hpp"

#include <cstdint>

namespace pge {

// A small, fast, well-mixed 64-bit generator (splitmix64). Integer only: portable.
class SplitMix64 {
 public:
  explicit SplitMix64(std::uint64_t seed) : state_(seed) {}
  std::uint64_t next();
  // Uniform in [0, 1) with 53 random bits.
  double uniform();
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }

 private:
  std::uint64_t state_;
};

struct GasParams {
  std::uint32_t bodies = 1000;
  double radius = 0.01;
  double area_fraction = 0.3;   // total disc area / box area
  double speed = 1;             // velocity components uniform in [-speed, speed]
  double gravity = 0;           // downward; 0 for a free gas
  double until = 10;
  std::uint64_t max_events = 100000;
  std::uint64_t seed = 1;
  // Polygons only: > 0 makes every moving polygon turn (pge-scene/2), its angular velocity
  // uniform in [-spin, spin] rad/s from a generator of its own (the same seed gives the same
  // positions and velocities with and without spin).
  double spin = 0;
};

// Equal discs of unit mass in a square box of four fixed segments, on a jittered grid so that
// no two overlap; elastic (restitution 1).
Scene make_gas(const GasParams& params);

// Rain on pegs (the same parameters): the discs start in the upper half of a square box at the
// area fraction, fall under `gravity` (1 if 0) through a staggered lattice of fixed discs of the
// same radius, 8 radii apart, that fills the lower half; elastic, so the rain never settles.
Scene make_pegs(const GasParams& params);

// A gas of polygons (the same parameters): moving squares and triangles alternately, each
// inside a circle of the given radius and turned by a random angle, among fixed pentagons in a
// square box (one pentagon per 16 moving bodies); the area fraction counts the circles. Elastic.
Scene make_polygons(const GasParams& params);

}  // namespace pge
