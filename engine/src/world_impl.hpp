// The event-driven world. Each moving body keeps its own reference time and is brought up to
// date only when an event touches it; each keeps one scheduled event (its earliest predicted
// contact) in an indexed 4-ary heap (event_heap.hpp), and an event whose partner has changed
// since it was predicted is dropped and its owner rescheduled (lazy invalidation by version
// counters). Which pairs a body is predicted against is the broad phase's choice
// (broad_phase.hpp): every body, or the bodies in the grid cells around it; the grid's cell
// crossings, which change no motion, are each body's second event in the same heap.
//
// The definitions of World<T>, included by one translation unit per scalar (world_float.cpp,
// world_double.cpp, world_long_double.cpp, world_quad.cpp), each instantiating it for its own
// scalar: one unit of all four took 2.6 minutes to compile under the sanitizers, the longest
// step of the build, while the other core waited.
#pragma once

#include "pge/world.hpp"

#include "pge/constants.hpp"
#include "pge/hash.hpp"
#include "pge/validate.hpp"

#include "aligned.hpp"
#include "broad_phase.hpp"
#include "contact.hpp"
#include "event_heap.hpp"
#include "refine.hpp"
#include "tunnel_watch.hpp"

#include <boost/math/special_functions/next.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <optional>
#include <queue>
#include <sstream>
#include <stdexcept>

