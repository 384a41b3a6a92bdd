// A deliberately naive stepping engine: moving circles and fixed thin walls (segments), gravity,
// fixed-step semi-implicit Euler, and contacts found only where a step *ends* overlapping. It is
// the kind of engine the referee is for: fast enough, and wrong whenever a body crosses a wall
// within one step (tunnelling). Nothing here comes from PGE's engine; only the scene is PGE's
// (pge::Scene, read from a pge-scene/1 file by pge::io).
#pragma once

#include "pge/scene.hpp"

#include <cstddef>
#include <string>
#include <vector>

namespace naive {

struct Vec {
  double x = 0, y = 0;
};

struct Body {
  std::string id;
  bool wall = false;  // a fixed segment from a to b; otherwise a moving circle
  Vec position, velocity, a, b;
  double radius = 0, mass = 1;
};

// Two bodies found touching at the end of a step (indices into bodies(), a < b).
struct Contact {
  std::size_t a = 0, b = 0;
};

class Engine {
 public:
  // Circles and segments only; throws std::invalid_argument for anything else.
  explicit Engine(const pge::Scene& scene);
  // One step of dt seconds; returns the contacts found (and answered) at its end.
  std::vector<Contact> step(double dt);
  double time() const { return time_; }
  const std::vector<Body>& bodies() const { return bodies_; }

 private:
  bool touch(std::size_t i, std::size_t j, Vec& normal) const;
  void bounce(std::size_t i, std::size_t j, Vec normal);

  std::vector<Body> bodies_;
  Vec gravity_;
  double restitution_ = 1;
  double time_ = 0;
};

}  // namespace naive
