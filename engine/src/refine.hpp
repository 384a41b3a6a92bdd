// Correctly rounded event times for the certified solver. A prediction solves the contact
// polynomial built in T from the bodies' rounded states at `now`; its root is exact for that
// polynomial, but the polynomial is not the exact contact function of the paths the bodies
// really follow. Before a certified event is processed its time is therefore re-derived from
// those paths: each moving body follows p(t) = p0 + v0 (t - t0) + acc (t - t0)^2 / 2 with its
// stored values read as exact numbers (the state the exact oracle reads, oracle/), and the
// event's feature pair has an exact contact function whose sign is decided in dyadic rationals.
// Walking T values outwards from the predicted time and bisecting finds the two adjacent T
// values around the crossing; the sign at their midpoint picks the nearer one (ties to even).
// The contact functions are the oracle's (squared forms, so no square root is ever taken):
//   circle-circle  |d|^2 - (ra + rb)^2
//   circle-edge    side^2 - r^2 |e|^2, side = cross(centre - edge start, e); a polygon's edge
//                  is one-sided (side <= 0 is behind it: negative), a segment's two-sided
//   circle-vertex  |centre - vertex|^2 - r^2
//   vertex-edge    cross(vertex - edge start, e)
// Costs a few dozen exact evaluations per processed event (not per prediction).
#pragma once

#include "body_shape.hpp"
#include "event_heap.hpp"

#include "pge/roots.hpp"
#include "pge/vec2.hpp"

#include <cmath>
#include <limits>
#include <optional>

namespace pge {
namespace refine {

using detail::exact::Dyadic;

// A dyadic rational with the arithmetic Vec2, dot and cross need.
struct Exact {
  Dyadic d;
  Exact() = default;
  Exact(int v) { d.m = v; detail::exact::normalize(d); }  // NOLINT: Vec2's members start as {0}
  explicit Exact(Dyadic v) : d(std::move(v)) { detail::exact::normalize(d); }
  template <class T> static Exact of(const T& x) { return Exact(detail::exact::to_dyadic(x)); }