namespace pge {

static_assert(kMaxBodies < (std::size_t{1} << 31), "the grid tags shared bodies' cell entries with bit 31");

template <class T> struct World<T>::Impl {
  // The fields every prediction reads come first, so that a scan over all bodies touches as
  // few cache lines as it can; the shape's outline data and the rest follow.
  // A fixed straight face a body rests on (resting contact, DESIGN.md): the line through
  // `origin` along the unit tangent `u`, `length` long, with unit normal `n` pointing from the
  // face towards the resting body. The body's contact with it spans [s_lo, s_hi] along u,
  // relative to the body's reference point (0 and 0 for a circle's centre; a polygon's lowest
  // vertices).
  struct Support {
    BodyIndex body = kNoBody;
    Vec2<T> n, origin, u;
    T length{}, s_lo{}, s_hi{};
  };

  // Aligned to a cache line, with what every prediction reads first: for double, the motion
  // and the grid cell fill the first line; the version, the exclusion, what a collision reads
  // (inverse mass, restitution, storm count) and the shape's kind, radius and span the second.
  // A prediction of two circles or a collision reads no other line of a body (with 1e5 bodies,
  // the bodies do not fit in cache, and each further line is another miss; visit_cells
  // prefetches both).
  struct alignas(64) Body {
    bool fixed = false;
    std::uint8_t supports = 0;  // faces in `support` that hold the body
    // With the grid on: a moving body's cell, or kInCells, kOutside or kGlobal (see Impl). Here
    // rather than in an array of its own, where each event's bodies would cost one more miss.
    std::uint32_t cell = CellGrid::kGlobal;
    // Motion since t0: p(t) = p0 + v0 (t - t0) + acc (t - t0)^2 / 2.
    T t0{};
    Vec2<T> p0, v0, acc;
    std::uint64_t version = 0;  // bumped whenever the body's motion changes
    // A circle pair the exact paths say never touches although the rounded prediction did
    // (refine_near_top): not predicted again while both bodies keep their motions (the
    // versions below, read only when no_contact_with is the partner).
    BodyIndex no_contact_with = kNoBody;
    std::uint32_t storm_count = 0;
    T inv_mass{};          // 0 for fixed bodies
    T restitution{1};
    T storm_start{};
    BodyShape<T> shape;         // kind, radius and span first; a moving polygon's vertex is p(t) + local
    std::uint64_t no_contact_version = 0, no_contact_partner_version = 0;
    T mass{};
    std::string id;
    // The field's acceleration (own + gravity); `acc` is the path's, which resting removes
    // components from. At most two faces hold a body in 2-D (a V holds it still).
    Vec2<T> field_acc;
    std::array<Support, 2> support;

    bool rests_on(BodyIndex j) const {
      for (int k = 0; k < supports; ++k)
        if (support[static_cast<std::size_t>(k)].body == j) return true;
      return false;
    }
  };

  struct Timer {
    T time;
    std::uint64_t seq;
    TimerCallback callback;
    bool operator>(const Timer& o) const { return time > o.time || (time == o.time && seq > o.seq); }
  };

  std::vector<Body, CacheAligned<Body>> bodies;
  std::vector<BodyIndex> moving;         // indices of moving bodies, ascending
  EventHeap<T> heap;                     // per moving body: its next contact and cell crossing

  // ---- Broad phase (broad_phase.hpp). With the grid off every body is a candidate of every
  // other; with it on, a body's candidates are the bodies in the 3x3 cells around its cell and
  // the global bodies, or every body for a global one.
  static constexpr std::uint32_t kGlobal = CellGrid::kGlobal;
  static constexpr std::uint32_t kInCells = CellGrid::kGlobal - 1;   // a fixed body in the cells
  static constexpr std::uint32_t kOutside = CellGrid::kGlobal - 2;   // a fixed body no cell reaches
  bool grid_on = false;
  // Whether events request their next reads ahead (prefetch_line): from kPrefetchMinBodies on.
  // Below it a world's hot lines fit in the L2 and the requests only cost: on the 1e3 gas they
  // took 3,056-3,147 ns per event to 3,272-3,335 (bench_scale gas_interleaved, 2026-11-22).
  static constexpr std::size_t kPrefetchMinBodies = 4096;
  bool prefetching = false;
  CellGrid grid;
  std::vector<BodyIndex> globals;        // bodies the grid does not hold
  std::vector<BodyIndex> candidates;     // scratch list of visit_cells
  std::vector<BodyIndex> refine_owners;  // scratch list of refine_near_top
  std::vector<std::uint32_t> seen;       // per body: the last candidate scan that met it (fixed
  std::uint32_t scan = 0;                // bodies sit in several cells)
  std::priority_queue<Timer, std::vector<Timer>, std::greater<>> timers;
  std::uint64_t timer_seq = 0;
  T now{};
  T horizon{};
  SolverKind solver = SolverKind::Robust;
  std::uint64_t max_events = 0;
  double fps = 0;
  std::uint64_t next_frame = 0;
  StopReason reason = StopReason::ReachedUntil;
  bool finished = false;
  bool stop_requested = false;
  StormInfo<T> storm;
  EventCounts counts;
  Overlap worst_contact;
  CollisionCallback on_collision;
  FrameCallback on_frame;
  MotionCallback on_motion_change;

  Kinematics<T> kinematics(const Body& b, const T& t) const {
    if (b.fixed) return {b.p0, Vec2<T>{}, Vec2<T>{}};
    const T tau = t - b.t0;
    return {b.p0 + b.v0 * tau + b.acc * (tau * tau / T(2)), b.v0 + b.acc * tau, b.acc};
  }

  void rebase(Body& b, const T& t) {
    if (b.fixed) return;
    const Kinematics<T> k = kinematics(b, t);
    b.p0 = k.p;
    b.v0 = k.v;
    b.t0 = t;
  }

  // The earliest contact of the pair (lo < hi) from `now` to the horizon.
  std::optional<PredictedContact<T>> predict(BodyIndex lo, BodyIndex hi) {
    const Body& a = bodies[lo];
    const Body& b = bodies[hi];
    if (a.fixed && b.fixed) return std::nullopt;
    if (excluded(a, hi, b) || excluded(b, lo, a)) return std::nullopt;
    if (a.rests_on(hi) || b.rests_on(lo)) return std::nullopt;  // touching all along: no event
    if (continues_support(a, b) || continues_support(b, a)) return std::nullopt;  // a joint: no event
    ++counts.predictions;
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
      c = circle_pair_contact(solver, p, horizon - now);  // the polynomial built once
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

  // A float near-graze of two circles predicted again from their contact polynomial built in
  // double from the same stored paths: the stored floats are exact in double, so its rounding
  // is 2^29 times smaller than float's, and double's own near-graze test (2^-36, far above that
  // rounding) tells whether it decides the pair; if not (nothing), the exact paths must. A float
  // near-graze is anything within 2^-15 of the pair's scale (refine::near_graze_relative): the
  // exact solver deciding them all made a float gas of 1,000 discs four times as slow
  // (fixtures/scenes/basics/gas-1000.json, 4.4 s to 18 s; 2.7 s through double). The time is
  // rounded to float from double (refine_near_top rounds it once from the exact paths).
  std::optional<std::optional<PredictedContact<T>>> wide_circle_prediction(const Body& a, const Body& b) const {
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

  // b's position minus a's at `now`, like terms first: the stored positions cancel before the
  // displacements since each body's t0 are added, so the rounding is relative to the pair's
  // separation rather than to its distance from the origin (kb.p - ka.p rounds each position
  // first). The predicted time is then a few ulps of the clock from the exact one wherever the
  // pair is, and the refinement's walk (refine.hpp) is short.
  Vec2<T> separation(const Body& a, const Body& b) const {
    const auto displacement = [&](const Body& x) {
      if (x.fixed) return Vec2<T>{};
      const T tau = now - x.t0;
      return x.v0 * tau + x.acc * (tau * tau / T(2));
    };
    return (b.p0 - a.p0) + (displacement(b) - displacement(a));
  }

  // A body's stored path, and the same as the exact contact functions read it (refine.hpp).
  static refine::Path<T> path_of(const Body& b) { return {&b.shape, b.fixed, b.t0, b.p0, b.v0, b.acc}; }
  static refine::ExactBody<T> exact_of(const Body& b) { return refine::exact_body(path_of(b)); }

  // A scheduled contact's time, correctly rounded from the exact paths (refine.hpp); nothing if
  // no crossing is found near the predicted time.
  std::optional<T> refined_time(const Scheduled<T>& s) const {
    const refine::Path<T> a = path_of(bodies[s.lo]), b = path_of(bodies[s.hi]);
    refine::ContactSigner<T> sign(a, b, s);
    return refine::correctly_rounded_crossing(s.time, now, sign);
  }

  // The feature pair (fa, fb) of the contact `kind` of the pair (lo, hi), as the refinement's
  // exact functions read a scheduled contact.
  static Scheduled<T> feature_pair(BodyIndex lo, BodyIndex hi, ContactKind kind, std::uint16_t fa, std::uint16_t fb) {
    Scheduled<T> s;
    s.lo = lo;
    s.hi = hi;
    s.contact = kind;
    s.feature_a = fa;
    s.feature_b = fb;
    return s;
  }

  // A line contact of the pair (lo, hi) whose rounded function passes within rounding of a
  // double root, decided from the exact paths (refine.hpp, exact_line_graze); a crossing's time
  // then correctly rounded from the exact paths, searched from `tau` (relative to now: the
  // rounded root, else the rounded minimum) and written back. Counted in counts.exact_predictions.
  GrazeVerdict line_graze(BodyIndex lo, BodyIndex hi, ContactKind kind, std::uint16_t fa, std::uint16_t fb, T& tau) {
    ++counts.exact_predictions;
    Scheduled<T> s = feature_pair(lo, hi, kind, fa, fb);
    const GrazeVerdict g = refine::exact_line_graze(exact_of(bodies[lo]), exact_of(bodies[hi]), s, refine::Exact::of(now));
    if (g != GrazeVerdict::Crosses) return g;
    s.time = T(now + tau);
    if (const std::optional<T> t = refined_time(s)) tau = *t - now;
    return g;
  }
  // Where the line contact of the pair (lo, hi)'s feature pair lies on its edge at the exact
  // crossing nearest now + tau (its time correctly rounded first): GrazeJudge::place. Counted in
  // counts.exact_predictions.
  EdgePlace crossing_place(BodyIndex lo, BodyIndex hi, ContactKind kind, std::uint16_t fa, std::uint16_t fb,
                           const T& tau) {
    ++counts.exact_predictions;
    Scheduled<T> s = feature_pair(lo, hi, kind, fa, fb);
    s.time = T(now + tau);
    const std::optional<T> t = refined_time(s);
    if (!t || *t < now) return EdgePlace::Unknown;
    s.time = *t;
    return crossing_place(exact_of(bodies[lo]), exact_of(bodies[hi]), s);
  }
  // The same for a scheduled line contact whose time is its correctly rounded crossing: the
  // crossing lies between the T values next to it (refine::exact_place_at_crossing).
  EdgePlace crossing_place(const refine::ExactBody<T>& a, const refine::ExactBody<T>& b, const Scheduled<T>& r) const {
    const T before = std::max(now, T(boost::math::float_prior(r.time)));
    const T after = boost::math::float_next(r.time);
    return refine::exact_place_at_crossing(a, b, r, refine::Exact::of(now), refine::Exact::of(before),
                                           refine::Exact::of(after));
  }
  struct LineGrazes final : GrazeJudge<T> {
    Impl& w;
    BodyIndex lo, hi;
    LineGrazes(Impl& w_, BodyIndex lo_, BodyIndex hi_) : w(w_), lo(lo_), hi(hi_) {}
    GrazeVerdict decide(ContactKind kind, std::uint16_t fa, std::uint16_t fb, T& tau) const override {
      return w.line_graze(lo, hi, kind, fa, fb, tau);
    }
    EdgePlace place(ContactKind kind, std::uint16_t fa, std::uint16_t fb, const T& tau) const override {
      return w.crossing_place(lo, hi, kind, fa, fb, tau);
    }
    T overlap_rounding(const T& scale) const override {
      return T(kSiblingRoundingUlps) * std::numeric_limits<T>::epsilon() *
             w.rounding_reach(w.bodies[lo], w.bodies[hi], scale);
    }
    std::optional<OverlapPairs> overlap_pairs() const override { return w.exact_overlap_pairs(lo, hi); }
  };

  // The overlap rule's pairs of the outlines (lo, hi) at now, from the exact paths
  // (refine::exact_overlap_pairs), each approaching or not by its exact contact function.
  // Counted in counts.exact_predictions.
  std::optional<OverlapPairs> exact_overlap_pairs(BodyIndex lo, BodyIndex hi) {
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

  // What a pair's rounded coordinates at now are relative to: the pair's coordinate scale at now
  // (pair_scale, the caller's) plus each body's motion since its path was stored (its position
  // at now is rounded from that path).
  T rounding_reach(const Body& a, const Body& b, const T& scale) const {
    using std::abs;
    const auto travel = [&](const Body& x) {
      if (x.fixed) return T(0);
      const T tau = abs(now - x.t0);
      return (abs(x.v0.x) + abs(x.v0.y) + (abs(x.acc.x) + abs(x.acc.y)) * tau) * tau;
    };
    return scale + travel(a) + travel(b);
  }

  static bool relative_acc_zero(const Body& a, const Body& b) {
    const Vec2<T> aa = a.fixed ? Vec2<T>{} : a.acc, ab = b.fixed ? Vec2<T>{} : b.acc;
    return aa.x == ab.x && aa.y == ab.y;
  }

  bool excluded(const Body& x, BodyIndex partner, const Body& y) const {
    return x.no_contact_with == partner && x.no_contact_version == x.version &&
           x.no_contact_partner_version == y.version;
  }

  // Two circles that pass within rounding of touching: predicted from the exact paths
  // (refine.hpp). Counted in counts.exact_predictions.
  // `overlapping`: whether the pair overlaps exactly at `now`.
  std::optional<PredictedContact<T>> exact_circle_prediction(const Body& a, const Body& b, bool& overlapping) {
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

  // The first contact of a pair whose exact contact polynomial in tau = t - now is `poly`
  // (refine.hpp), the overlap rule and the turning-overlap rule (roots.hpp) included, isolated
  // by the exact solver: its time now + tau (so rounded twice) and overlap flag. Up to the
  // refinement bound past the horizon (the exact time may still be the horizon, and
  // refine_near_top rounds it once, from the exact paths); nothing if none before it.
  struct ExactRoot {
    T time;
    bool overlap;
    bool turn;  // the turning-overlap rule's contact (ExactSolver::turned)
  };
  std::optional<ExactRoot> exact_first_contact(detail::exact::IntPoly poly) const {
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

  // The time of a turning-overlap contact (roots.hpp), the first local maximum of the pair's
  // exact contact polynomial after `now`: a crossing of its derivative from positive to
  // negative, correctly rounded from the exact paths like every other event time.
  // `poly`: the exact contact polynomial in tau = t - now (refine::exact_feature_poly).
  std::optional<T> refined_turn(const detail::exact::IntPoly& poly, const T& predicted) const {
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

  // The turning-overlap rule's contact, decided without the exact solver where it can be: in a
  // storm of a pair pressed together (each contact leaves it overlapping by round-off and
  // receding at rounding speed, and the Sturm chains cost 2 ms a contact) the contact function
  // P(tau) of the exact paths (`poly`) is concave from 0 to just past its turn. With
  //   P(0) < 0 and P'(0) > 0 (overlapping, receding), the turn's correctly rounded time m from
  //   P''s crossing nearest `hint` (refined_turn), tau1 = the next T after m, minus now,
  //   P'(tau1) <= 0 and P'' < 0 on [0, tau1] (bounded above by its Taylor terms at 0),
  // P' falls on [0, tau1] and has one root there, the first maximum of P, and P stays below
  // P(0) + P'(0) tau1 up to it: if that is negative the pair turns back overlapping, at m.
  // Every test is an exact sign; nothing when one fails (the exact solver decides).
  std::optional<T> concave_turn(const detail::exact::IntPoly& poly, const T& hint) const {
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

  // What deciding a scheduled contact again from the exact paths found.
  enum class Exactly : std::uint8_t {
    Contact,  // the pair's first contact, the overlap rules included, its time rounded once
    None,     // no contact of the pair (of two circles) or of its feature pair before the bound
    Unknown,  // not decided exactly (see exact_contact)
  };

  // A scheduled contact decided again from the exact contact polynomial of its feature pair
  // (refine::exact_feature_poly), the overlap and turning-overlap rules included, its time
  // rounded once from the exact paths (now + tau is rounded twice): r's time and overlap flag
  // on Contact. Not decided (Unknown) for a circle on or behind a polygon edge's line (no
  // polynomial is its function there), nor when the contact found lies off the scheduled
  // feature (the centre or vertex beyond the edge's ends, a vertex's business: predicting
  // again from the rounded state would schedule the same contact again), where the caller keeps
  // the rounded time. `hint`: the rounded time, where the walks start.
  Exactly exact_contact(Scheduled<T>& r, const T& hint) {
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

  // The bound on a rounded vertex/edge function's rounding, in ulps of its terms' magnitude
  // (may_touch_first).
  static constexpr double kSiblingRoundingUlps = 1024;

  // Whether the exact function of vertex k of o.P against edge j of o.Q may have a downward
  // crossing that the prediction's rules take in [0, window] (relative to now), judged from its
  // rounded function p with a generous bound on its rounding (kSiblingRoundingUlps; a bound too
  // small would leave an earlier contact undecided, one too large costs exact quadratics):
  // not when p stays beyond the bound on one side throughout; yes when it comes within the
  // bound of zero at now or at its extremum (a touch or graze, whose crossing is the
  // rounding's call); otherwise p's crossings are simple and each exact one lies within
  // bound / |p'| of a rounded one, so yes only for a downward rounded root that early whose
  // contact the prediction's rules (judge_root, its corner slack widened by exactly that
  // motion along the edge) take.
  static bool may_touch_first(const OutlineView<T>& o, std::size_t k, std::size_t j, const Vec2<T>& d0, const Poly<T>& p,
                              const T& window, const T& reach, const T& scale) {
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

  // The refinement re-derives the scheduled feature pair only, but another vertex/edge pair of
  // the same two outlines may touch exactly before it while its rounded root came later, or
  // never: a box resting on a tilted segment with two vertices on its line, whose rounded
  // contact functions are within rounding of zero (one of them exactly zero at now and
  // receding by less than the rounding of its rate, then pulled back by gravity, a root 1e-17
  // after now that the rounded quadratic does not have; scripts/tilted-tiles-sweep.py). So
  // every other vertex/edge pair that may touch before the scheduled time (may_touch_first) is
  // decided from its exact polynomial (refine::exact_feature_poly, a quadratic); an exact
  // crossing before that time that the prediction's rules take
  // (judge_root: on the edge, entering, the corner rule) replaces the scheduled contact, its
  // time correctly rounded.
  void earlier_outline_contact(Scheduled<T>& r) {
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

  // Whether the scheduled contact's point (a line contact's vertex or circle centre; a
  // circle-vertex contact's centre, against the vertex's two edges) lies within a generous bound
  // on its rounding of an edge's end at its time, or at any time within the refinement's window
  // of it: only there can the exact paths put it on the other side of the end
  // (off_feature_contact asks them only then). The bound: kSiblingRoundingUlps of the terms of
  // the projection dot(point - start, e) (the world coordinates it is rounded from), plus the
  // relative motion along e over the window and two ulps of the time.
  bool near_edge_end(const Scheduled<T>& r) const {
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

  static bool off_edge(EdgePlace p) { return p == EdgePlace::Before || p == EdgePlace::After; }
  // A line contact (a vertex or a circle against an edge) whose correctly rounded crossing the
  // exact paths put beyond an end of the edge (crossing_place): the prediction's corner slack,
  // widened by the motion along a nearly tangent edge, accepted a point up to that motion
  // beyond the corner, but the oracle counts only a point on the closed edge, and the true
  // first contact is the corner's other feature pair, later (scripts/edge-end-sweep.py,
  // end-356: a triangle's edge nearly along its motion took a segment's end 5e-12 of its length
  // beyond the corner, 10,219 ulps before the triangle's vertex met the segment). The earliest
  // exact contact of a sibling feature pair within the refinement's window of the crossing
  // (refine_bound, where the refinement already moves times) replaces it: for outlines every
  // other vertex/edge pair (earlier_outline_contact), for a circle the vertex at that end. If
  // none is there, the rounded decision stands. A circle's vertex contact is checked against
  // its adjacent edges instead (earlier_circle_edge_contact). Only near an end (near_edge_end).
  void off_feature_contact(Scheduled<T>& r) {
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

  // A circle scheduled against a vertex whose rounded prediction put its contact with an
  // adjacent edge just beyond the edge's end (a circle aimed at a segment's end: its edge and
  // end contact functions meet tangentially there, and rounding picks either; the edge's is
  // first where the exact point lies inside, by a few ulps in long double,
  // scripts/edge-end-sweep.py): each adjacent edge's exact crossing before the scheduled time
  // whose point lies strictly inside the edge (crossing_place) replaces it.
  void earlier_circle_edge_contact(Scheduled<T>& r) {
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

  // Whether the scheduled contact's point lies on its features at its time (in T, as the
  // prediction accepts it): the circle's centre or the vertex projects onto the edge.
  bool on_feature(const Scheduled<T>& s) const {
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

  // Exact times for certified events (refine.hpp). A prediction from the rounded state can be
  // off by hundreds of ulps, so the queue's order near its top is not the exact order: before
  // the top event is processed, it and every unrefined contact scheduled within
  // kRefineWindowRelative of it are re-derived exactly (a contact whose partner has changed is
  // predicted again instead). Returns true if anything changed (the caller merges again).
  // Overlap-rule contacts at `now` are checked too (the rounded state may overlap where the
  // exact paths are still an ulp apart). The turning-overlap rule's contact (later than now) is
  // decided again from the exact polynomial of its feature pair and its turning point correctly
  // rounded (refined_turn).
  // The latest time whose contacts may be exactly as early as t (kRefineWindowRelative, at
  // least kRefineWindowUlps of T).
  static T refine_bound(const T& t) {
    using std::abs;
    static const T relative =
        std::max(T(kRefineWindowRelative), T(kRefineWindowUlps) * std::numeric_limits<T>::epsilon());
    return t + relative * std::max(T(1), abs(t));
  }

  bool refine_near_top() {
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

  // Whether a contact scheduled at the horizon is a collision rather than a touch: two circles
  // are asked of the exact polynomial (a double root inside its window is no root), where a
  // rounded approach test cannot see relative speeds of rounding size; other pairs are asked
  // whether they approach at that time (the impulse test of collide).
  // (Exactly: the contact function at the horizon is negative, the crossing came before it, or
  // zero and decreasing just after it, a crossing exactly at it; zero and rising is a graze, and
  // positive means the exact contact is after the horizon, however close.)
  bool collides_at_horizon(const Scheduled<T>& s) {
    if (s.contact == ContactKind::CircleCircle && solver != SolverKind::Fast) {
      const refine::Exact t_now = refine::Exact::of(now);
      const detail::exact::IntPoly poly = refine::exact_circle_poly(exact_of(bodies[s.lo]), exact_of(bodies[s.hi]), t_now);
      const detail::exact::Dyadic tau = (refine::Exact::of(horizon) - t_now).d;
      const int at = detail::exact::sign_at(poly, tau);
      return at < 0 || (at == 0 && detail::exact::sign_just_after(poly, tau) < 0);
    }
    return approaching(s);
  }

  bool approaching(const Scheduled<T>& s) const {
    const Body& a = bodies[s.lo];
    const Body& b = bodies[s.hi];
    const Kinematics<T> ka = kinematics(a, s.time), kb = kinematics(b, s.time);
    const PredictedContact<T> contact{s.time, s.contact, s.feature_a, s.feature_b, s.at_start_overlap, s.corner};
    const ContactGeometry<T> g = contact_geometry(contact, a.shape, ka, b.shape, kb);
    return dot(kb.v - ka.v, g.normal) < T(0) && dot(g.normal, g.normal) > T(0);
  }

  // Offers the pair (i, j)'s earliest contact to `best`, the owner i's candidate event.
  void offer(BodyIndex i, BodyIndex j, Scheduled<T>& best) {
    const BodyIndex lo = std::min(i, j), hi = std::max(i, j);
    auto c = predict(lo, hi);
    if (!c) return;
    Scheduled<T> s{c->time, lo, hi, c->contact, c->feature_a, c->feature_b, c->at_start_overlap, c->corner,
                   j, bodies[j].version};
    if (s.key_less(best)) best = s;
  }

  // Calls f(j) for every body j != i that i is predicted against (see the broad phase above).
  template <class F> void for_candidates(BodyIndex i, F f) {
    if (!grid_on || bodies[i].cell == kGlobal) {
      for (BodyIndex j = 0; j < bodies.size(); ++j)
        if (j != i) f(j);
      return;
    }
    visit_cells(i, bodies[i].cell, kGlobal, f);
    for (BodyIndex j : globals) f(j);
  }

  // Calls f(j) for the bodies j != i in the 3x3 cells around `c`, less those also around
  // `except` (a cell, or kGlobal), fixed bodies once, in the grid's order. The candidates are
  // gathered and their Body lines prefetched first: with 1e5 bodies they are scattered over
  // memory, and a prediction is too long for the processor to reach the next candidate's load
  // on its own, so the misses would otherwise come one after another.
  template <class F> void visit_cells(BodyIndex i, std::uint32_t c, std::uint32_t except, F& f) {
    std::vector<BodyIndex> list;
    list.swap(candidates);  // reentrant: a nested call would find an empty scratch list
    list.clear();
    next_scan();
    const auto keep = [&](BodyIndex j) { list.push_back(j); };
    grid.visit_around(c, [&](BodyIndex j, bool shared) { visit_once(i, j, shared, keep); }, except);
    for (BodyIndex j : list) prefetch_hot(bodies[j]);
    for (BodyIndex j : list) f(j);
    candidates.swap(list);
  }
  void prefetch_cells(BodyIndex i) const {
    if (bodies[i].cell < grid.cell_count()) grid.prefetch_around(bodies[i].cell);
  }
  void prefetch_candidates(BodyIndex i) const {
    if (bodies[i].cell < grid.cell_count())
      grid.visit_around(bodies[i].cell, [&](BodyIndex j, bool) { prefetch_hot(bodies[j]); });
  }
  // The two cache lines of a Body that a prediction of two circles reads (see Body).
  static void prefetch_hot(const Body& b) {
    prefetch_line(&b);
    prefetch_line(reinterpret_cast<const char*>(&b) + 64);
  }

  void next_scan() {
    if (++scan == 0) {  // wrapped: forget every mark
      std::fill(seen.begin(), seen.end(), 0u);
      scan = 1;
    }
  }
  // A fixed body registered in several cells (`shared`) is offered once per scan.
  template <class F> void visit_once(BodyIndex i, BodyIndex j, bool shared, F& f) {
    if (j == i) return;
    if (shared) {
      if (seen[j] == scan) return;
      seen[j] = scan;
    }
    f(j);
  }

  void reschedule(BodyIndex i) {
    const T crossing = grid_on ? crossing_time(i, now) : EventHeap<T>::never();
    Scheduled<T> best;
    for_candidates(i, [&](BodyIndex j) { offer(i, j, best); });
    const Body& b = bodies[i];
    for (int k = 0; k < b.supports; ++k) {
      const std::optional<T> t = leave_time(b, b.support[static_cast<std::size_t>(k)]);
      if (!t || !(*t < best.time || !best.valid())) continue;
      const BodyIndex f = b.support[static_cast<std::size_t>(k)].body;
      Scheduled<T> s;
      s.time = *t;
      s.lo = std::min(i, f);
      s.hi = std::max(i, f);
      s.feature_a = static_cast<std::uint16_t>(k);
      s.partner = f;
      s.refined = true;  // not a contact: nothing to re-derive
      s.leave = true;
      best = s;
    }
    heap.set(i, best, crossing);
  }

  // ---- Broad phase: cells, crossings, global bodies (broad_phase.hpp).

  // The grid for this scene, or none (grid_on false): the cell's body radius R is the largest
  // reach among the moving bodies no larger than 4 times their median reach; larger bodies are
  // global. The grid covers the moving bodies' positions and the fixed bodies of comparable
  // extent, two cells beyond, with at most 16 cells per moving body (larger cells otherwise).
  void setup_grid(BroadPhase mode) {
    for (Body& b : bodies) b.cell = kGlobal;
    grid_on = mode == BroadPhase::Grid || (mode == BroadPhase::Auto && moving.size() >= kGridMinMovingBodies);
    if (!grid_on || moving.empty()) {
      grid_on = false;
      return;
    }
    std::vector<double> reach;
    reach.reserve(moving.size());
    for (BodyIndex i : moving) reach.push_back(to_double(bodies[i].shape.reach));
    std::vector<double> sorted = reach;
    std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2), sorted.end());
    const double median = sorted[sorted.size() / 2];
    double radius = 0;
    for (double r : reach)
      if (r <= 4 * median) radius = std::max(radius, r);
    const double margin = radius / 8;
    double side = 2 * radius * (1 + 0x1p-10) + 2 * margin;
    // The region: moving positions, then fixed boxes no larger than 64 times their extent.
    double lo_x = std::numeric_limits<double>::infinity(), lo_y = lo_x, hi_x = -lo_x, hi_y = -lo_x;
    for (BodyIndex i : moving) {
      const double x = to_double(bodies[i].p0.x), y = to_double(bodies[i].p0.y);
      lo_x = std::min(lo_x, x); hi_x = std::max(hi_x, x);
      lo_y = std::min(lo_y, y); hi_y = std::max(hi_y, y);
    }
    const double extent = std::max(hi_x - lo_x, hi_y - lo_y) + side;
    std::vector<std::array<double, 4>> boxes(bodies.size());
    for (BodyIndex j = 0; j < bodies.size(); ++j) {
      if (!bodies[j].fixed) continue;
      boxes[j] = fixed_box(bodies[j]);
      const auto& b = boxes[j];
      if (std::max(b[2] - b[0], b[3] - b[1]) > 64 * extent) continue;
      lo_x = std::min(lo_x, b[0]); lo_y = std::min(lo_y, b[1]);
      hi_x = std::max(hi_x, b[2]); hi_y = std::max(hi_y, b[3]);
    }
    const double cap = 16.0 * static_cast<double>(moving.size()) + 4096;
    const double w = hi_x - lo_x, h = hi_y - lo_y;
    side = std::max(side, std::sqrt((w + 4 * side) * (h + 4 * side) / cap));
    for (int k = 0; k < 64 && (w / side + 5) * (h / side + 5) > cap; ++k) side *= 1.25;
    if (!(std::isfinite(side) && side > 0 && std::isfinite(w) && std::isfinite(h))) {
      grid_on = false;
      return;
    }
    const auto nx = static_cast<std::uint32_t>(std::ceil(w / side) + 4), ny = static_cast<std::uint32_t>(std::ceil(h / side) + 4);
    grid.configure(lo_x - 2 * side, lo_y - 2 * side, side, margin, nx, ny);
    seen.assign(bodies.size(), 0u);
    for (std::size_t k = 0; k < moving.size(); ++k) {
      const BodyIndex i = moving[k];
      if (reach[k] > radius) {
        make_global(i);
        continue;
      }
      const std::uint32_t c = grid.cell_of(to_double(bodies[i].p0.x), to_double(bodies[i].p0.y));
      if (c == kGlobal) {
        make_global(i);
        continue;
      }
      bodies[i].cell = c;
      grid.insert(c, i);
    }
    // A fixed body in every cell its box grown by R + m covers (a moving body in a cell may be
    // m outside it and reach R further): a moving body finds it in its own cell, and so among
    // the 3x3 around it. More cells than the cap: global.
    const double fixed_cap = std::max(4096.0, 8.0 * static_cast<double>(moving.size()));
    for (BodyIndex j = 0; j < bodies.size(); ++j) {
      if (!bodies[j].fixed) continue;
      const auto& b = boxes[j];
      const double grow = radius + margin;
      std::uint32_t x0, y0, x1, y1;
      if (!grid.cover(b[0] - grow, b[1] - grow, b[2] + grow, b[3] + grow, x0, y0, x1, y1)) {
        bodies[j].cell = kOutside;
        continue;
      }
      if ((static_cast<double>(x1 - x0) + 1) * (static_cast<double>(y1 - y0) + 1) > fixed_cap) {
        make_global(j);
        continue;
      }
      bodies[j].cell = kInCells;
      for (std::uint32_t y = y0; y <= y1; ++y)
        for (std::uint32_t x = x0; x <= x1; ++x) grid.insert(y * nx + x, j, /*shared=*/true);
    }
  }

  // A fixed body's bounding box (lo x, lo y, hi x, hi y), in double.
  static std::array<double, 4> fixed_box(const Body& b) {
    if (!b.shape.is_outline()) {
      const double x = to_double(b.p0.x), y = to_double(b.p0.y), r = to_double(b.shape.radius);
      return {x - r, y - r, x + r, y + r};
    }
    std::array<double, 4> box{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
                              -std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
    for (const Vec2<T>& v : b.shape.world) {
      const double x = to_double(v.x), y = to_double(v.y);
      box[0] = std::min(box[0], x); box[1] = std::min(box[1], y);
      box[2] = std::max(box[2], x); box[3] = std::max(box[3], y);
    }
    return box;
  }

  // Takes body i out of the grid for good: it becomes every body's candidate and they its.
  // The caller reschedules it (a full scan) if it is moving.
  void make_global(BodyIndex i) {
    if (!bodies[i].fixed && bodies[i].cell < kOutside) grid.remove(bodies[i].cell, i);
    bodies[i].cell = kGlobal;
    globals.push_back(i);
    ++counts.global_bodies;
    if (!bodies[i].fixed) heap.set_crossing(i, EventHeap<T>::never());
  }

  // The time of moving body i's next cell crossing from time `from` (its position then is
  // inside its cell's exit box; never() if none before the horizon or if it is global), or
  // makes it global (and answers never()) where double cell arithmetic cannot be trusted to
  // an eighth of the margin until then: its position evaluated in T and in double, and the
  // crossing's time rounded to T, each off by at most a few ulps of the terms' magnitudes.
  T crossing_time(BodyIndex i, const T& from) {
    if (bodies[i].cell == kGlobal) return EventHeap<T>::never();
    const Body& b = bodies[i];
    const Kinematics<T> k = kinematics(b, from);
    double lo_x, lo_y, hi_x, hi_y;
    grid.exit_box(bodies[i].cell, lo_x, lo_y, hi_x, hi_y);
    const double px = to_double(k.p.x), py = to_double(k.p.y), vx = to_double(k.v.x), vy = to_double(k.v.y);
    const double ax = to_double(k.a.x), ay = to_double(k.a.y);
    const double limit = to_double(horizon - from);
    std::optional<double> s = earliest_exit(px, vx, ax / 2, lo_x, hi_x, limit);
    const std::optional<double> sy = earliest_exit(py, vy, ay / 2, lo_y, hi_y, limit);
    if (sy && (!s || *sy < *s)) s = sy;
    using std::abs;
    const double until = s ? *s : std::max(limit, 0.0);
    const double tau = to_double(from - b.t0) + until;
    const double eps = std::max(static_cast<double>(std::numeric_limits<T>::epsilon()), 0x1p-52);
    const double speed = std::abs(vx) + std::abs(vy) + (std::abs(ax) + std::abs(ay)) * until;
    const double scale = std::max(std::abs(lo_x), std::abs(hi_x)) + std::max(std::abs(lo_y), std::abs(hi_y)) +
                         to_double(abs(b.p0.x) + abs(b.p0.y)) +
                         to_double(abs(b.v0.x) + abs(b.v0.y)) * tau +
                         to_double(abs(b.acc.x) + abs(b.acc.y)) * tau * tau / 2 +
                         speed * (to_double(abs(from)) + until);
    if (!(8 * eps * scale <= grid.margin() / 8)) {
      make_global(i);
      return EventHeap<T>::never();
    }
    return s ? from + T(*s) : EventHeap<T>::never();
  }

  // Moving body i's crossing at `at`: it moves to the cell it is in then, and is predicted
  // against the bodies around that cell that were not around the old one. No motion changes, so
  // nothing else is predicted again, and the predictions are made from `now` (the last event's
  // time, at or before `at`), which the pair's paths are known from: they cannot touch before
  // `at`, where they were not neighbours.
  void cross(BodyIndex i, const T& at) {
    ++counts.crossings;
    const std::uint32_t old = bodies[i].cell;
    const Kinematics<T> k = kinematics(bodies[i], at);
    const std::uint32_t c = grid.cell_of(to_double(k.p.x), to_double(k.p.y));
    if (c == kGlobal || c == old) {  // out of the grid, or not past the exit box: global
      make_global(i);
      reschedule(i);
      return;
    }
    // The old cell, the new one and the new neighbours, requested at once.
    if (prefetching) grid.prefetch_around(c);
    grid.remove(old, i);
    grid.insert(c, i);
    bodies[i].cell = c;
    Scheduled<T> best = heap.at(i);
    auto f = [&](BodyIndex j) { offer(i, j, best); };
    visit_cells(i, c, old, f);
    const T next = crossing_time(i, at);
    heap.set(i, best, next);
    if (bodies[i].cell == kGlobal) reschedule(i);
  }

  // ---- Resting contact (DESIGN.md): a contact state instead of a storm of zero-time events.

  // The largest normal speed w off face body f, pressed by acc_normal, that is rounding noise
  // for the moving body m. Inelastic (restitution < 1): a rise w^2 / (2 |a_n|) below
  // kRestHeightUlps ulps of m's coordinate scale (the rounding of its own position): a Zeno
  // sequence of bounces ends there, after finitely many. Elastic (restitution 1): only a normal
  // speed within kRestHeightUlps ulps of m's speed, the rounding of its velocity, so that no
  // energy an elastic bounce would keep is taken away.
  T rest_speed(const Body& m, BodyIndex f, const T& acc_normal) const {
    using std::abs;
    using std::sqrt;
    const T ulps = T(kRestHeightUlps) * std::numeric_limits<T>::epsilon();
    if (std::min(m.restitution, bodies[f].restitution) < T(1))
      return sqrt(T(2) * abs(acc_normal) * ulps * m.shape.coordinate_scale(kinematics(m, now).p));
    return ulps * sqrt(dot(m.v0, m.v0));
  }

  // The face of fixed body `f` whose outward normal is (within kRestNormalTolerance) the unit
  // normal `n` and which holds the contact point; nothing when the contact is on a vertex only.
  std::optional<Support> face_of(BodyIndex f, const Vec2<T>& n, const Vec2<T>& point) const {
    const BodyShape<T>& shape = bodies[f].shape;
    if (!shape.is_outline()) return std::nullopt;  // curved: resting on it is not a straight path
    std::optional<Support> best;
    T best_cos{};
    for (std::size_t k = 0; k < shape.edges.size(); ++k) {
      const T len = shape.edge_length[k];
      if (!(len > T(0))) continue;
      // Divided, not multiplied by 1 / len: an axis-aligned edge's direction is then exactly a
      // unit axis, so the resting body's projected acceleration has no normal part at all (with
      // the reciprocal, a floor of length 7.98828125 gave (-0.9999999999999999, 0), and a ball
      // resting on it sank by 4e-16 in 4 s: found by the tile-joint motif).
      const Vec2<T> u{shape.edges[k].x / len, shape.edges[k].y / len};
      const Vec2<T> out{u.y, -u.x};  // outward for counter-clockwise outlines; a segment has both sides
      const T c = dot(out, n);
      if (!(c >= T(1) - T(kRestNormalTolerance))) continue;
      const T s = dot(point - shape.world[k], u);
      const T slack = T(kRestNormalTolerance) * len;
      if (s < -slack || s > len + slack) continue;
      if (best && !(c > best_cos)) continue;
      best_cos = c;
      best = Support{f, out, shape.world[k], u, len, T(0), T(0)};
    }
    return best;
  }

  // A resting body's contact interval along the face: a circle touches at its centre's
  // projection; a polygon along its vertices lowest towards the face.
  static void contact_span(const Body& m, Support& s) {
    if (!m.shape.is_outline()) return;
    T low = std::numeric_limits<T>::infinity();
    for (const Vec2<T>& v : m.shape.local) low = std::min(low, dot(v, s.n));
    const T tol = T(kRestVertexTolerance) * m.shape.size;
    bool first = true;
    for (const Vec2<T>& v : m.shape.local) {
      if (dot(v, s.n) > low + tol) continue;
      const T along = dot(v, s.u);
      s.s_lo = first ? along : std::min(s.s_lo, along);
      s.s_hi = first ? along : std::max(s.s_hi, along);
      first = false;
    }
  }

  // Adjacent times tried past a leave's rounded root before it is taken as it is.
  static constexpr int kLeaveSteps = 64;

  // When a resting body's contact interval leaves its face (it slides past an end), or nothing
  // before the horizon. Along the face, s(t) = (p(t) - origin) . u is at most quadratic.
  std::optional<T> leave_time(const Body& m, const Support& s) const {
    const Kinematics<T> k = kinematics(m, now);
    const T c0 = dot(k.p - s.origin, s.u), c1 = dot(k.v, s.u), c2 = dot(k.a, s.u) / T(2);
    std::optional<T> out;
    // Off the start: s + s_hi falls below 0. Off the end: length - (s + s_lo) falls below 0.
    const Poly<T> polys[2] = {Poly<T>{{c0 + s.s_hi, c1, c2, T(0), T(0)}, 2},
                              Poly<T>{{s.length - s.s_lo - c0, -c1, -c2, T(0), T(0)}, 2}};
    for (int end = 0; end < 2; ++end) {
      const Poly<T>& p = polys[end];
      if (never_decreasing(p) && p.c[0] >= T(0)) continue;
      const RootOutcome<T> r = earliest_downward_root(solver, p, T(0), horizon - now);
      if (r.status != RootStatus::Root) continue;
      // The first time the body is past the end as the engine rounds its position: exactly at
      // the end it still touches the face's edge with no normal speed, a contact at the very
      // instant it leaves, predicted again after every such graze.
      T t = now + r.t;
      auto past = [&](const T& at) {
        const T along = dot(kinematics(m, at).p - s.origin, s.u);
        return end == 0 ? along + s.s_hi < T(0) : along + s.s_lo > s.length;
      };
      for (int step = 0; step < kLeaveSteps && !past(t); ++step) t = boost::math::float_next(t);
      if (!out || t < *out) out = t;
    }
    return out;
  }

  // Which of a body's faces hold it, from its field acceleration: the faces pressed with a
  // non-negative reaction (at most two constraints in 2-D, tried from none to both), the path's
  // acceleration without their components, and its velocity without its normal components.
  // Faces that do not press are dropped.
  void resolve_supports(Body& m) {
    const Vec2<T> a = m.field_acc;
    auto project = [](const Vec2<T>& x, const Vec2<T>& n) { return x - n * dot(x, n); };
    int keep_mask = 0;
    Vec2<T> acc = a;
    if (m.supports == 1) {
      if (dot(a, m.support[0].n) < T(0)) {
        keep_mask = 1;
        acc = project(a, m.support[0].n);
      }
    } else if (m.supports == 2) {
      const Vec2<T> n0 = m.support[0].n, n1 = m.support[1].n;
      const Vec2<T> a0 = project(a, n0), a1 = project(a, n1);
      if (dot(a, n0) >= T(0) && dot(a, n1) >= T(0)) {
        keep_mask = 0;
      } else if (dot(a, n0) < T(0) && dot(a0, n1) >= T(0)) {
        keep_mask = 1;
        acc = a0;
      } else if (dot(a, n1) < T(0) && dot(a1, n0) >= T(0)) {
        keep_mask = 2;
        acc = a1;
      } else {
        keep_mask = 3;  // pressed into both faces: held still
        acc = Vec2<T>{};
      }
    }
    int kept = 0;
    for (int k = 0; k < m.supports; ++k)
      if (keep_mask & (1 << k)) m.support[static_cast<std::size_t>(kept++)] = m.support[static_cast<std::size_t>(k)];
    m.supports = static_cast<std::uint8_t>(kept);
    m.acc = acc;
    if (kept == 2) {
      m.v0 = Vec2<T>{};
    } else if (kept == 1) {
      const Vec2<T> n = m.support[0].n;
      const Vec2<T> v = m.v0;
      m.v0 = project(v, n);
      // A tilted face's unit normal is rounded, and so are the projections: their normal
      // components are rounding, up to a few ulps of |a| and |v|, and over time would carry the
      // body into the face, where no contact is predicted (found by fuzz_engine under an
      // acceleration of 9e9: fixtures/regressions/rest-on-a-tilted-face-drifts-in.json). Both
      // are lifted off the face by kRestLiftUlps ulps of the unprojected magnitudes, more than
      // that rounding: the body can then only drift off the face by as much, a gap, never an
      // overlap. An axis-aligned face projects exactly and is left alone.
      if (n.x != T(0) && n.y != T(0)) {
        using std::sqrt;
        const T lift = T(kRestLiftUlps) * std::numeric_limits<T>::epsilon();
        m.acc += n * (lift * sqrt(dot(a, a)));
        m.v0 += n * (lift * sqrt(dot(v, v)));
      }
    }
  }

  // After a collision changed moving body m's velocity (rebased to now): faces it rested on and
  // now leaves or is pushed into by more than a rest speed stop holding it (a push into a face
  // is the face's own contact, found at once by the next prediction); then, if the contact was
  // with a fixed face that presses it and its bounce off that face would be rounding noise, it
  // rests on that face too.
  void update_rest(BodyIndex mi, BodyIndex partner, const Vec2<T>& normal_to_m, const Vec2<T>& point) {
    Body& m = bodies[mi];
    int kept = 0;
    for (int k = 0; k < m.supports; ++k) {
      const Support& s = m.support[static_cast<std::size_t>(k)];
      using std::abs;
      // Hit by another moving body: the face keeps holding it only if the hit left its normal
      // speed exactly zero; removing any normal speed there would change the two bodies'
      // momentum inside their own collision (found by fuzz_engine,
      // fixtures/regressions/rest-snap-in-a-two-body-collision.json). A normal speed left is
      // the face's own contact to settle, at once, as a contact with the face.
      const T w = dot(m.v0, s.n);
      const bool keep = bodies[partner].fixed ? abs(w) <= rest_speed(m, s.body, dot(m.field_acc, s.n)) : w == T(0);
      if (keep) m.support[static_cast<std::size_t>(kept++)] = s;
    }
    m.supports = static_cast<std::uint8_t>(kept);
    if (bodies[partner].fixed && !m.rests_on(partner) && m.supports < 2) {
      using std::sqrt;
      const T len = sqrt(dot(normal_to_m, normal_to_m));
      if (len > T(0)) {
        if (std::optional<Support> f = face_of(partner, normal_to_m * (T(1) / len), point)) {
          const T pressing = dot(m.acc, f->n);  // the path's: a face already held counts
          contact_span(m, *f);
          // Not at a face's end on the way off it (just slid off it, say): that is a graze of
          // the face's end vertex, not a rest.
          const std::optional<T> off = pressing < T(0) ? leave_time(m, *f) : std::nullopt;
          if (pressing < T(0) && dot(m.v0, f->n) <= rest_speed(m, partner, pressing) && !(off && *off <= now)) {
            m.support[static_cast<std::size_t>(m.supports++)] = *f;
            ++counts.rests;
          }
        }
      }
    }
    resolve_supports(m);  // with no face left: the field's acceleration again
  }

  // Whether fixed body j continues a face that the resting body m slides on: an edge of j on the
  // face's line, both its ends exactly (cross(x - origin, u) == 0 in T: exact for axis-aligned
  // faces; a tilted face's rounded direction rarely passes), running the same way, so with the
  // same outward normal (floor tiles, boxes side by side). j is convex, so it lies wholly behind
  // that line, and m, which moves along it, can meet j only on the line: a joint, never an
  // approach. Predicted, the rounding of m's height made contacts there (a ball landed an ulp
  // deep struck the next tile's corner in a storm of 3e-8 impulses). The oracle skips the same
  // pairs (oracle/src/search.cpp, flush_with_support).
  bool continues_support(const Body& m, const Body& j) const {
    if (m.supports == 0 || !j.fixed || !j.shape.is_outline()) return false;
    const BodyShape<T>& shape = j.shape;
    for (int k = 0; k < m.supports; ++k) {
      const Support& f = m.support[static_cast<std::size_t>(k)];
      const auto on_line = [&](const Vec2<T>& x) { return pge::cross(x - f.origin, f.u) == T(0); };
      for (std::size_t e = 0; e < shape.edges.size(); ++e)
        if (dot(shape.edges[e], f.u) > T(0) && on_line(shape.world[e]) && on_line(shape.world[(e + 1) % shape.world.size()]))
          return true;
    }
    return false;
  }

  // The fixed face that continues `old` past the end the resting body m is leaving it by (floor
  // tiles, boxes side by side): the same outward normal, holding the end point, its line through
  // that point within the rounding of m's position (kRestHeightUlps ulps of its coordinate
  // scale; a step is a real contact, left to the predictions). Nothing if there is none.
  std::optional<Support> continuing_face(BodyIndex mi, const Support& old) {
    using std::abs;
    const Body& m = bodies[mi];
    const Vec2<T> p = kinematics(m, now).p;
    const bool off_end = dot(p - old.origin, old.u) + old.s_lo > old.length;
    const Vec2<T> end = off_end ? old.origin + old.u * old.length : old.origin;
    const T tolerance = T(kRestHeightUlps) * std::numeric_limits<T>::epsilon() * m.shape.coordinate_scale(p);
    std::optional<Support> next;
    for_candidates(mi, [&](BodyIndex j) {
      if (next || j == old.body || !bodies[j].fixed) return;
      const std::optional<Support> f = face_of(j, old.n, end);
      if (f && abs(dot(end - f->origin, f->n)) <= tolerance) next = f;
    });
    if (next) contact_span(m, *next);
    return next;
  }

  // A resting body slides off its face's end: the face stops holding it, and a face that
  // continues it holds it instead (without this a ball crossing the joint of two collinear
  // segments collided with the first one's end in a storm of zero impulses: the contact point an
  // ulp past its end still counts as on its edge, and a face's end is no place to rest).
  void leave(const Scheduled<T>& s, BodyIndex owner) {
    Body& m = bodies[owner];
    rebase(m, now);
    const std::size_t k = s.feature_a;
    if (k < static_cast<std::size_t>(m.supports) && m.support[k].body == s.partner) {
      const Support old = m.support[k];
      for (std::size_t j = k; j + 1 < static_cast<std::size_t>(m.supports); ++j) m.support[j] = m.support[j + 1];
      --m.supports;
      if (const std::optional<Support> next = continuing_face(owner, old); next && !m.rests_on(next->body)) {
        m.support[static_cast<std::size_t>(m.supports++)] = *next;
        ++counts.rests;
      }
    }
    resolve_supports(m);
    ++m.version;
    ++counts.leaves;
    reschedule(owner);
  }

  // Initial schedule: each pair predicted once, offered to both of its bodies (with the grid:
  // each moving body's candidates, a pair of moving bodies predicted from both sides).
  void schedule_all() {
    if (grid_on) {
      for (BodyIndex i : moving) reschedule(i);
      return;
    }
    std::vector<Scheduled<T>> best(bodies.size());
    for (BodyIndex i = 0; i < bodies.size(); ++i) {
      for (BodyIndex j = i + 1; j < bodies.size(); ++j) {
        auto c = predict(i, j);
        if (!c) continue;
        Scheduled<T> s{c->time, i, j, c->contact, c->feature_a, c->feature_b, c->at_start_overlap, c->corner, j,
                       bodies[j].version};
        if (!bodies[i].fixed && s.key_less(best[i])) best[i] = s;
        s.partner = i;
        s.partner_version = bodies[i].version;
        if (!bodies[j].fixed && s.key_less(best[j])) best[j] = s;
      }
    }
    for (BodyIndex i : moving) heap.set(i, best[i]);
  }

  void note_storm(BodyIndex i, BodyIndex partner) {
    Body& b = bodies[i];
    using std::abs;
    const T window = T(kStormWindowRelative) * std::max(T(1), abs(now));
    if (b.storm_count > 0 && now - b.storm_start <= window) {
      ++b.storm_count;
    } else {
      b.storm_start = now;
      b.storm_count = 1;
    }
    if (b.storm_count > kStormCollisions && !finished) {
      storm = {now, std::min(i, partner), std::max(i, partner), b.storm_count};
      reason = StopReason::EventStorm;
      finished = true;
    }
  }

  void collide(const Scheduled<T>& s) {
    Body& a = bodies[s.lo];
    Body& b = bodies[s.hi];
    // Both bodies' candidates are requested before either is predicted again (their cells'
    // records were requested when this event reached the top).
    if (grid_on && prefetching) {
      if (!a.fixed) prefetch_candidates(s.lo);
      if (!b.fixed) prefetch_candidates(s.hi);
    }
    rebase(a, now);
    rebase(b, now);
    const Kinematics<T> ka = kinematics(a, now), kb = kinematics(b, now);
    const PredictedContact<T> contact{now, s.contact, s.feature_a, s.feature_b, s.at_start_overlap, s.corner};
    const ContactGeometry<T> g = contact_geometry(contact, a.shape, ka, b.shape, kb);

    CollisionInfo<T> info;
    info.time = now;
    info.a = s.lo;
    info.b = s.hi;
    info.contact = s.contact;
    info.feature_a = s.contact == ContactKind::EdgeVertex ? public_edge(a.shape, s.feature_a) : s.feature_a;
    info.feature_b = s.contact == ContactKind::VertexEdge ? public_edge(b.shape, s.feature_b) : s.feature_b;
    info.corner = s.corner;
    info.point = g.point;
    info.gap = g.gap;
    info.at_start_overlap = s.at_start_overlap;
    info.va_before = ka.v;
    info.vb_before = kb.v;

    // Impulse along the (unnormalised) normal n: j = -(1 + e) (v_rel . n) / (n . n (1/ma + 1/mb)).
    // An axis-aligned normal is replaced by the exact unit vector along it first: equal masses
    // along an axis then swap their velocities exactly, as a Newton's cradle must, where
    // v.n / n.n * n with a normal such as (0.2000000000000000111, 0) left a rounding residue that
    // set resting balls moving (fixtures/scenes/simultaneous/cradle-10-decimal.json). Other
    // normals keep their length: a diagonal one such as (-1, 1) is exact as it is, and its
    // unit vector would not be.
    using std::sqrt;
    Vec2<T> n = g.normal;
    if (n.y == T(0) && n.x != T(0)) n = Vec2<T>{n.x > T(0) ? T(1) : T(-1), T(0)};
    if (n.x == T(0) && n.y != T(0)) n = Vec2<T>{T(0), n.y > T(0) ? T(1) : T(-1)};
    const T nn = dot(n, n);
    const T vn = dot(kb.v - ka.v, n);
    const T n_len = sqrt(nn);
    info.normal = n_len > T(0) ? n * (T(1) / n_len) : n;
    info.approach_speed = n_len > T(0) ? -vn / n_len : T(0);
    const T inv_sum = a.inv_mass + b.inv_mass;
    if (vn < T(0) && nn > T(0) && inv_sum > T(0)) {
      const T e = std::min(a.restitution, b.restitution);
      const T j = -(T(1) + e) * vn / (nn * inv_sum);
      a.v0 -= n * (j * a.inv_mass);
      b.v0 += n * (j * b.inv_mass);
      info.impulse = j * n_len;
      ++counts.collisions;
      if (s.at_start_overlap) ++counts.overlap_starts;
    } else {
      ++counts.grazes;  // predicted, but not approaching at the contact: no impulse is due
    }
    // Resting contact: faces that stop holding a body, and a face that starts to.
    if (!a.fixed) update_rest(s.lo, s.hi, -g.normal, g.point);
    if (!b.fixed) update_rest(s.hi, s.lo, g.normal, g.point);
    info.va_after = a.v0;
    info.vb_after = b.v0;

    const Overlap o = measure_overlap(-g.gap, g.contact_distance, rounding_scale(a.shape, ka, b.shape, kb, now), s.lo, s.hi);
    if (o.ulps > worst_contact.ulps) worst_contact = o;
    ++a.version;
    ++b.version;
    if (!a.fixed) note_storm(s.lo, s.hi);
    if (!b.fixed) note_storm(s.hi, s.lo);
    if (!a.fixed) reschedule(s.lo);
    if (!b.fixed) reschedule(s.hi);
    if (on_collision) on_collision(info);
    if (max_events > 0 && counts.collisions + counts.grazes >= max_events && !finished) {
      reason = StopReason::MaxEvents;
      finished = true;
    }
  }

  // The length at which a pair's contact is rounded, in units of epsilon: its largest coordinate
  // magnitude (vertices included), plus how far it closes in the time it takes the clock to
  // move by its relative precision (an event time t is rounded to ulp(t), in which the pair
  // closes |v_rel| ulp(t)); a long run is as precise as its clock.
  static T rounding_scale(const BodyShape<T>& sa, const Kinematics<T>& ka, const BodyShape<T>& sb,
                          const Kinematics<T>& kb, const T& t) {
    using std::abs;
    using std::sqrt;
    const Vec2<T> dv = kb.v - ka.v;
    return pair_scale(sa, ka.p, sb, kb.p) + sqrt(dot(dv, dv)) * abs(t);
  }

  // Overlap depth as a fraction of the contact distance and in units of the pair's rounding:
  // epsilon * (rounding scale + contact distance).
  static Overlap measure_overlap(const T& depth, const T& contact_distance, const T& scale, BodyIndex a, BodyIndex b) {
    if (!(depth > T(0))) return {};
    const T unit = std::numeric_limits<T>::epsilon() * (scale + contact_distance);
    return {depth, depth / contact_distance, depth / unit, a, b};
  }

#ifdef PGE_VALIDATE
  // Expensive validation (PGE_VALIDATE builds): after every event, time has not gone back,
  // every moving body's state is finite, and (for scenes small enough to scan every event) no
  // pair overlaps past the bound; otherwise the scan runs every 1024th event.
  T last_validated_time{};
  std::uint64_t validations = 0;
  T start_overlap_depth{};  // the scene's overlap at the start, allowed to stay (overlap_past_bound)
  // The overlap scan is O(n^2): past this many bodies it would take longer than the run.
  static constexpr std::size_t kValidateScanMaxBodies = 5000;
  void validate(const World& self) {
    using std::isfinite;
    if (now < last_validated_time) throw std::logic_error("PGE_VALIDATE: time went backwards");
    last_validated_time = now;
    for (BodyIndex i : moving) {
      const Kinematics<T> k = kinematics(bodies[i], now);
      if (!(isfinite(k.p.x) && isfinite(k.p.y) && isfinite(k.v.x) && isfinite(k.v.y)))
        throw std::logic_error("PGE_VALIDATE: body \"" + bodies[i].id + "\" has a non-finite state");
    }
    if (bodies.size() <= 200 || (bodies.size() <= kValidateScanMaxBodies && (++validations & 1023) == 0)) {
      const Overlap o = self.largest_overlap();
      if (overlap_past_bound(to_double(o.ulps), to_double(o.depth), to_double(start_overlap_depth)))
        throw std::logic_error("PGE_VALIDATE: bodies \"" + bodies[o.a].id + "\" and \"" + bodies[o.b].id +
                               "\" overlap past the bound");
    }
  }
#endif

  // Every moving body's path, from one motion change to the next, tested against the fixed
  // bodies just before it changes and at the end of the run (WorldOptions::watch_tunnels; always
  // in PGE_VALIDATE builds, which stop a solver that promises every collision at the first
  // pass-through).
#ifdef PGE_VALIDATE
  static constexpr bool kValidating = true;
#else
  static constexpr bool kValidating = false;
#endif
  std::optional<TunnelWatch<T>> tunnel_watch;
  bool tunnels_finished = false;
  // Body i's motion is about to change at `now` (or the run ends). Its path since t0 is tested
  // (rebase() moves t0 only when the motion changes); a moving segment has no interior point.
  void watch_path(BodyIndex i) {
    if (!tunnel_watch) return;
    const Body& b = bodies[i];
    if (b.fixed || b.shape.kind == ShapeKind::Segment) return;
    const Vec2d offset = b.shape.kind == ShapeKind::Polygon ? vertex_centroid(b.shape.local) : Vec2d{};
    if (!tunnel_watch->leave(i, offset, b.t0, b.p0, b.v0, b.acc, now)) return;
    if (!kValidating || !promises_every_collision(solver)) return;
    const Tunnel& t = tunnel_watch->tunnels().back();
    throw TunnelError(t, "PGE_VALIDATE: " + tunnel_text(t, bodies[t.body].id, bodies[t.fixed].id));
  }
  void watch_end() {
    if (!tunnel_watch || tunnels_finished) return;
    tunnels_finished = true;
    for (BodyIndex i : moving) watch_path(i);
  }

  T frame_time(std::uint64_t k) const { return T(static_cast<double>(k)) / T(fps); }
};

template <class T> World<T>::World(const Scene& scene, const WorldOptions& options) : impl_(std::make_unique<Impl>()) {
  BroadPhase mode = options.broad_phase;
  if (mode == BroadPhase::Auto) {
    const char* env = std::getenv("PGE_BROAD_PHASE");
    if (env && *env && !parse_broad_phase(env, mode))
      throw std::invalid_argument(std::string("PGE_BROAD_PHASE: expected auto, grid or all-pairs, got \"") + env + "\"");
  }
  if (auto problem = validate_scene(scene)) {
    std::string where = problem->body >= 0 ? "body \"" + scene.bodies[problem->body].id + "\": " : "";
    throw std::invalid_argument(where + problem->field + ": " + problem->message);
  }
  if (scene.bodies.size() > kMaxBodies)
    throw UnsupportedScene(-1, std::to_string(scene.bodies.size()) + " bodies: at most " + std::to_string(kMaxBodies));
  if (mode == BroadPhase::AllPairs && scene.bodies.size() > kMaxBodiesWithoutBroadPhase)
    throw UnsupportedScene(-1, std::to_string(scene.bodies.size()) + " bodies: at most " +
                                   std::to_string(kMaxBodiesWithoutBroadPhase) +
                                   " without the broad phase (every pair is predicted once at the start)");
  Impl& w = *impl_;
  w.horizon = T(options.until >= 0 ? options.until : scene.run.until);
  w.solver = options.solver.value_or(scene.run.solver);
  w.max_events = options.max_events > 0 ? options.max_events : scene.run.max_events;
  w.fps = options.frames_per_second >= 0 ? options.frames_per_second : scene.run.frames_per_second;
  // The overrides get the scene's own checks (validate_scene): a horizon in the supported
  // range, and a bounded number of frames, which max_events does not limit.
  const double until = options.until >= 0 ? options.until : scene.run.until;
  auto shortest = [](double x) {
    std::ostringstream s;
    s << x;
    return s.str();
  };
  if (!(until <= kMaxSceneMagnitude))
    throw std::invalid_argument("until: out of the supported range: at most " + shortest(kMaxSceneMagnitude) +
                                " seconds, got " + shortest(until));
  if (!(std::isfinite(w.fps) && w.fps * until <= kMaxFramesPerRun))
    throw std::invalid_argument("frames per second: " + shortest(w.fps) + " gives more than the supported " +
                                shortest(kMaxFramesPerRun) + " frames over " + shortest(until) + " s");
  w.bodies.reserve(scene.bodies.size());
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    const BodyDesc& d = scene.bodies[i];
    typename Impl::Body b;
    b.id = d.id;
    b.shape = make_body_shape<T>(d);
    b.fixed = d.fixed;
    b.mass = d.fixed ? T(0) : T(d.mass);
    b.inv_mass = d.fixed ? T(0) : T(1) / T(d.mass);
    b.restitution = T(d.restitution >= 0 ? d.restitution : scene.world.restitution);
    b.p0 = vec_cast<T>(d.position);
    if (!d.fixed) {
      b.v0 = vec_cast<T>(d.velocity);
      const Vec2d total = d.acceleration + (d.gravity ? scene.world.gravity : Vec2d{});
      b.acc = vec_cast<T>(total);
      b.field_acc = b.acc;
      w.moving.push_back(static_cast<BodyIndex>(i));
    }
    w.bodies.push_back(std::move(b));
  }
  w.heap.reset(w.bodies.size(), w.moving);
  w.prefetching = w.bodies.size() >= Impl::kPrefetchMinBodies;
  w.heap.set_prefetching(w.prefetching);
  w.setup_grid(mode);
  w.schedule_all();
#ifdef PGE_VALIDATE
  if (w.bodies.size() <= Impl::kValidateScanMaxBodies) w.start_overlap_depth = largest_overlap().depth;
#endif
  if (options.watch_tunnels || Impl::kValidating) w.tunnel_watch.emplace(scene);
}

template <class T> World<T>::~World() = default;
template <class T> World<T>::World(World&&) noexcept = default;
template <class T> World<T>& World<T>::operator=(World&&) noexcept = default;

template <class T> void World<T>::on_collision(CollisionCallback cb) { impl_->on_collision = std::move(cb); }
template <class T> void World<T>::on_frame(FrameCallback cb) { impl_->on_frame = std::move(cb); }
template <class T> void World<T>::on_motion_change(MotionCallback cb) { impl_->on_motion_change = std::move(cb); }
template <class T> void World<T>::add_timer(T time, TimerCallback cb) {
  if (time < impl_->now || time > impl_->horizon) return;
  impl_->timers.push({time, impl_->timer_seq++, std::move(cb)});
}

template <class T> bool World<T>::step() {
  Impl& w = *impl_;
  while (!w.finished) {
    if (w.stop_requested) {
      w.reason = StopReason::Stopped;
      w.finished = true;
      break;
    }
    // The three sources, merged in the fixed order: time, then kind (collision, timer, frame).
    // When the heap's earliest event is a cell crossing, every contact is at or after it.
    const bool crossing_first = !w.heap.empty() && w.heap.top_is_crossing();
    // The events after this one are most likely its children's in the heap: their entries and
    // bodies are fetched while this one is processed (with 1e5 bodies each is a cache miss).
    if (w.prefetching) {
      w.heap.visit_next([&](BodyIndex j, BodyIndex partner) {
        w.heap.prefetch(j);
        Impl::prefetch_hot(w.bodies[j]);
        if (partner == kNoBody) return;
        w.heap.prefetch(partner);
        Impl::prefetch_hot(w.bodies[partner]);
      });
    }
    const Scheduled<T>* contact = w.heap.empty() || crossing_first ? nullptr : &w.heap.top();
    const bool has_contact = contact && contact->valid();
    // This event's bodies, fetched one step ago, name their cells: the cells' records are
    // fetched now, while the event's time is re-derived and its impulse applied.
    if (has_contact && w.grid_on && w.prefetching) {
      w.prefetch_cells(w.heap.top_index());
      w.prefetch_cells(contact->partner);
    }
    const bool has_timer = !w.timers.empty();
    const bool has_frame = w.fps > 0 && w.frame_time(w.next_frame) <= w.horizon;
    // A cell crossing due no later than every other event is bookkeeping: no motion changes
    // and the clock stays where it is (cross()). Robust and certified take crossings up to the
    // refinement bound past the horizon, so that a contact predicted there (behind the
    // crossing in the heap) is still re-derived exactly below.
    if (crossing_first) {
      const T at = w.heap.top_time();
      const T last = w.solver == SolverKind::Fast ? w.horizon : Impl::refine_bound(w.horizon);
      if (at <= last && (!has_timer || !(w.timers.top().time < at)) && (!has_frame || !(w.frame_time(w.next_frame) < at))) {
        w.cross(w.heap.top_index(), at);
        continue;
      }
    }
    T best = std::numeric_limits<T>::infinity();
    EventKind kind = EventKind::Collision;
    // Robust and certified: a contact predicted just past the horizon is re-derived exactly
    // before the horizon check (its exact time may be the horizon).
    if (has_contact && w.solver != SolverKind::Fast && !contact->refined && contact->time > w.horizon &&
        contact->time <= Impl::refine_bound(w.horizon) && w.refine_near_top())
      continue;
    if (has_contact) best = contact->time;
    if (has_timer && w.timers.top().time < best) { best = w.timers.top().time; kind = EventKind::Timer; }
    if (has_frame && w.frame_time(w.next_frame) < best) { best = w.frame_time(w.next_frame); kind = EventKind::Frame; }
    if (!(best <= w.horizon)) {
      w.now = w.horizon;
      w.reason = StopReason::ReachedUntil;
      w.finished = true;
      break;
    }
    if (kind == EventKind::Collision && contact->leave) {
      const Scheduled<T> s = *contact;
      const BodyIndex owner = w.heap.top_index();
      w.now = std::max(w.now, s.time);
      w.watch_path(owner);
      w.leave(s, owner);
      if (w.on_motion_change) w.on_motion_change(owner, w.now);
      continue;
    }
    if (kind == EventKind::Collision) {
      const Scheduled<T> s = *contact;
      const BodyIndex owner = w.heap.top_index();
      const auto& partner = w.bodies[s.partner];
      if (!partner.fixed && partner.version != s.partner_version) {
        ++w.counts.stale;  // the partner moved differently since this was predicted
        w.reschedule(owner);
        continue;
      }
      // Robust and certified: the event's time, and the time of every other contact that might
      // be the same instant or earlier, are re-derived from the exact paths before any is
      // processed; then the queue is merged again (see refine_near_top).
      if (w.solver != SolverKind::Fast && w.refine_near_top()) continue;
      // A contact exactly at the horizon counts only if it is a collision: the solvers take a
      // touch arriving at the horizon as a root (what follows it is beyond the run), but one
      // that is not approaching there is a graze, which is no event (the oracle agrees). The
      // run ends instead of reporting a zero-impulse event.
      if (s.time >= w.horizon && !w.collides_at_horizon(s)) {
        w.now = w.horizon;
        w.reason = StopReason::ReachedUntil;
        w.finished = true;
        break;
      }
      w.now = std::max(w.now, s.time);
      w.watch_path(owner);
      w.watch_path(s.partner);
      w.collide(s);
#ifdef PGE_VALIDATE
      w.validate(*this);
#endif
      return true;
    }
    if (kind == EventKind::Timer) {
      typename Impl::Timer t = w.timers.top();
      w.timers.pop();
      w.now = std::max(w.now, t.time);
      ++w.counts.timers;
      t.callback(*this, w.now);
      return true;
    }
    w.now = std::max(w.now, best);
    ++w.next_frame;
    ++w.counts.frames;
    if (w.on_frame) w.on_frame(*this, w.now);
    return true;
  }
  w.watch_end();
  return false;
}

template <class T> StopReason World<T>::run() {
  while (step()) {
  }
  return impl_->reason;
}

template <class T> void World<T>::stop() { impl_->stop_requested = true; }
template <class T> T World<T>::time() const { return impl_->now; }
template <class T> T World<T>::horizon() const { return impl_->horizon; }
template <class T> StopReason World<T>::stop_reason() const { return impl_->reason; }
template <class T> const StormInfo<T>& World<T>::storm() const { return impl_->storm; }
template <class T> const EventCounts& World<T>::counts() const { return impl_->counts; }
template <class T> const std::vector<Tunnel>& World<T>::tunnels() const {
  static const std::vector<Tunnel> kNone;
  return impl_->tunnel_watch ? impl_->tunnel_watch->tunnels() : kNone;
}
template <class T> std::size_t World<T>::body_count() const { return impl_->bodies.size(); }
template <class T> const std::string& World<T>::body_id(BodyIndex i) const { return impl_->bodies.at(i).id; }
template <class T> bool World<T>::is_fixed(BodyIndex i) const { return impl_->bodies.at(i).fixed; }
template <class T> T World<T>::mass(BodyIndex i) const { return impl_->bodies.at(i).mass; }

template <class T> BodySnapshot<T> World<T>::snapshot(BodyIndex i) const {
  const Kinematics<T> k = impl_->kinematics(impl_->bodies.at(i), impl_->now);
  return {k.p, k.v};
}

template <class T> BodyMotion<T> World<T>::motion(BodyIndex i) const {
  const auto& b = impl_->bodies.at(i);
  if (b.fixed) return {T(0), b.p0, Vec2<T>{}, Vec2<T>{}};
  BodyMotion<T> m{b.t0, b.p0, b.v0, b.acc};
  for (int k = 0; k < b.supports; ++k) m.supports[static_cast<std::size_t>(k)] = b.support[static_cast<std::size_t>(k)].body;
  return m;
}
template <class T> Vec2<T> World<T>::field_acceleration(BodyIndex i) const {
  const auto& b = impl_->bodies.at(i);
  return b.fixed ? Vec2<T>{} : b.field_acc;
}
template <class T> ShapeKind World<T>::shape(BodyIndex i) const { return impl_->bodies.at(i).shape.kind; }
template <class T> T World<T>::radius(BodyIndex i) const { return impl_->bodies.at(i).shape.radius; }
template <class T> T World<T>::restitution(BodyIndex i) const { return impl_->bodies.at(i).restitution; }
template <class T> const std::vector<Vec2<T>>& World<T>::local_vertices(BodyIndex i) const {
  return impl_->bodies.at(i).shape.local;
}
template <class T> const std::vector<Vec2<T>>& World<T>::world_vertices(BodyIndex i) const {
  return impl_->bodies.at(i).shape.world;
}
template <class T> SolverKind World<T>::solver() const { return impl_->solver; }
template <class T> BroadPhase World<T>::broad_phase() const {
  return impl_->grid_on ? BroadPhase::Grid : BroadPhase::AllPairs;
}

template <class T> std::size_t World<T>::memory_bytes() const {
  const Impl& w = *impl_;
  std::size_t bytes = sizeof(Impl) + w.bodies.capacity() * sizeof(typename Impl::Body);
  for (const auto& b : w.bodies) {
    const auto& s = b.shape;
    bytes += b.id.capacity() > 15 ? b.id.capacity() + 1 : 0;
    bytes += (s.local.capacity() + s.world.capacity() + s.edges.capacity()) * sizeof(Vec2<T>) +
             s.edge_length.capacity() * sizeof(T);
  }
  bytes += w.moving.capacity() * sizeof(BodyIndex) + w.heap.memory_bytes();
  bytes += w.seen.capacity() * sizeof(std::uint32_t) +
           w.globals.capacity() * sizeof(BodyIndex) + w.grid.memory_bytes();
  return bytes;
}

template <class T> void World<T>::set_velocity(BodyIndex i, Vec2<T> velocity) {
  Impl& w = *impl_;
  auto& b = w.bodies.at(i);
  if (b.fixed) throw std::invalid_argument("set_velocity: body \"" + b.id + "\" is fixed");
  w.watch_path(i);
  w.rebase(b, w.now);
  b.v0 = velocity;
  // A new velocity ends the contact state; a face the body still presses on takes it back at
  // once, through its own contact.
  b.supports = 0;
  b.acc = b.field_acc;
  ++b.version;
  w.reschedule(i);
  if (w.on_motion_change) w.on_motion_change(i, w.now);
}

template <class T> T World<T>::kinetic_energy() const {
  T e{};
  for (BodyIndex i : impl_->moving) {
    const auto& b = impl_->bodies[i];
    const Vec2<T> v = impl_->kinematics(b, impl_->now).v;
    e += b.mass * dot(v, v) / T(2);
  }
  return e;
}

template <class T> T World<T>::potential_energy() const {
  T e{};
  for (BodyIndex i : impl_->moving) {
    const auto& b = impl_->bodies[i];
    e -= b.mass * dot(b.field_acc, impl_->kinematics(b, impl_->now).p);
  }
  return e;
}

template <class T> Vec2<T> World<T>::momentum() const {
  Vec2<T> m;
  for (BodyIndex i : impl_->moving) {
    const auto& b = impl_->bodies[i];
    m += impl_->kinematics(b, impl_->now).v * b.mass;
  }
  return m;
}

template <class T> typename World<T>::Overlap World<T>::largest_overlap() const {
  const Impl& w = *impl_;
  Overlap worst;
  for (BodyIndex i = 0; i < w.bodies.size(); ++i) {
    for (BodyIndex j = i + 1; j < w.bodies.size(); ++j) {
      const auto& a = w.bodies[i];
      const auto& b = w.bodies[j];
      if (a.fixed && b.fixed) continue;
      const Kinematics<T> ka = w.kinematics(a, w.now), kb = w.kinematics(b, w.now);
      const Separation<T> sep = separation(a.shape, ka.p, b.shape, kb.p);
      const Overlap o = Impl::measure_overlap(-sep.gap, sep.contact_distance,
                                              Impl::rounding_scale(a.shape, ka, b.shape, kb, w.now), i, j);
      if (o.ulps > worst.ulps) worst = o;
    }
  }
  return worst;
}

template <class T> typename World<T>::Overlap World<T>::largest_contact_overlap() const { return impl_->worst_contact; }

template <class T> std::uint64_t World<T>::state_hash() const {
  StateHasher h;
  h.add(impl_->now);
  for (BodyIndex i = 0; i < impl_->bodies.size(); ++i) {
    const Kinematics<T> k = impl_->kinematics(impl_->bodies[i], impl_->now);
    h.add(k.p.x);
    h.add(k.p.y);
    h.add(k.v.x);
    h.add(k.v.y);
  }
  return h.value();
}

}  // namespace pge
