#include "pge/validate.hpp"

#include "pge/constants.hpp"

#include "geometry.hpp"

#include <algorithm>
#include <cmath>
#include <charconv>

namespace pge {
namespace {

// Shortest text that reads back to the same double.
std::string fmt_num(double x) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, x);
  return std::string(buf, r.ptr);
}

bool finite2(const Vec2d& v) { return std::isfinite(v.x) && std::isfinite(v.y); }

std::optional<SceneProblem> check_body(const BodyDesc& b, int i) {
  auto problem = [&](std::string field, std::string msg) {
    return std::optional<SceneProblem>(SceneProblem{i, std::move(field), std::move(msg)});
  };
  if (!finite2(b.position)) return problem("position", "must be finite");
  if (!finite2(b.velocity)) return problem("velocity", "must be finite");
  if (!finite2(b.acceleration)) return problem("acceleration", "must be finite");
  if (!b.fixed && !(std::isfinite(b.mass) && b.mass > 0))
    return problem("mass", "must be positive and finite, got " + fmt_num(b.mass));
  if (b.restitution >= 0 && b.restitution > 1)
    return problem("restitution", "must be in [0, 1], got " + fmt_num(b.restitution));
  if (std::isnan(b.restitution)) return problem("restitution", "must be in [0, 1], got nan");
  switch (b.shape) {
    case ShapeKind::Circle:
      if (!(std::isfinite(b.radius) && b.radius > 0))
        return problem("circle.radius", "must be positive and finite, got " + fmt_num(b.radius));
      break;
    case ShapeKind::Segment:
      if (!finite2(b.a) || !finite2(b.b)) return problem("segment", "endpoints must be finite");
      if (b.a == b.b) return problem("segment", "endpoints a and b coincide (zero length)");
      break;
    case ShapeKind::Polygon: {
      const auto& v = b.vertices;
      const std::size_t n = v.size();
      if (n < 3) return problem("polygon.vertices", "needs at least 3 vertices, got " + std::to_string(n));
      for (std::size_t k = 0; k < n; ++k)
        if (!finite2(v[k])) return problem("polygon.vertices[" + std::to_string(k) + "]", "must be finite");
      // Repeats first: a repeated vertex also makes a zero turn, which is not what is wrong.
      for (std::size_t k = 0; k < n; ++k)
        if (v[(k + 1) % n] == v[k])
          return problem("polygon.vertices[" + std::to_string((k + 1) % n) + "]", "repeats the previous vertex");
      for (std::size_t k = 0; k < n; ++k) {
        const Vec2d e0 = v[(k + 1) % n] - v[k];
        const Vec2d e1 = v[(k + 2) % n] - v[(k + 1) % n];
        const double turn = cross(e0, e1);
        const std::string where = "polygon.vertices[" + std::to_string((k + 1) % n) + "]";
        if (turn == 0) return problem(where, "is collinear with its neighbours");
        if (turn < 0) return problem(where, "turns clockwise: vertices must be convex and counter-clockwise");
      }
      // Every corner turns left; a convex polygon also winds exactly once.
      double area2 = 0;
      for (std::size_t k = 0; k < n; ++k) area2 += cross(v[k], v[(k + 1) % n]);
      if (!(area2 > 0)) return problem("polygon.vertices", "must enclose a positive area");
      double winding = 0;
      for (std::size_t k = 0; k < n; ++k) {
        const Vec2d e0 = v[(k + 1) % n] - v[k];
        const Vec2d e1 = v[(k + 2) % n] - v[(k + 1) % n];
        winding += std::atan2(cross(e0, e1), dot(e0, e1));
      }
      if (winding > 2 * M_PI * 1.5) return problem("polygon.vertices", "winds more than once (self-intersecting)");
      break;
    }
  }
  return std::nullopt;
}

// A polygon's or segment's vertices in world coordinates (a segment is the outline [a, b]).
struct WorldOutline {
  const BodyDesc& body;
  std::size_t size() const { return body.shape == ShapeKind::Segment ? 2 : body.vertices.size(); }
  Vec2d operator()(std::size_t k) const {
    if (body.shape == ShapeKind::Segment) return body.position + (k == 0 ? body.a : body.b);
    return body.position + body.vertices[k];
  }
};

// Overlap at the start between two bodies, as a fraction of their contact distance: the radius
// sum, a circle's radius against a wall or polygon, or the smaller size of two outlines.
double start_overlap(const BodyDesc& x, const BodyDesc& y) {
  // Two fixed bodies never interact: walls and cushions may meet and cross.
  if (x.fixed && y.fixed) return -1;
  if (x.shape == ShapeKind::Circle && y.shape == ShapeKind::Circle) {
    const double r = x.radius + y.radius;
    const double d = std::hypot(y.position.x - x.position.x, y.position.y - x.position.y);
    return (r - d) / r;
  }
  const BodyDesc* c = x.shape == ShapeKind::Circle ? &x : (y.shape == ShapeKind::Circle ? &y : nullptr);
  if (c) {
    const BodyDesc& other = c == &x ? y : x;
    const WorldOutline outline{other};
    return (c->radius - point_outline_distance(c->position, outline, outline.size())) / c->radius;
  }
  const WorldOutline ox{x}, oy{y};
  const double depth = -outline_separation<double>(ox, ox.size(), oy, oy.size());
  return depth / std::min(outline_size<double>(ox, ox.size()), outline_size<double>(oy, oy.size()));
}

}  // namespace

std::optional<SceneProblem> validate_scene(const Scene& scene) {
  if (!finite2(scene.world.gravity)) return SceneProblem{-1, "world.gravity", "must be finite"};
  if (!(scene.world.restitution >= 0 && scene.world.restitution <= 1))
    return SceneProblem{-1, "world.restitution", "must be in [0, 1], got " + fmt_num(scene.world.restitution)};
  if (!(std::isfinite(scene.run.until) && scene.run.until > 0))
    return SceneProblem{-1, "run.until", "must be positive and finite, got " + fmt_num(scene.run.until)};
  if (!(std::isfinite(scene.run.frames_per_second) && scene.run.frames_per_second >= 0))
    return SceneProblem{-1, "run.frames_per_second", "must be >= 0 and finite, got " + fmt_num(scene.run.frames_per_second)};
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    if (scene.bodies[i].id.empty()) return SceneProblem{static_cast<int>(i), "id", "must be a non-empty string"};
    for (std::size_t j = 0; j < i; ++j)
      if (scene.bodies[j].id == scene.bodies[i].id)
        return SceneProblem{static_cast<int>(i), "id", "duplicates the id of bodies[" + std::to_string(j) + "]"};
    if (auto p = check_body(scene.bodies[i], static_cast<int>(i))) return p;
  }
  // Pairwise start overlap: O(n^2), which is fine for scene loading up to ~10^4 bodies;
  // the broad phase will take this over for larger scenes.
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    for (std::size_t j = i + 1; j < scene.bodies.size(); ++j) {
      const double o = start_overlap(scene.bodies[i], scene.bodies[j]);
      if (o > kStartOverlapTolerance)
        return SceneProblem{static_cast<int>(j), "position",
                            "overlaps body \"" + scene.bodies[i].id + "\" at the start by " + fmt_num(o) +
                                " of the contact distance (tolerance " + fmt_num(kStartOverlapTolerance) + ")"};
    }
  }
  return std::nullopt;
}

}  // namespace pge
