#include "pge/validate.hpp"

#include "pge/constants.hpp"

#include "geometry.hpp"

#include <algorithm>
#include <cmath>
#include <charconv>
#include <cstdint>
#include <limits>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

namespace pge {
namespace {

// Shortest text that reads back to the same double.
std::string fmt_num(double x) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, x);
  return std::string(buf, r.ptr);
}

bool finite2(const Vec2d& v) { return std::isfinite(v.x) && std::isfinite(v.y); }

// Within the supported range (constants.hpp): 0, or a magnitude in [kMinSceneScale,
// kMaxSceneMagnitude]. Callers check finiteness first, so that NaN and infinities keep their
// own message. Tiny non-zero values are excluded too: products of them fall into subnormals,
// whose rounding error is absolute rather than relative, and the engine's error bounds are
// relative (a velocity of 5e-312 broke the momentum bound in fuzzing).
bool in_range(double x) { return x == 0 || (std::abs(x) >= kMinSceneScale && std::abs(x) <= kMaxSceneMagnitude); }
bool in_range2(const Vec2d& v) { return in_range(v.x) && in_range(v.y); }
bool scale_in_range(double x) { return x >= kMinSceneScale && x <= kMaxSceneMagnitude; }
std::string out_of_range(const Vec2d& v) {
  return "is out of the supported range: each component 0 or of magnitude in [" + fmt_num(kMinSceneScale) + ", " +
         fmt_num(kMaxSceneMagnitude) + "], got [" + fmt_num(v.x) + ", " + fmt_num(v.y) + "]";
}
std::string scale_out_of_range(double x) {
  return "is out of the supported range [" + fmt_num(kMinSceneScale) + ", " + fmt_num(kMaxSceneMagnitude) +
         "], got " + fmt_num(x);
}

// The rotation fields (pge-scene/2): finite, in range, and only where they mean something.
std::optional<SceneProblem> check_rotation(const BodyDesc& b, int i) {
  auto problem = [&](std::string field, std::string msg) {
    return std::optional<SceneProblem>(SceneProblem{i, std::move(field), std::move(msg)});
  };
  if (!std::isfinite(b.angle)) return problem("angle", "must be finite, got " + fmt_num(b.angle));
  if (!std::isfinite(b.angular_velocity))
    return problem("angular_velocity", "must be finite, got " + fmt_num(b.angular_velocity));
  if (!(b.inertia >= 0 && std::isfinite(b.inertia)))
    return problem("inertia", "must be positive and finite, got " + fmt_num(b.inertia));
  if (!(in_range(b.angle) && std::abs(b.angle) <= kMaxAngle))
    return problem("angle", "is out of the supported range: 0 or of magnitude in [" + fmt_num(kMinSceneScale) + ", " +
                                fmt_num(kMaxAngle) + "] radians, got " + fmt_num(b.angle));
  if (!(in_range(b.angular_velocity) && std::abs(b.angular_velocity) <= kMaxAngularVelocity))
    return problem("angular_velocity", "is out of the supported range: 0 or of magnitude in [" +
                                           fmt_num(kMinSceneScale) + ", " + fmt_num(kMaxAngularVelocity) +
                                           "] rad/s, got " + fmt_num(b.angular_velocity));
  if (b.inertia != 0 && !scale_in_range(b.inertia)) return problem("inertia", scale_out_of_range(b.inertia));
  if (b.rotates && b.shape == ShapeKind::Circle)
    return problem("rotates", "a circle does not rotate (without friction its spin never matters)");
  if (!b.rotates) {
    for (const auto& [field, value] : {std::pair<const char*, double>{"angle", b.angle},
                                       {"angular_velocity", b.angular_velocity}, {"inertia", b.inertia}})
      if (value != 0 || std::signbit(value)) return problem(field, "only on a rotating body (\"rotates\": true)");
  }
  if (b.fixed && b.inertia != 0) return problem("inertia", "not allowed on a fixed body (its inertia is infinite)");
  return std::nullopt;
}

