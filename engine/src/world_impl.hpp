// The event-driven world. Each moving body keeps its own reference time and is brought up to
// date only when an event touches it; each keeps one scheduled event (its earliest predicted
// contact) in an indexed 4-ary heap (event_heap.hpp), and an event whose partner has changed
// since it was predicted is dropped and its owner rescheduled (lazy invalidation by version
// counters). Which pairs a body is predicted against is the broad phase's choice
// (broad_phase.hpp): every body, or the bodies in the grid cells around it; the grid's cell
// crossings, which change no motion, are each body's second event in the same heap.
//
// World<T>::Impl: the state, and each subsystem's members declared with their contracts. Their
// definitions live one file per subsystem, each a part that includes this one:
//   world_events.hpp       the event loop (construction, step) merging contacts, crossings,
//                          timers and frames
//   world_api.hpp          World's other public members (queries, energies, state hash)
//   world_predict.hpp      narrow phase: a pair's earliest contact
//   world_refine.hpp       refinement: scheduled contacts re-derived from the exact paths
//   world_broad_phase.hpp  broad phase and scheduling: candidates, cell crossings, the heap
//   world_rest.hpp         resting contact
//   world_response.hpp     the impulse of a collision, storms, overlap measures
//   world_rotation.hpp     pairs with a rotating body: prediction, impulse, overlap measures
//   world_validate.hpp     PGE_VALIDATE checks and the tunnel watch
// The parts are included by one translation unit per scalar (world_float.cpp,
// world_double.cpp, world_long_double.cpp, world_quad.cpp), each instantiating World for its
// own scalar: one unit of all four took 2.6 minutes to compile under the sanitizers, the
// longest step of the build, while the other core waited.
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

