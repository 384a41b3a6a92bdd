// The robust solver: relative degree reduction, a walk over the pieces between the inflection
// points (closed forms), stable closed forms for degree <= 2 and safeguarded Halley iteration
// elsewhere, and a retry in a wider type when a sign it needs is within rounding. Also the helpers
// the fast and certified solvers share (signs, the Horner error bound, the wider types).
// Included by pge/roots.hpp.
#pragma once

#include "pge/constants.hpp"
#include "pge/scalar.hpp"

#include <boost/math/special_functions/next.hpp>

#include <cmath>
#include <cstdint>
#include <limits>
#include <type_traits>
#include <utility>

namespace pge {
namespace detail {

template <class T> int sign_of(const T& x) { return (x > T(0)) - (x < T(0)); }

template <class T> T abs_of(const T& x) { return x < T(0) ? -x : x; }

// A type in which the values of T, the midpoints of adjacent T values and k! c (k <= 4) are
// exact: at least two more significand bits and at least T's exponent range. `void` past the
// widest. Robust retries a doubtful solve in it; certified evaluates doubtful signs in it.
using Wide240 = boost::multiprecision::number<boost::multiprecision::cpp_bin_float<240, boost::multiprecision::digit_base_2>,
                                              boost::multiprecision::et_off>;
template <class T> struct Wider { using type = void; };
template <> struct Wider<float> { using type = double; };
template <> struct Wider<double> { using type = long double; };
template <> struct Wider<long double> { using type = Quad; };
template <> struct Wider<Quad> { using type = Wide240; };
static_assert(std::numeric_limits<long double>::digits >= std::numeric_limits<double>::digits + 3,
              "the solvers need long double wider than double (x86 extended precision)");

template <class T> T unit_roundoff() { return std::numeric_limits<T>::epsilon() / T(2); }

// p(x) in T and a bound on its error: |value - p(x)| <= bound, where p's coefficients may each
// carry up to two roundings (derivatives computed in T). The a-priori Horner bound gamma(2d)
// sum |c_k| |x|^k (Higham, "Accuracy and Stability of Numerical Algorithms", 2nd ed., eq. 5.3)
// is covered by (2d + 4) u times the computed sum, which also absorbs the sum's own rounding and
// the coefficients' (u = epsilon / 2); the min() term covers underflow.
template <class T> struct Evaluation {
  T value;
  T bound;
};

template <class T> Evaluation<T> evaluate_with_bound(const Poly<T>& q, const T& x) {
  const T ax = x < T(0) ? T(-x) : x;
  T v = q.c[q.degree];
  T s = v < T(0) ? T(-v) : v;
  for (int j = q.degree - 1; j >= 0; --j) {
    v = v * x + q.c[j];
    s = s * ax + (q.c[j] < T(0) ? T(-q.c[j]) : q.c[j]);
  }
  const int d = q.degree;
  return {v, s * T(2 * d + 4) * unit_roundoff<T>() + T(2 * d + 2) * std::numeric_limits<T>::min()};
}

template <class T> int trimmed_degree(const Poly<T>& p) {
  int d = p.degree;
  while (d > 0 && p.c[d] == T(0)) --d;
  return d;
}

// The degree of p once leading terms that cannot matter on [lo, hi] are dropped: c_d t^d is
// negligible when |c_d| m^(d-k) <= kNegligibleTermEpsilons epsilon |c_k| for some lower non-zero
// c_k (m = max(|lo|, |hi|)), for then |c_d t^d| <= kNegligibleTermEpsilons epsilon |c_k t^k| on
// the whole interval, below the rounding error of evaluating p there. Exactly zero leading
// coefficients go too. This keeps a 1e-30 t^4 term from turning a quadratic into a quartic whose
// extra roots lie far outside the interval but whose closed forms and critical points lose digits.
template <class T> int reduced_degree(const Poly<T>& p, const T& lo, const T& hi) {
  const T m = abs_of(lo) > abs_of(hi) ? abs_of(lo) : abs_of(hi);
  const T tolerance = std::numeric_limits<T>::epsilon() * T(kNegligibleTermEpsilons);
  int d = trimmed_degree(p);
  while (d > 0) {
    T lead = abs_of(p.c[d]);
    bool negligible = false;
    for (int k = d - 1; k >= 0 && !negligible; --k) {
      lead *= m;
      negligible = p.c[k] != T(0) && lead <= tolerance * abs_of(p.c[k]);
    }
    if (!negligible) break;
    --d;
    while (d > 0 && p.c[d] == T(0)) --d;
  }
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
// Halley steps x - 2 p p' / (2 p'^2 - p p'') from x (value, slope and curvature in one Horner
// pass; cubic convergence: about 5 steps on collision quartics against 7 for Newton), kept inside
// the bracket by a bisection step whenever one would leave it; the bracket shrinks by the sign of
// p at every step. Stops when the step falls below rounding of x (below `settle` |x|), or when the
// bracket closes on adjacent floating-point numbers. Started at the end where p p'' > 0 (Fourier's
// condition), the steps approach the root from one side.
template <class T>
T refine_root(const Poly<T>& p, T a, T b, int sign_a, T x, const T& settle = std::numeric_limits<T>::epsilon() / T(2)) {
  for (int it = 0; it < kMaxRootIterations; ++it) {
    T f = p.c[p.degree], slope(0), half_curvature(0);
    for (int k = p.degree - 1; k >= 0; --k) {
      half_curvature = half_curvature * x + slope;
      slope = slope * x + f;
      f = f * x + p.c[k];
    }
    if (f == T(0)) return x;
    if (sign_of(f) == sign_a) a = x; else b = x;
    const T denominator = slope * slope - f * half_curvature;
    T next = denominator != T(0) ? T(x - f * slope / denominator) : x;
    if (denominator != T(0) && abs_of(next - x) <= settle * abs_of(x)) return next;
    if (!(next > a && next < b)) {
      next = a + (b - a) / T(2);
      if (!(next > a && next < b)) return abs_of(p(a)) <= abs_of(p(b)) ? a : b;  // adjacent
    }
    x = next;
  }
  return x;
}

// refine_root from the end of (a, b) that Fourier's condition picks, judged by the curvature of
// p at the midpoint (callers' brackets lie between inflection points). A `candidate` (certified's,
// which proves it and steps it to the nearest T itself) needs fewer steps: it stops once a step is
// below sqrt(epsilon) |x| (the cubic convergence has then reached rounding), and it starts where
// p's tangent at the other end o meets zero, which lies between the root and Fourier's end (p is
// convex or concave on the bracket) and usually much nearer the root.
template <class T>
T refine_root(const Poly<T>& p, const Poly<T>& d2, const T& a, const T& b, int sign_a, bool candidate = false) {
  const T mid = a + (b - a) / T(2);
  const T curvature = d2(mid);
  const bool from_a = (curvature > T(0)) == (sign_a > 0);
  T start = curvature == T(0) ? mid : (from_a ? a : b);
  if (!candidate) return refine_root(p, a, b, sign_a, start);
  const T& o = from_a ? b : a;
  T f = p.c[p.degree], slope(0);
  for (int k = p.degree - 1; k >= 0; --k) {
    slope = slope * o + f;
    f = f * o + p.c[k];
  }
  const T tangent = slope != T(0) ? T(o - f / slope) : o;
  if (curvature != T(0) && tangent > a && tangent < b) start = tangent;
  using std::sqrt;
  return refine_root(p, a, b, sign_a, start, T(sqrt(std::numeric_limits<T>::epsilon())));
}

// The roots of p (degree <= 2) strictly inside (lo, hi), sorted, by the closed forms: the
// inflection points of a polynomial of degree <= 4.
template <class T> int interior_roots(const Poly<T>& p, const T& lo, const T& hi, T* out) {
  const int deg = trimmed_degree(p);
  int n = 0;
  if (deg == 1) {
    const T t = -p.c[0] / p.c[1];
    if (t > lo && t < hi) out[n++] = t;
  } else if (deg == 2) {
    T r1, r2;
    if (quadratic_roots(p.c[2], p.c[1], p.c[0], r1, r2) == 0) return 0;
    if (r1 > lo && r1 < hi) out[n++] = r1;
    if (r2 > lo && r2 < hi && r2 != r1) out[n++] = r2;
  }
  return n;
}

// The root of p in (a, b) where p(a) > 0 > p(b) and p has no other root (p monotone, or with one
// extremum).
template <class T>
T downward_root_in_piece(const Poly<T>& p, const Poly<T>& d2, int deg, const T& a, const T& b, bool candidate) {
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
  return refine_root(p, d2, a, b, 1, candidate);
}

enum class Walk { Stopped, Finished, Doubt };

// Whether the computed value of p at x cannot be trusted for its sign: within its error bound.
// `abs_sum` is sum |c_k|: sum |c_k| max(1, |x|)^d bounds the sum in the error bound, so a value
// above that cheap bound needs no second Horner pass (the common case).
template <class T> bool doubtful(const Poly<T>& p, const T& x, const T& abs_sum, T& value) {
  value = p(x);
  const T ax = abs_of(x);
  T scale = abs_sum;
  if (ax > T(1))
    for (int k = 0; k < p.degree; ++k) scale *= ax;
  const int d = p.degree;
  if (abs_of(value) > scale * T(2 * d + 5) * unit_roundoff<T>() + T(2 * d + 2) * std::numeric_limits<T>::min())
    return false;
  const Evaluation<T> e = evaluate_with_bound(p, x);
  return !(abs_of(e.value) > e.bound);
}

// The robust walk (see robust_visit_downward_roots). p has its reduced degree (>= 1). `emit`
// receives the downward roots in order. Returns Doubt, before emitting anything more, when a
// sign it needs is within rounding and `widest` is false. With `checked` false it takes every
// computed sign as it is, never doubts and finds its roots as candidates (refine_root):
// certified's, which it proves itself.
template <class T, class Emit>
Walk robust_walk(const Poly<T>& p, const T& lo, const T& hi, StartRule rule, Emit& emit, bool widest, bool checked = true) {
  const Poly<T> d1 = p.derivative();
  T abs_sum(0);
  for (int k = 0; k <= p.degree; ++k) abs_sum += abs_of(p.c[k]);
  auto unsure = [&](const T& x, T& value) {
    if (checked) return doubtful(p, x, abs_sum, value);
    value = p(x);
    return false;
  };
  T p_lo;
  if (unsure(lo, p_lo) && !widest) return Walk::Doubt;
  // At lo: touching or overlapping, and decreasing, collides at once (the overlap rule).
  if ((p_lo == T(0) || (p_lo < T(0) && rule == StartRule::OverlapCollides)) && sign_just_after(d1, lo) < 0)
    if (emit(lo, p_lo < T(0))) return Walk::Stopped;
  if (!(lo < hi)) return Walk::Finished;

  // Pieces between lo, the inflection points (roots of p'', closed forms: degree <= 2) and hi.
  // p' is monotone on each, so p is monotone or has a single extremum there.
  T ends[4];
  int n = 0;
  if (p.degree >= 3) n = interior_roots(d1.derivative(), lo, hi, ends);
  ends[n++] = hi;
  const Poly<T> d2 = d1.derivative();
  T u = lo;
  int s_u = p_lo != T(0) ? sign_of(p_lo) : sign_just_after(p, lo);  // p's sign just after u
  for (int i = 0; i < n; ++i) {
    const T v = ends[i];
    T p_v;
    if (unsure(v, p_v) && !widest) return Walk::Doubt;
    const int s_v = sign_of(p_v);
    const int slope_u = sign_of(d1(u)), slope_v = sign_of(d1(v));
    const bool has_min = slope_u < 0 && slope_v > 0, has_max = slope_u > 0 && slope_v < 0;
    // The extremum inside (u, v) and p's value there; a doubtful value is a graze at the widest.
    auto extremum = [&](T& c, T& p_c) {
      if (d1.degree == 1) {  // a parabola's vertex, in closed form
        c = -d1.c[0] / d1.c[1];
        c = c < u ? u : (c > v ? v : c);
      } else {
        c = refine_root(d1, d2.derivative(), u, v, slope_u, !checked);
      }
      if (unsure(c, p_c)) {
        if (!widest) return false;
        p_c = T(0);
      }
      return true;
    };
    T c, p_c;
    if (s_u > 0 && s_v < 0) {
      if (emit(downward_root_in_piece(p, d2, p.degree, u, v, !checked), false)) return Walk::Stopped;
    } else if (s_u > 0 && s_v == 0 && has_min) {  // p dips below zero and comes back to it at v
      if (!extremum(c, p_c)) return Walk::Doubt;
      if (emit(downward_root_in_piece(p, d2, p.degree, u, c, !checked), false)) return Walk::Stopped;
    } else if (s_u > 0 && s_v == 0) {  // p arrives at zero from above: a root at hi, or a crossing
      if ((v == hi || sign_just_after(p, v) < 0) && emit(v, false)) return Walk::Stopped;
    } else if (s_u > 0 && s_v > 0 && has_min) {
      if (!extremum(c, p_c)) return Walk::Doubt;
      if (p_c < T(0) && emit(downward_root_in_piece(p, d2, p.degree, u, c, !checked), false)) return Walk::Stopped;
    } else if (s_u < 0 && s_v == 0 && has_max) {  // p rises above zero and comes down to it at v
      if (!extremum(c, p_c)) return Walk::Doubt;
      if (p_c > T(0) && (v == hi || sign_just_after(p, v) < 0) && emit(v, false)) return Walk::Stopped;
    } else if (s_u < 0 && s_v < 0 && has_max) {
      if (!extremum(c, p_c)) return Walk::Doubt;
      if (p_c > T(0) && emit(downward_root_in_piece(p, d2, p.degree, c, v, !checked), false)) return Walk::Stopped;
    }
    s_u = s_v != 0 ? s_v : sign_just_after(p, v);
    u = v;
  }
  return Walk::Finished;
}

// Solves in T, and again in the next wider type if a sign it needs is within rounding; the
// first `skip` roots are not passed on (they were visited before the retry).
template <class T, class Visit>
bool robust_solve(const Poly<T>& p_in, const T& lo, const T& hi, StartRule rule, Visit& visit, int skip) {
  if (!(lo <= hi)) return false;
  Poly<T> p = p_in;
  p.degree = reduced_degree(p_in, lo, hi);
  if (p.degree == 0) return false;  // a constant neither approaches nor crosses
  using W = typename Wider<T>::type;
  constexpr bool widest = std::is_void_v<W>;
  int emitted = 0;
  auto emit = [&](const T& t, bool overlap) {
    ++emitted;
    return emitted > skip && visit(t, overlap);
  };
  const Walk walk = robust_walk(p, lo, hi, rule, emit, widest);
  if (walk != Walk::Doubt) return walk == Walk::Stopped;
  if constexpr (!widest) {
    Poly<W> pw;
    pw.degree = p_in.degree;
    for (int k = 0; k <= p_in.degree; ++k) pw.c[k] = W(p_in.c[k]);
    auto narrowed = [&](const W& t, bool overlap) { return visit(static_cast<T>(t), overlap); };
    return robust_solve(pw, W(lo), W(hi), rule, narrowed, emitted > skip ? emitted : skip);
  }
  return false;  // unreachable: the widest type never doubts
}

// What robust_solve(p, 0, hi, OverlapCollides) answers for the commonest prediction of all, two
// bodies apart and approaching on a convex parabola (c0 > 0 > c1, c2 > 0: two circles without
// relative acceleration), by the same steps as robust_walk takes on it (the degree reduction,
// the signs at 0, at hi and at the vertex with their doubts, the closed-form root) without its
// general machinery: the same root, bit for bit (tests/test_solvers.cpp compares the two).
// Unsure: a case it leaves to robust_solve (a doubtful sign, the degree reduced, a closed form
// outside its piece); None: no root in [0, hi]; Root: the root, in `root`.
enum class ParabolaRoot : std::uint8_t { Unsure, None, Root };
template <class T> ParabolaRoot approaching_parabola_root(const Poly<T>& p, const T& hi, T& root) {
  const T &c0 = p.c[0], &c1 = p.c[1], &c2 = p.c[2];
  if (p.degree != 2 || !(c0 > T(0)) || !(c1 < T(0)) || !(c2 > T(0)) || !(hi > T(0))) return ParabolaRoot::Unsure;
  if (reduced_degree(p, T(0), hi) != 2) return ParabolaRoot::Unsure;
  T abs_sum(0);
  for (int k = 0; k <= 2; ++k) abs_sum += abs_of(p.c[k]);
  T value;
  if (doubtful(p, T(0), abs_sum, value)) return ParabolaRoot::Unsure;
  const auto root_before = [&](const T& b) {  // downward_root_in_piece's closed form
    T r1, r2;
    if (quadratic_roots(c2, c1, c0, r1, r2) != 2 || !(r1 >= T(0) && r1 <= b)) return ParabolaRoot::Unsure;
    root = r1;
    return ParabolaRoot::Root;
  };
  T p_hi;
  if (doubtful(p, hi, abs_sum, p_hi)) return ParabolaRoot::Unsure;
  const T twice_c2 = c2 * T(2);
  const bool has_min = twice_c2 * hi + c1 > T(0);  // p' < 0 at 0 (c1) and > 0 at hi
  if (p_hi < T(0)) return root_before(hi);
  if (p_hi == T(0)) {
    if (has_min) return ParabolaRoot::Unsure;
    root = hi;
    return ParabolaRoot::Root;
  }
  if (!has_min) return ParabolaRoot::None;
  T vertex = -c1 / twice_c2;
  vertex = vertex < T(0) ? T(0) : (vertex > hi ? hi : vertex);
  T p_vertex;
  if (doubtful(p, vertex, abs_sum, p_vertex)) return ParabolaRoot::Unsure;
  if (p_vertex < T(0)) return root_before(vertex);
  return ParabolaRoot::None;
}

}  // namespace detail

// The robust solver (see SolverKind): the degree reduced where leading terms are negligible on
// [lo, hi]; pieces between the inflection points (closed forms), on which p is monotone or has
// one extremum; the extremum computed only when it decides something (a minimum between two
// positive values, a maximum between two negative ones); roots by the stable closed forms for
// degree <= 2 and safeguarded Newton otherwise; only the roots up to the one the visitor accepts.
// A sign within rounding of zero (a near-double root, a root at an end) makes it solve again in
// the next wider type (float, double, long double, quad, 240-bit), where the question usually has
// a clear answer; past the widest, an extremum that is still doubtful counts as a graze.
template <class T, class Visit>
bool robust_visit_downward_roots(const Poly<T>& p, const T& lo, const T& hi, StartRule rule, Visit&& visit) {
  return detail::robust_solve(p, lo, hi, rule, visit, 0);
}

}  // namespace pge