  friend Exact operator+(const Exact& a, const Exact& b) {
    detail::exact::Int ma, mb;
    Dyadic r;
    r.e = detail::exact::align(a.d, b.d, ma, mb);
    r.m = ma + mb;
    return Exact(std::move(r));
  }
  friend Exact operator-(const Exact& a) {
    Dyadic r = a.d;
    r.m = -r.m;
    return Exact(std::move(r));
  }
  friend Exact operator-(const Exact& a, const Exact& b) { return a + (-b); }
  friend Exact operator*(const Exact& a, const Exact& b) {
    Dyadic r;
    r.m = a.d.m * b.d.m;
    r.e = a.d.e + b.d.e;
    return Exact(std::move(r));
  }
  Exact half() const {
    Dyadic r = d;
    r.e -= 1;
    return Exact(std::move(r));
  }
  int sign() const { return detail::exact::sign_of_int(d.m); }
};

using ExactVec = Vec2<Exact>;

template <class T> ExactVec exact_vec(const Vec2<T>& v) { return {Exact::of(v.x), Exact::of(v.y)}; }

// One body as the exact contact functions read it.
template <class T> struct ExactBody {
  const BodyShape<T>* shape = nullptr;
  bool fixed = false;
  Exact t0;
  ExactVec p0, v0, half_acc;

  ExactVec position(const Exact& t) const {
    if (fixed) return p0;
    const Exact tau = t - t0;
    return p0 + (v0 + half_acc * tau) * tau;
  }
  // Vertex k: a fixed body's rounded world vertex, a moving body's exact p(t) + local[k].
  ExactVec vertex(const ExactVec& p, std::size_t k) const {
    return shape->fixed ? exact_vec(shape->world[k]) : p + exact_vec(shape->local[k]);
  }
  // Edge k's vector (vertex k+1 - vertex k) in the body's own frame: constant in time.
  ExactVec edge(std::size_t k) const {
    const auto& v = shape->fixed ? shape->world : shape->local;
    return exact_vec(v[(k + 1) % v.size()]) - exact_vec(v[k]);
  }
};

template <class T>
ExactBody<T> exact_body(const BodyShape<T>& shape, bool fixed, const T& t0, const Vec2<T>& p0, const Vec2<T>& v0,
                        const Vec2<T>& acc) {
  ExactBody<T> b;
  b.shape = &shape;
  b.fixed = fixed;
  b.p0 = exact_vec(p0);
  if (!fixed) {
    b.t0 = Exact::of(t0);
    b.v0 = exact_vec(v0);
    b.half_acc = {Exact::of(acc.x).half(), Exact::of(acc.y).half()};
  }
  return b;
}

// Sign of the exact contact function of the scheduled feature pair at time t (negative:
// overlapping, zero: touching).
template <class T>
int contact_sign(const ExactBody<T>& a, const ExactBody<T>& b, const Scheduled<T>& s, const Exact& t) {
  const ExactVec pa = a.position(t), pb = b.position(t);
  switch (s.contact) {
    case ContactKind::CircleCircle: {
      const ExactVec d = pb - pa;
      const Exact rr = Exact::of(a.shape->radius) + Exact::of(b.shape->radius);
      return (dot(d, d) - rr * rr).sign();
    }
    case ContactKind::CircleEdge:
    case ContactKind::CircleVertex: {
      const bool a_circle = a.shape->kind == ShapeKind::Circle;
      const ExactBody<T>& o = a_circle ? b : a;
      const ExactVec& c = a_circle ? pa : pb;
      const ExactVec& po = a_circle ? pb : pa;
      const std::size_t k = a_circle ? s.feature_b : s.feature_a;
      const Exact r = Exact::of(a_circle ? a.shape->radius : b.shape->radius);
      const ExactVec q = c - o.vertex(po, k);
      if (s.contact == ContactKind::CircleVertex) return (dot(q, q) - r * r).sign();
      const ExactVec e = o.edge(k);
      const Exact side = cross(q, e);
      if (o.shape->kind == ShapeKind::Polygon && side.sign() <= 0) return -1;  // behind a one-sided edge
      return (side * side - r * r * dot(e, e)).sign();
    }
    case ContactKind::VertexEdge:
    case ContactKind::EdgeVertex: {
      const bool a_vertex = s.contact == ContactKind::VertexEdge;
      const ExactBody<T>& vb = a_vertex ? a : b;
      const ExactBody<T>& eb = a_vertex ? b : a;
      const std::size_t k = a_vertex ? s.feature_a : s.feature_b;  // vertex
      const std::size_t j = a_vertex ? s.feature_b : s.feature_a;  // internal edge
      const ExactVec d = vb.vertex(a_vertex ? pa : pb, k) - eb.vertex(a_vertex ? pb : pa, j);
      return cross(d, eb.edge(j)).sign();
    }
  }
  return 1;
}

// --- Near-grazes of two circles, decided exactly (robust and certified).
// The contact polynomial built from rounded states decides a pair that passes within rounding
// of touching by its rounding: a path one ulp inside the radius sum can come out as a graze (a
// missed collision) and one ulp outside as a hit (a phantom). When the rounded polynomial's
// closest approach in the window is that close to zero, the pair is predicted again from the
// exact polynomial of the exact paths (the oracle's), isolated with the exact solver.

// Relative closeness below which a closest approach counts as a near-graze: far above the
// rounding of the polynomial (a few hundred ulps of its scale), far below any real miss.
inline constexpr double kNearGrazeRelative = 0x1p-36;

// Whether the rounded function p = |d + dv t + da t^2 / 2|^2 - r^2 comes within rounding of
// zero at a local minimum in (0, horizon], or starts within rounding of zero while approaching
// or receding by less than 2^-36 of its relative speed (p'(0) = 2 d.dv against 2 |d| |dv|): a
// touching pair whose approach is the rounding's call. That includes the ever smaller
// residues a cascade of hand-overs leaves (relative speeds of 1e-16, 1e-32, ...), which the
// robust solver's degree reduction would drop as negligible. `scale` is the pair's coordinate
// magnitude.
template <class T>
bool near_graze(const Poly<T>& p, const Vec2<T>& d, const Vec2<T>& dv, const Vec2<T>& da, const T& r, const T& scale,
                const T& horizon) {
  using std::abs;
  using std::sqrt;
  // The square of the pair's length scale at t (|d| + r + |dv| t + |da| t^2 / 2 + scale), bounded
  // by Cauchy-Schwarz without square roots: this runs on every prediction of two circles.
  const auto reach2 = [&](const T& t) {
    const T rs = r + scale;
    return T(4) * (dot(d, d) + rs * rs + dot(dv, dv) * (t * t) + dot(da, da) * (t * t * t * t / T(4)));
  };
  const auto close = [&](const T& t) { return abs(p(t)) <= T(kNearGrazeRelative) * reach2(t); };
  if (abs(p.c[0]) <= T(kNearGrazeRelative) * reach2(T(0)) &&
      p.c[1] <= T(2 * kNearGrazeRelative) * sqrt(dot(d, d) * dot(dv, dv)))
    return true;
  if (p.degree == 2) {
    if (!(p.c[2] > T(0)) || !(p.c[1] < T(0))) return false;
    const T t = -p.c[1] / (T(2) * p.c[2]);
    return t <= horizon && close(t);
  }
  // Local minima of p: where p' crosses zero going up, that is where -p' crosses going down.
  Poly<T> falling = p.derivative();
  for (int k = 0; k <= falling.degree; ++k) falling.c[k] = -falling.c[k];
  bool found = false;
  robust_visit_downward_roots(falling, T(0), horizon, StartRule::CrossingsOnly, [&](const T& t, bool) {
    found = close(t);
    return found;
  });
  return found;
}

// The exact contact polynomial of two circles in tau = t - now (a positive multiple of it, in
// integers): |pb(now + tau) - pa(now + tau)|^2 - (ra + rb)^2 from the exact paths.
template <class T>
detail::exact::IntPoly exact_circle_poly(const ExactBody<T>& a, const ExactBody<T>& b, const Exact& now) {
  // Each path in tau: c0 + c1 tau + c2 tau^2 with D = now - t0: c0 = p(now), c1 = v0 + acc D, c2 = acc / 2.
  const auto path = [&](const ExactBody<T>& x, ExactVec c[3]) {
    c[0] = x.position(now);
    if (x.fixed) return;
    const Exact dt = now - x.t0;
    c[1] = x.v0 + x.half_acc * dt + x.half_acc * dt;
    c[2] = x.half_acc;
  };
  ExactVec ca[3], cb[3], d[3];
  path(a, ca);
  path(b, cb);
  for (int k = 0; k < 3; ++k) d[k] = cb[k] - ca[k];
  Exact f[5];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) f[i + j] = f[i + j] + dot(d[i], d[j]);
  const Exact rr = Exact::of(a.shape->radius) + Exact::of(b.shape->radius);
  f[0] = f[0] - rr * rr;
  // Scale to integers: every coefficient times 2^-(least exponent).
  detail::exact::IntPoly out;
  long low = 0;
  bool any = false;
  for (const Exact& c : f)
    if (c.d.m != 0) {
      low = any ? std::min(low, c.d.e) : c.d.e;
      any = true;
    }
  for (int k = 0; k < 5; ++k)
    if (f[k].d.m != 0) out.c[k] = f[k].d.m << static_cast<unsigned>(f[k].d.e - low);
  out.degree = 4;
  while (out.degree > 0 && out.c[out.degree] == 0) --out.degree;
  return out;
}

// Doublings of the step before the walk gives up (the prediction is then kept as it is).
inline constexpr int kRefineMaxDoublings = 80;

// The T nearest the exact crossing (positive before, non-positive after) closest to
// `predicted`, not before `now`: `now` itself when the pair is already touching or overlapping
// then; nothing when no crossing is found near it (a touch the exact paths never make).
template <class T, class Sign> std::optional<T> correctly_rounded_crossing(const T& predicted, const T& now, Sign sign) {
  using std::abs;
  const auto at = [&](const T& t) { return sign(Exact::of(t)); };
  const T unit = std::max(abs(predicted) * std::numeric_limits<T>::epsilon(), std::numeric_limits<T>::denorm_min());
  T lo = predicted, hi = predicted;
  T step = unit;
  if (at(predicted) > 0) {
    for (int k = 0;; ++k) {
      if (k > kRefineMaxDoublings) return std::nullopt;
      const T next = lo + step;
      step = step * T(2);
      if (!(next > lo)) continue;
      if (at(next) <= 0) {
        hi = next;
        break;
      }
      lo = next;
    }
  } else {
    for (int k = 0;; ++k) {
      // Already touching or overlapping at `now` (left so by the previous event's rounding):
      // the overlap rule's time.
      if (hi <= now) return now;
      if (k > kRefineMaxDoublings) return std::nullopt;
      T next = hi - step;
      step = step * T(2);
      if (next < now) next = now;
      if (!(next < hi)) continue;
      if (at(next) > 0) {
        lo = next;
        break;
      }
      hi = next;
    }
  }
  // Bisect to adjacent T values: at(lo) > 0 >= at(hi).
  for (;;) {
    const T mid = lo + (hi - lo) / T(2);
    if (!(mid > lo && mid < hi)) break;
    (at(mid) > 0 ? lo : hi) = mid;
  }
  const Exact mid(detail::exact::midpoint(detail::exact::to_dyadic(lo), detail::exact::to_dyadic(hi)));
  const int s = sign(mid);
  if (s > 0) return hi;  // the crossing is past the midpoint
  if (s < 0) return std::max(lo, now);
  return std::max(detail::exact::round_to_scalar<T>(mid.d), now);  // exactly halfway: ties to even
}

}  // namespace refine
}  // namespace pge