std::optional<SceneProblem> check_body(const BodyDesc& b, int i) {
  auto problem = [&](std::string field, std::string msg) {
    return std::optional<SceneProblem>(SceneProblem{i, std::move(field), std::move(msg)});
  };
  if (!finite2(b.position)) return problem("position", "must be finite");
  if (!finite2(b.velocity)) return problem("velocity", "must be finite");
  if (!finite2(b.acceleration)) return problem("acceleration", "must be finite");
  if (!in_range2(b.position)) return problem("position", out_of_range(b.position));
  if (!in_range2(b.velocity)) return problem("velocity", out_of_range(b.velocity));
  if (!in_range2(b.acceleration)) return problem("acceleration", out_of_range(b.acceleration));
  if (!b.fixed && !(std::isfinite(b.mass) && b.mass > 0))
    return problem("mass", "must be positive and finite, got " + fmt_num(b.mass));
  if (!b.fixed && !scale_in_range(b.mass)) return problem("mass", scale_out_of_range(b.mass));
  if (b.restitution >= 0 && b.restitution > 1)
    return problem("restitution", "must be in [0, 1], got " + fmt_num(b.restitution));
  if (std::isnan(b.restitution)) return problem("restitution", "must be in [0, 1], got nan");
  // Like every other value, a restitution is 0 or at least kMinSceneScale: a subnormal one
  // (found by fuzz_engine: 2.4e-309) makes velocities of that size, whose exact arithmetic
  // needs thousand-bit integers and made one run take seconds.
  if (b.restitution > 0 && b.restitution < kMinSceneScale)
    return problem("restitution", "is out of the supported range: 0 or in [1e-30, 1], got " + fmt_num(b.restitution));
  if (auto p = check_rotation(b, i)) return p;
  switch (b.shape) {
    case ShapeKind::Circle:
      if (!(std::isfinite(b.radius) && b.radius > 0))
        return problem("circle.radius", "must be positive and finite, got " + fmt_num(b.radius));
      if (!scale_in_range(b.radius)) return problem("circle.radius", scale_out_of_range(b.radius));
      break;
    case ShapeKind::Segment:
      if (!finite2(b.a) || !finite2(b.b)) return problem("segment", "endpoints must be finite");
      if (!in_range2(b.a)) return problem("segment.a", out_of_range(b.a));
      if (!in_range2(b.b)) return problem("segment.b", out_of_range(b.b));
      if (b.a == b.b) return problem("segment", "endpoints a and b coincide (zero length)");
      break;
    case ShapeKind::Polygon: {
      const auto& v = b.vertices;
      const std::size_t n = v.size();
      if (n < 3) return problem("polygon.vertices", "needs at least 3 vertices, got " + std::to_string(n));
      if (n > kMaxPolygonVertices)
        return problem("polygon.vertices", "has " + std::to_string(n) + " vertices: at most " +
                                               std::to_string(kMaxPolygonVertices) + " (constants.hpp, kMaxPolygonVertices)");
      for (std::size_t k = 0; k < n; ++k)
        if (!finite2(v[k])) return problem("polygon.vertices[" + std::to_string(k) + "]", "must be finite");
      for (std::size_t k = 0; k < n; ++k)
        if (!in_range2(v[k])) return problem("polygon.vertices[" + std::to_string(k) + "]", out_of_range(v[k]));
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
    const Vec2d r = body.shape == ShapeKind::Segment ? (k == 0 ? body.a : body.b) : body.vertices[k];
    if (body.angle == 0) return body.position + r;
    // A turned body (pge-scene/2): its coordinates turn about `position` by `angle`.
    return body.position + rotated(body.angle, r);
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

// --- Start overlap, through a uniform grid ----------------------------------------------------
// Only bodies whose bounding boxes meet can overlap, so the pairwise check runs on the pairs
// that share a grid cell: O(n) for scenes of bodies of similar size that do not pile up,
// instead of O(n^2) (a million bodies would take days). It reports the same pair as checking
// every pair (i, j), i < j, in order: the least offending pair in that order.

struct Box {
  double x0, y0, x1, y1;
};

// The body's bounding box in world coordinates, widened so that rounding (here and in
// start_overlap) can never make a pair that start_overlap reports miss the box test: both
// round at about epsilon of the coordinates' magnitude, 2^-32 of it is millions of times more.
Box bounding_box(const BodyDesc& b) {
  Box box{};
  if (b.shape == ShapeKind::Circle) {
    box = {b.position.x - b.radius, b.position.y - b.radius, b.position.x + b.radius, b.position.y + b.radius};
  } else {
    const WorldOutline outline{b};
    const Vec2d first = outline(0);
    box = {first.x, first.y, first.x, first.y};
    for (std::size_t k = 1; k < outline.size(); ++k) {
      const Vec2d p = outline(k);
      box = {std::min(box.x0, p.x), std::min(box.y0, p.y), std::max(box.x1, p.x), std::max(box.y1, p.y)};
    }
  }
  const double magnitude = std::max({std::abs(box.x0), std::abs(box.y0), std::abs(box.x1), std::abs(box.y1)});
  const double slack = 0x1p-32 * magnitude + 0x1p-32 * std::max(box.x1 - box.x0, box.y1 - box.y0);
  return {box.x0 - slack, box.y0 - slack, box.x1 + slack, box.y1 + slack};
}

bool boxes_meet(const Box& a, const Box& b) { return a.x0 <= b.x1 && b.x0 <= a.x1 && a.y0 <= b.y1 && b.y0 <= a.y1; }

// A body covering more cells than this along its box is checked against every body instead
// of being entered in each cell: a long wall in a gas of small discs. Scenes with many such
// bodies are not "reasonable" for the grid and cost O(n) per large body.
constexpr std::int64_t kMaxCellsPerBody = 64;
// Cell indices are clamped to this magnitude so that a scene spread over 1e30 with cells of
// 1e-30 cannot overflow and a cell packs into 64 bits; clamping is monotonic, so boxes that
// meet still share a cell (far-out cells merely merge).
constexpr double kMaxCellIndex = 0x1p30;

class Grid {
 public:
  Grid(double origin_x, double origin_y, double cell) : ox_(origin_x), oy_(origin_y), cell_(cell) {}
  std::int64_t ix(double x) const { return index((x - ox_) / cell_); }
  std::int64_t iy(double y) const { return index((y - oy_) / cell_); }
  // Both indices offset into [0, 2^31] and packed: one key per cell.
  static std::uint64_t key(std::int64_t cx, std::int64_t cy) {
    const auto ux = static_cast<std::uint64_t>(cx + (std::int64_t{1} << 30));
    const auto uy = static_cast<std::uint64_t>(cy + (std::int64_t{1} << 30));
    return (ux << 32) | uy;
  }

 private:
  static std::int64_t index(double q) {
    return static_cast<std::int64_t>(std::floor(std::clamp(q, -kMaxCellIndex, kMaxCellIndex)));
  }
  double ox_, oy_, cell_;
};

struct Offender {
  std::size_t i = 0, j = 0;
  double overlap = 0;
  bool found = false;
  bool before(std::size_t a, std::size_t b) const { return !found || a < i || (a == i && b < j); }
};

std::optional<SceneProblem> start_overlap_problem(const Scene& scene) {
  const std::vector<BodyDesc>& bodies = scene.bodies;
  const std::size_t n = bodies.size();
  if (n < 2) return std::nullopt;
  Offender worst;
  auto consider = [&](std::size_t a, std::size_t b) {  // a < b
    if (!worst.before(a, b)) return;
    const double o = start_overlap(bodies[a], bodies[b]);
    if (o > kStartOverlapTolerance) worst = {a, b, o, true};
  };

  std::vector<Box> boxes(n);
  std::vector<double> sizes(n);
  double ox = std::numeric_limits<double>::infinity(), oy = ox;
  for (std::size_t i = 0; i < n; ++i) {
    boxes[i] = bounding_box(bodies[i]);
    sizes[i] = std::max(boxes[i].x1 - boxes[i].x0, boxes[i].y1 - boxes[i].y0);
    ox = std::min(ox, boxes[i].x0);
    oy = std::min(oy, boxes[i].y0);
  }
  // Cells of the median body size: a typical body then covers about four cells, and long
  // walls do not make the cells coarse.
  std::nth_element(sizes.begin(), sizes.begin() + static_cast<std::ptrdiff_t>(n / 2), sizes.end());
  const Grid grid(ox, oy, std::max(sizes[n / 2], std::numeric_limits<double>::min()));

  struct Entry {
    std::uint64_t key;
    std::uint32_t body;
    bool operator<(const Entry& o) const { return key < o.key || (key == o.key && body < o.body); }
  };
  std::vector<Entry> entries;
  entries.reserve(4 * n);
  std::vector<std::size_t> large;
  for (std::size_t i = 0; i < n; ++i) {
    const Box& b = boxes[i];
    const std::int64_t x0 = grid.ix(b.x0), x1 = grid.ix(b.x1), y0 = grid.iy(b.y0), y1 = grid.iy(b.y1);
    if (x1 - x0 >= kMaxCellsPerBody || y1 - y0 >= kMaxCellsPerBody) {
      large.push_back(i);
      continue;
    }
    for (std::int64_t cx = x0; cx <= x1; ++cx)
      for (std::int64_t cy = y0; cy <= y1; ++cy) entries.push_back({Grid::key(cx, cy), static_cast<std::uint32_t>(i)});
  }
  std::sort(entries.begin(), entries.end());

  // Each pair that shares cells is tested once: in the cell holding the lower-left corner of
  // the intersection of the two boxes (which both boxes cover, as the boxes meet).
  for (std::size_t begin = 0; begin < entries.size();) {
    std::size_t end = begin;
    while (end < entries.size() && entries[end].key == entries[begin].key) ++end;
    for (std::size_t p = begin; p < end; ++p) {
      for (std::size_t q = p + 1; q < end; ++q) {
        const std::size_t a = entries[p].body, b = entries[q].body;  // a < b: sorted by body
        if (bodies[a].fixed && bodies[b].fixed) continue;             // never interact
        if (!boxes_meet(boxes[a], boxes[b])) continue;
        const double cx = std::max(boxes[a].x0, boxes[b].x0), cy = std::max(boxes[a].y0, boxes[b].y0);
        if (Grid::key(grid.ix(cx), grid.iy(cy)) != entries[p].key) continue;
        consider(a, b);
      }
    }
    begin = end;
  }
  for (std::size_t l : large)
    for (std::size_t k = 0; k < n; ++k) {
      // A pair of two large bodies is met twice: take it from its lower index.
      if (k == l || (k < l && std::binary_search(large.begin(), large.end(), k))) continue;
      if (bodies[l].fixed && bodies[k].fixed) continue;
      if (boxes_meet(boxes[l], boxes[k])) consider(std::min(l, k), std::max(l, k));
    }

  if (!worst.found) return std::nullopt;
  return SceneProblem{static_cast<int>(worst.j), "position",
                      "overlaps body \"" + bodies[worst.i].id + "\" at the start by " + fmt_num(worst.overlap) +
                          " of the contact distance (tolerance " + fmt_num(kStartOverlapTolerance) + ")"};
}

}  // namespace

std::optional<SceneProblem> validate_scene(const Scene& scene) {
  if (!finite2(scene.world.gravity)) return SceneProblem{-1, "world.gravity", "must be finite"};
  if (!in_range2(scene.world.gravity)) return SceneProblem{-1, "world.gravity", out_of_range(scene.world.gravity)};
  if (!(scene.world.restitution >= 0 && scene.world.restitution <= 1))
    return SceneProblem{-1, "world.restitution", "must be in [0, 1], got " + fmt_num(scene.world.restitution)};
  if (scene.world.restitution > 0 && scene.world.restitution < kMinSceneScale)
    return SceneProblem{-1, "world.restitution",
                        "is out of the supported range: 0 or in [1e-30, 1], got " + fmt_num(scene.world.restitution)};
  if (!(std::isfinite(scene.run.until) && scene.run.until > 0))
    return SceneProblem{-1, "run.until", "must be positive and finite, got " + fmt_num(scene.run.until)};
  if (!(scene.run.until <= kMaxSceneMagnitude))
    return SceneProblem{-1, "run.until", "is out of the supported range: at most " + fmt_num(kMaxSceneMagnitude) +
                                             " seconds, got " + fmt_num(scene.run.until)};
  if (!(std::isfinite(scene.run.frames_per_second) && scene.run.frames_per_second >= 0))
    return SceneProblem{-1, "run.frames_per_second", "must be >= 0 and finite, got " + fmt_num(scene.run.frames_per_second)};
  if (!(scene.run.frames_per_second * scene.run.until <= kMaxFramesPerRun))
    return SceneProblem{-1, "run.frames_per_second",
                        "gives " + fmt_num(scene.run.frames_per_second * scene.run.until) + " frames over run.until; at most " +
                            fmt_num(kMaxFramesPerRun) + " are supported"};
  // Body indices are 32-bit in the grid below (and BodyIndex in the engine).
  if (scene.bodies.size() > std::numeric_limits<std::uint32_t>::max() - 1)
    return SceneProblem{-1, "bodies", "too many bodies: " + std::to_string(scene.bodies.size())};
  // Ids: the first earlier body with the same id, as a pairwise scan would find, in O(n).
  std::unordered_map<std::string_view, std::size_t> first_with_id;
  first_with_id.reserve(scene.bodies.size());
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    if (scene.bodies[i].id.empty()) return SceneProblem{static_cast<int>(i), "id", "must be a non-empty string"};
    const auto [it, inserted] = first_with_id.try_emplace(scene.bodies[i].id, i);
    if (!inserted)
      return SceneProblem{static_cast<int>(i), "id", "duplicates the id of bodies[" + std::to_string(it->second) + "]"};
    if (auto p = check_body(scene.bodies[i], static_cast<int>(i))) return p;
  }
  return start_overlap_problem(scene);
}

}  // namespace pge
