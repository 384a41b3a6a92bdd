// The first contact of two bodies of which at least one turns (issue "Rotation", item 4): the
// robust solver's pair prediction, over every feature pair, with rigorous enclosures.
//
// Shapes. A circle (radius > 0, no vertices; it carries no angle) or a convex outline: the
// vertices counter-clockwise in the body's frame about its centre (a segment is an outline of two
// vertices, whose two edges face both ways). `reach` bounds every point of the shape from the
// centre (the bounding circle).
//
// Features. Outline against outline: each vertex of either against each edge of the other.
// Circle against outline: the circle against each edge and each vertex. Circles against each
// other do not need this: their contact does not depend on angles. Every contact of two convex
// shapes that were apart is first a point of one boundary meeting the other, so the first contact
// is the earliest feature root at which the feature really touches: a vertex root counts where the
// vertex lies on the edge (along in [0, e.e], possibly, by its enclosure), a circle-vertex root
// always (the vertex is on the circle). A root on an edge's line beyond the edge is searched past
// (past_crossing) and the search goes on.
//
// Work. The bounding circles first: the search starts where their distance can first be zero
// (the earliest root of |d|^2 - (reach_a + reach_b)^2, a polynomial, no waves), and a pair whose
// bounding circles never meet in the window costs one search of a quadratic. Then conservative
// advancement while the shapes are proven far apart (advance). Of two outlines, a feature is
// searched only from the time its point can first reach its edge (its distance from the edge's
// line over the fastest closing speed), and, once the shapes are proven apart, only where its
// vertex may be its outline's support point towards the edge (supporting(): on the 20-polygon
// spinning gas of docs/rotation.md it leaves out half the features of the pairs proven apart).
// Each feature's
// search is bounded by `max_boxes`; past it the pair's result is Undecided at the earliest time
// up to which no feature is known to touch, and the caller predicts again from there (progress
// every call; a body spinning many turns between contacts costs about a constant per turn, see
// roots_rotating.hpp).
#pragma once

#include "pge/detail/contact_rotating.hpp"
#include "pge/detail/corner.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <span>
#include <vector>
#include <type_traits>

