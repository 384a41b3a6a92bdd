// The contact functions of rotating features (issue "Rotation", item 4), as WaveSums
// (roots_rotating.hpp) whose every coefficient encloses the exact value for the stored paths.
//
// A body's stored path: centre c(t) = p0 + v0 (t - t0) + a (t - t0)^2 / 2 and angle
// theta(t) = theta0 + w (t - t0); a point r of the body (relative to the centre, in the body's
// frame) is at c(t) + R(theta(t)) r. Re-expressed from an origin o as c(s) = c0 + c1 s + c2 s^2
// and theta(s) = phase + w s, s = t - o (PathAt; exact when o = t0).
//
// Because a rotation keeps cross and dot products, every function below is a sum of a polynomial
// and at most two waves. With d(s) = c_P(s) - c_Q(s) the centre of P relative to Q's,
// phi = theta_P - theta_Q, and Q's feature given in Q's frame (edge start q, edge vector e, or
// vertex q), P's in P's (vertex r):
//
//   vertex r of P against edge (q, e) of Q, the signed distance times |e| (positive in front of a
//   counter-clockwise edge):
//     cross(V - A, E) = cos(theta_Q) cross(d, e) + sin(theta_Q) dot(d, e)
//                     + cos(phi) cross(r, e) - sin(phi) dot(r, e) - cross(q, e)
//   and where along the edge, dot(V - A, E) (on the edge for values in [0, e.e]):
//                       cos(theta_Q) dot(d, e) - sin(theta_Q) cross(d, e)
//                     + cos(phi) dot(r, e) + sin(phi) cross(r, e) - dot(q, e)
//   a circle of radius rho against an edge: the same with r = 0, minus rho |e|;
//   a circle against a vertex q of Q, the squared distance minus rho^2:
//     |d|^2 + |q|^2 - rho^2 - 2 cos(theta_Q) dot(d, q) + 2 sin(theta_Q) cross(d, q).
//
// Waves that do not turn fold into the polynomial, and waves with the same or the opposite
// argument merge (add_wave): a pair of which only one body turns has one wave, not two.
#pragma once

#include "pge/detail/roots_rotating.hpp"
#include "pge/vec2.hpp"

#include <array>
#include <cstddef>

