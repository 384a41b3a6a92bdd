// Contact functions of feature pairs (DESIGN.md, "What an event is"), their earliest
// approaching root, and the geometry of a contact once it happens.
#pragma once

#include "pge/event.hpp"
#include "pge/roots.hpp"
#include "pge/scene.hpp"
#include "pge/vec2.hpp"

#include <cmath>
#include <cstdint>
#include <optional>

namespace pge {

template <class T> struct Kinematics {
  Vec2<T> p, v, a;  // position, velocity, acceleration at one instant
};

template <class T> struct ShapeRef {
  ShapeKind shape;
  T radius;
  Vec2<T> seg_a, seg_b;  // segment endpoints in world coordinates at the instant of the kinematics
};

template <class T> struct PredictedContact {
  T time;  // relative to the instant of the kinematics
  ContactKind contact;
  std::uint16_t feature_a;
  std::uint16_t feature_b;
  bool at_start_overlap;

  bool before(const PredictedContact& o) const {
    if (time != o.time) return time < o.time;
    if (contact != o.contact) return contact < o.contact;
    if (feature_a != o.feature_a) return feature_a < o.feature_a;
    return feature_b < o.feature_b;
  }
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
template <class T>
std::optional<RootOutcome<T>> point_contact(SolverKind solver, const Vec2<T>& d, const Vec2<T>& dv, const Vec2<T>& da, const T& r,
                                            const T& horizon) {
  const Poly<T> p = distance_poly(d, dv, da, r);
  // Without relative acceleration the function is a convex parabola: if it is not decreasing
  // now it never will be, so most pairs of a gas are dismissed here without a solve.
  if (p.degree == 2 && p.c[1] >= T(0)) return std::nullopt;
  const RootOutcome<T> root = earliest_downward_root(solver, p, T(0), horizon);
  if (root.status != RootStatus::Root) return std::nullopt;
  return root;
}

// A circle against a segment: the edge interior from either side (a one-sided distance to the
// line, degree <= 2, accepted where the centre projects inside the edge), and each endpoint as
// a point at distance r. `q` is the centre relative to endpoint a; v and acc are relative.
template <class T>
std::optional<PredictedContact<T>> circle_segment_contact(SolverKind solver, const Vec2<T>& q, const Vec2<T>& v, const Vec2<T>& acc,
                                                          const T& r, const Vec2<T>& u, const T& horizon,
                                                          bool segment_first) {
  using std::sqrt;
  std::optional<PredictedContact<T>> best;
  auto offer = [&](const T& t, ContactKind kind, std::uint16_t seg_feature, bool overlap) {
    PredictedContact<T> c{t, kind, segment_first ? seg_feature : std::uint16_t(0),
                          segment_first ? std::uint16_t(0) : seg_feature, overlap};
    if (!best || c.before(*best)) best = c;
  };

  const Vec2<T> m = perp(u);
  const T len = sqrt(dot(m, m));
  const T uu = dot(u, u);
  const T s0 = dot(q, m);  // signed distance times len
  const int side_now = (s0 > T(0)) - (s0 < T(0));
  for (int side : {1, -1}) {
    Poly<T> p;
    p.c[0] = T(side) * s0 - r * len;
    p.c[1] = T(side) * dot(v, m);
    p.c[2] = T(side) * dot(acc, m) / T(2);
    p.degree = 2;
    const StartRule rule = side == side_now ? StartRule::OverlapCollides : StartRule::CrossingsOnly;
    visit_downward_roots(solver, p, T(0), horizon, rule, [&](const T& t, bool overlap) {
      const Vec2<T> qt = q + v * t + acc * (t * t / T(2));
      const T along = dot(qt, u);
      if (along < T(0) || along > uu) return false;  // off the edge: a vertex's business
      offer(t, ContactKind::CircleEdge, 0, overlap);
      return true;
    });
  }
  for (std::uint16_t k = 0; k < 2; ++k) {
    const Vec2<T> d = k == 0 ? q : q - u;
    if (auto root = point_contact(solver, d, v, acc, r, horizon))
      offer(root->t, ContactKind::CircleVertex, k, root->at_start_overlap);
  }
  return best;
}

template <class T>
std::optional<PredictedContact<T>> predict_contact(SolverKind solver, const ShapeRef<T>& sa, const Kinematics<T>& ka,
                                                   const ShapeRef<T>& sb, const Kinematics<T>& kb,
                                                   const T& horizon) {
  if (sa.shape == ShapeKind::Circle && sb.shape == ShapeKind::Circle) {
    auto root = point_contact(solver, kb.p - ka.p, kb.v - ka.v, kb.a - ka.a, sa.radius + sb.radius, horizon);
    if (!root) return std::nullopt;
    return PredictedContact<T>{root->t, ContactKind::CircleCircle, 0, 0, root->at_start_overlap};
  }
  if (sa.shape == ShapeKind::Segment && sb.shape == ShapeKind::Circle)
    return circle_segment_contact(solver, kb.p - sa.seg_a, kb.v - ka.v, kb.a - ka.a, sb.radius, sa.seg_b - sa.seg_a,
                                  horizon, true);
  if (sa.shape == ShapeKind::Circle && sb.shape == ShapeKind::Segment)
    return circle_segment_contact(solver, ka.p - sb.seg_a, ka.v - kb.v, ka.a - kb.a, sa.radius, sb.seg_b - sb.seg_a,
                                  horizon, false);
  return std::nullopt;  // segment against segment: both fixed in this version
}

template <class T> struct ContactGeometry {
  Vec2<T> normal;  // from body a towards body b, not normalised
  Vec2<T> point;
  T gap;           // signed separation (negative: overlap)
  T contact_distance;  // radius sum, or the circle's radius against a segment
};

template <class T> struct Separation {
  T gap;
  T contact_distance;
};

// Geometry of a circle (centre c, radius r) against a segment feature, oriented from the
// segment towards the circle.
template <class T>
ContactGeometry<T> circle_segment_geometry(ContactKind kind, std::uint16_t seg_feature, const Vec2<T>& c,
                                           const T& r, const Vec2<T>& ea, const Vec2<T>& eb) {
  using std::sqrt;
  if (kind == ContactKind::CircleVertex) {
    const Vec2<T> vtx = seg_feature == 0 ? ea : eb;
    const Vec2<T> n = c - vtx;
    return {n, vtx, sqrt(dot(n, n)) - r, r};
  }
  const Vec2<T> m = perp(eb - ea);
  const T len = sqrt(dot(m, m));
  const T s = dot(c - ea, m) / len;
  const Vec2<T> n = s >= T(0) ? m : -m;
  using std::abs;
  return {n, c - n * (r / len), abs(s) - r, r};
}

template <class T>
ContactGeometry<T> contact_geometry(ContactKind kind, std::uint16_t fa, std::uint16_t fb, const ShapeRef<T>& sa,
                                    const Kinematics<T>& ka, const ShapeRef<T>& sb, const Kinematics<T>& kb) {
  using std::sqrt;
  if (kind == ContactKind::CircleCircle) {
    const Vec2<T> n = kb.p - ka.p;
    const T dist = sqrt(dot(n, n));
    const T rr = sa.radius + sb.radius;
    const Vec2<T> point = dist > T(0) ? ka.p + n * (sa.radius / dist) : ka.p;
    return {n, point, dist - rr, rr};
  }
  if (sa.shape == ShapeKind::Segment) return circle_segment_geometry(kind, fa, kb.p, sb.radius, sa.seg_a, sa.seg_b);
  ContactGeometry<T> g = circle_segment_geometry(kind, fb, ka.p, sa.radius, sb.seg_a, sb.seg_b);
  g.normal = -g.normal;  // from the circle (a) towards the segment (b)
  return g;
}

// Separation of two bodies at given positions (shape references already placed), for overlap
// measurement; nothing for pairs that cannot touch in this version.
template <class T>
std::optional<Separation<T>> separation(const ShapeRef<T>& sa, const Vec2<T>& pa, const ShapeRef<T>& sb,
                                        const Vec2<T>& pb) {
  using std::sqrt;
  if (sa.shape == ShapeKind::Circle && sb.shape == ShapeKind::Circle) {
    const Vec2<T> d = pb - pa;
    return Separation<T>{sqrt(dot(d, d)) - (sa.radius + sb.radius), sa.radius + sb.radius};
  }
  const bool a_circle = sa.shape == ShapeKind::Circle;
  const ShapeRef<T>& circle = a_circle ? sa : sb;
  const ShapeRef<T>& seg = a_circle ? sb : sa;
  if (circle.shape != ShapeKind::Circle || seg.shape != ShapeKind::Segment) return std::nullopt;
  const Vec2<T> c = a_circle ? pa : pb;
  const Vec2<T> u = seg.seg_b - seg.seg_a;
  T lambda = dot(c - seg.seg_a, u) / dot(u, u);
  lambda = lambda < T(0) ? T(0) : (lambda > T(1) ? T(1) : lambda);
  const Vec2<T> d = c - (seg.seg_a + u * lambda);
  return Separation<T>{sqrt(dot(d, d)) - circle.radius, circle.radius};
}

}  // namespace pge
