// The fast solver's prediction for a pair of which one or both bodies turn (issue "Rotation",
// item 4: "fast: plain floating point, what a game engine would do, the contrast baseline").
//
// Conservative advancement in plain floating point, as game engines find a time of impact: from
// `lo`, step by the shapes' distance over the fastest their points can close (the centres'
// relative speed over the window plus each body's |omega| times its reach), until the distance is
// within a slop (2^-20 of the smaller reach) and the closest features approach; then Newton's
// method on that feature's gap places the crossing (polish). No enclosure, no proof: distances,
// bounds and the Newton steps are rounded like any other double. Measured on 150 random pairs of
// turning shapes, the time is within 3.4 ulps of a 50-digit reference
// (RotationPairs.FastSearchFindsTheContactsNearTheReferenceTime); what it gets wrong is what a
// proof would catch: a graze that comes closer than the slop without touching is a contact
// (fixtures/scenes/rotation/corner-near-misses-a-wall-for-1000-turns.json: fast strikes the wall on the
// first turn), and far from the origin the gap loses digits to cancellation (4.8e-11 s off at
// 1e6). The robust and certified solvers (predict_rotating.hpp) are held to the expect blocks;
// this one is run beside them for contrast.
//
// Work. Each step costs one sine and cosine per turning body and one point-to-segment distance
// per feature pair (none while the bounding circles are farther apart than the slop); a step
// shrinks the distance to a contact ahead by at least the fraction of vmax at which the closest
// points close, so a head-on approach ends in a few steps. A search takes at most
// kFastRotatingSteps steps; past them the result is Undecided at the time reached (no contact
// found before it), and the caller predicts again from there, as for the robust search's box
// budget.
#pragma once

#include "pge/detail/predict_rotating.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