namespace pge::detail {

// A body's motion as the engine stores it (the values read exactly).
template <class B> struct StoredPath {
  B t0{};
  Vec2<B> p0, v0, a;
  B theta0{}, omega{};
};

template <class B> struct PathAt {
  B origin{};
  std::array<Vec2<Interval<B>>, 3> c;  // centre: c[0] + c[1] s + c[2] s^2
  Interval<B> phase, omega;             // angle: phase + omega s
};

template <class B> Vec2<Interval<B>> enclose(const Vec2<B>& v) { return {Interval<B>(v.x), Interval<B>(v.y)}; }

template <class B> PathAt<B> path_at(const StoredPath<B>& p, const B& origin) {
  using I = Interval<B>;
  PathAt<B> out;
  out.origin = origin;
  const I s0 = I(origin) - I(p.t0);
  const Vec2<I> v0 = enclose(p.v0), half_a = enclose(p.a) * I(B(0.5));
  out.c[0] = enclose(p.p0) + v0 * s0 + half_a * s0.square();
  out.c[1] = v0 + enclose(p.a) * s0;
  out.c[2] = half_a;
  out.omega = I(p.omega);
  out.phase = I(p.theta0) + out.omega * s0;
  return out;
}

// A polynomial in s with vector coefficients (degree <= 2: a centre, or a difference of two).
template <class B> struct VecPoly {
  std::array<Vec2<Interval<B>>, 3> c;
  int degree = 2;
};

template <class B> VecPoly<B> relative_centre(const PathAt<B>& P, const PathAt<B>& Q) {
  VecPoly<B> d;
  for (std::size_t k = 0; k < 3; ++k) d.c[k] = P.c[k] - Q.c[k];
  // Drop vanishing leading terms (no relative acceleration, or no relative motion at all).
  auto zero = [](const Vec2<Interval<B>>& v) {
    return v.x.lo() == B(0) && v.x.hi() == B(0) && v.y.lo() == B(0) && v.y.hi() == B(0);
  };
  while (d.degree > 0 && zero(d.c[static_cast<std::size_t>(d.degree)])) --d.degree;
  return d;
}

// dot or cross of a vector polynomial with a constant vector, coefficient by coefficient.
template <class B, class Op> IntervalPoly<B> apply(const VecPoly<B>& d, const Vec2<Interval<B>>& e, Op op) {
  IntervalPoly<B> r;
  r.degree = d.degree;
  for (int k = 0; k <= d.degree; ++k) r.c[static_cast<std::size_t>(k)] = op(d.c[static_cast<std::size_t>(k)], e);
  return r;
}

template <class B> IntervalPoly<B> squared_norm(const VecPoly<B>& d) {
  IntervalPoly<B> r;
  r.degree = 2 * d.degree;
  for (int i = 0; i <= d.degree; ++i)
    for (int j = 0; j <= d.degree; ++j)
      r.c[static_cast<std::size_t>(i + j)] =
          r.c[static_cast<std::size_t>(i + j)] + dot(d.c[static_cast<std::size_t>(i)], d.c[static_cast<std::size_t>(j)]);
  return r;
}

template <class B> IntervalPoly<B> constant_poly(const Interval<B>& v) {
  IntervalPoly<B> r;
  r.c[0] = v;
  return r;
}

// Adds C(s) cos(w s + phase) + S(s) sin(w s + phase) to f. A feature that does not turn (w and
// phase exactly zero: cos = 1, sin = 0) folds into the polynomial; a wave whose argument is the
// same as, or exactly the negative of, one already there joins it (cos(-x) = cos x,
// sin(-x) = -sin x): the vertex of a body that does not turn against the edge of one that does
// has phi = -theta_Q. So a pair of which one body turns has one wave, not two.
template <class B>
void add_wave(WaveSum<B>& f, const Interval<B>& omega, const Interval<B>& phase, const IntervalPoly<B>& cos_part,
              const IntervalPoly<B>& sin_part) {
  const auto same = [](const Interval<B>& x, const Interval<B>& y) { return x.lo() == y.lo() && x.hi() == y.hi(); };
  const Interval<B> zero(B(0));
  if (same(omega, zero) && same(phase, zero)) {
    f.base = f.base + cos_part;
    return;
  }
  for (int j = 0; j < f.wave_count; ++j) {
    Wave<B>& w = f.waves[static_cast<std::size_t>(j)];
    if (same(w.omega, omega) && same(w.phase, phase)) {
      w.cos_part = w.cos_part + cos_part;
      w.sin_part = w.sin_part + sin_part;
      return;
    }
    if (same(w.omega, -omega) && same(w.phase, -phase)) {
      w.cos_part = w.cos_part + cos_part;
      w.sin_part = w.sin_part + Interval<B>(B(-1)) * sin_part;
      return;
    }
  }
  Wave<B>& w = f.waves[static_cast<std::size_t>(f.wave_count++)];
  w.omega = omega;
  w.phase = phase;
  w.cos_part = cos_part;
  w.sin_part = sin_part;
}

template <class B> struct FeatureFunctions {
  WaveSum<B> gap;    // crosses zero downward at the contact
  WaveSum<B> along;  // where the contact point lies on the edge (in [0, e.e] on it)
  Interval<B> length_sq;  // e.e
};

// Cross and dot as functions, for apply().
template <class B> struct CrossWith {
  Interval<B> operator()(const Vec2<Interval<B>>& a, const Vec2<Interval<B>>& b) const { return cross(a, b); }
};
template <class B> struct DotWith {
  Interval<B> operator()(const Vec2<Interval<B>>& a, const Vec2<Interval<B>>& b) const { return dot(a, b); }
};

// Vertex r of P (or, with rho > 0 and r = 0, a circle of radius rho centred on P's path)
// against the edge of Q from vertex q to vertex q_end (e = q_end - q, enclosed: the edge between
// the stored vertices, whatever B makes of the difference). P and Q are expressed from the same
// origin.
template <class B>
FeatureFunctions<B> point_edge_functions(const PathAt<B>& P, const Vec2<B>& r, const B& rho, const PathAt<B>& Q,
                                         const Vec2<B>& q, const Vec2<B>& q_end) {
  using I = Interval<B>;
  const VecPoly<B> d = relative_centre(P, Q);
  const Vec2<I> qi = enclose(q), ei = enclose(q_end) - qi, ri = enclose(r);
  const IntervalPoly<B> d_cross = apply(d, ei, CrossWith<B>{}), d_dot = apply(d, ei, DotWith<B>{});
  FeatureFunctions<B> out;
  out.length_sq = dot(ei, ei);
  for (WaveSum<B>* f : {&out.gap, &out.along}) f->origin = P.origin;
  out.gap.base = constant_poly(-cross(qi, ei) - (rho > B(0) ? I(rho) * out.length_sq.sqrt() : I(B(0))));
  out.along.base = constant_poly(-dot(qi, ei));
  add_wave(out.gap, Q.omega, Q.phase, d_cross, d_dot);
  add_wave(out.along, Q.omega, Q.phase, d_dot, I(B(-1)) * d_cross);
  if (r.x != B(0) || r.y != B(0)) {
    const I phase = P.phase - Q.phase, omega = P.omega - Q.omega;
    add_wave(out.gap, omega, phase, constant_poly(cross(ri, ei)), constant_poly(-dot(ri, ei)));
    add_wave(out.along, omega, phase, constant_poly(dot(ri, ei)), constant_poly(cross(ri, ei)));
  }
  return out;
}

// A circle of radius rho on P's path against the vertex q of Q: squared distance minus rho^2.
template <class B>
WaveSum<B> circle_vertex_function(const PathAt<B>& P, const B& rho, const PathAt<B>& Q, const Vec2<B>& q) {
  using I = Interval<B>;
  const VecPoly<B> d = relative_centre(P, Q);
  const Vec2<I> qi = enclose(q);
  WaveSum<B> f;
  f.origin = P.origin;
  f.base = squared_norm(d) + constant_poly(dot(qi, qi) - I(rho) * I(rho));
  add_wave(f, Q.omega, Q.phase, I(B(-2)) * apply(d, qi, DotWith<B>{}), I(B(2)) * apply(d, qi, CrossWith<B>{}));
  return f;
}

}  // namespace pge::detail
