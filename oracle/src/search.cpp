#include "search.hpp"

#include "corner.hpp"
#include "overlap_rule.hpp"
#include "rotating.hpp"

#include <algorithm>

namespace pge::oracle::detail {
namespace {

bool any_feature_may_touch(Frame& fr, FeatureCache& features, BodyPair p, const Interval& tau, const Dyadic& tau_hi) {
  if (rotating_pair(fr, p.first, p.second)) return rotating_may_touch(fr, p.first, p.second, tau_hi);
  for (const Feature& ft : features.of(fr, p.first, p.second))
    if (may_touch(contact_polys<Interval>(ft, fr), tau)) return true;
  return false;
}

}  // namespace

std::optional<PairResult> pair_contact(Frame& fr, FeatureCache& features, BodyIndex a, BodyIndex b,
                                       const Dyadic& tau_hi, const Interval& window, bool filter, SearchCounters& n) {
  if (rotating_pair(fr, a, b)) return rotating_pair_contact(fr, a, b, tau_hi, n);
  std::optional<PairResult> best;
  for (const Feature& ft : features.of(fr, a, b)) {
    if (filter && !may_touch(contact_polys<Interval>(ft, fr), window)) continue;
    ++n.features_exact;
    const bool vertex_edge = ft.to_edge && ft.point.vertex >= 0;
    const auto overlap_ok = [&] { return !vertex_edge || overlap_rule_applies(fr, ft); };
    const auto corner_ok = [&](const RealRoot& r, int end) { return corner_enters(fr, features, ft, end, r); };
    const std::optional<Contact> c = earliest_contact(exact_contact_polys(ft, fr), tau_hi, overlap_ok, corner_ok);
    if (!c) continue;
    const int order = best ? compare(*c->tau, *best->tau) : -1;
    if (order < 0) {
      best = PairResult{c->tau, c->overlap_rule, {ft.id}};
    } else if (order == 0) {
      best->features.push_back(ft.id);
      best->overlap_rule = best->overlap_rule || c->overlap_rule;
    }
  }
  return best;
}

// Whether fixed body j is flush with a support s of the resting body i: an edge of j on the line
// of the face of s that i rests on, running the same way (the same outward side), exactly. i
// then slides along one surface from s onto j: floor tiles, boxes side by side. The engine skips
// the same pairs (World::continues_support). The face is the edge of s that i lies in front of
// (outlines run counter-clockwise, a segment both ways) and whose direction is nearest to i's
// motion (its acceleration, or without one its velocity; at rest, any edge it is in front of),
// decided exactly. The motion need not be exactly parallel to it: a resting body moves along its
// face within the rounding of its state (the engine projects the field's acceleration onto the
// face in its scalar), and touches it all along, which is no event; by the same token it touches
// the flush continuation of that face, and its path, an ulp inside the line, meets j's end a
// rounding's worth before the joint (a ball placed on two collinear tilted tiles at decimal
// coordinates, in long double: scripts/tilted-tiles-sweep.py, and
// fixtures/regressions/ball-slides-across-a-tilted-tile-joint.json).
static bool flush_with_support(const Frame& fr, BodyIndex i, BodyIndex j) {
  const BodyModel<Dyadic>& m = fr.exact_body(i);
  const BodyModel<Dyadic>& b = fr.exact_body(j);
  if (m.fixed || !b.fixed || b.shape == ShapeKind::Circle || b.rotates) return false;
  const V2<Dyadic>& w = !m.acc.x.is_zero() || !m.acc.y.is_zero() ? m.acc : m.v0;
  for (const BodyIndex s : m.supports) {
    if (s == kNoBody || s == j) continue;
    const BodyModel<Dyadic>& f = fr.exact_body(s);
    if (f.shape == ShapeKind::Circle || f.rotates) continue;
    // The faces i is in front of, and of those the nearest to w's direction: the largest
    // dot(w, e)^2 / |e|^2, compared cross-multiplied.
    std::vector<int> faces;
    Dyadic best_dot2, best_len2;
    for (int k = 0; k < vertex_count(f); ++k) {
      const V2<Dyadic> e = edge_vector(f, k);
      if (cross(m.p0 - f.world[static_cast<std::size_t>(k)], e).sign() <= 0) continue;
      const Dyadic d = dot(w, e);
      const Dyadic dot2 = d * d, len2 = dot(e, e);
      const int c = faces.empty() ? 1 : compare(dot2 * best_len2, best_dot2 * len2);
      if (c < 0) continue;
      if (c > 0) faces.clear();
      faces.push_back(k);
      best_dot2 = dot2;
      best_len2 = len2;
    }
    for (const int k : faces) {
      const V2<Dyadic>& a = f.world[static_cast<std::size_t>(k)];
      const V2<Dyadic> e = edge_vector(f, k);
      for (int l = 0; l < vertex_count(b); ++l) {
        const V2<Dyadic>& c = b.world[static_cast<std::size_t>(l)];
        const V2<Dyadic>& d = b.world[static_cast<std::size_t>(next_vertex(b, l))];
        if (cross(c - a, e).is_zero() && cross(d - a, e).is_zero() && dot(d - c, e).sign() > 0) return true;
      }
    }
  }
  return false;
}

// A body resting on a fixed face (ExactMotion::supports) touches it all along its path: a
// contact state, which has no events (DESIGN.md, resting contact); so does a body flush with that
// face, which the resting body meets only where the two join.
static bool resting_pair(const Frame& fr, BodyIndex i, BodyIndex j) {
  return fr.exact_body(i).rests_on(j) || fr.exact_body(j).rests_on(i) || flush_with_support(fr, i, j) ||
         flush_with_support(fr, j, i);
}

std::uint64_t pair_count(const Frame& fr) {
  std::uint64_t moving = 0, fixed = 0;
  for (BodyIndex i = 0; i < fr.size(); ++i) (fr.exact_body(i).fixed ? fixed : moving) += 1;
  return moving * (moving - (moving > 0 ? 1 : 0)) / 2 + moving * fixed;
}

std::vector<BodyPair> candidate_pairs(Frame& fr, FeatureCache& features, const Dyadic& tau_hi, bool filter,
                                      SpatialFilter* spatial, std::uint64_t total, BodyPair skip, SearchCounters& n) {
  const bool skip_is_pair = skip.first < skip.second && skip.second < fr.size() &&
                            !(fr.exact_body(skip.first).fixed && fr.exact_body(skip.second).fixed);
  const std::uint64_t examined = total - (skip_is_pair ? 1 : 0);
  n.pairs_examined += examined;
  std::vector<BodyPair> pairs;
  if (spatial && filter) {
    pairs = spatial->pairs_within(fr.now(), tau_hi);
  } else {
    for (BodyIndex i = 0; i < fr.size(); ++i)
      for (BodyIndex j = i + 1; j < fr.size(); ++j)
        if (!(fr.exact_body(i).fixed && fr.exact_body(j).fixed)) pairs.push_back({i, j});
  }
  const Interval tau(0.0, Interval::enclose(tau_hi).hi());
  std::vector<BodyPair> out;
  for (const BodyPair& p : pairs)
    if (p != skip && !resting_pair(fr, p.first, p.second) && (!filter || any_feature_may_touch(fr, features, p, tau, tau_hi)))
      out.push_back(p);
  if (filter) n.pairs_filtered += examined - out.size();
  return out;
}

}  // namespace pge::oracle::detail
