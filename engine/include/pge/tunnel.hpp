// Tunnelling: a moving body that passed through a fixed body between two looks at it (issue 22).
//
// What is true of every correct run: a moving body's interior point (a circle's centre, a
// polygon's vertex centroid) never touches a fixed body. A circle's centre stays a radius away
// from every fixed face, a polygon's centroid as far as its own sides; a collision turns the
// body back before either reaches the face, and a body that goes round the end of a segment
// crosses the segment's line at least that far beyond the end. So a path of that point that
// meets a fixed segment or polygon side within the side's extent, or enters a fixed circle,
// went through the body, whatever collisions were reported: that is tunnelling. The margin is a
// body's size, not a rounding error, so the test runs in double for every scalar and never
// alarms on a correct run. The same test serves the event-driven engine (one arc between two
// events) and the fixed-step peers (one straight step), so that `pge compare` counts
// tunnelling alike for all of them. A World follows its bodies with it when asked
// (WorldOptions::watch_tunnels; always in PGE_VALIDATE builds) and lists what it found
// (World::tunnels()).
#pragma once

#include "pge/event.hpp"
#include "pge/scene.hpp"
#include "pge/vec2.hpp"

#include <array>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace pge {

// A path of a body's position: p(s) = p0 + v s + acc s^2 / 2 for s in [s0, s1]. An arc of the
// engine between two events, or a straight step of a fixed-step engine (acc = 0).
struct PositionPath {
  Vec2d p0, v, acc;
  double s0 = 0, s1 = 1;
};

// The straight path from `from` (s = 0) to `to` (s = 1).
PositionPath straight_path(Vec2d from, Vec2d to);

// The point of a moving body the test follows, as an offset from its position: a circle's
// centre (0), a polygon's vertex centroid (strictly inside a convex polygon, wherever the scene
// put the position). A segment has no interior point: one lying flat on a floor has every point
// on the face, so moving segments are not followed (nothing).
std::optional<Vec2d> interior_offset(const BodyDesc& moving);
// A polygon's vertex centroid (relative to its position), in double: interior_offset's point.
template <class T> Vec2d vertex_centroid(const std::vector<Vec2<T>>& vertices) {
  Vec2d sum;
  for (const Vec2<T>& v : vertices) sum += vec_cast<double>(v);
  return sum * (1.0 / static_cast<double>(vertices.size()));
}

// A scene's fixed bodies placed in the world once, to test paths against. From a few dozen
// fixed bodies on (pegs), a uniform grid over their boxes finds the few near a path, so that a
// test costs about the same with 10 fixed bodies or 10,000. Not thread-safe (a scratch list).
class FixedBodies {
 public:
  explicit FixedBodies(const Scene& scene);
  // The first fixed body (in scene order) that the interior point of scene body `moving`
  // passes through along `path` (of its position), or kNoBody. A moving segment: kNoBody.
  BodyIndex passed_through(BodyIndex moving, const PositionPath& path) const;
  // The same for the point `offset` from the position along `path` (interior_offset of the body).
  BodyIndex point_passed_through(Vec2d offset, const PositionPath& path) const;

 private:
  struct Placed {  // a fixed body in world coordinates
    BodyIndex index = kNoBody;
    bool circle = false;
    Vec2d centre;               // circle
    double radius = 0;
    std::vector<Vec2d> edges;   // segment: a, b; polygon: its vertices (closed)
    Vec2d lo, hi;               // bounding box
  };
  struct Grid {  // cells over the fixed bodies' boxes; nx == 0: none (every body is tested)
    Vec2d lo, cell;
    std::uint32_t nx = 0, ny = 0;
    std::vector<std::uint32_t> start;        // cell k lists items[start[k] .. start[k + 1])
    std::vector<std::uint32_t> items;        // indices into fixed_
    std::vector<std::uint32_t> everywhere;   // bodies spanning too many cells: always tested
  };
  bool hits(const Placed& f, const PositionPath& path, Vec2d offset, Vec2d lo, Vec2d hi) const;
  void build_grid();
  std::array<std::uint32_t, 4> cell_range(Vec2d lo, Vec2d hi) const;  // x0, x1, y0, y1 (clamped)
  std::vector<Placed> fixed_;
  std::vector<std::optional<Vec2d>> offsets_;  // interior_offset of every body (fixed: unused)
  Grid grid_;
  mutable std::vector<std::uint32_t> candidates_;  // scratch of passed_through
};

// A moving body that passed through a fixed body, along the path it followed from `from` to `to`
// (simulated times).
struct Tunnel {
  BodyIndex body = kNoBody, fixed = kNoBody;
  double from = 0, to = 0;
};

// "body \"ball\" passed through fixed body \"wall\" between t = 1 and t = 2".
std::string tunnel_text(const Tunnel& t, const std::string& body_id, const std::string& fixed_id);

// Thrown by PGE_VALIDATE builds when a body of a solver that promises every collision
// (promises_every_collision, roots.hpp) passes through a fixed body: a std::logic_error, as every
// validation failure.
struct TunnelError : std::logic_error {
  Tunnel tunnel;
  TunnelError(const Tunnel& t, const std::string& what) : std::logic_error(what), tunnel(t) {}
};

}  // namespace pge
