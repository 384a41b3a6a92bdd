// The feature pairs of two bodies (DESIGN.md, "What an event is"), named by event.hpp's
// conventions, and their contact functions in either number type.
#pragma once

#include "model.hpp"
#include "pge/oracle.hpp"

#include <cstdint>
#include <unordered_map>
#include <vector>

namespace pge::oracle::detail {

struct PointRef {
  BodyIndex body = kNoBody;
  int vertex = -1;  // -1: the circle's centre
};

struct Feature {
  FeaturePair id;    // as reported for the pair (a, b), a < b
  PointRef point;    // a circle's centre (with its radius) or a vertex (radius 0)
  bool to_edge = false;
  PointRef other;    // point against point: the other centre or vertex
  BodyIndex edge_body = kNoBody;  // point against edge: the edge from vertex `edge` to the next
  int edge = 0;
  bool one_sided = false;  // polygon edges: touched from outside only
  // Vertex against edge: the side of the edge line the vertex's body lies on (+1: along the
  // normal (e.y, -e.x)); 0: a segment parallel to the edge, decided by where it is at tau = 0.
  int sigma = 1;
};

// Every feature pair of bodies a < b that can be the first contact between them. A vertex
// against an edge is listed only when the vertex is extreme towards the edge (its body lies
// wholly on one side of the line through it parallel to the edge): any other vertex can reach
// the edge line only after another feature of its body has touched.
std::vector<Feature> pair_features(const Frame& frame, BodyIndex a, BodyIndex b);

// Feature lists depend only on the bodies' shapes (constant in time), and deriving them takes
// exact arithmetic: they are derived once per body pair and kept.
class FeatureCache {
 public:
  const std::vector<Feature>& of(const Frame& frame, BodyIndex a, BodyIndex b);

 private:
  std::unordered_map<std::uint64_t, std::vector<Feature>> lists_;
};

// A contact function and the conditions for a root of it to be a contact on the feature.
template <class N> struct ContactPolys {
  Poly<N> f;                  // > 0 apart, 0 touching, < 0 overlapping (up to a positive factor)
  bool on_edge = false;       // edge interior: the projection (P - A).e must lie in [0, e.e]
  Poly<N> projection;         // (P - A) . e
  N length2{};                // e . e
  bool needs_outside = false; // circle against a one-sided edge: cross(P - A, e) > 0
  Poly<N> side;               // cross(P - A, e): e.e times the signed distance along the normal
  bool undecided = false;     // (interval) sigma could not be fixed: the filter cannot discard
  bool degenerate = false;    // (exact) a point sliding along the edge line: never a contact
  bool vertex_point = false;  // a vertex against an edge: meeting the edge's end is a corner
};

// Point against point: |Q - P|^2 - reach^2.
template <class N> ContactPolys<N> point_point(const PointPath<N>& p, const PointPath<N>& q, const N& reach) {
  ContactPolys<N> c;
  const PointPath<N> d = q - p;
  c.f = d.x * d.x + d.y * d.y - Poly<N>::constant(reach * reach);
  return c;
}

template <class N> int sign_for_sigma(const N& s0);
template <> inline int sign_for_sigma(const Dyadic& s0) { return s0.sign(); }
template <> inline int sign_for_sigma(const Interval& s0) {
  return s0.certainly_positive() ? 1 : (s0.certainly_negative() ? -1 : 0);
}

// Point P (radius r, 0 for a vertex) against the edge line through A with direction e. With
// s = cross(P - A, e) (|e| times the signed distance along the normal (e.y, -e.x)):
//   circle: s^2 - r^2 e.e, zero where the distance is r on either side; a one-sided edge also
//           needs s > 0 (s^2 - r^2 e.e has the sign of s - r|e| there, and its roots with s < 0
//           belong to the far side of the line);
//   vertex: sigma s, the distance measured from the side the vertex's body lies on.
template <class N>
ContactPolys<N> point_edge(const PointPath<N>& p, const PointPath<N>& a, const V2<N>& e, const N* radius,
                           bool one_sided, int sigma) {
  ContactPolys<N> c;
  const PointPath<N> d = p - a;
  c.side = d.x * Poly<N>::constant(e.y) - d.y * Poly<N>::constant(e.x);
  c.projection = d.x * Poly<N>::constant(e.x) + d.y * Poly<N>::constant(e.y);
  c.length2 = dot(e, e);
  c.on_edge = true;
  if (radius) {
    c.f = c.side * c.side - Poly<N>::constant((*radius) * (*radius) * c.length2);
    c.needs_outside = one_sided;
    return c;
  }
  c.vertex_point = true;
  if (sigma == 0) {
    sigma = sign_for_sigma(c.side.c[0]);
    if (sigma == 0) {
      c.undecided = true;  // interval: unknown side; exact: on the line, sliding along it
      c.degenerate = true;
      return c;
    }
  }
  c.f = c.side * N(sigma);
  return c;
}

template <class N> ContactPolys<N> contact_polys(const Feature& ft, Frame& frame) {
  std::optional<PointPath<N>> p_store, q_store;
  const PointPath<N>& p = point_ref<N>(frame, ft.point.body, ft.point.vertex, p_store);
  const BodyModel<N>& pb = frame.body<N>(ft.point.body);
  if (!ft.to_edge) {
    const BodyModel<N>& qb = frame.body<N>(ft.other.body);
    const N rp = ft.point.vertex < 0 ? pb.radius : N{};
    const N rq = ft.other.vertex < 0 ? qb.radius : N{};
    return point_point(p, point_ref<N>(frame, ft.other.body, ft.other.vertex, q_store), rp + rq);
  }
  const BodyModel<N>& eb = frame.body<N>(ft.edge_body);
  const PointPath<N> a = point_of<N>(frame, ft.edge_body, ft.edge);
  const N* radius = ft.point.vertex < 0 ? &pb.radius : nullptr;
  return point_edge(p, a, edge_vector(eb, ft.edge), radius, ft.one_sided, ft.sigma);
}

// contact_polys<Dyadic>(ft, frame), kept in the frame for `ft` (a feature of a FeatureCache
// list: its address names it for the frame's life).
inline const ContactPolys<Dyadic>& exact_contact_polys(const Feature& ft, Frame& frame) {
  std::shared_ptr<const void>& slot = frame.polys_slot(&ft);
  if (!slot) slot = std::make_shared<const ContactPolys<Dyadic>>(contact_polys<Dyadic>(ft, frame));
  return *static_cast<const ContactPolys<Dyadic>*>(slot.get());
}

}  // namespace pge::oracle::detail
