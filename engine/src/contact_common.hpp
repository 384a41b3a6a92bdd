// What every contact category shares: the predicted contact, the geometry of a contact once it
// happens, and the squared-distance contact function of two points.
#pragma once

#include "body_shape.hpp"

#include "pge/constants.hpp"
#include "pge/event.hpp"
#include "pge/roots.hpp"
#include "pge/vec2.hpp"

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>

namespace pge {

// Feature indices are 16-bit (pge/event.hpp). validate_scene refuses polygons of more than
// kMaxPolygonVertices vertices, so every vertex and edge index fits; feature_index narrows a
// loop index and throws rather than wrap if that promise is ever broken (a 70,000-gon once
// reported its edge 68,055 as 2,519). It runs once per contact offered, not per pair tested.
static_assert(kMaxPolygonVertices - 1 <= std::numeric_limits<std::uint16_t>::max(),
              "every vertex and edge index of a polygon must fit a 16-bit feature index");
inline std::uint16_t feature_index(std::size_t k) {
  if (k >= kMaxPolygonVertices)
    throw std::logic_error("feature index " + std::to_string(k) + " past kMaxPolygonVertices");
  return static_cast<std::uint16_t>(k);
}

template <class T> struct PredictedContact {
  T time;  // relative to the instant of the kinematics
  ContactKind contact;
  std::uint16_t feature_a;  // engine feature indices (a segment's side b->a is its edge 1)
  std::uint16_t feature_b;
  bool at_start_overlap;
  bool corner = false;  // a vertex against an edge's end: the corner rule decides the normal
  bool rotating = false;  // a pair with a rotating body (world_rotation.hpp): no exact refinement
  bool resume = false;    // rotating: no contact before `time`, predict again then (Scheduled::resume)
  bool at_start = false;  // rotating: found at its search's start, so `time` is exact (RotatingContact)

  bool before(const PredictedContact& o) const {
    if (time != o.time) return time < o.time;
    if (contact != o.contact) return contact < o.contact;
    if (feature_a != o.feature_a) return feature_a < o.feature_a;
    return feature_b < o.feature_b;
  }
};

// Keeps the earliest of the contacts offered, in the fixed order of PredictedContact::before.
template <class T> void keep_earliest(std::optional<PredictedContact<T>>& best, const PredictedContact<T>& c) {
  if (!best || c.before(*best)) best = c;
}

template <class T> struct ContactGeometry {
  Vec2<T> normal;  // from body a towards body b, not normalised
  Vec2<T> point;
  T gap;           // signed separation (negative: overlap)
  T contact_distance;  // radius sum, a circle's radius against a wall or polygon, or the
                       // smaller size of two polygons / segments
};

template <class T> struct Separation {
  T gap;
  T contact_distance;
};

// |d + dv t + da t^2 / 2|^2 - r^2: the squared-distance contact function of two points (circle
// centres, or a centre and a vertex). Degree 2 when the relative acceleration is zero, else 4.
template <class T> Poly<T> distance_poly(const Vec2<T>& d, const Vec2<T>& dv, const Vec2<T>& da, const T& r) {
  Poly<T> p;
  p.c[0] = dot(d, d) - r * r;
  p.c[1] = T(2) * dot(d, dv);
  if (da.x == T(0) && da.y == T(0)) {
    p.c[2] = dot(dv, dv);
    p.degree = 2;
  } else {
    p.c[2] = dot(dv, dv) + dot(d, da);
    p.c[3] = dot(dv, da);
    p.c[4] = dot(da, da) / T(4);
    p.degree = 4;
  }
  return p;
}

// Earliest approaching contact of two points at distance r, relative time in [0, horizon].
// `p` is the pair's distance_poly (for callers that have it already).
template <class T>
std::optional<RootOutcome<T>> point_contact(SolverKind solver, const Poly<T>& p, const T& horizon) {
  // Without relative acceleration the function is a convex parabola: if it is not decreasing
  // now it never will be, so most pairs of a gas are dismissed here without a solve.
  if (p.degree == 2 && p.c[1] >= T(0)) return std::nullopt;
  const RootOutcome<T> root = earliest_downward_root(solver, p, T(0), horizon);
  if (root.status != RootStatus::Root) return std::nullopt;
  return root;
}

template <class T>
std::optional<RootOutcome<T>> point_contact(SolverKind solver, const Vec2<T>& d, const Vec2<T>& dv, const Vec2<T>& da, const T& r,
                                            const T& horizon) {
  return point_contact(solver, distance_poly(d, dv, da, r), horizon);
}

// A line contact function c0 + c1 t + c2 t^2 (a signed distance to a line, scaled) that is
// non-decreasing for all t >= 0 has no downward root and no overlap-rule root: skipped unsolved.
template <class T> bool never_decreasing(const Poly<T>& p) { return p.c[1] >= T(0) && p.c[2] >= T(0); }

// A line contact whose rounded function comes within rounding of a double root (a graze, or a
// near-graze: a ball touching a ceiling at the apex of its bounce) crosses zero or not by the
// rounding of the state it was built from; robust and certified ask the exact paths instead
// (world_refine.hpp, through refine.hpp's exact_line_graze). The judge knows the pair; nullptr (fast):
// the rounded function decides.
enum class GrazeVerdict : std::uint8_t {
  Undecided,  // not a case the exact test covers: the rounded function decides
  Misses,     // the exact function stays positive: no contact of this feature pair there
  Crosses,    // the exact function crosses downward: at the time written back
};
// Where a line contact's point lies on its edge at the exact crossing (refine.hpp,
// exact_place_at_crossing): strictly inside, strictly beyond the start or the end, or not
// decided (an end itself, the corner rule's).
enum class EdgePlace : std::uint8_t { Unknown, Before, On, After };

// The vertex/edge pairs of two outlines that realise their least penetration: the pairs the
// separating-axis overlap rule may collide (contact_polygon.hpp). Side 0 is a vertex k of body a
// on an edge j of body b (VertexEdge), side 1 a vertex of b on an edge of a (EdgeVertex); each
// approaching or not at now (its contact function decreasing just after now: the overlap rule
// collides it then). A strictly convex outline has at most two vertices deepest on one axis,
// and axes tie only by coincidence, so a few slots hold every case met.
struct OverlapPairs {
  struct Pair {
    std::uint8_t side;
    std::uint16_t k, j;
    bool approaching;
  };
  static constexpr std::size_t kCapacity = 8;
  std::array<Pair, kCapacity> pairs{};
  std::size_t count = 0;

