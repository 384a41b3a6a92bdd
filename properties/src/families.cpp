#include "pge/families.hpp"

#include <cmath>
#include <numbers>
#include <string>

namespace pge {

std::uint64_t SplitMix64::next() {
  std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ull);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

double SplitMix64::uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }

Scene make_gas(const GasParams& p) {
  Scene s;
  s.name = "gas-" + std::to_string(p.bodies);
  s.world.gravity = {0, p.gravity == 0 ? 0.0 : -p.gravity};  // no negative zero in the file
  s.run.until = p.until;
  s.run.max_events = p.max_events;
  // Box side from the area fraction: n pi r^2 = fraction * side^2.
  const double side = std::sqrt(p.bodies * std::numbers::pi * p.radius * p.radius / p.area_fraction);
  const auto per_row = static_cast<std::uint32_t>(std::ceil(std::sqrt(static_cast<double>(p.bodies))));
  const double cell = side / per_row;
  // Jitter keeps every disc inside its own cell: centres stay r away from the cell's edges.
  const double slack = cell / 2 - p.radius;
  auto wall = [&](const char* id, Vec2d a, Vec2d b) {
    BodyDesc w;
    w.id = id;
    w.shape = ShapeKind::Segment;
    w.fixed = true;
    w.a = a;
    w.b = b;
    s.bodies.push_back(w);
  };
  wall("wall-bottom", {0, 0}, {side, 0});
  wall("wall-right", {side, 0}, {side, side});
  wall("wall-top", {side, side}, {0, side});
  wall("wall-left", {0, side}, {0, 0});
  SplitMix64 rng(p.seed);
  for (std::uint32_t i = 0; i < p.bodies; ++i) {
    BodyDesc b;
    b.id = "b" + std::to_string(i);
    b.shape = ShapeKind::Circle;
    b.radius = p.radius;
    b.mass = 1;
    const double cx = (i % per_row + 0.5) * cell, cy = (i / per_row + 0.5) * cell;
    const double jitter = slack > 0 ? slack * 0.9 : 0;
    b.position = {cx + rng.uniform(-jitter, jitter), cy + rng.uniform(-jitter, jitter)};
    b.velocity = {rng.uniform(-p.speed, p.speed), rng.uniform(-p.speed, p.speed)};
    s.bodies.push_back(b);
  }
  return s;
}

}  // namespace pge
