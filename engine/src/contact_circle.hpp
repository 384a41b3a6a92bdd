// Circles against circles, segments and polygons: contact prediction and contact geometry.
#pragma once

#include "contact_common.hpp"

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <optional>

namespace pge {

// A circle against a segment: the edge interior from either side (a one-sided distance to the
// line, degree <= 2, accepted where the centre projects inside the edge), and each endpoint as
// a point at distance r. `q` is the centre relative to endpoint a; v and acc are relative.
template <class T>
std::optional<PredictedContact<T>> circle_segment_contact(SolverKind solver, const Vec2<T>& q, const Vec2<T>& v, const Vec2<T>& acc,
                                                          const T& r, const Vec2<T>& u, const T& horizon,
                                                          bool segment_first, const GrazeJudge<T>* grazes = nullptr) {
  using std::sqrt;
  std::optional<PredictedContact<T>> best;
  auto offer = [&](const T& t, ContactKind kind, std::uint16_t seg_feature, bool overlap) {
    keep_earliest(best, PredictedContact<T>{t, kind, segment_first ? seg_feature : std::uint16_t(0),
                                            segment_first ? std::uint16_t(0) : seg_feature, overlap});
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
    const auto on_edge = [&](const T& t) {
      const Vec2<T> qt = q + v * t + acc * (t * t / T(2));
      const T along = dot(qt, u);
      return along >= T(0) && along <= uu;  // off the edge: a vertex's business
    };
    const std::optional<AcceptedRoot<T>> rounded = first_accepted_root(solver, p, horizon, rule, on_edge);
    // A near-graze from the side the circle is on: the exact paths decide.
    T t = T(0);
    const auto magnitude = [&](const T& at) { return cross_magnitude(q, v, acc, at, u) + r * len; };
    if (grazes && side == side_now && near_line_graze(p, horizon, magnitude, t)) {
      if (rounded && !rounded->overlap) t = rounded->t;
      const GrazeVerdict g = grazes->decide(ContactKind::CircleEdge, 0, 0, t);
      if (g == GrazeVerdict::Crosses && on_edge(t)) offer(t, ContactKind::CircleEdge, 0, false);
      if (g != GrazeVerdict::Undecided) continue;
    }
    if (rounded) offer(rounded->t, ContactKind::CircleEdge, 0, rounded->overlap);
  }
  for (std::uint16_t k = 0; k < 2; ++k) {
    const Vec2<T> d = k == 0 ? q : q - u;
    if (auto root = point_contact(solver, d, v, acc, r, horizon))
      offer(root->t, ContactKind::CircleVertex, k, root->at_start_overlap);
  }
  return best;
}

// A circle (centre c, velocity v and acceleration acc relative to the polygon) against a convex
// polygon: each edge interior from outside only (polygon edges are one-sided), as the distance
// of the centre in front of the edge's line minus r, accepted where the centre projects inside
// the edge; and each vertex as a point at distance r (a circle of radius 0).
template <class T>
std::optional<PredictedContact<T>> circle_polygon_contact(SolverKind solver, const Vec2<T>& c, const Vec2<T>& v,
                                                          const Vec2<T>& acc, const T& r, const BodyShape<T>& poly,
                                                          const Vec2<T>& poly_p, const T& horizon, bool polygon_first,
                                                          const GrazeJudge<T>* grazes = nullptr) {
  std::optional<PredictedContact<T>> best;
  auto offer = [&](const T& t, ContactKind kind, std::size_t feature, bool overlap) {
    const std::uint16_t f = feature_index(feature);
    keep_earliest(best, PredictedContact<T>{t, kind, polygon_first ? f : std::uint16_t(0),
                                            polygon_first ? std::uint16_t(0) : f, overlap});
  };
  const std::size_t n = poly.vertex_count();
  for (std::size_t j = 0; j < n; ++j) {
    const Vec2<T>& e = poly.edges[j];
    const Vec2<T> q = (c - poly.base(poly_p, j)) - poly.offset(j);  // centre relative to the edge's start
    const T front = cross(q, e);                                    // distance in front times |e|
    Poly<T> p;
    p.c[0] = front - r * poly.edge_length[j];
    p.c[1] = cross(v, e);
    p.c[2] = cross(acc, e) / T(2);
    p.degree = 2;
    if (never_decreasing(p)) continue;
    // Behind the edge's line the function measures no separation: only crossings count there.
    const StartRule rule = front > T(0) ? StartRule::OverlapCollides : StartRule::CrossingsOnly;
    const T ee = dot(e, e);
    const auto on_edge = [&](const T& t) {
      const T along = dot(q + v * t + acc * (t * t / T(2)), e);
      return along >= T(0) && along <= ee;  // off the edge: a vertex's business
    };
    const std::optional<AcceptedRoot<T>> rounded = first_accepted_root(solver, p, horizon, rule, on_edge);
    // A near-graze in front of the edge: the exact paths decide.
    T t = T(0);
    const auto magnitude = [&](const T& at) { return cross_magnitude(q, v, acc, at, e) + r * poly.edge_length[j]; };
    if (grazes && front > T(0) && near_line_graze(p, horizon, magnitude, t)) {
      if (rounded && !rounded->overlap) t = rounded->t;
      const std::uint16_t f = feature_index(j);
      const GrazeVerdict g = grazes->decide(ContactKind::CircleEdge, polygon_first ? f : std::uint16_t(0),
                                            polygon_first ? std::uint16_t(0) : f, t);
      if (g == GrazeVerdict::Crosses && on_edge(t)) offer(t, ContactKind::CircleEdge, j, false);
      if (g != GrazeVerdict::Undecided) continue;
    }
    if (rounded) offer(rounded->t, ContactKind::CircleEdge, j, rounded->overlap);
  }
  for (std::size_t k = 0; k < n; ++k) {
    const Vec2<T> d = (c - poly.base(poly_p, k)) - poly.offset(k);
    if (auto root = point_contact(solver, d, v, acc, r, horizon))
      offer(root->t, ContactKind::CircleVertex, k, root->at_start_overlap);
  }
  return best;
}

// Geometry of a circle (centre c, radius r) against a segment feature, oriented from the
// segment towards the circle.
template <class T>
ContactGeometry<T> circle_segment_geometry(ContactKind kind, std::uint16_t seg_feature, const Vec2<T>& c, const T& r,
                                           const BodyShape<T>& seg, const Vec2<T>& seg_p) {
  using std::abs;
  using std::sqrt;
  if (kind == ContactKind::CircleVertex) {
    const Vec2<T> n = (c - seg.base(seg_p, seg_feature)) - seg.offset(seg_feature);
    return {n, seg.vertex(seg_p, seg_feature), sqrt(dot(n, n)) - r, r};
  }
  const Vec2<T> m = perp(seg.edges[0]);
  const T len = sqrt(dot(m, m));
  const T s = dot((c - seg.base(seg_p, 0)) - seg.offset(0), m) / len;
  const Vec2<T> n = s >= T(0) ? m : -m;
  return {n, c - n * (r / len), abs(s) - r, r};
}

// Geometry of a circle (centre c, radius r) against a polygon's edge or vertex, oriented from
// the polygon towards the circle: the edge's outward normal, or from the vertex to the centre.
template <class T>
ContactGeometry<T> circle_polygon_geometry(ContactKind kind, std::uint16_t feature, const Vec2<T>& c, const T& r,
                                           const BodyShape<T>& poly, const Vec2<T>& poly_p) {
  using std::sqrt;
  const Vec2<T> q = (c - poly.base(poly_p, feature)) - poly.offset(feature);
  if (kind == ContactKind::CircleVertex) return {q, poly.vertex(poly_p, feature), sqrt(dot(q, q)) - r, r};
  const Vec2<T> m = outward_normal(poly.edges[feature]);
  const T len = poly.edge_length[feature];
  return {m, c - m * (r / len), cross(q, poly.edges[feature]) / len - r, r};
}

}  // namespace pge