  // False when the slots are full (the caller falls back to the rounded rule).
  bool add(int side, std::size_t k, std::size_t j) {
    if (count == kCapacity) return false;
    pairs[count++] = Pair{static_cast<std::uint8_t>(side), feature_index(k), feature_index(j), false};
    return true;
  }
  const Pair* find(int side, std::size_t k, std::size_t j) const {
    for (std::size_t i = 0; i < count; ++i)
      if (pairs[i].side == side && pairs[i].k == k && pairs[i].j == j) return &pairs[i];
    return nullptr;
  }
};

template <class T> struct GrazeJudge {
  // The feature pair (engine features, in the pair's a/b order) whose rounded function passes
  // within rounding of a double root; `t` (relative to now) is where to look for its crossing:
  // the rounded root if there is one, else the rounded minimum. On Crosses, `t` becomes the
  // crossing's time.
  virtual GrazeVerdict decide(ContactKind kind, std::uint16_t feature_a, std::uint16_t feature_b, T& t) const = 0;
  // Where the line contact of the feature pair (VertexEdge or EdgeVertex) lies on its edge at
  // the exact crossing nearest its rounded root `t` (relative to now), for a root the rounded
  // rule finds within its slack of an edge's end.
  virtual EdgePlace place(ContactKind kind, std::uint16_t feature_a, std::uint16_t feature_b, const T& t) const = 0;
  // A bound on the rounding of the pair's separating-axis values at now (the vertices' depths
  // in front of the edges' lines, computed from positions rounded from the stored paths), the
  // pair's coordinate scale at now (pair_scale) given.
  virtual T overlap_rounding(const T& scale) const = 0;
  // The overlap rule's pairs decided from the exact paths at now, for a pair whose rounded
  // separating-axis test lies within overlap_rounding() of touching; nothing where the exact
  // paths do not overlap (refine::exact_overlap_pairs: the rounded rule decides there).
  virtual std::optional<OverlapPairs> overlap_pairs() const = 0;

 protected:
  ~GrazeJudge() = default;
};

// Whether the line contact function p (c0 + c1 t + c2 t^2) falls to a minimum in (0, horizon]
// that is within rounding of zero (kLineGrazeRelative of magnitude(t_min), the size of the terms
// it is computed from at that time); `t_min` is that minimum's time.
template <class T, class Magnitude>
bool near_line_graze(const Poly<T>& p, const T& horizon, const Magnitude& magnitude, T& t_min) {
  using std::abs;
  if (!(p.c[2] > T(0)) || !(p.c[1] < T(0))) return false;
  t_min = -p.c[1] / (T(2) * p.c[2]);
  return t_min <= horizon && abs(p(t_min)) <= T(kLineGrazeRelative) * magnitude(t_min);
}

// The size of the terms of cross(q + v t + acc t^2 / 2, e), component by component (what its
// rounding is relative to; a wall reaching far along x adds nothing to a distance measured in y):
// the magnitude near_line_graze is given. The rounding of q itself, from positions far from the
// origin, is not counted: such a pair's near-grazes are left to the rounded function.
template <class T> T cross_magnitude(const Vec2<T>& q, const Vec2<T>& v, const Vec2<T>& acc, const T& t, const Vec2<T>& e) {
  using std::abs;
  const auto part = [&](const T& qi, const T& vi, const T& ai) { return abs(qi) + (abs(vi) + abs(ai) * t) * t; };
  return part(q.x, v.x, acc.x) * abs(e.y) + part(q.y, v.y, acc.y) * abs(e.x);
}

// The earliest downward root of p in [0, horizon] that `accept(t)` takes (a contact point on the
// feature), and whether the overlap rule gave it; nothing if there is none.
template <class T> struct AcceptedRoot {
  T t;
  bool overlap;
};
template <class T, class Accept>
std::optional<AcceptedRoot<T>> first_accepted_root(SolverKind solver, const Poly<T>& p, const T& horizon, StartRule rule,
                                                   const Accept& accept) {
  std::optional<AcceptedRoot<T>> out;
  visit_downward_roots(solver, p, T(0), horizon, rule, [&](const T& t, bool overlap) {
    if (!accept(t)) return false;
    out = AcceptedRoot<T>{t, overlap};
    return true;
  });
  return out;
}

// The largest coordinate magnitude of the pair at positions pa, pb: the scale of its rounding.
template <class T>
T pair_scale(const BodyShape<T>& sa, const Vec2<T>& pa, const BodyShape<T>& sb, const Vec2<T>& pb) {
  return std::max(sa.coordinate_scale(pa), sb.coordinate_scale(pb));
}

// Whether the bounding circles of the two bodies (see BodyShape::reach) overlap now or come
// into contact before the horizon; a pair whose circles do not cannot touch, and is skipped.
template <class T>
bool bounding_circles_meet(SolverKind solver, const BodyShape<T>& sa, const Kinematics<T>& ka, const BodyShape<T>& sb,
                           const Kinematics<T>& kb, const T& horizon) {
  const T reach = sa.reach + sb.reach;
  const T r = reach + T(kBoundingSlackRelative) * (reach + pair_scale(sa, ka.p, sb, kb.p));
  const Vec2<T> d = kb.p - ka.p;
  if (dot(d, d) <= r * r) return true;
  return point_contact(solver, d, kb.v - ka.v, kb.a - ka.a, r, horizon).has_value();
}

}  // namespace pge
