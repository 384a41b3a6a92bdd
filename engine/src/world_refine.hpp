// World<T>::Impl, part of world_impl.hpp. Refinement: scheduled contacts near the top of the queue
// re-derived from the exact paths (refine.hpp), their times correctly rounded, and the sibling
// feature pairs that may touch first.
#pragma once

#include "world_impl.hpp"

namespace pge {

template <class T> inline auto World<T>::Impl::refined_time(const Scheduled<T>& s) const -> std::optional<T> {
  const refine::Path<T> a = path_of(bodies[s.lo]), b = path_of(bodies[s.hi]);
  refine::ContactSigner<T> sign(a, b, s);
  if (const std::optional<T> t = sign.rounded_crossing(s.time, now)) return t;
  return refine::correctly_rounded_crossing(s.time, now, sign);
}

template <class T>
inline auto World<T>::Impl::feature_pair(BodyIndex lo, BodyIndex hi, ContactKind kind, std::uint16_t fa,
    std::uint16_t fb)
    -> Scheduled<T> {
  Scheduled<T> s;
  s.lo = lo;
  s.hi = hi;
  s.contact = kind;
  s.feature_a = fa;
  s.feature_b = fb;
  return s;
}

template <class T>
inline auto World<T>::Impl::line_graze(BodyIndex lo, BodyIndex hi, ContactKind kind, std::uint16_t fa, std::uint16_t fb,
    T& tau)
    -> GrazeVerdict {
  ++counts.exact_predictions;
  Scheduled<T> s = feature_pair(lo, hi, kind, fa, fb);
  const GrazeVerdict g = refine::exact_line_graze(exact_of(bodies[lo]), exact_of(bodies[hi]), s, refine::Exact::of(now));
  if (g != GrazeVerdict::Crosses) return g;
  s.time = T(now + tau);
  if (const std::optional<T> t = refined_time(s)) tau = *t - now;
  return g;
}

template <class T>
inline auto World<T>::Impl::crossing_place(BodyIndex lo, BodyIndex hi, ContactKind kind, std::uint16_t fa,
    std::uint16_t fb, const T& tau)
    -> EdgePlace {
  ++counts.exact_predictions;
  Scheduled<T> s = feature_pair(lo, hi, kind, fa, fb);
  s.time = T(now + tau);
  const std::optional<T> t = refined_time(s);
  if (!t || *t < now) return EdgePlace::Unknown;
  s.time = *t;
  return crossing_place(exact_of(bodies[lo]), exact_of(bodies[hi]), s);
}

template <class T>
inline auto World<T>::Impl::crossing_place(const refine::ExactBody<T>& a, const refine::ExactBody<T>& b,
    const Scheduled<T>& r) const
    -> EdgePlace {
  const T before = std::max(now, T(boost::math::float_prior(r.time)));
  const T after = boost::math::float_next(r.time);
  return refine::exact_place_at_crossing(a, b, r, refine::Exact::of(now), refine::Exact::of(before),
                                         refine::Exact::of(after));
}

template <class T>
inline auto World<T>::Impl::exact_overlap_pairs(BodyIndex lo, BodyIndex hi) -> std::optional<OverlapPairs> {
  ++counts.exact_predictions;
  const refine::ExactBody<T> a = exact_of(bodies[lo]), b = exact_of(bodies[hi]);
  const refine::Exact t_now = refine::Exact::of(now);
  std::optional<OverlapPairs> out = refine::exact_overlap_pairs(a, b, t_now);
  if (!out) return out;
  for (std::size_t i = 0; i < out->count; ++i) {
    OverlapPairs::Pair& x = out->pairs[i];
    const bool vertex_of_a = x.side == 0;
    const Scheduled<T> s = feature_pair(lo, hi, vertex_of_a ? ContactKind::VertexEdge : ContactKind::EdgeVertex,
                                        vertex_of_a ? x.k : x.j, vertex_of_a ? x.j : x.k);
    const std::optional<detail::exact::IntPoly> poly = refine::exact_feature_poly(a, b, s, t_now);
    x.approaching =
        poly && detail::exact::sign_just_after(detail::exact::derivative(*poly), detail::exact::Dyadic{}) < 0;
  }
  return out;
}

template <class T> inline auto World<T>::Impl::rounding_reach(const Body& a, const Body& b, const T& scale) const -> T {
  using std::abs;
  const auto travel = [&](const Body& x) {
    if (x.fixed) return T(0);
    const T tau = abs(now - x.t0);
    return (abs(x.v0.x) + abs(x.v0.y) + (abs(x.acc.x) + abs(x.acc.y)) * tau) * tau;
  };
  return scale + travel(a) + travel(b);
}

template <class T>
inline auto World<T>::Impl::refined_turn(const detail::exact::IntPoly& poly, const T& predicted) const
    -> std::optional<T> {
  struct SlopeSign {
    detail::exact::IntPoly slope;
    refine::Exact now;
    int exact(const refine::Exact& t) const { return detail::exact::sign_at(slope, (t - now).d); }
    int operator()(const T& t, const T& dt = T(0)) const {
      return exact(dt == T(0) ? refine::Exact::of(t) : refine::Exact::of(t) + refine::Exact::of(dt));
    }
  };
  SlopeSign sign{detail::exact::derivative(poly), refine::Exact::of(now)};
  return refine::correctly_rounded_crossing(predicted, now, sign);
}

template <class T>
inline auto World<T>::Impl::concave_turn(const detail::exact::IntPoly& poly, const T& hint) const -> std::optional<T> {
  using refine::Exact;
  const Exact t_now = Exact::of(now);
  if (poly.degree < 2 || !(poly.c[0] < 0) || !(poly.c[1] > 0)) return std::nullopt;
  const std::optional<T> m = refined_turn(poly, std::max(hint, now));
  if (!m || !(*m >= now)) return std::nullopt;
  const T after = boost::math::float_next(*m);
  const Exact tau1 = Exact::of(after) - t_now;
  if (detail::exact::sign_at(detail::exact::derivative(poly), tau1.d) > 0) return std::nullopt;
  const auto coefficient = [&](int k) { return Exact(refine::Dyadic{poly.c[k], 0}); };
  const auto magnitude = [&](int k) { return Exact(refine::Dyadic{poly.c[k] < 0 ? -poly.c[k] : poly.c[k], 0}); };
  // P''(tau) <= 2 c2 + 6 |c3| tau1 + 12 |c4| tau1^2 on [0, tau1].
  Exact curvature = Exact(2) * coefficient(2);
  Exact power = tau1;
  for (int k = 3; k <= poly.degree; ++k) {
    curvature = curvature + Exact(k * (k - 1)) * magnitude(k) * power;
    power = power * tau1;
  }
  if (curvature.sign() >= 0) return std::nullopt;
  if ((coefficient(0) + coefficient(1) * tau1).sign() >= 0) return std::nullopt;
  return m;
}

template <class T> inline auto World<T>::Impl::exact_contact(Scheduled<T>& r, const T& hint) -> Exactly {
  const refine::Exact t_now = refine::Exact::of(now);
  const std::optional<detail::exact::IntPoly> poly =
      refine::exact_feature_poly(exact_of(bodies[r.lo]), exact_of(bodies[r.hi]), r, t_now);
  if (!poly) return Exactly::Unknown;
  Scheduled<T> out = r;
  if (const std::optional<T> t = concave_turn(*poly, hint)) {
    out.at_start_overlap = true;
    out.time = *t;
  } else {
    ++counts.exact_predictions;
    const std::optional<ExactRoot> c = exact_first_contact(*poly);
    if (!c) return Exactly::None;
    out.at_start_overlap = c->overlap;
    out.time = c->time;
    if (c->time > now) {
      // A crossing, or a turn, overlapping or exactly touching (a double root of the contact
      // function: no crossing to find); a turn's time is its derivative's crossing.
      const std::optional<T> u = c->turn ? refined_turn(*poly, c->time) : refined_time(out);
      if (u) out.time = std::max(now, *u);
    }
  }
  if (!on_feature(out)) return Exactly::Unknown;
  r = out;
  return Exactly::Contact;
}

template <class T>
inline auto World<T>::Impl::may_touch_first(const OutlineView<T>& o, std::size_t k, std::size_t j, const Vec2<T>& d0,
    const Poly<T>& p, const T& window, const T& reach, const T& scale)
    -> bool {
  using std::abs;
  const Vec2<T>& e = o.Q.edges[j];
  const T rounding = T(kSiblingRoundingUlps) * std::numeric_limits<T>::epsilon() *
                     (cross_magnitude(d0, o.dv, o.da, window, e) + reach * (abs(e.x) + abs(e.y)));
  T least = std::min(p(T(0)), p(window)), most = std::max(p(T(0)), p(window));
  const bool turns = p.c[2] != T(0);
  const T extremum = turns ? -p.c[1] / (T(2) * p.c[2]) : T(0);
  if (turns && extremum > T(0) && extremum < window) {
    least = std::min(least, p(extremum));
    most = std::max(most, p(extremum));
    if (abs(p(extremum)) <= rounding) return true;
  }
  if (least > rounding || most < -rounding) return false;
  if (abs(p(T(0))) <= rounding) return true;
  // A root within the corner slack of an end is one the exact paths may put on the edge where
  // the rounded corner rule rejects it (judge_root asks them there: crossing_place): a
  // triangle's corner meeting a segment's end in float, its vertex's exact crossing 1.6e-7 of
  // the segment inside the end and 8e-8 s before the segment's end met the triangle's edge,
  // while the rounded rule took the end's contact (scripts/edge-end-sweep.py seed 2, end-029).
  const auto near_end = [&](const T& t) {
    const Vec2<T> d = d0 + o.dv * t + o.da * (t * t / T(2));
    const EdgeSpot spot = locate_on_edge(d, o.dv + o.da * t, e, o.Q.edge_length[j], scale);
    return spot == EdgeSpot::Start || spot == EdgeSpot::End;
  };
  bool found = false;
  visit_downward_roots(SolverKind::Robust, p, T(0), window + window, StartRule::CrossingsOnly, [&](const T& t, bool) {
    const T slope = abs(p.c[1] + T(2) * p.c[2] * t);
    if (!(slope > T(0)) || t - rounding / slope <= window) found = near_end(t) || judge_root(o, k, j, d0, t, false, scale).has_value();
    return found;
  });
  return found;
}

template <class T> inline auto World<T>::Impl::earlier_outline_contact(Scheduled<T>& r) -> void {
  using std::abs;
  if (r.contact != ContactKind::VertexEdge && r.contact != ContactKind::EdgeVertex) return;
  if (!(r.time > now)) return;
  const Body& a = bodies[r.lo];
  const Body& b = bodies[r.hi];
  const Kinematics<T> ka = kinematics(a, now), kb = kinematics(b, now);
  const OutlineView<T> views[2] = {view_of(a.shape, ka, b.shape, kb), view_of(b.shape, kb, a.shape, ka)};
  const T window = r.time - now;
  // What the rounded functions' coefficients are relative to (rounding_reach).
  const T scale = pair_scale(a.shape, ka.p, b.shape, kb.p);
  const T reach = rounding_reach(a, b, scale);
  std::optional<refine::ExactBody<T>> ea, eb;
  const refine::Exact t_now = refine::Exact::of(now);
  const LineGrazes exact_judge(*this, r.lo, r.hi);
  for (int side = 0; side < 2; ++side) {
    const OutlineView<T>& o = views[side];
    const ContactKind kind = side == 0 ? ContactKind::VertexEdge : ContactKind::EdgeVertex;
    for (std::size_t j = 0; j < o.Q.vertex_count(); ++j) {
      for (std::size_t k = 0; k < o.P.vertex_count(); ++k) {
        const std::uint16_t fa = feature_index(side == 0 ? k : j), fb = feature_index(side == 0 ? j : k);
        if (kind == r.contact && fa == r.feature_a && fb == r.feature_b) continue;
        if (!extreme_towards(o, k, j)) continue;
        const Vec2<T> d0 = o.offset(k, j);
        if (!may_touch_first(o, k, j, d0, vertex_edge_poly(o, d0, j), window, reach, scale)) continue;
        if (!ea) {
          ea = exact_of(a);
          eb = exact_of(b);
        }
        Scheduled<T> c = r;
        c.contact = kind;
        c.feature_a = fa;
        c.feature_b = fb;
        c.at_start_overlap = false;
        c.corner = false;
        const std::optional<detail::exact::IntPoly> poly = refine::exact_feature_poly(*ea, *eb, c, t_now);
        if (!poly) continue;
        ++counts.exact_predictions;
        const std::optional<ExactRoot> root = exact_first_contact(*poly);
        // An overlap at now is the overlap rule's (least_penetration), not a sibling's; a
        // turn (overlapping by rounding, receding, turning back) is the turning-overlap
        // rule's contact at its correctly rounded turning point.
        if (!root || (root->overlap && !root->turn) || !(root->time <= r.time)) continue;
        const std::optional<VertexEdgeHit<T>> hit =
            judge_root(o, k, j, d0, root->time - now, root->turn, scale, &exact_judge, kind, fa, fb);
        if (!hit) continue;
        c.time = root->time;
        c.at_start_overlap = root->turn;
        if (root->time > now) {
          const std::optional<T> t = root->turn ? refined_turn(*poly, root->time) : refined_time(c);
          if (t) c.time = std::max(now, *t);
        }
        c.corner = hit->corner;
        // Beyond the edge's end exactly: the rounded rule's corner slack took it (see
        // off_feature_contact).
        if (c.time < r.time && !off_edge(crossing_place(*ea, *eb, c))) r = c;
      }
    }
  }
}

template <class T> inline auto World<T>::Impl::near_edge_end(const Scheduled<T>& r) const -> bool {
  using std::abs;
  const Body& a = bodies[r.lo];
  const Body& b = bodies[r.hi];
  const Kinematics<T> ka = kinematics(a, r.time), kb = kinematics(b, r.time);
  const bool vertex = r.contact == ContactKind::VertexEdge || r.contact == ContactKind::EdgeVertex;
  const bool a_edge = vertex ? r.contact == ContactKind::EdgeVertex : a.shape.kind != ShapeKind::Circle;
  const Body& eb = a_edge ? a : b;
  const Body& pb = a_edge ? b : a;
  const Kinematics<T>& ke = a_edge ? ka : kb;
  const Kinematics<T>& kp = a_edge ? kb : ka;
  const std::size_t f = a_edge ? r.feature_a : r.feature_b;  // the edge (or vertex) feature
  const Vec2<T> point = vertex ? pb.shape.vertex(kp.p, a_edge ? r.feature_b : r.feature_a) : kp.p;
  const Vec2<T> dv = kp.v - ke.v;
  const T window = refine_bound(r.time) - r.time + T(2) * std::numeric_limits<T>::epsilon() * abs(r.time);
  const auto l1 = [](const Vec2<T>& v) { return abs(v.x) + abs(v.y); };
  // Within the bound of 0 or of e.e, for the projection on edge j relative to the edge's start.
  const auto near = [&](std::size_t j, bool start_only, bool end_only) {
    const Vec2<T> start = eb.shape.vertex(ke.p, j);
    const Vec2<T>& e = eb.shape.edges[j];
    const T along = dot(point - start, e), ee = dot(e, e);
    const T bound = T(kSiblingRoundingUlps) * std::numeric_limits<T>::epsilon() * (l1(point) + l1(start)) * l1(e) +
                    l1(dv) * l1(e) * window;
    return (!end_only && abs(along) <= bound) || (!start_only && abs(along - ee) <= bound);
  };
  if (r.contact != ContactKind::CircleVertex) return near(f, false, false);
  if (eb.shape.kind == ShapeKind::Segment) return near(0, f == 0, f == 1);
  const std::size_t n = eb.shape.vertex_count();
  return near((f + n - 1) % n, false, true) || near(f, true, false);
}

template <class T> inline auto World<T>::Impl::off_feature_contact(Scheduled<T>& r) -> void {
  if (r.contact == ContactKind::CircleCircle || !near_edge_end(r)) return;
  if (r.contact == ContactKind::CircleVertex) {
    earlier_circle_edge_contact(r);
    return;
  }
  const refine::ExactBody<T> a = exact_of(bodies[r.lo]), b = exact_of(bodies[r.hi]);
  const EdgePlace place = crossing_place(a, b, r);
  if (!off_edge(place)) return;
  ++counts.exact_predictions;
  Scheduled<T> sibling = r;
  sibling.time = refine_bound(r.time);
  if (r.contact == ContactKind::CircleEdge) {
    const bool a_circle = bodies[r.lo].shape.kind == ShapeKind::Circle;
    const BodyShape<T>& outline = (a_circle ? bodies[r.hi] : bodies[r.lo]).shape;
    const std::size_t j = a_circle ? r.feature_b : r.feature_a;
    const std::uint16_t end = feature_index(place == EdgePlace::Before ? j : (j + 1) % outline.vertex_count());
    sibling.contact = ContactKind::CircleVertex;
    (a_circle ? sibling.feature_b : sibling.feature_a) = end;
    sibling.at_start_overlap = false;
    sibling.corner = false;
    const std::optional<detail::exact::IntPoly> poly = refine::exact_feature_poly(a, b, sibling, refine::Exact::of(now));
    const std::optional<ExactRoot> root = poly ? exact_first_contact(*poly) : std::nullopt;
    if (!root || root->overlap || !(root->time <= sibling.time)) return;
    sibling.time = root->time;
    if (root->time > now) {
      if (const std::optional<T> t = refined_time(sibling)) sibling.time = std::max(now, *t);
    }
    r = sibling;
    return;
  }
  earlier_outline_contact(sibling);
  if (sibling.time < refine_bound(r.time)) r = sibling;
}

template <class T> inline auto World<T>::Impl::earlier_circle_edge_contact(Scheduled<T>& r) -> void {
  const bool a_circle = bodies[r.lo].shape.kind == ShapeKind::Circle;
  const BodyShape<T>& outline = (a_circle ? bodies[r.hi] : bodies[r.lo]).shape;
  const std::size_t k = a_circle ? r.feature_b : r.feature_a;
  const std::size_t n = outline.vertex_count();
  const refine::ExactBody<T> a = exact_of(bodies[r.lo]), b = exact_of(bodies[r.hi]);
  const refine::Exact t_now = refine::Exact::of(now);
  // A segment's one edge (feature 0) ends at both vertices; a polygon's vertex k ends edge
  // k - 1 and starts edge k.
  const std::size_t edges[2] = {outline.kind == ShapeKind::Segment ? 0 : (k + n - 1) % n,
                                outline.kind == ShapeKind::Segment ? 0 : k};
  for (int i = 0; i < (outline.kind == ShapeKind::Segment ? 1 : 2); ++i) {
    Scheduled<T> c = r;
    c.contact = ContactKind::CircleEdge;
    (a_circle ? c.feature_b : c.feature_a) = feature_index(edges[i]);
    c.at_start_overlap = false;
    c.corner = false;
    const std::optional<detail::exact::IntPoly> poly = refine::exact_feature_poly(a, b, c, t_now);
    if (!poly) continue;
    ++counts.exact_predictions;
    const std::optional<ExactRoot> root = exact_first_contact(*poly);
    if (!root || root->overlap || !(root->time > now) || !(root->time <= r.time)) continue;
    c.time = root->time;
    const std::optional<T> t = refined_time(c);
    if (!t || !(*t > now) || !(*t < r.time)) continue;
    c.time = *t;
    if (crossing_place(a, b, c) == EdgePlace::On) r = c;
  }
}

template <class T> inline auto World<T>::Impl::on_feature(const Scheduled<T>& s) const -> bool {
  if (s.contact == ContactKind::CircleCircle || s.contact == ContactKind::CircleVertex) return true;
  const Body& a = bodies[s.lo];
  const Body& b = bodies[s.hi];
  const Kinematics<T> ka = kinematics(a, s.time), kb = kinematics(b, s.time);
  const bool a_edge = s.contact == ContactKind::EdgeVertex ||
                      (s.contact == ContactKind::CircleEdge && a.shape.kind != ShapeKind::Circle);
  const Body& eb = a_edge ? a : b;
  const Body& pb = a_edge ? b : a;
  const Kinematics<T>& ke = a_edge ? ka : kb;
  const Kinematics<T>& kp = a_edge ? kb : ka;
  const std::size_t j = a_edge ? s.feature_a : s.feature_b;
  const Vec2<T> point = s.contact == ContactKind::CircleEdge
                            ? kp.p
                            : pb.shape.vertex(kp.p, a_edge ? s.feature_b : s.feature_a);
  const Vec2<T> e = eb.shape.edges[j];
  const T along = dot(point - eb.shape.vertex(ke.p, j), e);
  return along >= T(0) && along <= dot(e, e);
}

template <class T> inline auto World<T>::Impl::refine_bound(const T& t) -> T {
  using std::abs;
  static const T relative =
      std::max(T(kRefineWindowRelative), T(kRefineWindowUlps) * std::numeric_limits<T>::epsilon());
  return t + relative * std::max(T(1), abs(t));
}

template <class T> inline auto World<T>::Impl::refine_near_top() -> bool {
  const T bound = refine_bound(heap.top().time);
  std::vector<BodyIndex>& owners = refine_owners;
  owners.clear();
  heap.visit_up_to(bound, [&](BodyIndex i) {
    if (!heap.at(i).refined) owners.push_back(i);
  });
  for (BodyIndex i : owners) {
    const Scheduled<T> s = heap.at(i);
    const Body& partner = bodies[s.partner];
    if (!partner.fixed && partner.version != s.partner_version) {
      ++counts.stale;
      reschedule(i);
      continue;
    }
    Scheduled<T> r = s;
    r.refined = true;
    // A contact the rounded state may have misjudged: the exact paths do not cross near the
    // predicted time, or already touch at `now` (where only an approaching pair collides:
    // the rounded state may have invented the contact, a pair left overlapping by one
    // rounding and receding exactly), or the contact is the turning-overlap rule's, a
    // turning point of the rounded prediction (whose sign there, and so whether the pair
    // separates first, is the rounding's call). It is decided again from the exact
    // polynomial of its feature pair, both overlap rules included (exact_contact); two
    // circles that never touch are excluded, and the owner's next contact is scheduled
    // instead. What exact_contact leaves undecided keeps the rounded decision, and so does a
    // feature pair that never touches (its bodies may still meet at another feature).
    const bool turn = s.at_start_overlap && s.time > now;
    bool again = turn;
    if (!turn) {
      const std::optional<T> t = refined_time(s);
      if (t && *t > now) {
        r.time = *t;
        off_feature_contact(r);
      } else {
        if (t) r.time = now;
        again = true;
      }
    }
    const Exactly decided = again ? exact_contact(r, s.time) : Exactly::Contact;
    if (decided == Exactly::None && s.contact == ContactKind::CircleCircle) {
      Body& x = bodies[i];
      const Body& y = bodies[s.partner];
      x.no_contact_with = s.partner;
      x.no_contact_version = x.version;
      x.no_contact_partner_version = y.version;
      reschedule(i);
      continue;
    }
    // A crossing that rounds to now with its point off the feature (exact_contact leaves it
    // Unknown): beyond an edge's end exactly, the earliest sibling within the refinement's
    // window replaces it, as for a crossing after now. (A triangle's corner meeting a
    // segment's end in float: after the impulse at the edge whose end it is, the segment's
    // end crossed the corner's other edge's line 0.1 ulp after now, 1.3e-7 of the edge before
    // its start, and the rounded corner rule collided it at once; the triangle's vertex met
    // the segment 1.4 ulps later. scripts/edge-end-sweep.py seed 2, end-290.)
    if (decided == Exactly::Unknown && !turn) off_feature_contact(r);
    earlier_outline_contact(r);
    heap.set(i, r);
  }
  return !owners.empty();
}

template <class T> inline auto World<T>::Impl::collides_at_horizon(const Scheduled<T>& s) -> bool {
  if (s.contact == ContactKind::CircleCircle && solver != SolverKind::Fast) {
    const refine::Exact t_now = refine::Exact::of(now);
    const detail::exact::IntPoly poly = refine::exact_circle_poly(exact_of(bodies[s.lo]), exact_of(bodies[s.hi]), t_now);
    const detail::exact::Dyadic tau = (refine::Exact::of(horizon) - t_now).d;
    const int at = detail::exact::sign_at(poly, tau);
    return at < 0 || (at == 0 && detail::exact::sign_just_after(poly, tau) < 0);
  }
  return approaching(s);
}

}  // namespace pge
