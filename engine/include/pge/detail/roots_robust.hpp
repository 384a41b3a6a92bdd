// The robust solver: bracketing between the roots of the derivative, closed forms where they are
// stable (degree <= 2), safeguarded Newton iteration elsewhere. Included by pge/roots.hpp.
#pragma once

#include "pge/constants.hpp"

#include <boost/math/special_functions/next.hpp>

#include <cmath>
#include <utility>

namespace pge {
namespace detail {

template <class T> int sign_of(const T& x) { return (x > T(0)) - (x < T(0)); }

template <class T> T abs_of(const T& x) { return x < T(0) ? -x : x; }

template <class T> int trimmed_degree(const Poly<T>& p) {
  int d = p.degree;
  while (d > 0 && p.c[d] == T(0)) --d;
  return d;
}

// Sign of p immediately after t: the sign of the first non-zero derivative at t.
template <class T> int sign_just_after(Poly<T> q, const T& t) {
  for (int k = 0; k <= 4; ++k) {
    const T v = q(t);
    if (v != T(0)) return sign_of(v);
    q = q.derivative();
  }
  return 0;
}

// The real roots r1 <= r2 of c2 t^2 + c1 t + c0 (c2 != 0) by the cancellation-free formula
// (the larger-magnitude root from -(c1 + sign(c1) sqrt(disc)) / 2, the other from the product
// of the roots). Returns the number of real roots counted with multiplicity (0 or 2).
template <class T> int quadratic_roots(const T& c2, const T& c1, const T& c0, T& r1, T& r2) {
  using std::sqrt;
  const T disc = c1 * c1 - T(4) * c2 * c0;
  if (disc < T(0)) return 0;
  const T s = sqrt(disc);
  const T q = c1 >= T(0) ? -(c1 + s) / T(2) : (s - c1) / T(2);
  if (q == T(0)) {  // c1 == 0 and c0 == 0: a double root at 0
    r1 = r2 = T(0);
    return 2;
  }
  r1 = q / c2;
  r2 = c0 / q;
  if (r2 < r1) std::swap(r1, r2);
  return 2;
}

// A root of p in the open bracket (a, b), where p(a) and p(b) have opposite non-zero signs:
// Newton steps kept inside the bracket, bisection when a step leaves it or stalls, and a final
// one-ulp probe so that the bracket closes on adjacent floating-point numbers.
template <class T> T refine_root(const Poly<T>& p, const Poly<T>& dp, T a, T b, int sign_a) {
  T x = a + (b - a) / T(2);
  T previous_width = b - a;
  for (int it = 0; it < kMaxRootIterations; ++it) {
    const T fx = p(x);
    if (fx == T(0)) return x;
    if (sign_of(fx) == sign_a) a = x; else b = x;
    const T mid = a + (b - a) / T(2);
    if (!(mid > a && mid < b)) break;  // a and b are adjacent
    const T d = dp(x);
    T next = d != T(0) ? x - fx / d : mid;
    if (!(next > a && next < b)) {
      next = mid;
    } else if (next == x || abs_of(next - x) < abs_of(b - a) * T(1e-3)) {
      // Newton has converged to within rounding: probe one ulp towards the far end of the
      // bracket, which either closes it or moves the near end.
      next = (x == a) ? boost::math::float_next(a) : boost::math::float_prior(b);
      if (!(next > a && next < b)) next = mid;
    }
    // Bisect when Newton is not at least halving the bracket every second step.
    const T width = b - a;
    if (width > previous_width / T(2) && next != mid && it % 2 == 1) next = mid;
    previous_width = width;
    x = next;
  }
  return abs_of(p(a)) <= abs_of(p(b)) ? a : b;
}

// The roots of p that lie strictly inside (lo, hi), sorted, at most 4; roots exactly at an
// interior breakpoint are included. Used for the critical points of the next degree up.
template <class T> int interior_roots(const Poly<T>& p, const T& lo, const T& hi, T* out) {
  const int deg = trimmed_degree(p);
  if (deg == 0) return 0;
  if (deg == 1) {
    const T t = -p.c[0] / p.c[1];
    if (t > lo && t < hi) { out[0] = t; return 1; }
    return 0;
  }
  if (deg == 2) {
    T r1, r2;
    if (quadratic_roots(p.c[2], p.c[1], p.c[0], r1, r2) == 0) return 0;
    int n = 0;
    if (r1 > lo && r1 < hi) out[n++] = r1;
    if (r2 > lo && r2 < hi && r2 != r1) out[n++] = r2;
    return n;
  }
  Poly<T> q = p;
  q.degree = deg;
  const Poly<T> dq = q.derivative();
  T crit[4];
  const int m = interior_roots(dq, lo, hi, crit);
  int n = 0;
  T a = lo;
  T fa = q(lo);
  for (int i = 0; i <= m; ++i) {
    const T b = i < m ? crit[i] : hi;
    const T fb = q(b);
    if (sign_of(fa) * sign_of(fb) < 0) out[n++] = refine_root(q, dq, a, b, sign_of(fa));
    if (i < m && fb == T(0)) out[n++] = b;
    a = b;
    fa = fb;
  }
  return n;
}

// The root of p inside the monotone piece (a, b) with p(a) > 0 > p(b).
template <class T>
T downward_root_in_piece(const Poly<T>& p, const Poly<T>& dp, int deg, const T& a, const T& b) {
  if (deg == 1) {
    T t = -p.c[0] / p.c[1];
    return t < a ? a : (t > b ? b : t);
  }
  if (deg == 2) {
    T r1, r2;
    if (quadratic_roots(p.c[2], p.c[1], p.c[0], r1, r2) == 2) {
      // The decreasing branch of a convex parabola holds its smaller root, of a concave one
      // its larger. Clamp: rounding may put the closed form an ulp outside the piece.
      T t = p.c[2] > T(0) ? r1 : r2;
      if (t >= a && t <= b) return t;
    }
  }
  return refine_root(p, dp, a, b, 1);
}

}  // namespace detail

// The robust solver (see SolverKind).
template <class T, class Visit>
bool robust_visit_downward_roots(const Poly<T>& p_in, const T& lo, const T& hi, StartRule rule, Visit&& visit) {
  using detail::sign_of;
  if (!(lo <= hi)) return false;
  Poly<T> p = p_in;
  p.degree = detail::trimmed_degree(p_in);
  if (p.degree == 0) return false;  // a constant neither approaches nor crosses
  const Poly<T> dp = p.derivative();

  // Breakpoints: lo, the critical points of p inside (lo, hi), hi. p is monotone between them.
  T b[6]{};
  T v[6]{};
  b[0] = lo;
  const int m = detail::interior_roots(dp, lo, hi, b + 1);
  b[m + 1] = hi;
  for (int i = 0; i <= m + 1; ++i) v[i] = p(b[i]);

  // At lo: touching or overlapping, and decreasing, collides at once (the overlap rule).
  const bool decreasing_at_lo = detail::sign_just_after(dp, lo) < 0;
  if (decreasing_at_lo && (v[0] == T(0) || (v[0] < T(0) && rule == StartRule::OverlapCollides))) {
    if (visit(lo, v[0] < T(0))) return true;
  }
  for (int i = 0; i <= m; ++i) {
    if (!(v[i] > T(0)) || v[i + 1] > T(0)) continue;
    if (v[i + 1] < T(0)) {
      if (visit(detail::downward_root_in_piece(p, dp, p.degree, b[i], b[i + 1]), false)) return true;
      continue;
    }
    // p reaches exactly zero at the end of the piece. At hi, it arrives decreasing. At a
    // critical point, it crosses only if it goes on below zero; otherwise it is a graze.
    const bool crosses = (i + 1 == m + 1) || v[i + 2] < T(0);
    if (crosses && visit(b[i + 1], false)) return true;
  }
  return false;
}

}  // namespace pge
