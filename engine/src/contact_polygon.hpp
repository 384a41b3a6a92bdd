// Polygons and segments against each other: every vertex of one body against every edge of the
// other (a point crossing a line, degree <= 2 for translating bodies), as PGE does, plus the
// two things PGE lacked: a corner rule, so that a vertex meeting a vertex (corner on corner,
// or parallel edges meeting end to end) is one collision with one normal, and a
// separating-axis overlap rule, so that a pair left overlapping by rounding still collides.
//
// A segment is the outline [a, b] with the edges a->b and b->a (its two sides, see
// geometry.hpp); its engine edge 1 is reported as the public edge 0.
#pragma once

#include "contact_common.hpp"
#include "pge/detail/corner.hpp"

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>

namespace pge {

// The vertices of body P against the edges of body Q, with P's motion relative to Q.
template <class T> struct OutlineView {
  const BodyShape<T>& P;
  const Vec2<T>& pP;
  const BodyShape<T>& Q;
  const Vec2<T>& pQ;
  Vec2<T> dv, da;  // velocity and acceleration of P relative to Q

  // Vertex k of P relative to the start of edge j of Q, at the instant of the positions.
  Vec2<T> offset(std::size_t k, std::size_t j) const {
    return (P.base(pP, k) - Q.base(pQ, j)) + (P.offset(k) - Q.offset(j));
  }
  // How far vertex k of P is in front of edge j of Q (negative: behind its line).
  T depth(std::size_t k, std::size_t j) const { return cross(offset(k, j), Q.edges[j]) / Q.edge_length[j]; }
  // The separating-axis value of Q's edge j: the depth of P's deepest vertex.
  T axis(std::size_t j) const {
    T nearest = std::numeric_limits<T>::infinity();
    for (std::size_t k = 0; k < P.vertex_count(); ++k) nearest = std::min(nearest, depth(k, j));
    return nearest;
  }
};

template <class T> OutlineView<T> view_of(const BodyShape<T>& P, const Kinematics<T>& kP, const BodyShape<T>& Q,
                                          const Kinematics<T>& kQ) {
  return {P, kP.p, Q, kQ.p, kP.v - kQ.v, kP.a - kQ.a};
}

// The separating-axis test of the pair: its largest axis value (negative: the least
// penetration of an overlapping pair), or the first value above `stop_above` found (an axis
// that separates by more than that: how much more does not matter), and on how many axes a
// vertex's depth lies within `stop_above` of zero on the way. Only the vertex/edge pairs that
// realise the least penetration measure a real separation, so only they may collide by the
// overlap rule.
template <class T> struct AxisTest {
  T largest;
  int near_zero_axes;
};
template <class T> AxisTest<T> largest_axis(const OutlineView<T>& pq, const OutlineView<T>& qp, const T& stop_above) {
  using std::abs;
  AxisTest<T> out{-std::numeric_limits<T>::infinity(), 0};
  for (const OutlineView<T>* o : {&pq, &qp}) {
    for (std::size_t j = 0; j < o->Q.vertex_count(); ++j) {
      T s = std::numeric_limits<T>::infinity();
      bool near_zero = false;
      for (std::size_t k = 0; k < o->P.vertex_count(); ++k) {
        const T d = o->depth(k, j);
        s = std::min(s, d);
        near_zero = near_zero || abs(d) <= stop_above;
      }
      if (near_zero) ++out.near_zero_axes;
      if (s > stop_above) {
        out.largest = s;
        return out;
      }
      out.largest = std::max(out.largest, s);
    }
  }
  return out;
}

// The interior directions of an outline at vertex i: back along the edge arriving there and
// along the edge leaving it (one direction twice at a segment's end).
template <class T> std::array<Vec2<T>, 2> interior_directions(const BodyShape<T>& s, std::size_t i) {
  const std::size_t n = s.vertex_count();
  return {-s.edges[(i + n - 1) % n], s.edges[i]};
}

// The overlap cone of vertex k of P touching Q at a point where Q's interior directions are
// `q` (at a vertex of Q: interior_directions; inside a segment: both directions along it): see
// overlap_cone_of (pge/detail/corner.hpp).
template <class T>
std::optional<Cone<T>> overlap_cone(const BodyShape<T>& P, std::size_t k, const std::array<Vec2<T>, 2>& q) {
  const auto p = interior_directions(P, k);
  return overlap_cone_of(q[0], q[1], p[0], p[1]);
}

template <class T> struct VertexEdgeHit {
  T t;
  bool overlap;
  bool corner;
};

// Which side of edge j's line P's body lies on after P has moved by `motion` relative to Q: the
// sign of the mean of its vertices' distances in front of the line (every vertex moves alike),
// +1 in front, -1 behind, 0 within the rounding of those distances.
template <class T> int body_side(const OutlineView<T>& o, std::size_t j, const Vec2<T>& motion, const T& scale) {
  using std::abs;
  const Vec2<T>& e = o.Q.edges[j];
  T sum{0}, size{0};
  for (std::size_t k = 0; k < o.P.vertex_count(); ++k) {
    const Vec2<T> d = o.offset(k, j) + motion;
    sum += cross(d, e);
    size += abs(d.x * e.y) + abs(d.y * e.x);
  }
  const T rounding = T(64) * std::numeric_limits<T>::epsilon() *
                     (size + T(o.P.vertex_count()) * scale * (abs(e.x) + abs(e.y)));
  if (sum > rounding) return 1;
  if (sum < -rounding) return -1;
  return 0;
}

// Whether a downward root t of the contact function of vertex k of P with edge j of Q (d0:
// the vertex relative to the edge's start at t = 0) is a collision, and of which kind.
template <class T>
std::optional<VertexEdgeHit<T>> judge_root(const OutlineView<T>& o, std::size_t k, std::size_t j, const Vec2<T>& d0,
                                           const T& t, bool overlap, const T& scale,
                                           const GrazeJudge<T>* exact = nullptr,
                                           ContactKind kind = ContactKind::VertexEdge, std::uint16_t fa = 0,
                                           std::uint16_t fb = 0) {
  const Vec2<T>& e = o.Q.edges[j];
  const Vec2<T> motion = o.dv * t + o.da * (t * t / T(2));
  const Vec2<T> d = d0 + motion;
  const Vec2<T> u = o.dv + o.da * t;
  const EdgeSpot spot = locate_on_edge(d, u, e, o.Q.edge_length[j], scale);
  if (spot == EdgeSpot::Off) return std::nullopt;
  // Crossing a polygon's edge inside it is entering the polygon. A segment has two sides and no
  // inside: a vertex crossing its line inside it enters from the side P's body is on, and comes
  // back out of an overlap (rounding can leave a vertex that has just bounced an ulp beyond the
  // line) from the other; the body's side is told by its vertices' mean, and where that is
  // within rounding of the line, by the overlap cone, as at corners. (The cone alone misjudges
  // a vertex whose own edge lies along the segment, sliding along it: a box on an incline at
  // decimal coordinates, fixtures/regressions/box-placed-on-an-incline.json.)
  const auto inside = [&]() -> std::optional<VertexEdgeHit<T>> {
    if (o.Q.kind == ShapeKind::Segment) {
      const int side = body_side(o, j, motion, scale);
      if (side < 0) return std::nullopt;
      if (side == 0) {
        const std::optional<Cone<T>> cone = overlap_cone(o.P, k, std::array<Vec2<T>, 2>{e, -e});
        if (!cone || !enters_cone(*cone, u, o.da)) return std::nullopt;
      }
    }
    return VertexEdgeHit<T>{t, false, false};
  };
  if (overlap) return VertexEdgeHit<T>{t, overlap, false};
  if (spot == EdgeSpot::Interior) return inside();
  // Inside the edge by the slack unwidened: a face contact, whatever the corner rule would say
  // (a box sliding along a tilted segment at a normal speed of rounding size has a widened
  // slack spanning the whole edge, and the corner rule's bisector normal kicked it off the
  // face at half a metre per second: fixtures/regressions/box-slides-up-a-tile-joint.json).
  if (locate_on_edge(d, Vec2<T>{}, e, o.Q.edge_length[j], scale) == EdgeSpot::Interior) return inside();
  // Near an end, where the rounding of the root's time and point decides which side of the end
  // the exact crossing lies on, robust and certified ask the exact paths (`exact`, the feature
  // pair (fa, fb) of the contact `kind`): strictly inside the edge is an edge contact, beyond
  // its end none (the end vertex's feature pairs meet instead, as the oracle counts them); at
  // the end itself the corner rule decides. (A triangle's corner aimed at a segment's end in
  // float was missed: both corner rules rejected the two feature pairs, though the vertex's
  // exact crossing lay inside the segment; scripts/edge-end-sweep.py.)
  if (exact) {
    const EdgePlace place = exact->place(kind, fa, fb, t);
    if (place == EdgePlace::On) return inside();
    if (place != EdgePlace::Unknown) return std::nullopt;
  }
  // Near an end by the slack widened by the tangential over the normal speed (the rounding of
  // the root's time moved along the edge), not by the slack itself: the corner rule.
  const std::size_t w = spot == EdgeSpot::End ? (j + 1) % o.Q.vertex_count() : j;
  const std::optional<Cone<T>> cone = overlap_cone(o.P, k, interior_directions(o.Q, w));
  if (cone && enters_cone(*cone, u, o.da)) return VertexEdgeHit<T>{t, false, true};
  return std::nullopt;  // passed or left, not entered
}

// The contact function of a vertex of P at d0 (relative to the start of Q's edge j at t = 0)
// with that edge: its distance in front of the edge's line times |e|, a quadratic in t.
template <class T> Poly<T> vertex_edge_poly(const OutlineView<T>& o, const Vec2<T>& d0, std::size_t j) {
  const Vec2<T>& e = o.Q.edges[j];
  Poly<T> p;
  p.c[0] = cross(d0, e);
  p.c[1] = cross(o.dv, e);
  p.c[2] = cross(o.da, e) / T(2);
  p.degree = 2;
  return p;
}

// The earliest approaching contact of vertex k of P with edge j of Q in [0, horizon]. The
// contact function is the distance of the vertex in front of the edge's line times |e|, a
// quadratic; a root counts where judge_root says so. A near-graze in front of the edge is
// decided by `grazes` (if given) as the feature pair (fa, fb) of the contact `kind`.
template <class T>
std::optional<VertexEdgeHit<T>> vertex_edge_contact(SolverKind solver, const OutlineView<T>& o, std::size_t k,
                                                    std::size_t j, StartRule rule, const T& scale, const T& horizon,
                                                    const GrazeJudge<T>* grazes = nullptr,
                                                    ContactKind kind = ContactKind::VertexEdge, std::uint16_t fa = 0,
                                                    std::uint16_t fb = 0) {
  const Vec2<T> d0 = o.offset(k, j);
  const Vec2<T>& e = o.Q.edges[j];
  const Poly<T> p = vertex_edge_poly(o, d0, j);
  if (never_decreasing(p)) return std::nullopt;
  std::optional<VertexEdgeHit<T>> hit;
  std::optional<T> first_root;  // the rounded function's first downward root, judged or not
  visit_downward_roots(solver, p, T(0), horizon, rule, [&](const T& t, bool overlap) {
    if (!first_root && !overlap) first_root = t;
    hit = judge_root(o, k, j, d0, t, overlap, scale, grazes, kind, fa, fb);
    return hit.has_value();
  });
  T t = T(0);
  const auto magnitude = [&](const T& at) { return cross_magnitude(d0, o.dv, o.da, at, e); };
  if (grazes && p.c[0] > T(0) && near_line_graze(p, horizon, magnitude, t)) {
    if (first_root) t = *first_root;
    const GrazeVerdict g = grazes->decide(kind, fa, fb, t);
    if (g == GrazeVerdict::Misses) return std::nullopt;
    // A crossing: judged as a root is (inside a segment, by the side P's body is on).
    if (g == GrazeVerdict::Crosses) {
      if (auto h = judge_root(o, k, j, d0, t, false, scale, grazes, kind, fa, fb)) return h;
    }
  }
  return hit;
}

// Whether vertex k of P may meet edge j of Q first: false when a neighbouring vertex of P lies
// behind the line through vertex k parallel to the edge (towards the edge's front, P's body then
// reaches past vertex k: its neighbour, or an edge of P, meets the edge's line or end first). The
// oracle has no such feature pair, so a contact the engine took on one, out of a pair left
// overlapping by rounding, was an event the oracle never has (a triangle's corner that had
// crossed a segment an ulp inside its end: the segment's end, whose segment runs into the
// triangle, crossed the triangle's edge 2.2e-8 s later; scripts/edge-end-sweep.py seed 5,
// end-104). Only where the rounded sign clears its rounding: a neighbouring edge parallel to
// the edge within rounding is kept.
// The test reads P's edges (vertex k+1 - vertex k): the neighbour after k lies behind where
// cross(edge k, e) < 0, the one before it where cross(edge k-1, e) > 0 (a segment's two edges
// are its one neighbour both ways).
template <class T> struct EdgeTurn {  // cross(edge k of P, e) and a bound on its rounding
  T value, rounding;
};
template <class T> EdgeTurn<T> edge_turn(const OutlineView<T>& o, std::size_t k, const Vec2<T>& e) {
  using std::abs;
  const Vec2<T>& d = o.P.edges[k];
  return {cross(d, e), T(8) * std::numeric_limits<T>::epsilon() * (abs(d.x * e.y) + abs(d.y * e.x))};
}
template <class T> bool extreme_between(const EdgeTurn<T>& before, const EdgeTurn<T>& after) {
  return !(after.value < -after.rounding) && !(before.value > before.rounding);
}
template <class T> bool extreme_towards(const OutlineView<T>& o, std::size_t k, std::size_t j) {
  const std::size_t n = o.P.vertex_count();
  const Vec2<T>& e = o.Q.edges[j];
  return extreme_between(edge_turn(o, (k + n - 1) % n, e), edge_turn(o, k, e));
}

// Every vertex of P against every edge of Q, offered as `kind` (VertexEdge when P is body a);
// the overlap rule's pairs are `exact`'s where given (side 0 or 1 as kind is VertexEdge or
// EdgeVertex), else those realising the rounded least penetration `overlap`.
template <class T>
void scan_vertex_edge(SolverKind solver, const OutlineView<T>& o, ContactKind kind, const std::optional<T>& overlap,
                      const OverlapPairs* exact, const T& scale, const T& horizon,
                      std::optional<PredictedContact<T>>& best, const GrazeJudge<T>* grazes) {
  const int side = kind == ContactKind::VertexEdge ? 0 : 1;
  for (std::size_t j = 0; j < o.Q.vertex_count(); ++j) {
    const bool axis_is_least = !exact && overlap && o.axis(j) == *overlap;
    const std::size_t n = o.P.vertex_count();
    EdgeTurn<T> before = edge_turn(o, n - 1, o.Q.edges[j]);
    for (std::size_t k = 0; k < n; ++k) {
      const EdgeTurn<T> after = edge_turn(o, k, o.Q.edges[j]);
      const bool extreme = extreme_between(before, after);
      before = after;
      if (!extreme) continue;
      const OverlapPairs::Pair* decided = exact ? exact->find(side, k, j) : nullptr;
      const bool real = exact ? decided != nullptr : axis_is_least && o.depth(k, j) == *overlap;
      const StartRule rule = real ? StartRule::OverlapCollides : StartRule::CrossingsOnly;
      const std::uint16_t vk = feature_index(k), ej = feature_index(j);
      const bool p_is_a = kind == ContactKind::VertexEdge;
      // An exact pair approaching collides now, whatever the sign its rounded function has there.
      const auto hit = decided && decided->approaching
                           ? std::optional<VertexEdgeHit<T>>(VertexEdgeHit<T>{T(0), true, false})
                           : vertex_edge_contact(solver, o, k, j, rule, scale, horizon, grazes, kind,
                                                 p_is_a ? vk : ej, p_is_a ? ej : vk);
      if (!hit) continue;
      keep_earliest(best, PredictedContact<T>{hit->t, kind, p_is_a ? vk : ej, p_is_a ? ej : vk, hit->overlap,
                                              hit->corner});
    }
  }
}

// The earliest approaching contact of two polygons / segments. Where the rounded
// separating-axis test lies within its rounding of touching on two or more axes, robust and
// certified take the overlap rule's pairs from the exact paths (`grazes`): at that size the
// rounded depths pick an axis by their rounding (a triangle's corner on a segment's end in float: after the impulse at
// the end, the end lay 2.6e-8 inside one of the triangle's edges and 1.1e-7 inside the other,
// the triangle's corner 1.1e-7 across the segment, all below float's rounding at those
// coordinates; the rounded test collided nothing where the oracle collides the end with the
// edge it is least inside, scripts/edge-end-sweep.py seed 4, end-216).
template <class T>
std::optional<PredictedContact<T>> outline_contact(SolverKind solver, const BodyShape<T>& sa, const Kinematics<T>& ka,
                                                   const BodyShape<T>& sb, const Kinematics<T>& kb, const T& horizon,
                                                   const GrazeJudge<T>* grazes = nullptr) {
  using std::abs;
  const OutlineView<T> ab = view_of(sa, ka, sb, kb);  // a's vertices against b's edges
  const OutlineView<T> ba = view_of(sb, kb, sa, ka);
  const T scale = pair_scale(sa, ka.p, sb, kb.p);
  const T rounding = grazes ? grazes->overlap_rounding(scale) : T(0);
  const AxisTest<T> axes = largest_axis(ab, ba, rounding);
  const std::optional<T> overlap = axes.largest < T(0) ? std::optional<T>(axes.largest) : std::nullopt;
  // With depths near zero on one axis only (a pair just after its collision, or a box sliding
  // flush along a wall), the rounded test has no other axis to mistake it for and stands: the
  // exact one is asked only where two or more axes are near zero (a corner against an edge, a
  // vertex near an edge's end).
  std::optional<OverlapPairs> exact;
  if (grazes && abs(axes.largest) <= rounding && axes.near_zero_axes >= 2) exact = grazes->overlap_pairs();
  const OverlapPairs* pairs = exact ? &*exact : nullptr;
  std::optional<PredictedContact<T>> best;
  scan_vertex_edge(solver, ab, ContactKind::VertexEdge, overlap, pairs, scale, horizon, best, grazes);
  scan_vertex_edge(solver, ba, ContactKind::EdgeVertex, overlap, pairs, scale, horizon, best, grazes);
  return best;
}

// Geometry of a vertex/edge contact, the normal from a towards b: the edge's outward normal, or
// at a corner the corner normal. The gap is the vertex's distance in front of the edge's line.
template <class T>
ContactGeometry<T> outline_geometry(ContactKind kind, std::uint16_t fa, std::uint16_t fb, bool corner, const BodyShape<T>& sa,
                                    const Kinematics<T>& ka, const BodyShape<T>& sb, const Kinematics<T>& kb) {
  const bool a_has_vertex = kind == ContactKind::VertexEdge;
  const OutlineView<T> o = a_has_vertex ? view_of(sa, ka, sb, kb) : view_of(sb, kb, sa, ka);
  const std::size_t k = a_has_vertex ? fa : fb;
  const std::size_t j = a_has_vertex ? fb : fa;
  const Vec2<T>& e = o.Q.edges[j];
  const Vec2<T> d = o.offset(k, j);
  Vec2<T> n = outward_normal(e);  // from Q (the edge's body) towards P (the vertex's)
  if (corner) {
    const std::size_t w = dot(d, e) <= dot(e, e) / T(2) ? j : (j + 1) % o.Q.vertex_count();
    if (const auto cone = overlap_cone(o.P, k, interior_directions(o.Q, w))) n = corner_normal(*cone);
  }
  return {a_has_vertex ? -n : n, o.P.vertex(o.pP, k), cross(d, e) / o.Q.edge_length[j], std::min(sa.size, sb.size)};
}

// The public index of an engine edge (a segment's side b->a is its edge 0).
template <class T> std::uint16_t public_edge(const BodyShape<T>& s, std::uint16_t edge) {
  return s.kind == ShapeKind::Segment ? std::uint16_t(0) : edge;
}

}  // namespace pge
