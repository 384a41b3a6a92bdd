// The scene description: what a scene file says, in doubles, independent of any file format.
// The engine is built from it; the io library reads and writes it.
#pragma once

#include "pge/roots.hpp"
#include "pge/vec2.hpp"

#include <cstdint>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

namespace pge {

enum class ShapeKind : std::uint8_t { Circle, Segment, Polygon };

struct BodyDesc {
  std::string id;                // unique, non-empty
  ShapeKind shape = ShapeKind::Circle;
  double radius = 0;             // circle
  Vec2d a, b;                    // segment endpoints, relative to `position`
  std::vector<Vec2d> vertices;   // polygon, counter-clockwise, relative to `position`
  Vec2d position;                // world position of the body's reference point
  Vec2d velocity;
  Vec2d acceleration;            // the body's own constant acceleration (added to gravity)
  bool fixed = false;            // fixed bodies have infinite mass and never move
  double mass = 1;               // moving bodies only; > 0
  bool gravity = true;           // whether world gravity acts on this (moving) body
  double restitution = -1;       // < 0: use the world's restitution
};

struct WorldDesc {
  Vec2d gravity;
  double restitution = 1;        // default per-body restitution, in [0, 1]
};

struct RunDesc {
  double until = 10;                   // simulated seconds
  std::uint64_t max_events = 1000000;  // collisions at most before the run stops
  double frames_per_second = 0;        // 0: no frame events
  SolverKind solver = SolverKind::Robust;
};


struct Scene {
  std::string name;
  WorldDesc world;
  std::vector<BodyDesc> bodies;
  RunDesc run;
};

}  // namespace pge
