#include "corner.hpp"

#include "contact.hpp"

#include <algorithm>
#include <vector>

namespace pge::oracle::detail {
namespace {

// The edges of a body that meet at vertex k (a segment has one edge, 0).
std::vector<int> edges_at(const BodyModel<Dyadic>& b, int k) {
  if (b.shape == ShapeKind::Segment) return {0};
  const int n = vertex_count(b);
  return {(k + n - 1) % n, k};
}

bool contains(const std::vector<int>& v, int x) { return std::find(v.begin(), v.end(), x) != v.end(); }

// The sign of f just after r: the sign of the first derivative of f not zero at r.
int sign_just_after(const Poly<Dyadic>& f, const RealRoot& r) {
  Poly<Dyadic> d = f;
  for (int k = 0; k <= f.deg; ++k) {
    const IntPoly p = to_int_poly(d);
    if (p.empty()) return 0;
    if (const int s = sign_at(p, r); s != 0) return s;
    d = derivative(d);
  }
  return 0;
}

}  // namespace

bool corner_enters(Frame& fr, FeatureCache& features, const Feature& ft, int end, const RealRoot& r) {
  const BodyIndex a_body = ft.point.body, b_body = ft.edge_body;
  const int v = ft.point.vertex;
  const int w = end == 0 ? ft.edge : next_vertex(fr.exact_body(b_body), ft.edge);
  const std::vector<int> at_w = edges_at(fr.exact_body(b_body), w), at_v = edges_at(fr.exact_body(a_body), v);
  for (const Feature& f : features.of(fr, std::min(a_body, b_body), std::max(a_body, b_body))) {
    if (!f.to_edge || f.point.vertex < 0) continue;
    const bool v_against_b = f.point.body == a_body && f.point.vertex == v && f.edge_body == b_body && contains(at_w, f.edge);
    const bool w_against_a = f.point.body == b_body && f.point.vertex == w && f.edge_body == a_body && contains(at_v, f.edge);
    if (!v_against_b && !w_against_a) continue;
    const ContactPolys<Dyadic> c = contact_polys<Dyadic>(f, fr);
    if (c.degenerate || sign_just_after(c.f, r) >= 0) return false;  // this line separates them
  }
  return true;
}

}  // namespace pge::oracle::detail