namespace pge::detail {

inline constexpr int kFastRotatingSteps = 128;

template <class B> class FastRotatingPredictor {
 public:
  FastRotatingPredictor(const RotatingShape<B>& a, const RotatingShape<B>& b) : a_(a), b_(b) {}

  RotatingContact<B> earliest(const B& lo, const B& hi) {
    using std::abs;
    RotatingContact<B> out;
    out.t = hi;
    const B window = hi - lo;
    const Vec2<B> dv = velocity_at(a_.path, lo) - velocity_at(b_.path, lo), da = a_.path.a - b_.path.a;
    const B vmax = norm(dv) + norm(da) * window + abs(a_.path.omega) * a_.reach + abs(b_.path.omega) * b_.reach;
    const B reach = a_.reach + b_.reach;
    // The smaller body sets the scale (a wall's reach is its length).
    const B slop = std::min(a_.reach, b_.reach) * B(1.0 / 1048576);  // 2^-20
    B t = lo, last = lo;  // last: the step before t (the contact is not before it)
    for (int step = 0; step < kFastRotatingSteps; ++step) {
      // The bounding circles first: no sine, no cosine, no feature while they are apart.
      B d = norm(centre_at(a_.path, t) - centre_at(b_.path, t)) - reach;
      if (!(d > slop)) {
        const Probe p = closest(t);
        d = p.distance;
        if (!(d > slop)) {
          if (p.approaching) {
            out.status = RootStatus::Root;
            out.t = polish(p, t, last, hi);
            out.at_start_overlap = t == lo && d < B(0);
            out.feature = p.feature;
            out.point_on_a = p.point_on_a;
            out.point = p.point;
            out.edge = p.edge;
            return out;
          }
          // Touching and parting (a pair that has just collided): a step of a slop, which may
          // overshoot a contact that follows within it (a tiny bounce); polish then steps back.
          d = slop;
        }
      }
      if (!(vmax > B(0))) return out;
      B next = t + d / vmax;
      if (!(next > t)) next = interval_next_up(t);
      if (!(next < hi)) return out;
      last = t;
      t = next;
    }
    out.status = RootStatus::Undecided;
    out.t = t;
    return out;
  }

 private:
  struct Probe {
    B distance = std::numeric_limits<B>::infinity();  // negative: overlapping, the least depth
    RotatingFeature feature = RotatingFeature::VertexEdge;
    bool point_on_a = false;
    std::size_t point = 0, edge = 0;
    bool approaching = false;
  };

  static B norm(const Vec2<B>& v) {
    using std::sqrt;
    return sqrt(dot(v, v));
  }
  static Vec2<B> velocity_at(const StoredPath<B>& p, const B& t) { return p.v0 + p.a * (t - p.t0); }

  // The body's points at t in world coordinates (an outline's vertices), its centre, its velocity.
  struct Placed {
    Vec2<B> centre, velocity;
    Vec2<B> inner;  // a point of the body: its vertices' mean (the centre may lie outside), or a circle's centre
    B omega{};
    std::vector<Vec2<B>> points;
  };
  static void place(const RotatingShape<B>& s, const B& t, Placed& out) {
    using std::cos;
    using std::sin;
    out.centre = centre_at(s.path, t);
    out.velocity = velocity_at(s.path, t);
    out.omega = s.path.omega;
    const B theta = angle_at(s.path, t), c = cos(theta), sn = sin(theta);
    out.points.clear();
    Vec2<B> sum{};
    for (const Vec2<B>& v : s.vertices) {
      out.points.push_back(out.centre + Vec2<B>{c * v.x - sn * v.y, sn * v.x + c * v.y});
      sum = sum + out.points.back();
    }
    out.inner = out.points.empty() ? out.centre : sum * (B(1) / B(out.points.size()));
  }
  // The velocity of the body's material point at x.
  static Vec2<B> point_velocity(const Placed& s, const Vec2<B>& x) { return s.velocity + perp(x - s.centre) * s.omega; }

  // Whether P's point at p and Q's at x close along n (from Q towards P).
  static bool closing(const Placed& P, const Vec2<B>& p, const Placed& Q, const Vec2<B>& x, const Vec2<B>& n) {
    return dot(point_velocity(P, p) - point_velocity(Q, x), n) < B(0);
  }

  // The features of P's point p (radius rho: a circle's centre) against Q's outline: the nearest
  // edge or vertex, and the deepest separating axis. Updates `best` where nearer.
  static void point_against(const Placed& P, const Vec2<B>& p, const B& rho, bool point_on_a, std::size_t point,
                            const Placed& Q, Probe& best) {
    using std::sqrt;
    const std::size_t n = Q.points.size();
    B axis_gap = -std::numeric_limits<B>::infinity();
    std::size_t axis = 0;
    B near = std::numeric_limits<B>::infinity();
    std::size_t near_edge = 0;
    B near_u = 0, near_gap = 0;
    const std::size_t side = n == 2 && cross(Q.points[1] - Q.points[0], P.inner - Q.points[0]) > B(0) ? 1 : 0;
    for (std::size_t k = 0; k < n; ++k) {
      const Vec2<B> qa = Q.points[k], e = Q.points[(k + 1) % n] - qa;
      const B ee = dot(e, e), along = dot(p - qa, e);
      const B len = sqrt(ee);
      const B gap = len > B(0) ? cross(e, p - qa) / -len : B(0);  // outward: (e.y, -e.x)
      if (gap > axis_gap) {
        axis_gap = gap;
        axis = k;
      }
      // The nearest point of an outline to a point outside it is on an edge that the point is
      // in front of (at a vertex, on one of its two edges at least); of two edges at the same
      // distance (a vertex, or a segment's two sides), the one the point faces more squarely.
      // A segment has two sides and no inside: the side P's inner point is on, and the point's
      // distance negative only where P's body has crossed the segment itself (the line from
      // P's inner point to the point meets it between its ends; a point past the segment's
      // line beyond its ends is only apart).
      if (n == 2 ? k != side : gap < B(0)) continue;
      const B u = ee > B(0) ? std::clamp(along / ee, B(0), B(1)) : B(0);
      B dist = norm(p - (qa + e * u));
      if (gap < B(0) && len > B(0)) {
        const B inner_gap = cross(e, P.inner - qa) / -len;  // >= 0: the side is P's inner point's
        const Vec2<B> meet = P.inner + (p - P.inner) * (inner_gap / (inner_gap - gap));
        const B at = dot(meet - qa, e);
        if (at >= B(0) && at <= ee) dist = gap;
      }
      if (dist < near || (dist == near && gap > near_gap)) {
        near = dist;
        near_gap = gap;
        near_edge = k;
        near_u = u;
      }
    }
    B distance;
    std::size_t edge = near_edge;
    Vec2<B> x, normal;
    RotatingFeature feature = rho > B(0) ? RotatingFeature::CircleEdge : RotatingFeature::VertexEdge;
    const Vec2<B> qa = Q.points[edge], e = Q.points[(edge + 1) % n] - qa;
    if (axis_gap <= B(0) && n > 2) {
      // Inside Q's outline: the least deep edge.
      distance = axis_gap - rho;
      edge = axis;
      const Vec2<B> ea = Q.points[axis], ee = Q.points[(axis + 1) % n] - ea;
      normal = Vec2<B>{ee.y, -ee.x};
      x = p - normal * (axis_gap / norm(normal));
    } else {
      // The normal the response will use (rotating_contact_geometry): the edge's outward one,
      // or from the vertex to a circle's centre.
      distance = near - rho;
      x = qa + e * near_u;
      normal = Vec2<B>{e.y, -e.x};
      if (rho > B(0) && (near_u == B(0) || near_u == B(1)) && near > B(0)) {
        feature = RotatingFeature::CircleVertex;
        edge = near_u == B(0) ? edge : (edge + 1) % n;
        normal = p - x;
      }
    }
    if (!(distance < best.distance)) return;
    best.distance = distance;
    best.feature = feature;
    best.point_on_a = point_on_a;
    best.point = point;
    best.edge = edge;
    // A circle's surface point: its centre moved towards Q by rho (a circle does not turn).
    const Vec2<B> on_p = rho > B(0) ? p - normal * (rho / norm(normal)) : p;
    best.approaching = closing(P, on_p, Q, x, normal);
  }

  // Newton's method on the touching feature's signed gap g (its distance from the edge's line,
  // or a circle's from the vertex, less the radius), from the step at which the advancement
  // stopped, a slop short of the contact, or past it (a step of a slop from a touching pair
  // that overshot a tiny bounce): its rate is the closest points' relative velocity along the
  // normal (the normal's own turning adds nothing there: it is perpendicular to it). Once a
  // step lands past the crossing (g < 0; from near the top of a slow arc Newton overshoots far)
  // the crossing is bracketed, and a step that would leave the bracket halves it instead. At
  // most kPolishSteps steps, all within [last, hi); none where the feature stops closing.
  static constexpr int kPolishSteps = 64;
  B polish(const Probe& p, B t, const B& last, const B& hi) {
    B before = last, after = hi;  // g >= 0 at `before` (the advancement's last step); < 0 at `after` once found
    bool bracketed = false;
    for (int step = 0; step < kPolishSteps; ++step) {
      const B g = gap(p, t, rate_);
      if (g == B(0)) break;
      if (g > B(0)) {
        before = t;
      } else {
        after = t;
        bracketed = true;
      }
      if (!bracketed && !(rate_ < B(0))) break;  // not closing, nothing past: stay
      B next = t - g / rate_;
      if (!(next > before && next < after)) {
        if (!bracketed) break;
        next = before + (after - before) / B(2);
      }
      if (next == t || next == before || next == after) break;
      t = next;
    }
    return t;
  }

  // Feature p's signed gap at t, and (in `rate`) its derivative.
  B gap(const Probe& p, const B& t, B& rate) {
    place(a_, t, pa_);
    place(b_, t, pb_);
    const Placed& P = p.point_on_a ? pa_ : pb_;
    const Placed& Q = p.point_on_a ? pb_ : pa_;
    const RotatingShape<B>& sp = p.point_on_a ? a_ : b_;
    const bool round = sp.circle();
    const Vec2<B> at = round ? P.centre : P.points[p.point];
    Vec2<B> x, n;
    if (p.feature == RotatingFeature::CircleVertex) {
      x = Q.points[p.edge];
      n = at - x;
    } else {
      const Vec2<B> qa = Q.points[p.edge], e = Q.points[(p.edge + 1) % Q.points.size()] - qa;
      n = Vec2<B>{e.y, -e.x};
      x = at - n * (dot(at - qa, n) / dot(n, n));
    }
    const B len = norm(n);
    if (!(len > B(0))) {
      rate = 0;
      return 0;
    }
    const Vec2<B> unit = n * (B(1) / len);
    rate = dot(point_velocity(P, at) - point_velocity(Q, x), unit);
    return dot(at - x, unit) - (round ? sp.radius : B(0));
  }

  Probe closest(const B& t) {
    place(a_, t, pa_);
    place(b_, t, pb_);
    Probe best;
    if (a_.circle() || b_.circle()) {
      const bool a_round = a_.circle();
      const Placed& C = a_round ? pa_ : pb_;
      point_against(C, C.centre, a_round ? a_.radius : b_.radius, a_round, 0, a_round ? pb_ : pa_, best);
      return best;
    }
    for (std::size_t i = 0; i < pa_.points.size(); ++i) point_against(pa_, pa_.points[i], B(0), true, i, pb_, best);
    for (std::size_t i = 0; i < pb_.points.size(); ++i) point_against(pb_, pb_.points[i], B(0), false, i, pa_, best);
    return best;
  }

  const RotatingShape<B>& a_;
  const RotatingShape<B>& b_;
  Placed pa_, pb_;
  B rate_{};
};

template <class B>
RotatingContact<B> predict_rotating_pair_fast(const RotatingShape<B>& a, const RotatingShape<B>& b, const B& lo, const B& hi) {
  return FastRotatingPredictor<B>(a, b).earliest(lo, hi);
}

}  // namespace pge::detail