namespace pge::detail {

template <class B> struct RotatingShape;

// A stored path's values in a wider type W (exactly: W holds every value of B).
template <class W, class B> StoredPath<W> widened_path(const StoredPath<B>& p) {
  const auto v = [](const Vec2<B>& x) { return Vec2<W>{W(x.x), W(x.y)}; };
  return {W(p.t0), v(p.p0), v(p.v0), v(p.a), W(p.theta0), W(p.omega)};
}

template <class B> struct RotatingShape {
  StoredPath<B> path;
  B radius{};                      // a circle: radius > 0 and no vertices
  std::span<const Vec2<B>> vertices;  // an outline: counter-clockwise, about the centre
  B reach{};                       // max distance of the shape's points from the centre
  bool circle() const { return vertices.empty(); }
};

enum class RotatingFeature : std::uint8_t { VertexEdge, CircleEdge, CircleVertex };

// The functions of a point of P (vertex `point` for VertexEdge, the circle's centre with its
// radius for CircleEdge) against Q's edge `edge`, in W from `origin`, the stored values converted
// exactly: the one construction behind every wider-type decision about a feature (the placement
// of a crossing, the place along the edge, the gap's rate).
template <class W, class B>
FeatureFunctions<W> widened_feature_functions(const RotatingShape<B>& sp, const RotatingShape<B>& sq, RotatingFeature feature,
                                              std::size_t point, std::size_t edge, const B& origin) {
  const auto v = [](const Vec2<B>& x) { return Vec2<W>{W(x.x), W(x.y)}; };
  const PathAt<W> P = path_at(widened_path<W>(sp.path), W(origin)), Q = path_at(widened_path<W>(sq.path), W(origin));
  const std::size_t n = sq.vertices.size();
  const Vec2<W> r = feature == RotatingFeature::VertexEdge ? v(sp.vertices[point]) : Vec2<W>{};
  return point_edge_functions(P, r, W(sp.radius), Q, v(sq.vertices[edge]), v(sq.vertices[(edge + 1) % n]));
}

template <class B> struct RotatingContact {
  RootStatus status = RootStatus::None;
  B t{};  // Root: the contact; Undecided: no contact is known before t; None: the window's end
  bool at_start_overlap = false;
  bool tangent = false;
  // Found at the search's start (t is where the search began): touching or overlapping there, so
  // t is the contact's exact time, not a rounding of it (corner_rule).
  bool at_start = false;
  RotatingFeature feature = RotatingFeature::VertexEdge;
  bool point_on_a = false;       // the vertex (or the circle) belongs to a; the edge (or vertex) to b
  std::size_t point = 0, edge = 0;  // the vertex index (VertexEdge); the edge index (k: vertex k to k + 1) or vertex
  std::uint64_t boxes = 0;       // work: boxes enclosed over every search
  // correctly_rounded asked, and the rounding of this root to B could not be decided in the
  // certifying type (round_correctly): t is then the robust placement.
  bool rounding_undecided = false;
};

struct RotatingOptions {
  std::uint64_t max_boxes = 100000;  // per feature search
  bool bounding_circles = true;      // start where the bounding circles can first touch
  bool advance = true;               // then advance conservatively while the shapes are far apart
  // Of two outlines, search a feature only from when its point can reach its edge and, while the
  // shapes are proven apart, only where its vertex may be the support point (outline_pair).
  bool prune_features = true;
  // The certified solver's promise: a crossing's time is the nearest value of B to the exact
  // contact time of the stored paths (round_correctly), or marked rounding_undecided.
  bool correctly_rounded = false;
};

// The type in which the certified solver decides a rounding to B: wide enough that its own
// rounding (about 2^-113 relative for Quad) is far below the distance from a transversal root to
// the middle between two values of B (half an ulp of B times the slope). Quad has none here:
// sine and cosine enclosures in 240 bits cost world_quad.cpp 30 s more to compile under the
// sanitizers, for a scalar nobody simulates rotation in; its roundings are counted undecided.
template <class B> struct Certifying { using type = Quad; };
template <> struct Certifying<float> { using type = double; };
template <> struct Certifying<Quad> { using type = void; };

// Where the bounding circles of two shapes (their reaches about their centres) can first meet
// in [lo, hi]: nothing if they overlap at lo; else the earliest root of |d|^2 - (reach_a +
// reach_b)^2 (a polynomial: no waves), None if they stay apart to hi, Undecided at the box
// budget with the time up to which they certainly do. Before a Root's t the squared distance
// is certainly above the reaches' sum squared: the Root is a bound, the last value of B before the
// meeting at which B's enclosure proves them apart (WaveRootFinder::bound_only), not placed to
// the ulp.
template <class B>
std::optional<WaveRoot<B>> bounding_circles_meet(const RotatingShape<B>& a, const RotatingShape<B>& b, const B& lo,
                                                 const B& hi, std::uint64_t max_boxes) {
  WaveSum<B> reach;
  reach.origin = lo;
  const Interval<B> r = Interval<B>(a.reach) + Interval<B>(b.reach);
  reach.base = squared_norm(relative_centre(path_at(a.path, lo), path_at(b.path, lo))) + constant_poly(-(r * r));
  if (!reach(Interval<B>(lo)).positive()) return std::nullopt;
  WaveRootFinder<B> finder(reach, StartRule::CrossingsOnly);
  finder.bound_only();
  return finder.earliest(lo, hi, max_boxes);
}

// What the caller's impulse test makes of a contact (set_contact_test): of one at the search's
// start, and of every vertex-edge root (the corner rule).
enum class ContactTest : std::uint8_t {
  Collides,      // its points approach: an impulse
  Touches,       // they do not (no impulse): searched past unless its gap goes certainly negative first
  PassesCorner,  // a vertex meeting a vertex whose relative motion does not enter the overlap cone
                 // (the corner rule): searched past whichever way its gap goes
};

template <class B> class RotatingPairPredictor {
 public:
  RotatingPairPredictor(const RotatingShape<B>& a, const RotatingShape<B>& b, StartRule rule, RotatingOptions opt)
      : a_(a), b_(b), rule_(rule), opt_(opt) {}

  // A contact at the search's start (touching there, or the overlap rule's) whose points `test`
  // says do not approach is searched past, as a graze already processed is (past_tangency),
  // unless its gap goes certainly negative first; a vertex-edge root anywhere that `test` says
  // passes a corner is searched past either way. The engine asks its impulse test here: a
  // contact without an impulse leaves the state as it is, and would be found again at once,
  // for ever.
  void set_contact_test(std::function<ContactTest(const RotatingContact<B>&)> test) { contact_test_ = std::move(test); }

  // The bounding circles' meeting (bounding_circles_meet) from the search's start to at least its
  // end, already asked by the caller: earliest() takes it instead of asking again.
  void set_bounding_circles(const std::optional<WaveRoot<B>>& meet) {
    circles_given_ = true;
    circles_apart_ = meet.has_value();
    if (meet) circles_ = *meet;
  }

  RotatingContact<B> earliest(const B& lo, const B& hi) {
    origin_ = lo;
    best_ = {};
    best_.t = hi;
    const PathAt<B> pa = path_at(a_.path, lo), pb = path_at(b_.path, lo);
    B from = lo;
    if (opt_.bounding_circles) {
      // Apart at lo: nothing can touch before the bounding circles do. (Overlapping at lo, even
      // while separating, a turning corner may still strike: the search starts at lo.)
      const std::optional<WaveRoot<B>> circles =
          !circles_given_ ? bounding_circles_meet(a_, b_, lo, hi, opt_.max_boxes)
                          : circles_apart_ ? std::optional<WaveRoot<B>>(circles_) : std::nullopt;
      if (circles) {
        const WaveRoot<B>& meet = *circles;
        best_.boxes += meet.boxes;
        // Asked over a longer span by the caller: a meeting (or the budget's end) past hi is none.
        if (meet.status == RootStatus::None || !(meet.t < hi)) return best_;
        if (meet.status == RootStatus::Undecided) {
          best_.status = RootStatus::Undecided;
          best_.t = meet.t;
          return best_;
        }
        // Before meet.t the squared distance is certainly above the reaches' sum squared.
        from = meet.t;
      }
    }
    if (opt_.advance) from = advance(from, hi);
    if (!(from < hi)) return best_;
    // The start rule belongs to lo (now); from a later start the shapes cannot overlap there.
    rule_now_ = from == lo ? rule_ : StartRule::CrossingsOnly;
    from_ = from;
    if (!a_.circle() && !b_.circle()) {
      outline_pair(pa, pb, from);
    } else if (a_.circle() != b_.circle()) {
      const bool a_round = a_.circle();
      circle_outline(a_round ? pa : pb, a_round ? a_ : b_, a_round ? pb : pa, a_round ? b_ : a_, a_round, from);
    }
    return best_;
  }

 private:
  // Conservative advancement: from `from`, steps of the proven distance between the shapes over
  // the fastest any of their points can close (the centres' relative speed over the window plus
  // each body's |omega| times its reach), while that distance is more than 1/1024 of the
  // reaches' sum; then the feature searches take over. (On the 1,000-polygon spinning gas,
  // bench_scale spinning_polygons/1000 with a window of half a reach, 2026-12-07: 1/1024 ran
  // 2,510-2,560 events/s, 1/64 2,210-2,270, 1/16384 1,870-2,370.) Each step costs one enclosure
  // of both shapes (one sin/cos each), where a feature search over a long window costs hundreds of boxes
  // of several sin/cos each: most pairs of a gas are proven apart until the owner's next event in
  // a few steps (the window's end, which the caller caps there). The distance is a lower bound:
  // the largest separation of the two outlines along any edge normal of either (a projection),
  // or a circle's centre's signed distance to an edge line less its radius. Returns the time up
  // to which no contact is possible (hi if none in the window).
  B advance(B t, const B& hi) {
    using I = Interval<B>;
    const PathAt<B> pa = path_at(a_.path, t), pb = path_at(b_.path, t);
    const VecPoly<B> d = relative_centre(pa, pb);
    const I window = I(hi) - I(t);
    const auto norm = [](const Vec2<I>& v) { return (v.x.square() + v.y.square()).sqrt(); };
    const I speed = norm(d.c[1]) + I(B(2)) * norm(d.c[2]) * window + I(pa.omega.magnitude()) * I(a_.reach) +
                    I(pb.omega.magnitude()) * I(b_.reach);
    const B vmax = speed.hi();
    if (!(vmax > B(0)) || !(vmax < std::numeric_limits<B>::infinity())) return t;
    vmax_ = vmax;
    const B close = (a_.reach + b_.reach) / B(1024);
    close_ = close;
    for (int step = 0; step < kAdvanceSteps; ++step) {
      const B dist = distance_lower_bound(t);
      apart_at_ = dist > B(0) ? t : std::numeric_limits<B>::quiet_NaN();
      if (!(dist > close)) return t;
      const B next = (I(t) + I(dist) / vmax).lo();
      if (!(next > t)) return t;
      if (next >= hi) return hi;
      t = next;
    }
    return t;
  }
  static constexpr int kAdvanceSteps = 64;
  // A search's end when only the best contact so far bounds it.
  static B no_end() { return std::numeric_limits<B>::infinity(); }

  // A body's points at t (its path taken at t), as enclosures, into `out`.
  static void points_at(const RotatingShape<B>& s, const PathAt<B>& p, std::vector<Vec2<Interval<B>>>& out) {
    const SinCos<B> sc = sin_cos(p.phase);
    out.clear();
    for (const Vec2<B>& v : s.vertices) {
      const Vec2<Interval<B>> r = enclose(v);
      out.push_back({p.c[0].x + sc.cos * r.x - sc.sin * r.y, p.c[0].y + sc.sin * r.x + sc.cos * r.y});
    }
  }

  // The separation along the normal of edge k of `edges`' outline of the points `other` (minus
  // `rho` for a circle's centre): a lower bound on their distance.
  static B separation_along(const std::vector<Vec2<Interval<B>>>& edges, std::size_t k,
                            const std::vector<Vec2<Interval<B>>>& other, const B& rho) {
    using I = Interval<B>;
    const std::size_t n = edges.size();
    const Vec2<I> e = edges[(k + 1) % n] - edges[k];
    const Vec2<I> out{e.y, -e.x};
    B least = std::numeric_limits<B>::infinity();
    for (const Vec2<I>& q : other) least = std::min(least, dot(out, q - edges[k]).lo());
    const I length = (out.x.square() + out.y.square()).sqrt();
    return least > B(0) ? (I(least) / length.hi()).lo() - rho : (least < B(0) ? least : B(0)) - rho;
  }

  // The largest of those over every edge of `edges`, and (in `axis`) the edge giving it.
  static B separation(const std::vector<Vec2<Interval<B>>>& edges, const std::vector<Vec2<Interval<B>>>& other,
                      const B& rho, std::size_t& axis) {
    B best = -std::numeric_limits<B>::infinity();
    for (std::size_t k = 0; k < edges.size(); ++k) {
      const B gap = separation_along(edges, k, other, rho);
      if (gap > best) {
        best = gap;
        axis = k;
      }
    }
    return best;
  }

  // A lower bound on the shapes' distance at t: the largest separation along any edge normal of
  // either. Conservative advancement asks it at times close together, where the axis that
  // separated best the last time usually still does: that axis alone is taken while it proves
  // at least half the last distance (and more than the advancement's threshold); otherwise
  // every axis again.
  B distance_lower_bound(const B& t) const {
    const PathAt<B> pa = path_at(a_.path, t), pb = path_at(b_.path, t);
    if (a_.circle() || b_.circle()) {
      const bool a_round = a_.circle();
      const PathAt<B>& pc = a_round ? pa : pb;
      centre_.assign(1, pc.c[0]);
      points_at(a_round ? b_ : a_, a_round ? pb : pa, points_a_);
      std::size_t axis = 0;
      return separation(points_a_, centre_, a_round ? a_.radius : b_.radius, axis);
    }
    points_at(a_, pa, points_a_);
    points_at(b_, pb, points_b_);
    if (axis_known_) {
      const B gap = axis_on_a_ ? separation_along(points_a_, axis_, points_b_, B(0))
                               : separation_along(points_b_, axis_, points_a_, B(0));
      if (gap > last_distance_ / B(2) && gap > close_) {
        last_distance_ = gap;
        return gap;
      }
    }
    std::size_t on_a = 0, on_b = 0;
    const B sa = separation(points_a_, points_b_, B(0), on_a), sb = separation(points_b_, points_a_, B(0), on_b);
    axis_known_ = true;
    axis_on_a_ = sa >= sb;
    axis_ = axis_on_a_ ? on_a : on_b;
    last_distance_ = std::max(sa, sb);
    return last_distance_;
  }

  // Every vertex of either outline against every edge of the other, nearest first: each
  // feature's distance from its edge's line at `from` (|gap| over |e|, a lower bound on its
  // distance from the edge) is also a bound on when it can first touch, at the fastest closing
  // speed (advance): its search starts there, a feature that cannot touch before the best
  // contact found so far is not searched at all, and the nearest ones, searched first, usually
  // give that contact at once. (Ties between two features at the same time keep the first
  // searched.) From a time at which the shapes are proven apart (`from` itself, or a little
  // after it for a pair that has just touched: apart_after) only the features whose vertex may be
  // its outline's support point towards the edge are searched (supporting()); every feature
  // is searched before it.
  void outline_pair(const PathAt<B>& pa, const PathAt<B>& pb, const B& from) {
    struct Job {
      B near;
      FeatureFunctions<B> f;
      bool point_on_a;
      std::size_t i, k;
      bool all_window;  // searched to the best contact; else only before `apart`
    };
    std::vector<Job> jobs;
    const Interval<B> at(from);
    const B apart = opt_.prune_features ? apart_after(from) : best_.t;
    for (const bool on_a : {true, false}) {
      const RotatingShape<B>& sp = on_a ? a_ : b_;
      const RotatingShape<B>& sq = on_a ? b_ : a_;
      const PathAt<B>& P = on_a ? pa : pb;
      const PathAt<B>& Q = on_a ? pb : pa;
      const std::size_t nq = sq.vertices.size();
      // Q's frame turned into P's over [apart, best_.t] (the paths are taken at their origin,
      // lo): the angle theta_Q - theta_P.
      const bool prune = apart < best_.t;
      SinCos<B> turn;
      if (prune) {
        const Interval<B> elapsed = hull(Interval<B>(apart) - Interval<B>(P.origin), Interval<B>(best_.t) - Interval<B>(P.origin));
        turn = sin_cos(Q.phase - P.phase + (Q.omega - P.omega) * elapsed);
      }
      for (std::size_t i = 0; i < sp.vertices.size(); ++i)
        for (std::size_t k = 0; k < nq; ++k) {
          const bool all_window = !prune || supporting(sp, i, sq, k, turn);
          if (!all_window && !(apart > from)) continue;
          FeatureFunctions<B> f = point_edge_functions(P, sp.vertices[i], B(0), Q, sq.vertices[k], sq.vertices[(k + 1) % nq]);
          const Interval<B> g = f.gap(at);
          const B gap = g.lo() > B(0) ? g.lo() : g.hi() < B(0) ? -g.hi() : B(0);
          const B near = gap > B(0) ? (Interval<B>(gap) / f.length_sq.sqrt().hi()).lo() : B(0);
          jobs.push_back({near, std::move(f), on_a, i, k, all_window});
        }
    }
    std::stable_sort(jobs.begin(), jobs.end(), [](const Job& x, const Job& y) { return x.near < y.near; });
    for (const Job& j : jobs) {
      // The feature cannot touch before `start`: its point is at least `near` from the edge.
      B start = vmax_ > B(0) && j.near > B(0) ? (Interval<B>(from) + Interval<B>(j.near) / vmax_).lo() : from;
      if (start >= best_.t) break;
      if (!opt_.prune_features) start = from;
      const B until = j.all_window ? best_.t : std::min(apart, best_.t);
      if (start >= until) continue;
      const RotatingShape<B>& sp = j.point_on_a ? a_ : b_;
      const RotatingShape<B>& sq = j.point_on_a ? b_ : a_;
      search_edge(j.f, j.point_on_a ? pa : pb, sp, sp.vertices[j.i], B(0), j.point_on_a ? pb : pa, sq, std::max(start, from),
                  until, {RotatingFeature::VertexEdge, j.point_on_a, j.i, j.k});
    }
  }

  // The first of `from` and a few times a little after it at which the shapes are proven apart
  // (a positive distance_lower_bound), or the window's end: a pair that has just touched is
  // usually apart after a small fraction of the time its points need to close by their reaches.
  B apart_after(const B& from) {
    if (apart_at_ == from || distance_lower_bound(from) > B(0)) return from;
    if (!(vmax_ > B(0))) return best_.t;
    const B span = (Interval<B>(a_.reach + b_.reach) / vmax_).lo();
    for (const int shift : {10, 6, 3}) {
      const B t = (Interval<B>(from) + Interval<B>(span / B(1 << shift))).hi();
      if (!(t < best_.t)) break;
      if (distance_lower_bound(t) > B(0)) return t;
    }
    return best_.t;
  }

  // Whether vertex i of P may be P's support point towards edge k of Q (the farthest of P's
  // vertices along -n_k, n_k the edge's outward normal) at some angle of Q's frame in P's whose
  // sine and cosine `turn` encloses. Where the shapes are apart at the window's start, the
  // first contact in it touches a vertex that is: at that time the shapes' interiors are apart,
  // so the set S of directions separating them (from Q towards P) is an arc, narrower than a
  // half turn where either is a polygon, whose ends are edge normals n_k of Q at the touching
  // vertex (S's end inside Q's normal cone there) or reversed edge normals -m_f of P (likewise);
  // an end n_k makes the feature (the touching vertex of P, edge k) one where the vertex is the
  // support point towards k, an end -m_f the feature (the touching vertex of Q, edge f of P). The
  // relative velocity u of the two touching points closes along some direction of S (they were
  // apart just before), so the open half turn of directions d with u.d < 0 meets S, and an arc
  // narrower than a half turn that meets an open half turn has an end inside it: that end's
  // feature has its vertex in front of its edge's line just before the contact, so its gap falls
  // through zero there (or touches it: a graze). One supporting feature thus crosses at the
  // first contact, and every other feature's root, on its edge, is a contact no earlier. The
  // support test needs only the vertex's neighbours: (v_i - v_j).(-n_k) >= 0 for j = i +- 1.
  static bool supporting(const RotatingShape<B>& sp, std::size_t i, const RotatingShape<B>& sq, std::size_t k,
                         const SinCos<B>& turn) {
    using I = Interval<B>;
    if (sp.vertices.size() < 3 && sq.vertices.size() < 3) return true;  // two rods: S may be a half turn
    const std::size_t nq = sq.vertices.size(), np = sp.vertices.size();
    const Vec2<I> e = enclose(sq.vertices[(k + 1) % nq]) - enclose(sq.vertices[k]);
    // -n_k in Q's frame is (-e.y, e.x); turned into P's frame.
    const I dx = -e.y, dy = e.x;
    const Vec2<I> d{turn.cos * dx - turn.sin * dy, turn.sin * dx + turn.cos * dy};
    const Vec2<I> v = enclose(sp.vertices[i]);
    for (const std::size_t j : {(i + 1) % np, (i + np - 1) % np}) {
      if (dot(v - enclose(sp.vertices[j]), d).hi() < B(0)) return false;
    }
    return true;
  }

  void circle_outline(const PathAt<B>& P, const RotatingShape<B>& sp, const PathAt<B>& Q, const RotatingShape<B>& sq,
                      bool point_on_a, const B& from) {
    const std::size_t nq = sq.vertices.size();
    for (std::size_t k = 0; k < nq; ++k) {
      const FeatureFunctions<B> f =
          point_edge_functions(P, Vec2<B>{}, sp.radius, Q, sq.vertices[k], sq.vertices[(k + 1) % nq]);
      search_edge(f, P, sp, Vec2<B>{}, sp.radius, Q, sq, from, no_end(), {RotatingFeature::CircleEdge, point_on_a, 0, k});
    }
    for (std::size_t k = 0; k < nq; ++k) {
      const WaveSum<B> f = circle_vertex_function(P, sp.radius, Q, sq.vertices[k]);
      search(f, nullptr, P, sp, Vec2<B>{}, sp.radius, Q, sq, from, no_end(), {RotatingFeature::CircleVertex, point_on_a, 0, k});
    }
  }

  struct Which {
    RotatingFeature feature;
    bool point_on_a;
    std::size_t point, edge;
  };

  // A point feature against an edge (`f`: roots of the gap where `along` may be in [0, e.e];
  // others are searched past), or a circle against a vertex (`gap` alone, f null). A start in
  // overlap (the rule's root at lo) counts only where the point may be inside Q's outline (every
  // edge's gap possibly <= 0; for a circle, the outline pushed out by its radius, a superset of
  // overlap at the corners), not merely behind this edge's line.
  //
  // A tangency touching the search's start (the gap within rounding of zero at lo, where a graze
  // was just processed) is that graze again, already at lo: searched past (past_tangency), or
  // taken as a crossing if the gap goes certainly negative on the way.
  //
  // A segment has two sides and no inside: a vertex crossing its line is a contact only from
  // the side P's body is on (as the translating engine judges it, contact_polygon.hpp), told by
  // the mean of P's vertices, a point inside P. Without it a corner that has just bounced off
  // one side, still on the line and leaving, would strike the other side at once.
  void search(const WaveSum<B>& gap, const FeatureFunctions<B>* f, const PathAt<B>& P, const RotatingShape<B>& sp,
              const Vec2<B>& r, const B& rho, const PathAt<B>& Q, const RotatingShape<B>& sq, B lo, const B& until,
              const Which& which) {
    StartRule rule = lo == from_ ? rule_now_ : StartRule::CrossingsOnly;
    const bool touching_at_start = gap(Interval<B>(lo)).contains_zero();
    for (;;) {
      const B hi = std::min(until, best_.t);
      if (!(lo < hi)) return;
      WaveRoot<B> root = f ? earliest_wave_root_on(gap, f->along, f->length_sq, lo, hi, rule, opt_.max_boxes)
                           : earliest_wave_root(gap, lo, hi, rule, opt_.max_boxes);
      best_.boxes += root.boxes;
      if (root.status != RootStatus::Root) {
        take(root, which);
        return;
      }
      if (root.tangent && touching_at_start) {
        const std::optional<B> past = past_tangency(gap, root.t, hi);
        if (past) {
          rule = StartRule::CrossingsOnly;
          lo = *past;
          continue;
        }
        root.tangent = false;  // it went below zero: a crossing, at the rounding's place
      }
      // A tangency the wider type shows to be a near miss is none: the search goes on past it.
      if (root.tangent && clear_in_wider(which, root.t))
        if (const std::optional<B> past = past_tangency(gap, root.t, hi)) {
          rule = StartRule::CrossingsOnly;
          lo = *past;
          continue;
        }
      bool on_edge = true;
      std::optional<B> first_negative;  // past_crossing(gap, root.t, hi), once asked
      if (f) {
        const Interval<B> along = f->along(Interval<B>(root.t));
        on_edge = along.hi() >= B(0) && along.lo() <= f->length_sq.hi();
        // At a corner met exactly (corner on corner, on a mirror at x = 76) the point at root.t,
        // a few ulps early, was certainly short of the edge's end for every feature pair there,
        // and the contact was missed (docs/rotation.md, E5): the span of the crossing decides,
        // first B's own (wider, cheap: the search past the crossing needs its end anyway), then
        // the wider type's.
        if (!on_edge && !root.at_start_overlap) {
          first_negative = past_crossing(gap, root.t, hi);
          const B last_positive = root.t > lo ? interval_next_down(root.t) : root.t;
          on_edge = *first_negative < hi && may_be_on(*f, Interval<B>(last_positive, *first_negative)) &&
                    crossing_may_be_on_edge(*f, which, root.t, lo, hi);
        }
      }
      if (on_edge && which.feature == RotatingFeature::VertexEdge && sq.vertices.size() == 2 &&
          behind_segment(P, sp, Q, sq, which.edge, root.t))
        on_edge = false;
      if (on_edge && (!root.at_start_overlap ||
                      (possibly_inside(P, r, rho, Q, sq, root.t) && (!f || possibly_shallowest(P, r, rho, Q, sq, which.edge, root.t)) &&
                       (which.feature != RotatingFeature::VertexEdge ||
                        !other_outline_axis_shallower(P, sp, Q, sq, which.point, which.edge, root.t))))) {
        // A contact at the start whose points do not approach, and whose gap does not go
        // certainly negative before it goes certainly positive or rising (or the window ends),
        // is searched past (see set_contact_test). One whose gap goes negative stays: a body
        // starting to rest on a face (a box lying on a floor under gravity) touches without
        // approaching, and resting contact begins at that zero-impulse event.
        // Placed first (refine): a root at the start may be placed later by the wider type,
        // and the tests below are of the contact where it is placed.
        if (!(root.t <= best_.t)) return;
        bool undecided = false;
        place(root, which, undecided);
        // A corner passed, not entered (the corner rule), is searched past either way, at the
        // start or later (its gap may fall through zero beyond the edge's end).
        const bool at_start = root.t == from_;
        if (at_start || which.feature == RotatingFeature::VertexEdge) {
          const ContactTest test = ask_contact_test(which, root);
          if (test == ContactTest::PassesCorner || (at_start && test == ContactTest::Touches)) {
            if (const std::optional<B> past = past_tangency(gap, root.t, hi)) {
              rule = StartRule::CrossingsOnly;
              lo = *past;
              continue;
            }
            if (test == ContactTest::PassesCorner) {
              rule = StartRule::CrossingsOnly;
              lo = past_crossing(gap, root.t, hi);
              continue;
            }
          }
        }
        keep(root, which, undecided);
        return;
      }
      rule = StartRule::CrossingsOnly;
      lo = first_negative ? *first_negative : past_crossing(gap, root.t, hi);
    }
  }

  // Whether the crossing of `which` first placed at t (by B's enclosure, a few values of B off)
  // may be on its edge: the point's place along the edge over the span in which the exact
  // crossing lies, from the last value of B before t (not before lo) at which the gap is
  // certainly positive to the first after it at which it is certainly negative (none before hi:
  // false), evaluated in the wider type where B has one. (B's own span may be many values of B
  // wide: in float it took a crossing past an edge's end for the contact, 6 ulps before the
  // contact of the feature pair next to it, on the 200-polygon spinning gas.)
  bool crossing_may_be_on_edge(const FeatureFunctions<B>& f, const Which& which, const B& t, const B& lo, const B& hi) const {
    using W = typename Wider<B>::type;
    if constexpr (std::is_void_v<W> || std::is_same_v<B, Quad>) {
      return may_be_on_over_span(f, t, lo, hi);
    } else {
      return may_be_on_over_span(wide_features<W>(which), t, lo, hi);
    }
  }
  template <class W>
  static bool may_be_on_over_span(const FeatureFunctions<W>& f, const B& t, const B& lo, const B& hi) {
    const auto at = [](const B& x) { return Interval<W>(W(x)); };
    B before = t, step = first_step_past(t);
    while (before > lo && !f.gap(at(before)).positive()) {
      before = t - step > lo ? B(t - step) : lo;
      step = step * B(2);
    }
    B after = t;
    step = first_step_past(t);
    while (!f.gap(at(after)).negative()) {
      if (!(t + step < hi)) return false;
      after = t + step;
      step = step * B(2);
    }
    return may_be_on(f, Interval<W>(W(before), W(after)));
  }
  template <class W> static bool may_be_on(const FeatureFunctions<W>& f, const Interval<W>& span) {
    const Interval<W> along = f.along(span);
    return along.hi() >= W(0) && along.lo() <= f.length_sq.hi();
  }

  void search_edge(const FeatureFunctions<B>& f, const PathAt<B>& P, const RotatingShape<B>& sp, const Vec2<B>& r,
                   const B& rho, const PathAt<B>& Q, const RotatingShape<B>& sq, const B& lo, const B& until,
                   const Which& which) {
    search(f.gap, &f, P, sp, r, rho, Q, sq, lo, until, which);
  }

  // The caller's test of a contact (set_contact_test), as its impulse would find; every contact
  // collides without one.
  ContactTest ask_contact_test(const Which& which, const WaveRoot<B>& root) const {
    if (!contact_test_) return ContactTest::Collides;
    RotatingContact<B> c;
    c.status = RootStatus::Root;
    c.t = root.t;
    c.at_start_overlap = root.at_start_overlap;
    c.at_start = root.t == from_;
    c.feature = which.feature;
    c.point_on_a = which.point_on_a;
    c.point = which.point;
    c.edge = which.edge;
    return contact_test_(c);
  }

  // Whether P's body lies certainly behind edge k of the segment Q at t (its vertices' mean).
  static bool behind_segment(const PathAt<B>& P, const RotatingShape<B>& sp, const PathAt<B>& Q,
                             const RotatingShape<B>& sq, std::size_t k, const B& t) {
    Vec2<B> sum;
    for (const Vec2<B>& v : sp.vertices) sum = sum + v;
    const B count = B(static_cast<int>(sp.vertices.size()));
    const Vec2<B> mean{sum.x / count, sum.y / count};
    return point_edge_functions(P, mean, B(0), Q, sq.vertices[k], sq.vertices[(k + 1) % 2]).gap(Interval<B>(t)).negative();
  }

  // The overlap rule's edge is the one the point is least behind (the translating engine's
  // least-penetration axis): a point an ulp behind one edge of a square, leaving it, is a whole
  // side behind the opposite edge, which must not collide it.
  bool possibly_shallowest(const PathAt<B>& P, const Vec2<B>& r, const B& rho, const PathAt<B>& Q,
                           const RotatingShape<B>& sq, std::size_t edge, const B& t) const {
    const std::size_t nq = sq.vertices.size();
    // Distances, not the functions' |e| multiples: compared crosswise, gap_k |e_edge| > gap_edge |e_k|.
    const auto gap = [&](std::size_t k) {
      const FeatureFunctions<B> f = point_edge_functions(P, r, rho, Q, sq.vertices[k], sq.vertices[(k + 1) % nq]);
      return std::pair{f.gap(Interval<B>(t)), f.length_sq.sqrt()};
    };
    const auto [mine, mine_length] = gap(edge);
    for (std::size_t k = 0; k < nq; ++k) {
      if (k == edge) continue;
      const auto [other, length] = gap(k);
      if ((other * mine_length).lo() > (mine * length).hi()) return false;
    }
    return true;
  }

  // The overlap rule between two outlines, as the referee has it (every edge line of either
  // outline is an axis, its depth the least signed distance of the other outline's vertices from
  // it): whether an edge of P is certainly shallower than vertex `point`'s depth behind Q's edge
  // `edge` (possibly_shallowest compares Q's edges). Without it, two triangles left overlapping by
  // rounding apex in apex after a corner impulse struck apex against edge with the edges' normals
  // at one instant, a storm, where the referee found P's edge the least penetrated.
  static bool other_outline_axis_shallower(const PathAt<B>& P, const RotatingShape<B>& sp, const PathAt<B>& Q,
                                           const RotatingShape<B>& sq, std::size_t point, std::size_t edge, const B& t) {
    const std::size_t np = sp.vertices.size(), nq = sq.vertices.size();
    const Interval<B> at(t);
    const FeatureFunctions<B> own =
        point_edge_functions(P, sp.vertices[point], B(0), Q, sq.vertices[edge], sq.vertices[(edge + 1) % nq]);
    const Interval<B> mine = own.gap(at), mine_length = own.length_sq.sqrt();
    for (std::size_t k = 0; k < np; ++k) {
      bool shallower = true;
      for (std::size_t j = 0; j < nq && shallower; ++j) {
        const FeatureFunctions<B> f = point_edge_functions(Q, sq.vertices[j], B(0), P, sp.vertices[k], sp.vertices[(k + 1) % np]);
        // Distances, compared crosswise: gap_j / |e_k| > mine / |e_edge|.
        if (!((f.gap(at) * mine_length).lo() > (mine * f.length_sq.sqrt()).hi())) shallower = false;
      }
      if (shallower) return true;
    }
    return false;
  }

  bool possibly_inside(const PathAt<B>& P, const Vec2<B>& r, const B& rho, const PathAt<B>& Q,
                       const RotatingShape<B>& sq, const B& t) const {
    const std::size_t nq = sq.vertices.size();
    for (std::size_t k = 0; k < nq; ++k) {
      if (point_edge_functions(P, r, rho, Q, sq.vertices[k], sq.vertices[(k + 1) % nq]).gap(Interval<B>(t)).positive()) return false;
    }
    return true;
  }

  // Keeps the earliest result; an Undecided one caps the window (no later root may be reported).
  // A crossing is placed again with the feature's function built in the wider type from the
  // stored values before it caps the window, so that a feature whose crossing is earlier by
  // less than the first placement's doubt is still found.
  void take(WaveRoot<B> r, const Which& which) {
    if (r.status == RootStatus::None || !(r.t <= best_.t)) return;
    bool undecided = false;
    place(r, which, undecided);
    keep(r, which, undecided);
  }

  // A crossing found by the search, placed again (refine; certified: round_correctly, else
  // `undecided`). A root at the start in overlap or a tangency keeps its place.
  void place(WaveRoot<B>& r, const Which& which, bool& undecided) const {
    if (r.status == RootStatus::Root && !r.at_start_overlap && !r.tangent) {
      bool loose = false;
      r.t = refine(which, r.t, best_.t, opt_.correctly_rounded ? nullptr : &loose);
      if (opt_.correctly_rounded) {
        if (const std::optional<B> nearest = round_correctly(which, r.t)) r.t = *nearest;
        else undecided = true;
      } else if (loose) {
        // Robust's promise is a few ulps: a slow crossing, placed by the wider type's enclosure
        // further than that from where the function is certainly negative, takes certified's
        // rounding where that decides (else it keeps the place: a graze-like crossing).
        if (const std::optional<B> nearest = round_correctly(which, r.t)) r.t = *nearest;
      }
    }
  }

  // Keeps a placed result if it is the earliest.
  void keep(const WaveRoot<B>& r, const Which& which, bool undecided) {
    if (r.status == RootStatus::None || !(r.t <= best_.t)) return;
    if (r.t == best_.t && best_.status == RootStatus::Root) return;  // ties: the first found stays
    const bool at_start = r.status == RootStatus::Root && r.t == from_;
    best_ = {r.status, r.t, r.at_start_overlap, r.tangent, at_start, which.feature, which.point_on_a, which.point,
             which.edge, best_.boxes, undecided};
  }

  // The value of B nearest to the downward crossing placed at t (the first value of B at which
  // the function is not certainly positive, up to rounding): the crossing is bracketed between
  // adjacent values lo < hi of B with the function certainly positive at lo and certainly
  // negative at hi, both evaluated in Certifying<B> from the stored values, then its sign at
  // their middle (exact in that type) decides: positive, the crossing is past the middle (hi);
  // negative, before it (lo). Nothing where a sign stays undecided (a crossing within the
  // certifying type's rounding of a value of B or of a middle, or a tangency), where the
  // bracket is more than a few values of B from t and the function not certainly decreasing
  // from t across it, or more than 2^24 values away.
  std::optional<B> round_correctly(const Which& which, const B& t) const {
    using W = typename Certifying<B>::type;
    if constexpr (std::is_void_v<W>) {
      return std::nullopt;
    } else {
      return round_correctly_in<W>(which, t);
    }
  }
  template <class W> std::optional<B> round_correctly_in(const Which& which, const B& t) const {
    const WaveSum<W> f = wide_function<W>(which);
    const auto sign = [&](const B& x) { return f(Interval<W>(W(x))).sign(); };
    const auto nearest = [&](const B& lo, const B& hi) -> std::optional<B> {  // adjacent, + then -
      const int s_mid = f(Interval<W>(W(lo) + (W(hi) - W(lo)) / W(2))).sign();
      if (s_mid == 0) return std::nullopt;
      return s_mid > 0 ? hi : lo;
    };
    // Within a few values of B of t: every value's sign, one by one.
    constexpr int kSteps = 4;
    B hi = t;
    int s_hi = sign(hi);
    for (int k = 0; k < kSteps && s_hi > 0; ++k) s_hi = sign(hi = interval_next_up(hi));
    if (s_hi == 0) return std::nullopt;
    if (s_hi < 0) {
      B lo = interval_next_down(hi);
      int s_lo = sign(lo);
      for (int k = 0; k < kSteps && s_lo < 0; ++k) {
        hi = lo;
        s_lo = sign(lo = interval_next_down(lo));
      }
      if (s_lo == 0) return std::nullopt;
      if (s_lo > 0) return nearest(lo, hi);
    }
    // Farther (a placement in B is off by its enclosure's width over the slope: a few values of
    // B on a steep crossing, hundreds on a slow one, a bounce at 1e-4 m/s): a value of B on
    // each side by steps of 1, 2, 4, ... values from t, then adjacent ones by bisection, with
    // the function certainly decreasing on all of the bracket and t (one crossing, and none
    // between t and the bracket).
    constexpr int kDoublings = 24;
    const int s_t = sign(t);
    if (s_t == 0) return std::nullopt;
    B good = t, bad = t;
    B step = s_t > 0 ? interval_next_up(t) - t : t - interval_next_down(t);
    for (int k = 0;; ++k) {
      if (k == kDoublings) return std::nullopt;
      const B x = s_t > 0 ? t + step : t - step;
      const int s_x = sign(x);
      if (s_x == 0) return std::nullopt;
      (s_x > 0 ? good : bad) = x;
      if (s_x != s_t) break;
      step = step * B(2);
    }
    if (!f.derivative()(Interval<W>(W(std::min(t, good)), W(std::max(t, bad)))).negative()) return std::nullopt;
    for (;;) {
      const B m = good + (bad - good) / B(2);
      if (!(good < m && m < bad)) break;
      const int s_m = sign(m);
      if (s_m == 0) return std::nullopt;
      (s_m > 0 ? good : bad) = m;
    }
    return nearest(good, bad);
  }

  // Whether the function of `which`, built in the wider type, is certainly positive on the
  // values of B next to t, a tangency's place (the minimum of a function convex there lies
  // between two adjacent values of B, t one of them): then the tangency is a near miss closer
  // than B's rounding, no contact. By the mean-value form about t, f(t) + f'([t-, t+]) ([t-, t+]
  // - t): f' is near zero there, where the natural enclosure over two ulps of time would spread
  // f by its slope's terms, far more than such a miss. (A diamond's corner passing a wall 7e-17
  // off, after an impulse of rounding size at an exact graze, was taken for a contact: docs/
  // rotation.md, E3.)
  bool clear_in_wider(const Which& which, const B& t) const {
    using W = typename Wider<B>::type;
    if constexpr (std::is_void_v<W> || std::is_same_v<B, Quad>) {
      return false;
    } else {
      const WaveSum<W> f = wide_function<W>(which);
      const Interval<W> around(W(interval_next_down(t)), W(interval_next_up(t)));
      const Interval<W> at{W(t)};
      return (f(at) + f.derivative()(around) * (around - at)).positive();
    }
  }

  // The crossing of `which` at or after t (the first value of B at which its function, built in
  // B, is not certainly positive; before t it is, so the crossing is not earlier): the first
  // value of B at which the function built in the wider type is not certainly positive, by
  // doubling steps from t and bisection. Coefficients built from the stored values in the wider
  // type carry its rounding, not B's, so the place is known to about B's own precision.
  //
  // With `loose`, also whether the crossing may lie more values of B after the place than robust
  // promises (promised_rotating_time_error_ulps): the wider type's function not certainly
  // negative there. On a steep crossing the wider type's enclosure is far narrower than an ulp
  // of B over the slope; on a slow one (a bounce at 1e-4 m/s) hundreds of values of B wide.
  B refine(const Which& which, const B& t, const B& hi, bool* loose = nullptr) const {
    using W = typename Wider<B>::type;
    if constexpr (std::is_void_v<W> || std::is_same_v<B, Quad>) {
      return t;
    } else {
      const WaveSum<W> f = wide_function<W>(which);
      const auto positive = [&](const B& x) { return f(Interval<W>(W(x))).positive(); };
      const auto place = [&]() {
        if (!positive(t)) return t;
        B good = t, bad = hi, step = interval_next_up(t) - t;
        for (B x = interval_next_up(t); x < hi; x = t + step) {
          if (!positive(x)) {
            bad = x;
            break;
          }
          good = x;
          step = step * B(2);
        }
        for (;;) {
          const B m = good + (bad - good) / B(2);
          if (!(good < m && m < bad)) return bad;
          (positive(m) ? good : bad) = m;
        }
      };
      const B placed = place();
      if (loose) {
        constexpr long long kPromise = *promised_rotating_time_error_ulps(SolverKind::Robust);
        B x = placed;
        for (long long k = 0; k < kPromise; ++k) x = interval_next_up(x);
        *loose = !f(Interval<W>(W(x))).negative();
      }
      return placed;
    }
  }

  // The functions of `which` (a point against an edge) in W, from the search's origin, the stored
  // values converted exactly.
  template <class W> FeatureFunctions<W> wide_features(const Which& which) const {
    return widened_feature_functions<W>(which.point_on_a ? a_ : b_, which.point_on_a ? b_ : a_, which.feature, which.point,
                                        which.edge, origin_);
  }

  // The function of `which` in W, from the search's origin, the stored values converted exactly.
  template <class W> WaveSum<W> wide_function(const Which& which) const {
    if (which.feature != RotatingFeature::CircleVertex) return wide_features<W>(which).gap;
    const RotatingShape<B>& sp = which.point_on_a ? a_ : b_;
    const RotatingShape<B>& sq = which.point_on_a ? b_ : a_;
    const PathAt<W> P = path_at(widened_path<W>(sp.path), W(origin_)), Q = path_at(widened_path<W>(sq.path), W(origin_));
    const Vec2<B>& q = sq.vertices[which.edge];
    return circle_vertex_function(P, W(sp.radius), Q, Vec2<W>{W(q.x), W(q.y)});
  }

  const RotatingShape<B>& a_;
  const RotatingShape<B>& b_;
  StartRule rule_, rule_now_ = StartRule::CrossingsOnly;
  B from_{};  // where the feature searches start (rule_now_ holds there)
  RotatingOptions opt_;
  std::function<ContactTest(const RotatingContact<B>&)> contact_test_;
  // set_bounding_circles: the caller's answer, if given (apart at lo: circles_ holds it)
  bool circles_given_ = false, circles_apart_ = false;
  WaveRoot<B> circles_{};
  RotatingContact<B> best_;
  B origin_{};
  // The fastest any point of one shape closes on the other over the search's window (advance);
  // 0 when not known (then nothing is pruned).
  B vmax_{};
  // distance_lower_bound's buffers and its last separating axis (an edge of a or of b).
  mutable std::vector<Vec2<Interval<B>>> points_a_, points_b_, centre_;
  mutable bool axis_known_ = false, axis_on_a_ = false;
  mutable std::size_t axis_ = 0;
  mutable B last_distance_{};
  B close_{};  // advance()'s threshold
  // The last time advance() proved the shapes apart (NaN if none).
  B apart_at_ = std::numeric_limits<B>::quiet_NaN();
};

// Where and along which normal two shapes touch at a predicted contact (double geometry at the
// contact's time, for the response): the point, the normal from a to b (any length), and
// whether it is a face on a face; with `corners`, the corner rule (robust and certified: the
// fast solver, a game engine's contrast, strikes the edge's normal and has no test that would
// search past a corner it passes, which it would then meet again and again).
//
// Face on face. When the vertex's neighbour along its own outline cannot be told from touching
// the same edge at that time either (its gap's enclosure is not certainly positive: the struck
// vertex itself may be certainly an ulp past the line at its contact time, and a neighbour on
// the same line with it; or not certainly farther from the line than the struck vertex: a
// correctly rounded time may be the double just before the crossing) and lies on the edge, the
// two faces meet along a stretch, not at a point: the point is then the middle of the stretch
// (of the two vertices' positions along the edge, clamped to it), on the struck edge's line,
// and the normal the edge's. The middle because a face that lands flat must bounce without
// turning (a box dropped flat on a floor leaves as the translating engine would have it): one
// impulse stands for pressure spread over the stretch, and its centre is the middle; either end
// would set the box spinning.
//
// Lever arms. The contact point relative to each body's centre is taken from the bodies' own
// frames, not from world coordinates: the point side's arm is its turned vertex (or, face on
// face, the turned middle of its two vertices; a circle's, its radius against the normal), and
// the other's is that plus the difference of the centres. Only the arm's part across the normal
// moves the impulse's angular terms, so the arm need not end on the edge's line. World
// coordinates would round the arm at the scale of the positions (1e-10 of an arm at 1e6 from
// the origin), and the middle of a box landing flat an ulp off its centre, setting it spinning.
//
// Corners (E1 in docs/rotation.md). A vertex struck at an end of the edge (within the corner
// slack, pge/detail/corner.hpp) meets the vertex there: the translating engine's corner rule
// with the directions turned to the contact's angles and the velocities and accelerations of
// the two material points that meet (the centres' plus the turns'). The contact collides only if
// the relative motion enters the overlap cone (`enters`), and along the cone's bisector, not the
// struck edge's normal: with the edge's normal a corner struck corner on corner kept
// approaching the other edge there, 1e-16 behind its line, and rounding chose which edge struck
// next at the same instant.
template <class B> struct RotatingGeometry {
  Vec2<B> point, normal;
  Vec2<B> arm_a, arm_b;  // point - centre of a, of b
  bool face_on_face = false;
  bool corner = false;   // a vertex meeting a vertex: the normal is the corner's
  bool enters = true;    // a corner: whether the relative motion enters the overlap cone
};

template <class B> Vec2<B> centre_at(const StoredPath<B>& p, const B& t) {
  const B s = t - p.t0;
  return p.p0 + p.v0 * s + p.a * (s * s / B(2));
}

template <class B> B angle_at(const StoredPath<B>& p, const B& t) { return p.theta0 + p.omega * (t - p.t0); }

// The size of the two shapes' coordinates at t (their centres' plus their reaches): the scale of
// the rounding of a world position computed from them.
template <class B> B coordinate_scale(const RotatingShape<B>& sp, const RotatingShape<B>& sq, const B& t) {
  using std::abs;
  const auto size = [&](const RotatingShape<B>& s) {
    const Vec2<B> c = centre_at(s.path, t);
    return std::max(abs(c.x), abs(c.y)) + s.reach;
  };
  return std::max(size(sp), size(sq));
}

// The corner slack (constants.hpp) in the units of a vertex's contact function (its distance
// from the edge's line times |e|; ee = e.e): what rounding may put between two points on a line.
template <class B> B corner_tolerance(const RotatingShape<B>& sp, const RotatingShape<B>& sq, const B& t, const B& ee) {
  using std::sqrt;
  return B(kCornerSlackUlps) * std::numeric_limits<B>::epsilon() * coordinate_scale(sp, sq, t) * ee / B(sqrt(ee));
}

// Whether vertex `point` of P, touching Q's edge `edge` at t, meets it strictly inside the edge,
// decided from the stored paths (enclosed in B, then, where that cannot tell, in W): its place
// along the edge at t, in (0, e.e) by more than the slide `u` (the points' relative velocity,
// world; e the edge, world) gives it before the gap closes. Behind the line at t (an overlap)
// the place at t itself; in front of it or on it within rounding, the crossing is up to
// |gap| / |u x e| later, |u.e| |gap| / |u x e| further along (in the functions' units).
template <class W, class B>
bool meets_inside_edge(const RotatingShape<B>& sp, const RotatingShape<B>& sq, std::size_t point, std::size_t edge,
                       const B& t, const Vec2<B>& u, const Vec2<B>& e) {
  using std::abs;
  // P is an outline here: its radius is 0, as the feature functions of a vertex take it.
  const FeatureFunctions<W> f = widened_feature_functions<W>(sp, sq, RotatingFeature::VertexEdge, point, edge, t);
  const Interval<W> at{W(t)};
  const Interval<W> along = f.along(at), gap = f.gap(at);
  W margin(0);
  if (!gap.negative()) {
    const W across = W(abs(cross(u, e)));
    if (!(across > W(0))) return false;
    const W size = std::max(abs(gap.lo()), abs(gap.hi()));
    // Twice the slide: u and e are B's roundings, and so is this quotient.
    margin = W(2) * size * W(abs(dot(u, e))) / across;
  }
  return (along - Interval<W>(margin)).positive() && (along + Interval<W>(margin) - f.length_sq).negative();
}
template <class B>
bool strictly_inside_edge(const RotatingShape<B>& sp, const RotatingShape<B>& sq, std::size_t point, std::size_t edge,
                          const B& t, const Vec2<B>& u, const Vec2<B>& e) {
  if (meets_inside_edge<B>(sp, sq, point, edge, t, u, e)) return true;
  using W = typename Certifying<B>::type;
  if constexpr (std::is_void_v<W>) {
    return false;
  } else {
    return meets_inside_edge<W>(sp, sq, point, edge, t, u, e);
  }
}

// The sign of the rate at which the contact's gap closes at t, by the exact stored paths: the
// derivative of the feature's gap function (a vertex or a circle against an edge; P the point's
// shape, Q the edge's), enclosed in W; 0 where W cannot tell. That derivative is the relative
// velocity of the two material points at the contact along the edge's normal (the normal's own
// turn adds the point's place along the edge times the turn, which the edge's material point
// adds back), so it is what an impulse there acts on, free of its rounding.
template <class W, class B>
int gap_rate_sign_in(const RotatingShape<B>& sp, const RotatingShape<B>& sq, const RotatingContact<B>& c, const B& t) {
  return widened_feature_functions<W>(sp, sq, c.feature, c.point, c.edge, t).gap.derivative()(Interval<W>(W(t))).sign();
}
// The same in B, then where that cannot tell in its wider type, then in its certifying type
// (double: long double, then quad); 0 where none can (a rate of exactly zero, or within quad's
// rounding of it). Not for a circle against a vertex.
template <class B>
int gap_rate_sign(const RotatingShape<B>& sp, const RotatingShape<B>& sq, const RotatingContact<B>& c, const B& t) {
  int sign = gap_rate_sign_in<B>(sp, sq, c, t);
  using Wide = typename Wider<B>::type;
  constexpr bool has_wide = std::is_same_v<Wide, double> || std::is_same_v<Wide, long double> || std::is_same_v<Wide, Quad>;
  if constexpr (has_wide) {
    if (sign == 0) sign = gap_rate_sign_in<Wide>(sp, sq, c, t);
  }
  using Sure = typename Certifying<B>::type;
  if constexpr (!std::is_void_v<Sure>) {
    if constexpr (!has_wide || !std::is_same_v<Sure, Wide>) {
      if (sign == 0) sign = gap_rate_sign_in<Sure>(sp, sq, c, t);
    }
  }
  return sign;
}

// The corner rule at vertex `point` of P struck at an end of Q's edge `edge` (qa to qb, world):
// whether the vertex is within the corner slack of an end and, if so, the corner's normal (from
// Q towards P) and whether the relative motion enters the overlap cone. `arm_p` and `arm_q` are
// the vertex relative to P's and Q's centres.
//
// A contact at its search's start (at_start: t is its exact time) is first placed on the edge by
// its exact paths, as the referee places it (a contact point strictly inside the edge is an edge
// contact, whatever the slack says): the place along the edge enclosed in B, then in the
// certifying type; only a place these cannot tell from the end takes the corner rule. (A
// diamond's corner struck corner on corner on a floor's end lay 3e-17 inside the floor after the
// impulse, moving down: the exact paths touch there and approach, a collision the corner rule,
// which saw the corner leaving past the end, had skipped: the referee's immediate contact.)
template <class B>
void corner_rule(const RotatingShape<B>& sp, const RotatingShape<B>& sq, std::size_t point, std::size_t edge, const B& t,
                 bool at_start, const Vec2<B>& qa, const Vec2<B>& qb, const Vec2<B>& arm_p, const Vec2<B>& arm_q,
                 Vec2<B>& out, RotatingGeometry<B>& g) {
  using std::sqrt;
  const B tp = angle_at(sp.path, t), tq = angle_at(sq.path, t);
  const Vec2<B> cp = centre_at(sp.path, t);
  // The material points' velocities and accelerations: the centre's plus the turn's.
  const auto velocity = [&](const StoredPath<B>& p, const Vec2<B>& arm) { return p.v0 + p.a * (t - p.t0) + perp(arm) * p.omega; };
  const auto acceleration = [&](const StoredPath<B>& p, const Vec2<B>& arm) { return p.a - arm * (p.omega * p.omega); };
  const Vec2<B> u = velocity(sp.path, arm_p) - velocity(sq.path, arm_q);
  const Vec2<B> acc = acceleration(sp.path, arm_p) - acceleration(sq.path, arm_q);
  const Vec2<B> e = qb - qa;
  if (at_start && strictly_inside_edge(sp, sq, point, edge, t, u, e)) return;
  const B scale = coordinate_scale(sp, sq, t);
  const Vec2<B> d = cp + arm_p - qa;
  const B len = sqrt(dot(e, e));
  const EdgeSpot spot = locate_on_edge(d, u, e, len, scale);
  if (spot != EdgeSpot::Start && spot != EdgeSpot::End) return;
  // Inside the edge by the slack unwidened: a face contact (as in the translating rule, which
  // says why).
  if (locate_on_edge(d, Vec2<B>{}, e, len, scale) == EdgeSpot::Interior) return;
  const std::size_t w = spot == EdgeSpot::End ? (edge + 1) % sq.vertices.size() : edge;
  // An outline's interior directions at vertex i, turned: back along the edge arriving there and
  // along the edge leaving it (one direction twice at a segment's end).
  const auto interior = [](const RotatingShape<B>& s, std::size_t i, const B& angle) {
    const std::size_t count = s.vertices.size();
    const Vec2<B>& v = s.vertices[i];
    return std::array<Vec2<B>, 2>{rotated(angle, s.vertices[(i + count - 1) % count] - v),
                                  rotated(angle, s.vertices[(i + 1) % count] - v)};
  };
  const std::array<Vec2<B>, 2> q = interior(sq, w, tq), p = interior(sp, point, tp);
  const std::optional<Cone<B>> cone = overlap_cone_of(q[0], q[1], p[0], p[1]);
  if (!cone) return;
  g.corner = true;
  // Each bounding ray turns with its body: Q's interior directions at Q's rate, P's (reversed)
  // at P's.
  const auto rate = [&](const Vec2<B>& ray) {
    const auto same = [&](const Vec2<B>& x) { return x.x == ray.x && x.y == ray.y; };
    return same(q[0]) || same(q[1]) ? sq.path.omega : sp.path.omega;
  };
  g.enters = enters_cone(*cone, u, acc, rate(cone->cw), rate(cone->ccw));
  out = corner_normal(*cone);
}

template <class B>
RotatingGeometry<B> rotating_contact_geometry(const RotatingShape<B>& a, const RotatingShape<B>& b,
                                              const RotatingContact<B>& c, bool corners = true) {
  const RotatingShape<B>& sp = c.point_on_a ? a : b;
  const RotatingShape<B>& sq = c.point_on_a ? b : a;
  const Vec2<B> cp = centre_at(sp.path, c.t), cq = centre_at(sq.path, c.t);
  const B tp = angle_at(sp.path, c.t), tq = angle_at(sq.path, c.t);
  const std::size_t n = sq.vertices.size();
  RotatingGeometry<B> g;
  // Outward from Q towards P; the arms from P's and Q's centres.
  Vec2<B> out, arm_p, arm_q;
  const Vec2<B> centres = cp - cq;
  if (c.feature == RotatingFeature::CircleVertex) {
    arm_q = rotated(tq, sq.vertices[c.edge]);
    const Vec2<B> v = cq + arm_q;
    g.point = v;
    out = cp - v;
    arm_p = arm_q - centres;
  } else {
    const Vec2<B> qa = cq + rotated(tq, sq.vertices[c.edge]), qb = cq + rotated(tq, sq.vertices[(c.edge + 1) % n]);
    const Vec2<B> e = qb - qa;
    out = Vec2<B>{e.y, -e.x};
    if (c.feature == RotatingFeature::CircleEdge) {
      using std::sqrt;
      const B len = sqrt(dot(e, e));
      arm_p = out * (-sp.radius / len);
      g.point = cp + arm_p;
    } else {
      arm_p = rotated(tp, sp.vertices[c.point]);
      g.point = cp + arm_p;
      const std::size_t m = sp.vertices.size();
      const PathAt<B> P = path_at(sp.path, c.t), Q = path_at(sq.path, c.t);
      const Interval<B> at(c.t);
      const B ee = dot(e, e);
      const Interval<B> struck =
          point_edge_functions(P, sp.vertices[c.point], B(0), Q, sq.vertices[c.edge], sq.vertices[(c.edge + 1) % n])
              .gap(at);
      for (const std::size_t j : {(c.point + 1) % m, (c.point + m - 1) % m}) {
        if (j == c.point) continue;
        const FeatureFunctions<B> f =
            point_edge_functions(P, sp.vertices[j], B(0), Q, sq.vertices[c.edge], sq.vertices[(c.edge + 1) % n]);
        const Interval<B> along = f.along(at), gap = f.gap(at);
        // Touching the line, or no farther from it than the struck vertex (a certified time
        // rounded to the double before the crossing: both an ulp's travel short of the line),
        // nor deeper behind it than the struck vertex by more than rounding (a triangle's apex
        // struck apex on apex meets the end of the other's far edge too, whose line its
        // neighbour lies a body's depth behind: not a face on that face).
        if ((gap.positive() && (gap - struck).positive()) || gap.hi() < struck.lo() - corner_tolerance(sp, sq, c.t, ee) ||
            along.hi() < B(0) || along.lo() > f.length_sq.hi())
          continue;
        // Both on the edge's line: the middle of their stretch along it, clamped to the edge.
        const Vec2<B> other = cp + rotated(tp, sp.vertices[j]);
        const B a0 = dot(g.point - qa, e), a1 = dot(other - qa, e);
        const B s0 = std::clamp(a0, B(0), ee), s1 = std::clamp(a1, B(0), ee);
        g.point = qa + e * ((s0 + s1) / (B(2) * ee));
        // Both vertices on the edge: the middle of the two, in P's frame; else (clamped to an
        // end) the middle on the edge, from world coordinates.
        arm_p = s0 == a0 && s1 == a1 ? rotated(tp, (sp.vertices[c.point] + sp.vertices[j]) * B(0.5)) : g.point - cp;
        g.face_on_face = true;
        break;
      }
      if (corners && !g.face_on_face) corner_rule(sp, sq, c.point, c.edge, c.t, c.at_start, qa, qb, arm_p, centres + arm_p, out, g);
    }
    arm_q = centres + arm_p;
  }
  g.normal = c.point_on_a ? -out : out;
  g.arm_a = c.point_on_a ? arm_p : arm_q;
  g.arm_b = c.point_on_a ? arm_q : arm_p;
  return g;
}

template <class B>
RotatingContact<B> predict_rotating_pair(const RotatingShape<B>& a, const RotatingShape<B>& b, const B& lo, const B& hi,
                                         StartRule rule, RotatingOptions opt = {},
                                         std::type_identity_t<std::function<ContactTest(const RotatingContact<B>&)>> test = {}) {
  RotatingPairPredictor<B> p(a, b, rule, opt);
  p.set_contact_test(std::move(test));
  return p.earliest(lo, hi);
}

}  // namespace pge::detail
