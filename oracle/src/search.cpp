#include "search.hpp"

#include "corner.hpp"
#include "overlap_rule.hpp"

#include <algorithm>

namespace pge::oracle::detail {
namespace {

bool any_feature_may_touch(Frame& fr, FeatureCache& features, BodyPair p, const Interval& tau) {
  for (const Feature& ft : features.of(fr, p.first, p.second))
    if (may_touch(contact_polys<Interval>(ft, fr), tau)) return true;
  return false;
}

}  // namespace

std::optional<PairResult> pair_contact(Frame& fr, FeatureCache& features, BodyIndex a, BodyIndex b,
                                       const Dyadic& tau_hi, const Interval& window, bool filter, SearchCounters& n) {
  std::optional<PairResult> best;
  for (const Feature& ft : features.of(fr, a, b)) {
    if (filter && !may_touch(contact_polys<Interval>(ft, fr), window)) continue;
    ++n.features_exact;
    const bool vertex_edge = ft.to_edge && ft.point.vertex >= 0;
    const auto overlap_ok = [&] { return !vertex_edge || overlap_rule_applies(fr, ft); };
    const auto corner_ok = [&](const RealRoot& r, int end) { return corner_enters(fr, features, ft, end, r); };
    const std::optional<Contact> c = earliest_contact(contact_polys<Dyadic>(ft, fr), tau_hi, overlap_ok, corner_ok);
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
// of the edge of s that i lies in front of and moves along (velocity and acceleration parallel
// to it), running the same way (the same outward side), all exactly. i then slides along one surface from s
// onto j: floor tiles, boxes side by side. The engine skips the same pairs
// (World::continues_support).
static bool flush_with_support(const Frame& fr, BodyIndex i, BodyIndex j) {
  const BodyModel<Dyadic>& m = fr.exact_body(i);
  const BodyModel<Dyadic>& b = fr.exact_body(j);
  if (m.fixed || !b.fixed || b.shape == ShapeKind::Circle) return false;
  for (const BodyIndex s : m.supports) {
    if (s == kNoBody || s == j) continue;
    const BodyModel<Dyadic>& f = fr.exact_body(s);
    if (f.shape == ShapeKind::Circle) continue;
    for (int k = 0; k < vertex_count(f); ++k) {
      const V2<Dyadic>& a = f.world[static_cast<std::size_t>(k)];
      const V2<Dyadic> e = edge_vector(f, k);
      // The face i rests on: i in front of it (outlines run counter-clockwise, a segment both
      // ways), moving along it.
      if (cross(m.p0 - a, e).sign() <= 0 || !cross(m.v0, e).is_zero() || !cross(m.acc, e).is_zero()) continue;
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
    if (p != skip && !resting_pair(fr, p.first, p.second) && (!filter || any_feature_may_touch(fr, features, p, tau)))
      out.push_back(p);
  if (filter) n.pairs_filtered += examined - out.size();
  return out;
}

}  // namespace pge::oracle::detail
