// The certified solver: robust's walk, with every sign it relies on proved by a rigorous error
// bound, and exact arithmetic (roots_exact.hpp) wherever a bound cannot decide.
//
// Structure. For the second derivative (and, to build it, the third), the solver keeps a list of
// points lo = x0 < x1 < ... < xn = hi with the certified sign of q = p^(k) at each (never zero)
// and this invariant: between two neighbours with equal signs q has no root; between neighbours
// with opposite signs it has exactly one distinct root, and the two are adjacent T values. (One
// exception to "certified": a root that is exactly a T value x is kept as the pair (x, next x),
// with x labelled by the sign q has just before it; see narrow.) Level
// k is built from level k+1: where q' keeps its sign q is monotone, so a sign change of q brackets
// one root, narrowed to adjacent T values; where q' changes sign (an adjacent pair) q has one
// extremum, and if q has the same sign at both ends a bound on |q'| over the pair proves that the
// extremum does not reach zero. On the pieces of p'' the walk over p is robust's: p' is monotone
// there, so p is monotone or has one extremum, bracketed (certified) only when it decides. A
// downward root is reported as the T whose neighbouring midpoints have opposite certified signs.
//
// Signs. q(x) is evaluated in T with the a-priori Horner bound |fl(q(x)) - q(x)| <=
// gamma(2d) sum |c_k| |x|^k (Higham, "Accuracy and Stability of Numerical Algorithms", 2nd ed.,
// eq. 5.3), plus one rounding of each derivative coefficient; then, if that cannot decide, in a
// wider type where x, the midpoints and the derivative coefficients are exact; then exactly.
// Any structural doubt (a value exactly zero, an extremum within the bound of zero, a bracket
// that will not close) sends the whole call to the exact solver.
// Included by pge/roots.hpp.
#pragma once

#include "pge/constants.hpp"
#include "pge/detail/interval.hpp"  // interval_next_up, interval_next_down: x's neighbours
#include "pge/detail/roots_exact.hpp"
#include "pge/scalar.hpp"

#include <boost/math/special_functions/next.hpp>
#include <boost/multiprecision/cpp_bin_float.hpp>

#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <type_traits>

