// World<T>::Impl, part of world_impl.hpp. Narrow phase: a pair's earliest contact from the rounded
// paths, with the exact paths asked where the rounding cannot decide (a graze of two circles, a
// line contact within rounding of a double root).
#pragma once

#include "world_impl.hpp"

namespace pge {

template <class T>
inline auto World<T>::Impl::predict(BodyIndex lo, BodyIndex hi, const T& limit) -> std::optional<PredictedContact<T>> {
  const Body& a = bodies[lo];
  const Body& b = bodies[hi];
  if (a.fixed && b.fixed) return std::nullopt;
  if (excluded(a, hi, b) || excluded(b, lo, a)) return std::nullopt;
  if (a.rests_on(hi) || b.rests_on(lo)) return std::nullopt;  // touching all along: no event
  if (continues_support(a, b) || continues_support(b, a)) return std::nullopt;  // a joint: no event
  ++counts.predictions;
  if (a.rotates || b.rotates) return predict_rotating(lo, hi, limit);
  const Kinematics<T> ka = kinematics(a, now), kb = kinematics(b, now);
  std::optional<PredictedContact<T>> c;
  if (solver != SolverKind::Fast && a.shape.kind == ShapeKind::Circle && b.shape.kind == ShapeKind::Circle) {
    const Vec2<T> d = separation(a, b), dv = kb.v - ka.v, da = kb.a - ka.a;
    const T r = a.shape.radius + b.shape.radius;
    const Poly<T> p = distance_poly(d, dv, da, r);
    if (refine::near_graze(p, d, dv, da, r, pair_scale(a.shape, ka.p, b.shape, kb.p), horizon - now)) {
      if constexpr (std::is_same_v<T, float>) {
        if (const std::optional<std::optional<PredictedContact<T>>> wide = wide_circle_prediction(a, b)) return *wide;
      }
      bool overlapping = false;
      auto exact = exact_circle_prediction(a, b, overlapping);
      // Overlapping (by round-off) and receding: no crossing to find exactly, and the
      // turning-overlap rule (roots.hpp) belongs to the rounded prediction below.
      if (exact || !overlapping) return exact;
    }
    // Apart and approaching without relative acceleration (most of a gas's predictions): the
    // robust walk's answer by its short form (roots_robust.hpp), for certified too. Its answer
    // is decided by signs with proven error bounds (a doubt leaves it to the solver), and a
    // predicted time only orders the queue: robust's and certified's event times are both
    // re-derived from the exact paths (refine_near_top), so certified's correctly rounded root
    // of the rounded polynomial bought nothing there (docs/solvers.md).
    T root{};
    const detail::ParabolaRoot parabola = detail::approaching_parabola_root(p, T(horizon - now), root);
    if (parabola == detail::ParabolaRoot::None) return std::nullopt;
    if (parabola == detail::ParabolaRoot::Root) {
      c = PredictedContact<T>{root, ContactKind::CircleCircle, 0, 0, false};
    } else {
      c = circle_pair_contact(solver, p, horizon - now);  // the polynomial built once
    }
  } else if (solver == SolverKind::Fast) {
    c = predict_contact(solver, a.shape, ka, b.shape, kb, horizon - now);
  } else {
    const LineGrazes grazes(*this, lo, hi);
    c = predict_contact(solver, a.shape, ka, b.shape, kb, horizon - now, &grazes);
  }
  if (!c) return std::nullopt;
  c->time = now + c->time;  // relative to absolute
  // Robust and certified keep contacts predicted just past the horizon: the exact time may
  // still be before it (refine_near_top decides).
  if (c->time > (solver == SolverKind::Fast ? horizon : refine_bound(horizon))) return std::nullopt;
  return c;
}

template <class T>
inline auto World<T>::Impl::wide_circle_prediction(const Body& a, const Body& b) const
    -> std::optional<std::optional<PredictedContact<T>>> {
  using W = double;
  const W t_now = W(now);
  const auto wide = [](const Vec2<T>& v) { return Vec2<W>{W(v.x), W(v.y)}; };
  struct Motion {
    Vec2<W> displacement, v, acc;
  };
  const auto motion = [&](const Body& x) {
    if (x.fixed) return Motion{};
    const W tau = t_now - W(x.t0);
    const Vec2<W> v0 = wide(x.v0), acc = wide(x.acc);
    return Motion{v0 * tau + acc * (tau * tau / W(2)), v0 + acc * tau, acc};
  };
  const Motion ma = motion(a), mb = motion(b);
  const Vec2<W> d = (wide(b.p0) - wide(a.p0)) + (mb.displacement - ma.displacement);
  const Vec2<W> dv = mb.v - ma.v, da = mb.acc - ma.acc;
  const W r = W(a.shape.radius) + W(b.shape.radius);
  const Poly<W> p = distance_poly(d, dv, da, r);
  const W window = W(horizon) - t_now;
  const auto scale = [&](const Body& x, const Motion& m) {  // BodyShape::coordinate_scale
    const Vec2<W> at = wide(x.p0) + m.displacement;
    return std::max(std::abs(at.x), std::abs(at.y)) + W(x.shape.span);
  };
  if (refine::near_graze(p, d, dv, da, r, std::max(scale(a, ma), scale(b, mb)), window)) return std::nullopt;
  const std::optional<PredictedContact<W>> c = circle_pair_contact(solver, p, window);
  if (!c) return std::optional<PredictedContact<T>>{};
  PredictedContact<T> out{T(t_now + c->time), ContactKind::CircleCircle, 0, 0, c->at_start_overlap};
  if (out.time > refine_bound(horizon)) return std::optional<PredictedContact<T>>{};
  return std::optional<PredictedContact<T>>{out};
}

template <class T> inline auto World<T>::Impl::separation(const Body& a, const Body& b) const -> Vec2<T> {
  const auto displacement = [&](const Body& x) {
    if (x.fixed) return Vec2<T>{};
    const T tau = now - x.t0;
    return x.v0 * tau + x.acc * (tau * tau / T(2));
  };
  return (b.p0 - a.p0) + (displacement(b) - displacement(a));
}

template <class T> inline auto World<T>::Impl::relative_acc_zero(const Body& a, const Body& b) -> bool {
  const Vec2<T> aa = a.fixed ? Vec2<T>{} : a.acc, ab = b.fixed ? Vec2<T>{} : b.acc;
  return aa.x == ab.x && aa.y == ab.y;
}

template <class T> inline auto World<T>::Impl::excluded(const Body& x, BodyIndex partner, const Body& y) const -> bool {
  return x.no_contact_with == partner && x.no_contact_version == x.version &&
         x.no_contact_partner_version == y.version;
}

template <class T>
inline auto World<T>::Impl::exact_circle_prediction(const Body& a, const Body& b, bool& overlapping)
    -> std::optional<PredictedContact<T>> {
  ++counts.exact_predictions;
  detail::exact::IntPoly poly = refine::exact_circle_poly(exact_of(a), exact_of(b), refine::Exact::of(now));
  overlapping = poly.c[0] < 0;
  // Overlapping and receding (not decreasing at now): no crossing now, and whatever follows
  // belongs to the turning-overlap rule or to a later crossing, which the rounded prediction
  // handles (the caller falls back to it, and refine_near_top decides it exactly once it is
  // near the top, exact_contact); skip the Sturm chain, the costly part.
  if (overlapping &&
      detail::exact::sign_just_after(detail::exact::derivative(poly), detail::exact::Dyadic{}) >= 0)
    return std::nullopt;
  const std::optional<ExactRoot> root = exact_first_contact(std::move(poly));
  if (!root) return std::nullopt;
  return PredictedContact<T>{root->time, ContactKind::CircleCircle, 0, 0, root->overlap};
}

template <class T>
inline auto World<T>::Impl::exact_first_contact(detail::exact::IntPoly poly) const -> std::optional<ExactRoot> {
  detail::exact::ExactSolver<T> exact(std::move(poly), detail::exact::Dyadic{},
                                      detail::exact::to_dyadic(T(refine_bound(horizon) - now)));
  std::optional<ExactRoot> out;
  auto visit = [&](const T& tau, bool overlap) {
    out = ExactRoot{now + tau, overlap, false};
    return true;
  };
  exact.visit(StartRule::OverlapCollides, 0, visit);
  if (out) out->turn = exact.turned();
  if (out && out->time > refine_bound(horizon)) return std::nullopt;
  return out;
}

template <class T> inline auto World<T>::Impl::offer(BodyIndex i, BodyIndex j, Scheduled<T>& best) -> void {
  const BodyIndex lo = std::min(i, j), hi = std::max(i, j);
  auto c = predict(lo, hi, best.valid() ? best.time : horizon);
  if (!c) return;
  const Scheduled<T> s = scheduled(*c, lo, hi, j);
  if (s.key_less(best)) best = s;
}

template <class T>
inline auto World<T>::Impl::scheduled(const PredictedContact<T>& c, BodyIndex lo, BodyIndex hi, BodyIndex partner) const
    -> Scheduled<T> {
  Scheduled<T> s{c.time, lo, hi, c.contact, c.feature_a, c.feature_b, c.at_start_overlap, c.corner,
                 partner, bodies[partner].version};
  if (c.rotating) {
    s.refined = true;  // the exact refinement is the translate-only paths'; see world_rotation.hpp
    s.resume = c.resume;
    s.at_start = c.at_start;
  }
  return s;
}

}  // namespace pge
