#include "overlap_rule.hpp"

#include <vector>

namespace pge::oracle::detail {
namespace {

struct Axis {
  BodyIndex edge_body;
  int edge;
  int sigma;
  Dyadic depth;    // min over the other body's vertices of sigma * cross(u - A, e): <= 0 if they meet
  Dyadic length2;  // e . e: the separation along the axis is depth / |e|
};

std::vector<V2<Dyadic>> vertices_now(Frame& fr, BodyIndex i) {
  const BodyModel<Dyadic>& b = fr.exact_body(i);
  std::vector<V2<Dyadic>> out;
  for (int k = 0; k < vertex_count(b); ++k) {
    const PointPath<Dyadic> p = point_of<Dyadic>(fr, i, k);
    out.push_back({p.x.c[0], p.y.c[0]});
  }
  return out;
}

Dyadic side_of(const V2<Dyadic>& u, const V2<Dyadic>& a, const V2<Dyadic>& e, int sigma) {
  return cross(u - a, e) * Dyadic(sigma);
}

// The axes of body `eb`'s edges, measured against the vertices `others` of the other body.
void axes_of(Frame& fr, BodyIndex eb, const std::vector<V2<Dyadic>>& own, const std::vector<V2<Dyadic>>& others,
             std::vector<Axis>& out) {
  const BodyModel<Dyadic>& b = fr.exact_body(eb);
  const bool segment = b.shape == ShapeKind::Segment;
  const int edges = segment ? 1 : vertex_count(b);
  for (int k = 0; k < edges; ++k) {
    const V2<Dyadic> e = edge_vector(b, k);
    for (int sigma : {1, -1}) {
      if (sigma < 0 && !segment) continue;  // polygon edges face outward only
      Dyadic depth = side_of(others[0], own[static_cast<std::size_t>(k)], e, sigma);
      for (const V2<Dyadic>& u : others) {
        const Dyadic s = side_of(u, own[static_cast<std::size_t>(k)], e, sigma);
        if (compare(s, depth) < 0) depth = s;
      }
      out.push_back({eb, k, sigma, depth, dot(e, e)});
    }
  }
}

// Compares the separations depth/|e| of two axes whose depths are <= 0: -1 if a's is smaller
// (a deeper penetration), 1 if larger, 0 if equal. With d <= 0, d1/sqrt(l1) < d2/sqrt(l2) iff
// d1^2 l2 > d2^2 l1.
int compare_separation(const Axis& a, const Axis& b) {
  return -compare(a.depth * a.depth * b.length2, b.depth * b.depth * a.length2);
}

}  // namespace

bool overlap_rule_applies(Frame& fr, const Feature& ft) {
  const BodyIndex vb = ft.point.body, eb = ft.edge_body;
  const std::vector<V2<Dyadic>> vv = vertices_now(fr, vb), ev = vertices_now(fr, eb);
  std::vector<Axis> axes;
  axes_of(fr, eb, ev, vv, axes);
  axes_of(fr, vb, vv, ev, axes);
  const Axis* best = nullptr;
  for (const Axis& ax : axes) {
    if (ax.depth.sign() > 0) return false;  // a separating axis: the bodies do not meet
    if (!best || compare_separation(ax, *best) > 0) best = &ax;
  }
  const Axis* own = nullptr;
  for (const Axis& ax : axes)
    if (ax.edge_body == eb && ax.edge == ft.edge && ax.sigma == ft.sigma) own = &ax;
  if (!own || compare_separation(*own, *best) != 0) return false;
  // The feature's vertex must be one of the deepest along its axis.
  const V2<Dyadic> a = ev[static_cast<std::size_t>(ft.edge)];
  const V2<Dyadic> e = edge_vector(fr.exact_body(eb), ft.edge);
  return side_of(vv[static_cast<std::size_t>(ft.point.vertex)], a, e, ft.sigma) == own->depth;
}

}  // namespace pge::oracle::detail