namespace pge {
namespace detail {

// How many calls of the certified solver this thread has sent to the exact solver: a cost
// measure (tests assert that common cases stay in floating point).
inline thread_local std::uint64_t certified_exact_fallbacks = 0;

// The decision from the Horner value v of a degree-d polynomial in W and the same Horner sum s
// over the coefficients' and the point's magnitudes (wide_sign_of's error bound).
template <class W> int wide_decision(const W& v, const W& s, int d) {
  const W bound = s * W(2 * d + 2) * (std::numeric_limits<W>::epsilon() / W(2)) + W(2 * d + 2) * std::numeric_limits<W>::min();
  if (v > bound) return 1;
  if (v < W(-bound)) return -1;
  if (v == W(0) && s == W(0)) return 0;
  return 2;
}
// The sign of q^(k)(x) evaluated in a wider type W in which x and j! / (j - k)! c_j are exact,
// with its Horner error bound: 1 or -1 when that decides, 2 when it cannot, 0 for an exact zero.
template <class T, class W> int wide_sign_of(const Poly<T>& q, int k, const W& x) {
  W v(0), s(0);
  const W ax = x < W(0) ? W(-x) : x;
  for (int j = q.degree; j >= k; --j) {
    W c = W(q.c[j]);
    for (int f = j; f > j - k; --f) c *= W(f);  // j! / (j-k)! c_j, exact in W
    v = v * x + c;
    s = s * ax + (c < W(0) ? W(-c) : c);
  }
  return wide_decision(v, s, q.degree - k);
}
// wide_sign_of(q, 0, x) and wide_sign_of(q, 0, y) in one pass: the same operations on each, the
// two Horner chains interleaved (each step of one waits on the last; the other fills the wait).
template <class T, class W> void wide_signs_of(const Poly<T>& q, const W& x, const W& y, int& sx, int& sy) {
  W vx(0), sumx(0), vy(0), sumy(0);
  const W ax = x < W(0) ? W(-x) : x, ay = y < W(0) ? W(-y) : y;
  for (int j = q.degree; j >= 0; --j) {
    const W c = W(q.c[j]), mc = c < W(0) ? W(-c) : c;
    vx = vx * x + c;
    vy = vy * y + c;
    sumx = sumx * ax + mc;
    sumy = sumy * ay + mc;
  }
  sx = wide_decision(vx, sumx, q.degree);
  sy = wide_decision(vy, sumy, q.degree);
}

// --- the common case, proved without the derivatives' structure (docs/solvers.md, "certified")

// p about a centre c: p(c + s) = sum q_k s^k, the q_k by repeated synthetic division, each within
// e_k of its computed value. Every q_k is a sum of terms c_j binom(j, k) c^(j - k), each carrying
// at most 2d roundings, so the same division on |c_j| and |c| bounds the error by gamma(2d) times
// its result; (4d + 8) u with d = 4 covers that and the rounding of the bound, the last term
// underflow.
template <class T> struct Taylor {
  T q[5]{}, e[5]{};
};

template <class T> Taylor<T> taylor_at(const Poly<T>& p, const T& c) {
  // As a quartic whatever the degree (the terms above it are zero), so that the loops unroll.
  Taylor<T> t;
  T s[5];
  const T ac = abs_of(c);
  for (int k = 0; k < 5; ++k) {
    t.q[k] = k <= p.degree ? p.c[k] : T(0);
    s[k] = abs_of(t.q[k]);
  }
  for (int i = 0; i < 4; ++i)
    for (int j = 3; j >= i; --j) {
      t.q[j] += c * t.q[j + 1];
      s[j] += ac * s[j + 1];
    }
  for (int k = 0; k < 5; ++k) t.e[k] = s[k] * T(24) * unit_roundoff<T>() + T(10) * std::numeric_limits<T>::min();
  return t;
}

// Whether p > 0 on all of [c - w, c + w], or p' < 0 on all of it, from the Taylor form at c: with
// a_k = |q_k| + e_k, p >= q0 - e0 + min(q2_low s^2 - a1 |s|) - a3 w^3 + min(q4 - e4, 0) w^4, where
// q2_low = q2 - e2, and p' <= q1 + e1 + 2 a2 w + 3 max(q3 + e3, 0) w^2 + 4 a4 w^3. Each side is a
// sum of non-negative terms of a few roundings each (the parabola's a1 w - q2_low w^2 is used only
// where it is at least half of a1 w), compared after the factor 1 + 32 u.
template <class T> bool positive_or_falling(const Taylor<T>& t, const T& w) {
  const T inflate = T(1) + T(32) * unit_roundoff<T>(), tiny = T(16) * std::numeric_limits<T>::min();
  T a[5];
  for (int k = 0; k < 5; ++k) a[k] = abs_of(t.q[k]) + t.e[k];
  const T w2 = w * w, w3 = w2 * w;
  // The least of q2_low s^2 - a1 |s| on [-w, w]: at the vertex if it lies inside, else at w.
  const T q2_low = t.q[2] - t.e[2];
  const T parabola = q2_low > T(0) && a[1] <= T(2) * q2_low * w ? a[1] * a[1] / (T(4) * q2_low) : a[1] * w - q2_low * w2;
  const T q4_low = t.q[4] - t.e[4];
  const T below = t.e[0] + parabola + a[3] * w3 + (q4_low < T(0) ? T(-q4_low) * w2 * w2 : T(0));
  if (t.q[0] > below * inflate + tiny) return true;
  const T q3_high = t.q[3] + t.e[3];
  const T above = t.e[1] + T(2) * a[2] * w + T(3) * (q3_high > T(0) ? q3_high : T(0)) * w2 + T(4) * a[4] * w3;
  return T(-t.q[1]) > above * inflate + tiny;
}

// Whether p' > 0 on all of [c - w, c + w]: p' >= q1 - e1 - 2 a2 w + 3 min(q3 - e3, 0) w^2 - 4 a4 w^3.
template <class T> bool rising(const Taylor<T>& t, const T& w) {
  const T inflate = T(1) + T(32) * unit_roundoff<T>(), tiny = T(16) * std::numeric_limits<T>::min();
  const T w2 = w * w;
  const T q3_low = t.q[3] - t.e[3];
  const T below = t.e[1] + T(2) * (abs_of(t.q[2]) + t.e[2]) * w + T(3) * (q3_low < T(0) ? T(-q3_low) : T(0)) * w2 +
                  T(4) * (abs_of(t.q[4]) + t.e[4]) * w2 * w;
  return t.q[1] > below * inflate + tiny;
}

// The same on [0, b] from p's own coefficients (exact: no shift), for 0 <= s <= b c_k s^k lying
// between min(c_k, 0) b^k and max(c_k, 0) b^k: p > 0, or p' < 0, or p' > 0 and p(0) > 0.
template <class T> bool positive_or_monotone_from_zero(const Poly<T>& p, const T& b) {
  const T inflate = T(1) + T(32) * unit_roundoff<T>(), tiny = T(16) * std::numeric_limits<T>::min();
  T below(0), slope_above(0), slope_below(0);  // sums of the negative and positive parts
  for (int k = p.degree; k >= 1; --k) {
    const T& c = p.c[k];
    below = (below + (c < T(0) ? T(-c) : T(0))) * b;
    if (k >= 2) {
      slope_above = (slope_above + (c > T(0) ? T(k) * c : T(0))) * b;
      slope_below = (slope_below + (c < T(0) ? T(-T(k) * c) : T(0))) * b;
    }
  }
  if (p.c[0] > below * inflate + tiny) return true;
  if (T(-p.c[1]) > slope_above * inflate + tiny) return true;
  return p.c[0] > T(0) && p.c[1] > slope_below * inflate + tiny;
}

// Whether at every t in [a, b] p(t) > 0 or p'(t) < 0 (then p, once not positive, stays negative to
// b: at a first return to zero it would be rising), by the Taylor form at the midpoint, or else
// at those of the halves, down to `depth` halvings.
template <class T> bool falls_where_not_positive(const Poly<T>& p, const T& a, const T& b, int depth) {
  if (a == T(0) && positive_or_monotone_from_zero(p, b)) return true;  // every prediction starts at 0
  const T c = a + (b - a) / T(2);
  const T w = (c - a > b - c ? c - a : b - c) * (T(1) + T(4) * unit_roundoff<T>());
  const Taylor<T> t = taylor_at(p, c);
  if (positive_or_falling(t, w)) return true;
  if (rising(t, w)) {  // then p > 0 on [a, b] if p(a) > 0
    const Evaluation<T> at_a = evaluate_with_bound(p, a);
    if (at_a.value > at_a.bound) return true;
  }
  if (depth == 0 || !(a < c && c < b)) return false;
  return falls_where_not_positive(p, a, c, depth - 1) && falls_where_not_positive(p, c, b, depth - 1);
}

enum class Quick { None, Root, Undecided };

// The midpoint of two values of T in W, where the midpoint of adjacent values is exact (the
// point whose sign decides a rounding to T).
template <class W, class T> W midpoint_in(const T& a, const T& b) { return (W(a) + W(b)) / W(2); }

// Decides the common prediction without the derivatives' structure (Certifier): robust's walk in T
// proposes the answer, and it is proved thus. None: p(hi) > 0 and p falls wherever it is not
// positive on [lo, hi], so p never reaches zero there. Root x: x- < x < x+ its neighbours in T,
// lo < x < hi, p positive at the midpoint of x- and x and negative at that of x and x+ (signs in
// the wider type), and p falls wherever it is not positive on [lo, x+]: then p > 0 from lo to its
// first zero, which lies between those midpoints, and p < 0 after it up to x+, so x is the
// earliest downward root correctly rounded (and p(lo) > 0: neither overlap rule applies).
// Anything else, and any sign the wider types cannot decide, is Undecided: the walk decides.
template <class T> Quick quick_earliest_root(const Poly<T>& p, const T& lo, const T& hi, T& t) {
  // Halvings of the Taylor proofs: for a root up to 3 (its last piece falls through the root);
  // for no root up to 7, where a window's dip that stays positive may need pieces a hundredth of
  // it wide (random double quartics: 218 of 4,096 left undecided with 3, for the walk at about
  // 900 ns each; 4 with 7, for 0.35 Taylor forms more per call).
  constexpr int kDepth = 3, kDepthNone = 7;
  if (!(lo < hi)) return Quick::Undecided;
  Poly<T> reduced = p;
  reduced.degree = reduced_degree(p, lo, hi);
  if (reduced.degree == 0) return Quick::Undecided;
  bool found = false;
  T x{};
  auto first = [&](const T& r, bool) {
    found = true;
    x = r;
    return true;
  };
  robust_walk(reduced, lo, hi, StartRule::CrossingsOnly, first, false, false);
  if (!found) {
    const Evaluation<T> at_hi = evaluate_with_bound(p, hi);
    const bool none = at_hi.value > at_hi.bound && falls_where_not_positive(p, lo, hi, kDepthNone);
    return none ? Quick::None : Quick::Undecided;
  }
  // Robust's root is within a few ulps: step to the T whose neighbouring midpoints bracket it.
  // A sign the wider type cannot decide (an ill-conditioned root) is asked again in the type
  // wider still where that is a hardware or quad type (x87 long double, then quad, for double:
  // on random double quartics 53 of 4,096 calls, each sent to the walk before, at about 900 ns).
  using W = typename Wider<T>::type;
  using W2 = typename Wider<W>::type;
  const auto again = [&](int s, const W& mid) {
    if constexpr (std::is_floating_point_v<W2> || std::is_same_v<W2, Quad>) {
      if (s == 2) return wide_sign_of(p, 0, W2(mid));
    }
    return s;
  };
  auto sign_between = [&](const T& a, const T& b) {
    const W mid = midpoint_in<W>(a, b);
    return again(wide_sign_of(p, 0, mid), mid);
  };
  if (!(x > lo && x < hi)) return Quick::Undecided;
  T up = interval_next_up(x), down = interval_next_down(x);
  int s_up = 0, s_down = 0;
  const W mid_up = midpoint_in<W>(x, up), mid_down = midpoint_in<W>(down, x);
  wide_signs_of(p, mid_up, mid_down, s_up, s_down);
  s_up = again(s_up, mid_up);
  s_down = again(s_down, mid_down);
  for (int step = 0; !(s_up == -1 && s_down == 1); ++step) {
    if (step == 4) return Quick::Undecided;
    if (s_up == 1 && s_down == 1) {  // the root lies above x+'s midpoint
      down = x;
      x = up;
      up = interval_next_up(x);
      s_down = 1;
      s_up = sign_between(x, up);
    } else if (s_up == -1 && s_down == -1) {  // below x-'s midpoint
      up = x;
      x = down;
      down = interval_next_down(x);
      s_up = -1;
      s_down = sign_between(down, x);
    } else {
      return Quick::Undecided;  // a sign the wider type cannot decide, or not a single crossing
    }
    if (!(x > lo && x < hi)) return Quick::Undecided;
  }
  if (!falls_where_not_positive(p, lo, up, kDepth)) return Quick::Undecided;
  t = x;
  return Quick::Root;
}

template <class T> class Certifier {
 public:
  enum class Verdict { Done, Undecided };

  Certifier(const Poly<T>& p, const T& lo, const T& hi) : lo_(lo), hi_(hi) {
    d_[0] = p;
    for (int k = 1; k <= 4; ++k) d_[k] = d_[k - 1].derivative();  // zero past the degree
  }

  // --- signs

  Evaluation<T> evaluate(int k, const T& x) const { return evaluate_with_bound(d_[k], x); }

  // The exact sign of p^(k)(x): 0 only if the value is exactly zero. Near a root the T
  // evaluation cannot decide, so `near_root` goes straight to the wider type.
  int sign(int k, const T& x, bool near_root = false) {
    if (!near_root) {
      const Evaluation<T> e = evaluate(k, x);
      if (abs_of(e.value) > e.bound) return sign_of(e.value);
    }
    using W = typename Wider<T>::type;
    const int s = wide_sign(k, W(x));
    if (s != 2) return s;
    return exact::sign_at(exact_poly(k), exact::to_dyadic(x));
  }

  // The sign of p^(k) at the exact midpoint of a and b.
  int sign_at_midpoint(const T& a, const T& b, int k = 0) {
    using W = typename Wider<T>::type;
    const int s = wide_sign(k, midpoint_in<W>(a, b));
    if (s != 2) return s;
    return exact::sign_at(exact_poly(k), exact::midpoint(exact::to_dyadic(a), exact::to_dyadic(b)));
  }

  // --- the structure (see the file comment)

  struct Points {
    int n = 0;
    T x[16];
    int s[16];
    void push(const T& t, int sign) { x[n] = t; s[n] = sign; ++n; }
  };

  // The structure of p^(k) on [lo, hi] (lo < hi), from that of p^(k+1).
  Verdict level(int k, Points& out) {
    const Poly<T>& q = d_[k];
    out.n = 0;
    if (q.degree == 0) {
      const int s = sign_of(q.c[0]);  // never 0: the degree was trimmed exactly
      out.push(lo_, s);
      out.push(hi_, s);
      return Verdict::Done;
    }
    Points below;
    if (level(k + 1, below) == Verdict::Undecided) return Verdict::Undecided;
    Points all;
    int s_prev = sign(k, below.x[0]);
    if (s_prev == 0) return Verdict::Undecided;
    all.push(below.x[0], s_prev);
    for (int i = 0; i + 1 < below.n; ++i) {
      const T& a = below.x[i];
      const T& b = below.x[i + 1];
      const int sb = sign(k, b);
      if (sb == 0) return Verdict::Undecided;
      if (below.s[i] == below.s[i + 1]) {
        if (sb != s_prev) {  // q monotone on [a, b]: one root inside
          T ra, rb;
          if (narrow(k, a, b, s_prev, ra, rb) == Verdict::Undecided) return Verdict::Undecided;
          if (ra != a) all.push(ra, s_prev);
          if (rb != b) all.push(rb, sb);
        }
      } else if (sb == s_prev && !extremum_clear(k, a, b, s_prev, below.s[i])) {
        return Verdict::Undecided;
      }
      all.push(b, sb);
      s_prev = sb;
    }
    // Keep the ends and the points next to a sign change: the next level up needs only where
    // this derivative keeps its sign and where it changes it.
    for (int i = 0; i < all.n; ++i) {
      const bool keep = i == 0 || i + 1 == all.n || all.s[i - 1] != all.s[i] || all.s[i] != all.s[i + 1];
      if (keep) out.push(all.x[i], all.s[i]);
    }
    return Verdict::Done;
  }

  // On [a, b], where q = p^(k) has one extremum (its derivative changes sign from s_slope_a) and
  // the sign s at both ends: true if q keeps the sign s throughout. Only an extremum towards zero
  // (a minimum of a positive q, a maximum of a negative one) needs the bound
  // |q(x) - q(e)| <= w (|q'(e)| + w max|q''|) for e an end and w = b - a.
  bool extremum_clear(int k, const T& a, const T& b, int s, int s_slope_a) {
    const bool towards_zero = (s > 0) == (s_slope_a < 0);
    if (!towards_zero) return true;
    const T w = b - a;
    const T r = abs_of(a) > abs_of(b) ? abs_of(a) : abs_of(b);
    T curvature(0);  // bound on |q''| over [a, b]
    if (d_[k].degree >= 2) {
      const Poly<T>& q2 = d_[k + 2];
      for (int j = q2.degree; j >= 0; --j) curvature = curvature * r + abs_of(q2.c[j]);
      curvature *= T(1) + T(2 * q2.degree + 4) * unit_roundoff<T>();
    }
    const T inflate = T(1) + T(32) * unit_roundoff<T>();
    for (const T& e : {a, b}) {
      const Evaluation<T> v = evaluate(k, e), slope = evaluate(k + 1, e);
      const T drift = (v.bound + w * (abs_of(slope.value) + slope.bound + w * curvature)) * inflate +
                      T(8) * std::numeric_limits<T>::min();
      if (sign_of(v.value) == s && abs_of(v.value) > drift) return true;
    }
    return false;
  }

  // q = p^(k) has exactly one root in (a, b), sign s_a at a and -s_a at b: a bracket ra < rb of
  // adjacent T values around it, with certified signs s_a at ra and -s_a at rb (or ra the root
  // itself, q(ra) = 0: see root_at).
  Verdict narrow(int k, const T& a, const T& b, int s_a, T& ra, T& rb) {
    const Poly<T>& q = d_[k];
    T guess;
    if (q.degree == 1) {
      guess = -q.c[0] / q.c[1];
    } else if (q.degree == 2) {
      T r1 = a, r2 = a;  // no real root in T arithmetic: the bisection below finds it
      quadratic_roots(q.c[2], q.c[1], q.c[0], r1, r2);
      guess = r1 > a && r1 < b ? r1 : r2;
    } else {
      guess = refine_root(q, d_[k + 2], a, b, s_a);
    }
    // A root exactly at a T value x (q(x) = 0; q has no other root in (a, b)) is bracketed by
    // (x, next x), x labelled s_a: q has the sign s_a on [a, x) and -s_a on (x, b], so every use
    // of the bracket stays true: q is monotone on [a, x] and on [x, b], the pair holds its one
    // root, and nearest(x, next x, s_a) returns x (the sign at their midpoint is -s_a). Common
    // with derivatives: under gravity 1, p''' of a disc against a corner vanishes at t = v_y.
    const auto root_at = [&](const T& x) {
      ra = x;
      rb = boost::math::float_next(x);
      return rb <= b ? Verdict::Done : Verdict::Undecided;
    };
    // Try the adjacent pair on the side of the guess that the certified sign points to.
    T lo = a, hi = b;
    if (guess > a && guess < b) {
      const int sg = sign(k, guess, true);
      if (sg == 0) return root_at(guess);
      if (sg == s_a) lo = guess; else hi = guess;
      const T probe = sg == s_a ? boost::math::float_next(guess) : boost::math::float_prior(guess);
      if (probe > a && probe < b) {
        const int sp = sign(k, probe, true);
        if (sp == 0) return root_at(probe);
        if (sp == s_a) lo = probe; else hi = probe;
      }
    }
    // Certified bisection for whatever is left (rarely more than nothing).
    for (int it = 0; it < kMaxRootIterations; ++it) {
      const T mid = lo + (hi - lo) / T(2);
      if (!(mid > lo && mid < hi)) {
        ra = lo;
        rb = hi;
        return Verdict::Done;
      }
      const int sm = sign(k, mid);
      if (sm == 0) return root_at(mid);
      if (sm == s_a) lo = mid; else hi = mid;
    }
    return Verdict::Undecided;
  }

  // The T nearest the single root of p in (a, b), where p falls from positive to negative: the
  // candidate from Halley's iteration is accepted when p is positive at the midpoint below it and
  // negative at the midpoint above it; otherwise a certified bracket of adjacent values decides.
  Verdict nearest_root(const T& a, const T& b, T& t) {
    T x = a;
    if (d_[0].degree == 2) {  // the cancellation-free closed form, as robust uses
      T r1 = a, r2 = a;
      quadratic_roots(d_[0].c[2], d_[0].c[1], d_[0].c[0], r1, r2);
      x = r1 > a && r1 < b ? r1 : r2;
    } else {
      x = refine_root(d_[0], d_[2], a, b, 1);
    }
    if (x > a && x < b) {
      const T up = boost::math::float_next(x), down = boost::math::float_prior(x);
      if (sign_at_midpoint(x, up) < 0 && sign_at_midpoint(down, x) > 0) {
        t = x;
        return Verdict::Done;
      }
    }
    T ra, rb;
    if (narrow(0, a, b, 1, ra, rb) == Verdict::Undecided) return Verdict::Undecided;
    t = nearest(ra, rb, 1);
    return Verdict::Done;
  }

  // The T nearest the single root of p^(k) in (a, b) (adjacent), p^(k)(a) of sign s_a.
  T nearest(const T& a, const T& b, int s_a, int k = 0) {
    const int s = sign_at_midpoint(a, b, k);
    if (s == 0) {  // a tie: the one with the even significand
      using std::frexp;
      using std::ldexp;
      int e = 0;
      const T scaled = ldexp(frexp(a, &e), std::numeric_limits<T>::digits);
      using std::fmod;
      return fmod(scaled, T(2)) == T(0) ? a : b;
    }
    return s == s_a ? b : a;
  }

  const Poly<T>& derivative(int k) const { return d_[k]; }

 private:
  template <class W> int wide_sign(int k, const W& x) const { return wide_sign_of(d_[0], k, x); }

  const exact::IntPoly& exact_poly(int k) {
    if (!exact_[k]) {
      exact::IntPoly e = exact::to_int_poly(d_[0]);
      for (int j = 0; j < k; ++j) e = exact::derivative(e);
      exact_[k] = e;
    }
    return *exact_[k];
  }

  T lo_, hi_;
  Poly<T> d_[5];
  std::optional<exact::IntPoly> exact_[5];
};

}  // namespace detail

namespace detail {

// The certified walk over the pieces of p'' (see the file comment); p is trimmed, of degree >= 1.
template <class T, class Visit>
bool certified_walk(const Poly<T>& p, const T& lo, const T& hi, StartRule rule, Visit& visit) {
  using Cert = Certifier<T>;
  Cert cert(p, lo, hi);
  int visited = 0;
  auto counted = [&](const T& t, bool overlap) {
    ++visited;
    return visit(t, overlap);
  };
  auto fall_back = [&] {
    ++detail::certified_exact_fallbacks;
    detail::exact::ExactSolver<T> exact(p, lo, hi);
    return exact.visit(rule, visited, visit);
  };

  // The overlap rule at lo: every sign here is certified (the chain ends at a non-zero constant).
  const int s_lo = cert.sign(0, lo);
  int after_lo = 0;  // p's sign just after lo when p(lo) = 0, p' decreasing just after lo otherwise
  if (s_lo <= 0)
    for (int k = 1; k <= p.degree && after_lo == 0; ++k) after_lo = cert.sign(k, lo);
  if (after_lo < 0 && (s_lo == 0 || (s_lo < 0 && rule == StartRule::OverlapCollides)))
    if (counted(lo, s_lo < 0)) return true;
  if (lo == hi) return false;

  // The pieces of p'' (level 2): p' is monotone on each, or (an adjacent pair) has one extremum.
  typename Cert::Points below;
  if (p.degree >= 2) {
    if (cert.level(2, below) == Cert::Verdict::Undecided) return fall_back();
  } else {  // p' is a constant
    below.push(lo, 1);
    below.push(hi, 1);
  }
  // Walk the pieces from lo, deciding lazily: the extremum of p in a piece is computed only when
  // it could hold a downward root, and the walk stops at the first root the visitor accepts.
  // The turning-overlap rule (pge/roots.hpp) is part of the walk: overlapping at lo and rising,
  // p rises to its first local maximum, where the pair collides if p is not positive there; that
  // maximum is the extremum of the first piece where p' changes sign downwards (p' > 0 on the
  // pieces before it, which are certified monotone), certified like any other decision.
  bool before_first_max = rule == StartRule::OverlapCollides && s_lo < 0 && after_lo > 0;
  int s_u = s_lo != 0 ? s_lo : after_lo;  // the sign of p just after u
  int slope_u = cert.sign(1, lo);
  if (slope_u == 0) return fall_back();
  for (int i = 0; i + 1 < below.n; ++i) {
    const T& u = below.x[i];
    const T& v = below.x[i + 1];
    const int slope_v = cert.sign(1, v);
    if (slope_v == 0) return fall_back();
    if (slope_u == slope_v && below.s[i] != below.s[i + 1] && !cert.extremum_clear(1, u, v, slope_u, below.s[i]))
      return fall_back();  // p' might touch zero in this adjacent pair
    const bool has_min = slope_u < 0 && slope_v > 0, has_max = slope_u > 0 && slope_v < 0;
    const int s_v = cert.sign(0, v);
    if (s_v == 0) {
      // A root exactly at a point: at hi it counts when p arrives from above without dipping
      // first; anything else is left to the exact solver.
      if (!(v == hi && s_u > 0 && !has_min)) return fall_back();
      return counted(hi, false);
    }
    T t;
    if (s_u > 0 && s_v < 0) {  // one root in (u, v)
      if (cert.nearest_root(u, v, t) == Cert::Verdict::Undecided) return fall_back();
      if (counted(t, false)) return true;
    } else if ((s_u > 0 && s_v > 0 && has_min) || (s_u < 0 && s_v < 0 && has_max)) {
      // The extremum decides: bracket it by adjacent T values (ca, cb) and look at p there.
      T ca, cb;
      if (cert.narrow(1, u, v, slope_u, ca, cb) == Cert::Verdict::Undecided) return fall_back();
      const int s_ca = cert.sign(0, ca), s_cb = cert.sign(0, cb);
      if (s_ca == 0 || s_cb == 0) return fall_back();
      // Minimum: p falls on [u, ca], so a negative p(ca) puts the root there. Maximum: p falls
      // on [cb, v], so a positive p(cb) puts it there. Otherwise the root, if any, lies in the
      // adjacent pair itself, where p changes sign at most once.
      const bool in_first = has_min && s_ca < 0, in_last = has_max && s_cb > 0;
      if (before_first_max && s_ca < 0 && s_cb < 0) {
        // The first maximum, in (ca, cb) where p is negative at both ends: it turns unless p
        // reaches zero in between, which only exact arithmetic can rule in or out.
        if (!cert.extremum_clear(0, ca, cb, -1, slope_u)) return fall_back();
        if (counted(cert.nearest(ca, cb, slope_u, 1), true)) return true;
      } else if (in_first || in_last) {
        if (cert.nearest_root(in_first ? u : cb, in_first ? ca : v, t) == Cert::Verdict::Undecided) return fall_back();
        if (counted(t, false)) return true;
      } else if (s_ca > 0 && s_cb < 0) {
        if (counted(cert.nearest(ca, cb, 1), false)) return true;
      } else if (s_ca == s_cb && !cert.extremum_clear(0, ca, cb, s_ca, slope_u)) {
        return fall_back();  // a near-double root: is it real?
      }
    }
    if (has_max) before_first_max = false;
    s_u = s_v;
    slope_u = slope_v;
  }
  return false;
}

}  // namespace detail

// The certified solver (see SolverKind). Coefficients and ends must be finite.
template <class T, class Visit>
bool certified_visit_downward_roots(const Poly<T>& p_in, const T& lo, const T& hi, StartRule rule, Visit&& visit) {
  using std::isfinite;
  if (!(lo <= hi) || !isfinite(lo) || !isfinite(hi)) return false;
  for (int k = 0; k <= p_in.degree; ++k)
    if (!isfinite(p_in.c[k])) return false;
  Poly<T> p = p_in;
  p.degree = detail::trimmed_degree(p_in);
  if (p.degree == 0) return false;
  T t;
  switch (detail::quick_earliest_root(p, lo, hi, t)) {
    case detail::Quick::None: return false;
    case detail::Quick::Undecided: return detail::certified_walk(p, lo, hi, rule, visit);
    case detail::Quick::Root: break;
  }
  if (visit(t, false)) return true;
  // Declined: the walk finds t again first (its roots are exact), and the rest after it.
  bool skipped = false;
  auto later = [&](const T& r, bool overlap) {
    if (skipped) return visit(r, overlap);
    skipped = true;
    return false;
  };
  return detail::certified_walk(p, lo, hi, rule, later);
}

}  // namespace pge