#include "pge/detail/predict_rotating.hpp"
#include "pge/detail/predict_rotating_fast.hpp"
#include "pge/detail/rigid.hpp"
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
    // Turns (docs/rotation.md): its angle, spin and pivot frame are in `spins`, and its path
    // p0, v0, acc is its pivot's. Every pair with such a body is predicted and answered by the
    // rotation subsystem (world_rotation.hpp), never by the translate-only code.
    bool rotates = false;
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

  // A rotating body's turn (docs/rotation.md). The angle is theta0 + omega (t - t0) with the
  // body's t0 (0 for a fixed body), and a vertex of the body is at p(t) + R(angle) vertices[k]:
  // `vertices` are the shape's points about the pivot in the body's frame, `pivot` the pivot
  // relative to the scene's `position` at angle 0 (a moving polygon's centroid, a moving
  // segment's midpoint, zero for a fixed body), so the scene's position is p(t) - R(angle) pivot.
  // A rotating pair's last prediction, kept by its lower body (world_rotation.hpp,
  // predict_rotating): valid while neither body's version has moved.
  struct RotatingMemo {
    BodyIndex partner;                       // the higher body
    std::uint64_t version_lo, version_hi;    // the bodies' versions when it was made
    T clear;                                 // no contact in [the search's now, clear)
    std::optional<PredictedContact<T>> result;  // what the search returned
  };
  struct Spin {
    T theta0{}, omega{};
    T inertia{}, inv_inertia{};  // 0 and 0 for a fixed body
    Vec2<T> pivot;
    std::vector<Vec2<T>> vertices;
    std::vector<RotatingMemo> memos;  // pairs with a higher body (rotating or not)
  };

  struct Timer {
    T time;
    std::uint64_t seq;
    TimerCallback callback;
    bool operator>(const Timer& o) const { return time > o.time || (time == o.time && seq > o.seq); }
  };

  std::vector<Body, CacheAligned<Body>> bodies;
  std::vector<BodyIndex> moving;         // indices of moving bodies, ascending
  std::vector<Spin> spins;               // per body when any body rotates; empty otherwise
  EventHeap<T> heap;                     // per moving body: its next contact and cell crossing

  // ---- Broad phase state (broad_phase.hpp). With the grid off every body is a candidate of every
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
    if (b.rotates) {
      Spin& r = spin_of(b);
      r.theta0 = r.theta0 + r.omega * (t - b.t0);
    }
    const Kinematics<T> k = kinematics(b, t);
    b.p0 = k.p;
    b.v0 = k.v;
    b.t0 = t;
  }

  // ---- Rotation (world_rotation.hpp): pairs of which one or both bodies turn.
  Spin& spin_of(const Body& b) { return spins[static_cast<std::size_t>(&b - bodies.data())]; }
  const Spin& spin_of(const Body& b) const { return spins[static_cast<std::size_t>(&b - bodies.data())]; }
  T angle_at(const Body& b, const T& t) const {
    if (!b.rotates) return T(0);
    const Spin& r = spin_of(b);
    return r.theta0 + r.omega * (t - (b.fixed ? T(0) : b.t0));
  }
  // The body's construction-time rotation state from its scene description (pivot, inertia,
  // vertices about the pivot, reach); p0 moves from the scene's position to the pivot.
  void setup_spin(std::size_t i, Body& b, const BodyDesc& d);
  // The body as the rotating predictor reads it: its stored path (pivot, angle) and its shape
  // about the path's point (a body that does not turn: angle 0, the shape about its position).
  detail::RotatingShape<T> rotating_shape(const Body& b) const;
  // The earliest contact of a pair with a rotating body, from now to the horizon
  // (detail::predict_rotating_pair; every solver uses it for now: docs/rotation.md). A search
  // that ran out of its box budget is a `resume` entry at the time up to which nothing touches.
  // The search covers [now, min(limit, horizon)]: a contact later than the owner's best event
  // is not the owner's next event, and a rotating search costs in proportion to its window.
  std::optional<PredictedContact<T>> predict_rotating(BodyIndex lo, BodyIndex hi, const T& limit);
  // The search itself from `from` (now, or where the pair's memo says nothing touches before:
  // predict_rotating asks it first); `clear` is set to the time before which it proved that
  // nothing touches.
  std::optional<PredictedContact<T>> search_rotating(BodyIndex lo, BodyIndex hi, const T& limit, const T& from, T& clear);
  // A predictor's contact record as the contact kind and features the heap and the events name.
  static PredictedContact<T> contact_of(const detail::RotatingContact<T>& c);
  // A scheduled contact of a rotating pair as the predictor's contact record, at time t.
  detail::RotatingContact<T> rotating_record(const Scheduled<T>& s, const T& t) const;
  // The contact's point and normal (from lo towards hi) at time t.
  detail::RotatingGeometry<T> rotating_geometry(const Scheduled<T>& s, const T& t) const;
  // Whether the contact points approach at s.time (the impulse test).
  bool rotating_approaching(const Scheduled<T>& s) const;
  // Whether the contact's point certainly approaches at `now` by the exact stored paths (after
  // an impulse: collide_rotating grows an impulse that leaves it so; E7 in docs/rotation.md).
  bool approaches_after(const Scheduled<T>& s) const;
  // The impulse test of a predictor's contact record of the pair (lo, hi), at its time, with the
  // corner rule's verdict (detail::ContactTest).
  detail::ContactTest rotating_contact_test(BodyIndex lo, BodyIndex hi, const detail::RotatingContact<T>& c) const;
  // The collision of a rotating pair at now: the impulse with lever arms (detail/rigid.hpp).
  void collide_rotating(const Scheduled<T>& s);
  // A body's vertex k in world coordinates at time t (rotating or not).
  Vec2<T> world_vertex(const Body& b, std::size_t k, const T& t) const;
  // Separation of two bodies at time t, either rotating, as `separation` measures it.
  Separation<T> separation_at(const Body& a, const Body& b, const T& t) const;
  // A pair's rounding scale at time t (rounding_scale), for pairs with a rotating body: each
  // body's position magnitude plus its reach.
  T rotating_rounding_scale(const Body& a, const Body& b, const T& t) const;

  // ---- Narrow phase (world_predict.hpp): a pair's earliest contact.
  // The earliest contact of the pair (lo < hi) from `now` to the horizon.
  // `limit`: a contact after it is of no use to the caller (the owner's best event so far); the
  // rotating search stops there (the translate-only predictions, closed forms, ignore it).
  std::optional<PredictedContact<T>> predict(BodyIndex lo, BodyIndex hi, const T& limit);

  // A float near-graze of two circles predicted again from their contact polynomial built in
  // double from the same stored paths: the stored floats are exact in double, so its rounding
  // is 2^29 times smaller than float's, and double's own near-graze test (2^-36, far above that
  // rounding) tells whether it decides the pair; if not (nothing), the exact paths must. A float
  // near-graze is anything within 2^-15 of the pair's scale (refine::near_graze_relative): the
  // exact solver deciding them all made a float gas of 1,000 discs four times as slow
  // (fixtures/scenes/basics/gas-1000.json, 4.4 s to 18 s; 2.7 s through double). The time is
  // rounded to float from double (refine_near_top rounds it once from the exact paths).
  std::optional<std::optional<PredictedContact<T>>> wide_circle_prediction(const Body& a, const Body& b) const;

  // b's position minus a's at `now`, like terms first: the stored positions cancel before the
  // displacements since each body's t0 are added, so the rounding is relative to the pair's
  // separation rather than to its distance from the origin (kb.p - ka.p rounds each position
  // first). The predicted time is then a few ulps of the clock from the exact one wherever the
  // pair is, and the refinement's walk (refine.hpp) is short.
  Vec2<T> separation(const Body& a, const Body& b) const;

  // A body's stored path, and the same as the exact contact functions read it (refine.hpp).
  static refine::Path<T> path_of(const Body& b) { return {&b.shape, b.fixed, b.t0, b.p0, b.v0, b.acc}; }
  static refine::ExactBody<T> exact_of(const Body& b) { return refine::exact_body(path_of(b)); }
  static bool relative_acc_zero(const Body& a, const Body& b);
  bool excluded(const Body& x, BodyIndex partner, const Body& y) const;

  // Two circles that pass within rounding of touching: predicted from the exact paths
  // (refine.hpp). Counted in counts.exact_predictions.
  // `overlapping`: whether the pair overlaps exactly at `now`.
  std::optional<PredictedContact<T>> exact_circle_prediction(const Body& a, const Body& b, bool& overlapping);

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
  std::optional<ExactRoot> exact_first_contact(detail::exact::IntPoly poly) const;

  // Offers the pair (i, j)'s earliest contact to `best`, the owner i's candidate event.
  void offer(BodyIndex i, BodyIndex j, Scheduled<T>& best);
  // The queue entry of the pair (lo, hi)'s predicted contact c, seen from the body whose partner
  // is `partner`.
  Scheduled<T> scheduled(const PredictedContact<T>& c, BodyIndex lo, BodyIndex hi, BodyIndex partner) const;

  // ---- Refinement (world_refine.hpp): scheduled contacts re-derived from the exact paths.
  // A scheduled contact's time, correctly rounded from the exact paths (refine.hpp); nothing if
  // no crossing is found near the predicted time.
  std::optional<T> refined_time(const Scheduled<T>& s) const;

  // The feature pair (fa, fb) of the contact `kind` of the pair (lo, hi), as the refinement's
  // exact functions read a scheduled contact.
  static Scheduled<T> feature_pair(BodyIndex lo, BodyIndex hi, ContactKind kind, std::uint16_t fa, std::uint16_t fb);

  // A line contact of the pair (lo, hi) whose rounded function passes within rounding of a
  // double root, decided from the exact paths (refine.hpp, exact_line_graze); a crossing's time
  // then correctly rounded from the exact paths, searched from `tau` (relative to now: the
  // rounded root, else the rounded minimum) and written back. Counted in counts.exact_predictions.
  GrazeVerdict line_graze(BodyIndex lo, BodyIndex hi, ContactKind kind, std::uint16_t fa, std::uint16_t fb, T& tau);

  // Where the line contact of the pair (lo, hi)'s feature pair lies on its edge at the exact
  // crossing nearest now + tau (its time correctly rounded first): GrazeJudge::place. Counted in
  // counts.exact_predictions.
  EdgePlace crossing_place(BodyIndex lo, BodyIndex hi, ContactKind kind, std::uint16_t fa, std::uint16_t fb,
                           const T& tau);
  // The same for a scheduled line contact whose time is its correctly rounded crossing: the
  // crossing lies between the T values next to it (refine::exact_place_at_crossing).
  EdgePlace crossing_place(const refine::ExactBody<T>& a, const refine::ExactBody<T>& b, const Scheduled<T>& r) const;
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
  std::optional<OverlapPairs> exact_overlap_pairs(BodyIndex lo, BodyIndex hi);

  // What a pair's rounded coordinates at now are relative to: the pair's coordinate scale at now
  // (pair_scale, the caller's) plus each body's motion since its path was stored (its position
  // at now is rounded from that path).
  T rounding_reach(const Body& a, const Body& b, const T& scale) const;

  // The time of a turning-overlap contact (roots.hpp), the first local maximum of the pair's
  // exact contact polynomial after `now`: a crossing of its derivative from positive to
  // negative, correctly rounded from the exact paths like every other event time.
  // `poly`: the exact contact polynomial in tau = t - now (refine::exact_feature_poly).
  std::optional<T> refined_turn(const detail::exact::IntPoly& poly, const T& predicted) const;

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
  std::optional<T> concave_turn(const detail::exact::IntPoly& poly, const T& hint) const;

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
  Exactly exact_contact(Scheduled<T>& r, const T& hint);

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
                              const T& window, const T& reach, const T& scale);
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
  void earlier_outline_contact(Scheduled<T>& r);

  // Whether the scheduled contact's point (a line contact's vertex or circle centre; a
  // circle-vertex contact's centre, against the vertex's two edges) lies within a generous bound
  // on its rounding of an edge's end at its time, or at any time within the refinement's window
  // of it: only there can the exact paths put it on the other side of the end
  // (off_feature_contact asks them only then). The bound: kSiblingRoundingUlps of the terms of
  // the projection dot(point - start, e) (the world coordinates it is rounded from), plus the
  // relative motion along e over the window and two ulps of the time.
  bool near_edge_end(const Scheduled<T>& r) const;
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
  void off_feature_contact(Scheduled<T>& r);

  // A circle scheduled against a vertex whose rounded prediction put its contact with an
  // adjacent edge just beyond the edge's end (a circle aimed at a segment's end: its edge and
  // end contact functions meet tangentially there, and rounding picks either; the edge's is
  // first where the exact point lies inside, by a few ulps in long double,
  // scripts/edge-end-sweep.py): each adjacent edge's exact crossing before the scheduled time
  // whose point lies strictly inside the edge (crossing_place) replaces it.
  void earlier_circle_edge_contact(Scheduled<T>& r);

  // Whether the scheduled contact's point lies on its features at its time (in T, as the
  // prediction accepts it): the circle's centre or the vertex projects onto the edge.
  bool on_feature(const Scheduled<T>& s) const;

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
  static T refine_bound(const T& t);
  bool refine_near_top();

  // Whether a contact scheduled at the horizon is a collision rather than a touch: two circles
  // are asked of the exact polynomial (a double root inside its window is no root), where a
  // rounded approach test cannot see relative speeds of rounding size; other pairs are asked
  // whether they approach at that time (the impulse test of collide).
  // (Exactly: the contact function at the horizon is negative, the crossing came before it, or
  // zero and decreasing just after it, a crossing exactly at it; zero and rising is a graze, and
  // positive means the exact contact is after the horizon, however close.)
  bool collides_at_horizon(const Scheduled<T>& s);

  // ---- Broad phase and scheduling (world_broad_phase.hpp, broad_phase.hpp): candidates, cell
  // crossings, global bodies, and each body's events in the heap.
  // Calls f(j) for every body j != i that i is predicted against (see the broad phase above).
  template <class F> void for_candidates(BodyIndex i, F f);

  // Calls f(j) for the bodies j != i in the 3x3 cells around `c`, less those also around
  // `except` (a cell, or kGlobal), fixed bodies once, in the grid's order. The candidates are
  // gathered and their Body lines prefetched first: with 1e5 bodies they are scattered over
  // memory, and a prediction is too long for the processor to reach the next candidate's load
  // on its own, so the misses would otherwise come one after another.
  template <class F> void visit_cells(BodyIndex i, std::uint32_t c, std::uint32_t except, F& f);
  void prefetch_cells(BodyIndex i) const;
  void prefetch_candidates(BodyIndex i) const;

  // The two cache lines of a Body that a prediction of two circles reads (see Body).
  static void prefetch_hot(const Body& b);
  void next_scan();

  // A fixed body registered in several cells (`shared`) is offered once per scan.
  template <class F> void visit_once(BodyIndex i, BodyIndex j, bool shared, F& f);
  void reschedule(BodyIndex i);

  // The grid for this scene, or none (grid_on false): the cell's body radius R is the largest
  // reach among the moving bodies no larger than 4 times their median reach; larger bodies are
  // global. The grid covers the moving bodies' positions and the fixed bodies of comparable
  // extent, two cells beyond, with at most 16 cells per moving body (larger cells otherwise).
  void setup_grid(BroadPhase mode);

  // A fixed body's bounding box (lo x, lo y, hi x, hi y), in double.
  static std::array<double, 4> fixed_box(const Body& b);

  // Takes body i out of the grid for good: it becomes every body's candidate and they its.
  // The caller reschedules it (a full scan) if it is moving.
  void make_global(BodyIndex i);

  // The time of moving body i's next cell crossing from time `from` (its position then is
  // inside its cell's exit box; never() if none before the horizon or if it is global), or
  // makes it global (and answers never()) where double cell arithmetic cannot be trusted to
  // an eighth of the margin until then: its position evaluated in T and in double, and the
  // crossing's time rounded to T, each off by at most a few ulps of the terms' magnitudes.
  T crossing_time(BodyIndex i, const T& from);

  // Moving body i's crossing at `at`: it moves to the cell it is in then, and is predicted
  // against the bodies around that cell that were not around the old one. No motion changes, so
  // nothing else is predicted again, and the predictions are made from `now` (the last event's
  // time, at or before `at`), which the pair's paths are known from: they cannot touch before
  // `at`, where they were not neighbours.
  void cross(BodyIndex i, const T& at);

  // Initial schedule: each pair predicted once, offered to both of its bodies (with the grid:
  // each moving body's candidates, a pair of moving bodies predicted from both sides).
  void schedule_all();

  // ---- Resting contact (world_rest.hpp, DESIGN.md): a contact state instead of a storm of
  // zero-time events.
  // The largest normal speed w off face body f, pressed by acc_normal, that is rounding noise
  // for the moving body m. Inelastic (restitution < 1): a rise w^2 / (2 |a_n|) below
  // kRestHeightUlps ulps of m's coordinate scale (the rounding of its own position): a Zeno
  // sequence of bounces ends there, after finitely many. Elastic (restitution 1): only a normal
  // speed within kRestHeightUlps ulps of m's speed, the rounding of its velocity, so that no
  // energy an elastic bounce would keep is taken away.
  T rest_speed(const Body& m, BodyIndex f, const T& acc_normal) const;

  // The face of fixed body `f` whose outward normal is (within kRestNormalTolerance) the unit
  // normal `n` and which holds the contact point; nothing when the contact is on a vertex only.
  std::optional<Support> face_of(BodyIndex f, const Vec2<T>& n, const Vec2<T>& point) const;

  // A resting body's contact interval along the face: a circle touches at its centre's
  // projection; a polygon along its vertices lowest towards the face.
  // A rotating body rests only while it does not turn (omega exactly 0, landed face on face):
  // its points about its pivot at its fixed angle stand for the translating body's local ones.
  void contact_span(const Body& m, Support& s) const;

  // Adjacent times tried past a leave's rounded root before it is taken as it is.
  static constexpr int kLeaveSteps = 64;

  // When a resting body's contact interval leaves its face (it slides past an end), or nothing
  // before the horizon. Along the face, s(t) = (p(t) - origin) . u is at most quadratic.
  std::optional<T> leave_time(const Body& m, const Support& s) const;

  // Which of a body's faces hold it, from its field acceleration: the faces pressed with a
  // non-negative reaction (at most two constraints in 2-D, tried from none to both), the path's
  // acceleration without their components, and its velocity without its normal components.
  // Faces that do not press are dropped.
  void resolve_supports(Body& m);

  // After a collision changed moving body m's velocity (rebased to now): faces it rested on and
  // now leaves or is pushed into by more than a rest speed stop holding it (a push into a face
  // is the face's own contact, found at once by the next prediction); then, if the contact was
  // with a fixed face that presses it and its bounce off that face would be rounding noise, it
  // rests on that face too.
  void update_rest(BodyIndex mi, BodyIndex partner, const Vec2<T>& normal_to_m, const Vec2<T>& point);

  // Whether fixed body j continues a face that the resting body m slides on: an edge of j on the
  // face's line, both its ends exactly (cross(x - origin, u) == 0 in T: exact for axis-aligned
  // faces; a tilted face's rounded direction rarely passes), running the same way, so with the
  // same outward normal (floor tiles, boxes side by side). j is convex, so it lies wholly behind
  // that line, and m, which moves along it, can meet j only on the line: a joint, never an
  // approach. Predicted, the rounding of m's height made contacts there (a ball landed an ulp
  // deep struck the next tile's corner in a storm of 3e-8 impulses). The oracle skips the same
  // pairs (oracle/src/search.cpp, flush_with_support).
  bool continues_support(const Body& m, const Body& j) const;

  // The fixed face that continues `old` past the end the resting body m is leaving it by (floor
  // tiles, boxes side by side): the same outward normal, holding the end point, its line through
  // that point within the rounding of m's position (kRestHeightUlps ulps of its coordinate
  // scale; a step is a real contact, left to the predictions). Nothing if there is none.
  std::optional<Support> continuing_face(BodyIndex mi, const Support& old);

  // A resting body slides off its face's end: the face stops holding it, and a face that
  // continues it holds it instead (without this a ball crossing the joint of two collinear
  // segments collided with the first one's end in a storm of zero impulses: the contact point an
  // ulp past its end still counts as on its edge, and a face's end is no place to rest).
  void leave(const Scheduled<T>& s, BodyIndex owner);

  // ---- Response (world_response.hpp): a collision's impulse, storms, overlap measures.
  bool approaching(const Scheduled<T>& s) const;
  void note_storm(BodyIndex i, BodyIndex partner);
  void collide(const Scheduled<T>& s);
  // What every collision's report starts with: the pair, features and velocities before (at now).
  CollisionInfo<T> collision_info(const Scheduled<T>& s, const Kinematics<T>& ka, const Kinematics<T>& kb) const;
  // What every collision ends with, translating or rotating: the worst overlap, versions,
  // storms, rescheduling, the callback and the collision budget.
  void finish_collision(const Scheduled<T>& s, const CollisionInfo<T>& info, const Overlap& o);

  // The length at which a pair's contact is rounded, in units of epsilon: its largest coordinate
  // magnitude (vertices included), plus how far it closes in the time it takes the clock to
  // move by its relative precision (an event time t is rounded to ulp(t), in which the pair
  // closes |v_rel| ulp(t)); a long run is as precise as its clock.
  static T rounding_scale(const BodyShape<T>& sa, const Kinematics<T>& ka, const BodyShape<T>& sb,
                          const Kinematics<T>& kb, const T& t);
  // Overlap depth as a fraction of the contact distance and in units of the pair's rounding:
  // epsilon * (rounding scale + contact distance).
  static Overlap measure_overlap(const T& depth, const T& contact_distance, const T& scale, BodyIndex a, BodyIndex b);


#ifdef PGE_VALIDATE
  // Expensive validation (PGE_VALIDATE builds): after every event, time has not gone back,
  // every moving body's state is finite, and (for scenes small enough to scan every event) no
  // pair overlaps past the bound; otherwise the scan runs every 1024th event.
  T last_validated_time{};
  std::uint64_t validations = 0;
  T start_overlap_depth{};  // the scene's overlap at the start, allowed to stay (overlap_past_bound)
  // The overlap scan is O(n^2): past this many bodies it would take longer than the run.
  static constexpr std::size_t kValidateScanMaxBodies = 5000;
  void validate(const World& self);
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
  void watch_path(BodyIndex i);
  void watch_end();

  T frame_time(std::uint64_t k) const { return T(static_cast<double>(k)) / T(fps); }
};

}  // namespace pge
