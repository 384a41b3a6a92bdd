// What the trace referee (pge/judge.hpp) shares between its modes: the scene as PGE reads it,
// body ids, errors naming a trace's line (or, in memory, its element) and field, and the
// exact geometry of two bodies at one instant.
#pragma once

#include "pge/judge.hpp"
#include "pge/oracle_state.hpp"

#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

namespace pge::oracle::detail {

// The scene's exact state at its start, as PGE's double engine holds it (fixed bodies' world
// vertices rounded once, as World does), and its ids.
// A rotating body's pivot (its path's point, ExactMotion::p0) sits at its reference point plus
// R(angle) pivot[i] (World::pivot; none for a body that does not rotate: its path's point is its
// reference point); a trace gives reference points (the scene's `position`, turned with the
// body). `pivot` and `reference` stay when `state` is moved out (events mode).
struct SceneModel {
  ExactState state;
  std::unordered_map<std::string, BodyIndex> index;
  std::vector<std::string> ids;
  std::vector<std::optional<ExactVec>> pivot;
  std::vector<Vec2d> reference;  // each body's reference point at the start (the scene's position)
};
SceneModel scene_model(const Scene& scene);

// Body i's pivot from a trace's reference point and angle: the nearest doubles of
// reference + R(angle) pivot[i] (turn.hpp; the reference point itself for a body that does not
// rotate). The referee's path of the body starts there.
ExactVec pivot_of(const SceneModel& m, BodyIndex i, const Vec2d& reference, double angle);
// Body i's reference point, in doubles, from its pivot and angle: what a trace gives.
Vec2d reference_of(const SceneModel& m, BodyIndex i, const ExactVec& pivot, const Dyadic& angle);
// The angle on body i's path at time t: theta0 + omega (t - t0), exactly.
Dyadic angle_at(const ExactMotion& m, const Dyadic& t);

// Errors about an element of `trace` (a step, a collision, the header): its line when read from
// a file, else the element's name ("steps[3]") before the field.
class TraceFailer {
 public:
  explicit TraceFailer(const Trace& trace) : trace_(trace) {}
  [[noreturn]] void fail(int line, const std::string& element, const std::string& field, const std::string& reason) const;
  BodyIndex body(const SceneModel& m, int line, const std::string& element, const std::string& field,
                 const std::string& id) const;
  void finite(double x, int line, const std::string& element, const std::string& field) const;
  void finite(const TraceState& s, int line, const std::string& element, const std::string& field) const;

 private:
  const Trace& trace_;
};

// A body at one instant, exactly: a circle's centre, or the world vertices (segment: a, b).
struct Placed {
  ShapeKind shape = ShapeKind::Circle;
  Dyadic radius;
  ExactVec centre;
  std::vector<ExactVec> vertices;
};
// `position` is a rotating body's pivot, turned by `angle` (turn.hpp: its vertices rounded far
// below every engine's rounding; exact at angle 0); `angle` is ignored for any other body.
Placed place(const ExactBody& body, const ExactVec& position, const Dyadic& angle = Dyadic());

// The exact sign of the separation of two bodies (-1 overlapping, 0 touching, 1 apart) and,
// when they overlap, the depth: how far apart they must move to touch (the separating-axis
// depth; for a circle, its radius less the distance of its centre, or plus it from inside a
// polygon), rounded once to double.
struct Separation {
  int sign = 1;
  double depth = 0;
};
Separation separation(const Placed& a, const Placed& b);
// World::largest_overlap's contact distance: radius sum; a circle's radius against a wall or a
// polygon; else the smaller size of the two, a size being the larger side of the bounding box.
double contact_distance(const ExactBody& a, const ExactBody& b);

struct Box {
  double lo_x = 0, lo_y = 0, hi_x = 0, hi_y = 0;
};
// A box certainly holding the body (outward by more than the rounding of its corners).
Box bounding_box(const Placed& p);

// A box certainly holding the body at every angle: its pivot's disc of reach (a rotating body),
// else bounding_box(place(body, position)).
Box reach_box(const ExactBody& body, const ExactVec& position);

// Kinetic energy plus the potential of the body's constant field, m (v.v / 2 - field.p) + I w^2 / 2
// (the turn's share: 0 for a body that does not rotate, whose inertia is 0).
Dyadic body_energy(const ExactBody& body, const ExactVec& position, const ExactVec& velocity,
                   const Dyadic& omega = Dyadic());

}  // namespace pge::oracle::detail
