// Semantic validation of a scene: what no file format can check by itself.
#pragma once

#include "pge/scene.hpp"

#include <optional>
#include <string>

namespace pge {

struct SceneProblem {
  int body = -1;        // index into Scene::bodies, or -1 for world/run
  std::string field;    // dotted path, e.g. "circle.radius", "mass", "run.until"
  std::string message;  // what is wrong, with the offending value
};

// The first problem found, in body order, or nothing when the scene is valid:
// positive finite radius and mass, non-degenerate segments, convex counter-clockwise polygons
// of at most kMaxPolygonVertices vertices without repeated or collinear vertices, restitution in
// [0, 1], no two bodies overlapping at the start (beyond kStartOverlapTolerance), a positive
// finite run horizon.
std::optional<SceneProblem> validate_scene(const Scene& scene);

}  // namespace pge
