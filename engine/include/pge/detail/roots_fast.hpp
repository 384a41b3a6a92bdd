// The fast solver: every real root from closed forms (quadratic formula, Cardano, Ferrari), as
// the original PGE computes them, then the downward ones in order. The baseline the other solvers
// are measured against: it loses digits on clustered, widely separated and near-double roots
// (Flocke, ACM TOMS Algorithm 954, 2015), and that loss is what the accuracy test records.
// Included by pge/roots.hpp after roots_robust.hpp (it reuses sign_of and trimmed_degree).
#pragma once

#include <boost/math/constants/constants.hpp>

#include <algorithm>
#include <cmath>

namespace pge {
namespace detail {

// Real roots of c2 t^2 + c1 t + c0 by the textbook formula (c2 != 0); appends to out.
template <class T> int fast_quadratic(const T& c2, const T& c1, const T& c0, T* out) {
  using std::sqrt;
  const T disc = c1 * c1 - T(4) * c2 * c0;
  if (disc < T(0)) return 0;
  const T s = sqrt(disc);
  out[0] = (-c1 - s) / (T(2) * c2);
  out[1] = (-c1 + s) / (T(2) * c2);
  return 2;
}

// Real roots of t^3 + a t^2 + b t + c by Cardano's formula (trigonometric form when all three
// roots are real).
template <class T> int fast_cubic(const T& a, const T& b, const T& c, T* out) {
  using std::acos;
  using std::cbrt;
  using std::cos;
  using std::sqrt;
  const T shift = a / T(3);
  const T p = b - a * shift;                                 // t = y - a/3: y^3 + p y + q
  const T q = T(2) * shift * shift * shift - b * shift + c;
  const T half_q = q / T(2);
  const T third_p = p / T(3);
  const T disc = half_q * half_q + third_p * third_p * third_p;
  if (disc > T(0)) {
    const T s = sqrt(disc);
    out[0] = cbrt(-half_q + s) + cbrt(-half_q - s) - shift;
    return 1;
  }
  if (p == T(0)) {  // then q == 0 too: a triple root
    out[0] = -shift;
    return 1;
  }
  const T r = sqrt(-third_p);
  T arg = -half_q / (r * r * r);
  arg = arg > T(1) ? T(1) : (arg < T(-1) ? T(-1) : arg);  // rounding may step outside acos's domain
  const T theta = acos(arg) / T(3);
  const T two_pi_3 = T(2) * boost::math::constants::pi<T>() / T(3);
  for (int k = 0; k < 3; ++k) out[k] = T(2) * r * cos(theta - T(k) * two_pi_3) - shift;
  return 3;
}

// Real roots of t^4 + a t^3 + b t^2 + c t + d by Ferrari's method: the depressed quartic
// y^4 + p y^2 + q y + r = 0 is split into two quadratics using the largest real root m of the
// resolvent cubic 8 m^3 - 4 p m^2 - 8 r m + (4 p r - q^2), which satisfies 2 m >= p.
template <class T> int fast_quartic(const T& a, const T& b, const T& c, const T& d, T* out) {
  using std::sqrt;
  const T shift = a / T(4);
  const T s2 = shift * shift;
  const T p = b - T(6) * s2;
  const T q = c - T(2) * b * shift + T(8) * s2 * shift;
  const T r = d - c * shift + b * s2 - T(3) * s2 * s2;
  int n = 0;
  if (q == T(0)) {  // biquadratic: y^2 = z for each root z >= 0 of z^2 + p z + r
    T z[2];
    if (fast_quadratic(T(1), p, r, z) == 2) {
      for (const T& zk : z) {
        if (zk < T(0)) continue;
        out[n++] = sqrt(zk) - shift;
        out[n++] = -sqrt(zk) - shift;
      }
    }
    return n;
  }
  T m[3];
  const int k = fast_cubic(T(-p) / T(2), T(-r), (T(4) * p * r - q * q) / T(8), m);
  T mm = m[0];
  for (int i = 1; i < k; ++i) mm = std::max(mm, m[i]);
  const T w2 = T(2) * mm - p;
  if (!(w2 > T(0))) return 0;  // rounding ate the split: the closed form gives up
  const T w = sqrt(w2);
  const T h = q / (T(2) * w);
  T y[2];
  if (fast_quadratic(T(1), -w, mm + h, y) == 2) { out[n++] = y[0] - shift; out[n++] = y[1] - shift; }
  if (fast_quadratic(T(1), w, mm - h, y) == 2) { out[n++] = y[0] - shift; out[n++] = y[1] - shift; }
  return n;
}

// Every real root the closed forms find for p (trimmed degree 1..4), sorted.
template <class T> int fast_real_roots(const Poly<T>& p, int deg, T* out) {
  int n = 0;
  const T& lead = p.c[deg];
  switch (deg) {
    case 1: out[n++] = -p.c[0] / p.c[1]; break;
    case 2: n = fast_quadratic(p.c[2], p.c[1], p.c[0], out); break;
    case 3: n = fast_cubic(p.c[2] / lead, p.c[1] / lead, p.c[0] / lead, out); break;
    default: n = fast_quartic(p.c[3] / lead, p.c[2] / lead, p.c[1] / lead, p.c[0] / lead, out); break;
  }
  std::sort(out, out + n);
  return n;
}

}  // namespace detail

// The fast solver (see SolverKind). Downward means p' < 0 at the computed root, the test PGE
// makes; the overlap rule at lo is the one every solver shares.
template <class T, class Visit>
bool fast_visit_downward_roots(const Poly<T>& p_in, const T& lo, const T& hi, StartRule rule, Visit&& visit) {
  if (!(lo <= hi)) return false;
  Poly<T> p = p_in;
  p.degree = detail::trimmed_degree(p_in);
  if (p.degree == 0) return false;
  const Poly<T> dp = p.derivative();
  const T v_lo = p(lo);
  bool took_lo = false;
  if (dp(lo) < T(0) && (v_lo == T(0) || (v_lo < T(0) && rule == StartRule::OverlapCollides))) {
    if (visit(lo, v_lo < T(0))) return true;
    took_lo = true;
  }
  T roots[4];
  const int n = detail::fast_real_roots(p, p.degree, roots);
  for (int i = 0; i < n; ++i) {
    const T& t = roots[i];
    if (t < lo || t > hi || (took_lo && t == lo)) continue;
    if (i > 0 && t == roots[i - 1]) continue;  // a double root found twice
    if (dp(t) < T(0) && visit(t, false)) return true;
  }
  return false;
}

}  // namespace pge
