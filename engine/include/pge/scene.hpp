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
  // Rotation (pge-scene/2; docs/rotation.md). A rotating body's angle is angle + angular_velocity
  // (t - t0) between events. A moving polygon turns about its centroid, a moving segment about
  // its midpoint, a fixed body about `position`; `position` stays the reference point of the
  // shape's coordinates at every angle. Circles never rotate. The defaults are a translate-only
  // body, which is every body of a pge-scene/1 file.
  bool rotates = false;
  double angle = 0;              // radians, rotating bodies only
  double angular_velocity = 0;   // rad/s, rotating bodies only
  double inertia = 0;            // about the centroid; 0: a uniform lamina (a segment: a thin rod)
                                 // of the body's mass; moving rotating bodies only
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
