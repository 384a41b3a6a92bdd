// Bodies for hand-made test scenes, built field by field (one home for what several test files
// built alike).
#pragma once

#include "pge/scene.hpp"
#include "pge/vec2.hpp"

#include <string>
#include <utility>

namespace pge::test_scene {

inline BodyDesc circle(std::string id, double r, Vec2d p, Vec2d v = {}, double mass = 1) {
  BodyDesc b;
  b.id = std::move(id);
  b.shape = ShapeKind::Circle;
  b.radius = r;
  b.position = p;
  b.velocity = v;
  b.mass = mass;
  return b;
}

inline BodyDesc fixed_circle(std::string id, double r, Vec2d p) {
  BodyDesc b = circle(std::move(id), r, p);
  b.fixed = true;
  return b;
}

// A fixed segment from a to b (position (0, 0): the ends are world coordinates).
inline BodyDesc wall(std::string id, Vec2d a, Vec2d b) {
  BodyDesc w;
  w.id = std::move(id);
  w.shape = ShapeKind::Segment;
  w.a = a;
  w.b = b;
  w.fixed = true;
  return w;
}

}  // namespace pge::test_scene
