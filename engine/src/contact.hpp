// Contact functions of feature pairs (DESIGN.md, "What an event is"), their earliest
// approaching root, and the geometry of a contact once it happens: the dispatch on the two
// shapes. The categories live in contact_circle.hpp (circles against anything) and
// contact_polygon.hpp (polygons and segments against each other).
#pragma once

#include "contact_circle.hpp"
#include "contact_common.hpp"
#include "contact_polygon.hpp"

#include <cmath>
#include <optional>

namespace pge {

// A circle (a) against a polygon or segment (b) that is not a fixed segment: the circle's
// motion relative to b.
template <class T>
std::optional<PredictedContact<T>> circle_outline_contact(SolverKind solver, const BodyShape<T>& circle, const Kinematics<T>& kc,
                                                          const BodyShape<T>& other, const Kinematics<T>& ko, const T& horizon,
                                                          bool other_first, const GrazeJudge<T>* grazes) {
  const Vec2<T> v = kc.v - ko.v, acc = kc.a - ko.a;
  if (other.kind == ShapeKind::Polygon)
    return circle_polygon_contact(solver, kc.p, v, acc, circle.radius, other, ko.p, horizon, other_first, grazes);
  // A moving segment: its endpoint a is exactly p + local a (the state an exact referee reads).
  return circle_segment_contact(solver, (kc.p - ko.p) - other.local[0], v, acc, circle.radius, other.edges[0], horizon,
                                other_first, grazes);
}

// Two circles, from their distance_poly `p`.
template <class T>
std::optional<PredictedContact<T>> circle_pair_contact(SolverKind solver, const Poly<T>& p, const T& horizon) {
  auto root = point_contact(solver, p, horizon);
  if (!root) return std::nullopt;
  return PredictedContact<T>{root->t, ContactKind::CircleCircle, 0, 0, root->at_start_overlap};
}

template <class T>
std::optional<PredictedContact<T>> predict_contact(SolverKind solver, const BodyShape<T>& sa, const Kinematics<T>& ka,
                                                   const BodyShape<T>& sb, const Kinematics<T>& kb, const T& horizon,
                                                   const GrazeJudge<T>* grazes = nullptr) {
  const bool a_circle = sa.kind == ShapeKind::Circle, b_circle = sb.kind == ShapeKind::Circle;
  if (a_circle && b_circle)
    return circle_pair_contact(solver, distance_poly(kb.p - ka.p, kb.v - ka.v, kb.a - ka.a, sa.radius + sb.radius), horizon);
  // Circles against fixed walls: the cheapest category, and the one a gas in a box lives on.
  if (sa.kind == ShapeKind::Segment && sa.fixed && b_circle)
    return circle_segment_contact(solver, kb.p - sa.seg_a, kb.v - ka.v, kb.a - ka.a, sb.radius, sa.seg_b - sa.seg_a,
                                  horizon, true, grazes);
  if (a_circle && sb.kind == ShapeKind::Segment && sb.fixed)
    return circle_segment_contact(solver, ka.p - sb.seg_a, ka.v - kb.v, ka.a - kb.a, sa.radius, sb.seg_b - sb.seg_a,
                                  horizon, false, grazes);
  if (!bounding_circles_meet(solver, sa, ka, sb, kb, horizon)) return std::nullopt;
  if (a_circle) return circle_outline_contact(solver, sa, ka, sb, kb, horizon, false, grazes);
  if (b_circle) return circle_outline_contact(solver, sb, kb, sa, ka, horizon, true, grazes);
  return outline_contact(solver, sa, ka, sb, kb, horizon, grazes);
}

// The contact's geometry at the instant of the kinematics (the contact time).
template <class T>
ContactGeometry<T> contact_geometry(const PredictedContact<T>& c, const BodyShape<T>& sa, const Kinematics<T>& ka,
                                    const BodyShape<T>& sb, const Kinematics<T>& kb) {
  using std::sqrt;
  if (c.contact == ContactKind::CircleCircle) {
    const Vec2<T> n = kb.p - ka.p;
    const T dist = sqrt(dot(n, n));
    const T rr = sa.radius + sb.radius;
    const Vec2<T> point = dist > T(0) ? ka.p + n * (sa.radius / dist) : ka.p;
    return {n, point, dist - rr, rr};
  }
  if (c.contact == ContactKind::VertexEdge || c.contact == ContactKind::EdgeVertex)
    return outline_geometry(c.contact, c.feature_a, c.feature_b, c.corner, sa, ka, sb, kb);
  // A circle against a segment's or polygon's feature, oriented from that body towards the circle.
  const bool a_circle = sa.kind == ShapeKind::Circle;
  const BodyShape<T>& other = a_circle ? sb : sa;
  const Kinematics<T>& kc = a_circle ? ka : kb;
  const Kinematics<T>& ko = a_circle ? kb : ka;
  const std::uint16_t feature = a_circle ? c.feature_b : c.feature_a;
  const T r = a_circle ? sa.radius : sb.radius;
  ContactGeometry<T> g = other.kind == ShapeKind::Segment
                             ? circle_segment_geometry(c.contact, feature, kc.p, r, other, ko.p)
                             : circle_polygon_geometry(c.contact, feature, kc.p, r, other, ko.p);
  if (a_circle) g.normal = -g.normal;  // from the circle (a) towards the other body (b)
  return g;
}

// Separation of two bodies at positions pa, pb, for overlap measurement: the gap (negative:
// overlapping by that depth) and the contact distance it is measured against.
template <class T>
Separation<T> separation(const BodyShape<T>& sa, const Vec2<T>& pa, const BodyShape<T>& sb, const Vec2<T>& pb) {
  using std::sqrt;
  if (sa.kind == ShapeKind::Circle && sb.kind == ShapeKind::Circle) {
    const Vec2<T> d = pb - pa;
    return {sqrt(dot(d, d)) - (sa.radius + sb.radius), sa.radius + sb.radius};
  }
  auto vertices_of = [](const BodyShape<T>& s, const Vec2<T>& p) { return [&s, &p](std::size_t k) { return s.vertex(p, k); }; };
  if (sa.kind != ShapeKind::Circle && sb.kind != ShapeKind::Circle) {
    return {outline_separation<T>(vertices_of(sa, pa), sa.vertex_count(), vertices_of(sb, pb), sb.vertex_count()),
            std::min(sa.size, sb.size)};
  }
  const bool a_circle = sa.kind == ShapeKind::Circle;
  const BodyShape<T>& circle = a_circle ? sa : sb;
  const BodyShape<T>& other = a_circle ? sb : sa;
  const Vec2<T>& c = a_circle ? pa : pb;
  const Vec2<T>& po = a_circle ? pb : pa;
  return {point_outline_distance(c, vertices_of(other, po), other.vertex_count()) - circle.radius, circle.radius};
}

}  // namespace pge
