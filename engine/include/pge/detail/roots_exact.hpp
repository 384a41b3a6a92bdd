// Exact arithmetic for the certified solver's fallback: every scalar value is a dyadic rational
// m 2^e, so the polynomial, the interval ends and every split point are exact, and signs are
// decided in integers (Boost.Multiprecision cpp_int, header-only). Roots are isolated with a Sturm
// sequence of the square-free part, so multiple roots need no special case. Slow (microseconds
// to milliseconds per call); reached only when the floating-point filter cannot decide.
// Included by pge/detail/roots_certified.hpp.
#pragma once

#include <boost/multiprecision/cpp_int.hpp>

#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>

namespace pge {
namespace detail {
namespace exact {

using Int = boost::multiprecision::cpp_int;
using Rat = boost::multiprecision::cpp_rational;

// m * 2^e, kept with m odd (or zero) so that equal values have equal representations.
struct Dyadic {
  Int m;
  long e = 0;
};

inline void normalize(Dyadic& x) {
  if (x.m == 0) { x.e = 0; return; }
  const unsigned z = boost::multiprecision::lsb(x.m < 0 ? Int(-x.m) : x.m);
  x.m >>= z;
  x.e += static_cast<long>(z);
}

// x exactly, by peeling 32-bit chunks off the significand (frexp/ldexp/floor are exact).
template <class T> Dyadic to_dyadic(const T& x) {
  using std::floor;
  using std::frexp;
  using std::ldexp;
  Dyadic d;
  if (x == T(0)) return d;
  int e = 0;
  T f = frexp(x < T(0) ? T(-x) : x, &e);
  long bits = 0;
  while (f != T(0)) {
    f = ldexp(f, 32);
    const T chunk = floor(f);
    f -= chunk;
    d.m <<= 32;
    d.m += static_cast<std::uint32_t>(chunk);
    bits += 32;
  }
  if (x < T(0)) d.m = -d.m;
  d.e = e - bits;
  normalize(d);
  return d;
}

// a and b scaled to a common exponent: the integers to compare or add, and that exponent.
inline long align(const Dyadic& a, const Dyadic& b, Int& ma, Int& mb) {
  const long e = a.e < b.e ? a.e : b.e;
  ma = a.m << static_cast<unsigned>(a.e - e);
  mb = b.m << static_cast<unsigned>(b.e - e);
  return e;
}

inline int compare(const Dyadic& a, const Dyadic& b) {
  Int ma, mb;
  align(a, b, ma, mb);
  return ma < mb ? -1 : (ma > mb ? 1 : 0);
}

inline Dyadic midpoint(const Dyadic& a, const Dyadic& b) {
  Int ma, mb;
  Dyadic m;
  m.e = align(a, b, ma, mb) - 1;
  m.m = ma + mb;
  normalize(m);
  return m;
}

inline int sign_of_int(const Int& v) { return v < 0 ? -1 : (v > 0 ? 1 : 0); }

// A polynomial with integer coefficients; only its signs matter, so any positive multiple of the
// true polynomial serves.
struct IntPoly {
  Int c[5];
  int degree = 0;
};

inline IntPoly derivative(const IntPoly& p) {
  IntPoly d;
  d.degree = p.degree > 0 ? p.degree - 1 : 0;
  for (int k = 1; k <= p.degree; ++k) d.c[k - 1] = p.c[k] * k;
  return d;
}

// Sign of p(x): p(m 2^e) 2^(-e d) = sum c_k m^k 2^(-e (d - k)) for e < 0, all in integers.
inline int sign_at(const IntPoly& p, const Dyadic& x) {
  Int r = p.c[p.degree];
  if (x.e >= 0) {
    const Int xi = x.m << static_cast<unsigned>(x.e);
    for (int k = p.degree - 1; k >= 0; --k) r = r * xi + p.c[k];
  } else {
    const auto s = static_cast<unsigned>(-x.e);
    for (int k = p.degree - 1; k >= 0; --k) r = r * x.m + (p.c[k] << (s * static_cast<unsigned>(p.degree - k)));
  }
  return sign_of_int(r);
}

// The exact coefficients of p, scaled by a power of two to integers; leading zeros trimmed.
template <class T> IntPoly to_int_poly(const Poly<T>& p) {
  IntPoly out;
  Dyadic d[5];
  long e_min = std::numeric_limits<long>::max();
  for (int k = 0; k <= p.degree; ++k) {
    d[k] = to_dyadic(p.c[k]);
    if (d[k].m != 0 && d[k].e < e_min) e_min = d[k].e;
  }
  for (int k = 0; k <= p.degree; ++k)
    if (d[k].m != 0) out.c[k] = d[k].m << static_cast<unsigned>(d[k].e - e_min);
  out.degree = p.degree;
  while (out.degree > 0 && out.c[out.degree] == 0) --out.degree;
  return out;
}

// Sign of p immediately after x (the first non-zero derivative at x); 0 only for p == 0.
inline int sign_just_after(IntPoly p, const Dyadic& x) {
  for (int k = 0; k <= 4; ++k) {
    const int s = sign_at(p, x);
    if (s != 0) return s;
    if (p.degree == 0) return 0;
    p = derivative(p);
  }
  return 0;
}

// --- rational polynomial algebra (degree <= 4), for the square-free part and the Sturm chain.

struct RatPoly {
  Rat c[5];
  int degree = -1;  // -1: the zero polynomial
};

inline void trim(RatPoly& p) {
  while (p.degree >= 0 && p.c[p.degree] == 0) --p.degree;
}

inline RatPoly to_rat(const IntPoly& p) {
  RatPoly r;
  for (int k = 0; k <= p.degree; ++k) r.c[k] = Rat(p.c[k]);
  r.degree = p.degree;
  trim(r);
  return r;
}

// a = q b + r with deg r < deg b (b non-zero); returns r, stores q if asked.
inline RatPoly divide(RatPoly a, const RatPoly& b, RatPoly* quotient = nullptr) {
  RatPoly q;
  q.degree = a.degree - b.degree;
  while (a.degree >= b.degree) {
    const int shift = a.degree - b.degree;
    const Rat f = a.c[a.degree] / b.c[b.degree];
    q.c[shift] = f;
    for (int k = 0; k <= b.degree; ++k) a.c[k + shift] -= f * b.c[k];
    a.c[a.degree] = 0;  // exactly cancelled; set so trim cannot keep it
    trim(a);
  }
  if (quotient) { trim(q); *quotient = q; }
  return a;
}

// A positive multiple of p with integer coefficients (signs are all the chain needs).
inline IntPoly to_int(const RatPoly& p) {
  Int scale = 1;
  for (int k = 0; k <= p.degree; ++k) scale = boost::multiprecision::lcm(scale, boost::multiprecision::denominator(p.c[k]));
  IntPoly out;
  out.degree = p.degree < 0 ? 0 : p.degree;
  for (int k = 0; k <= p.degree; ++k) out.c[k] = boost::multiprecision::numerator(p.c[k]) * (scale / boost::multiprecision::denominator(p.c[k]));
  return out;
}

// The Sturm chain of the square-free part of p: S0 = p / gcd(p, p'), S1 = S0', and
// S(i+1) = -rem(S(i-1), S(i)). For a square-free S0 the number of sign variations V(x) (zeros
// skipped) satisfies V(a) - V(b) = number of distinct roots of p in (a, b], for any a < b.
struct SturmChain {
  IntPoly s[5];
  int length = 0;

  int variations(const Dyadic& x) const {
    int count = 0, last = 0;
    for (int i = 0; i < length; ++i) {
      const int v = sign_at(s[i], x);
      if (v == 0) continue;
      if (last != 0 && v != last) ++count;
      last = v;
    }
    return count;
  }
};

inline SturmChain sturm_chain(const IntPoly& p) {
  const RatPoly rp = to_rat(p);
  RatPoly dp;
  dp.degree = rp.degree - 1;
  for (int k = 1; k <= rp.degree; ++k) dp.c[k - 1] = rp.c[k] * k;
  RatPoly g = rp, h = dp;  // Euclid: gcd(p, p')
  while (h.degree >= 0) {
    RatPoly r = divide(g, h);
    g = h;
    h = r;
  }
  RatPoly square_free = rp;
  if (g.degree > 0) divide(rp, g, &square_free);
  SturmChain chain;
  RatPoly a = square_free, b;
  b.degree = a.degree - 1;
  for (int k = 1; k <= a.degree; ++k) b.c[k - 1] = a.c[k] * k;
  chain.s[chain.length++] = to_int(a);
  while (b.degree >= 0 && chain.length < 5) {
    chain.s[chain.length++] = to_int(b);
    RatPoly r = divide(a, b);
    for (int k = 0; k <= r.degree; ++k) r.c[k] = -r.c[k];
    a = b;
    b = r;
  }
  return chain;
}

// --- rounding an exact value to the nearest T.

// q (0 <= q < 2^(digits + 1)) as a T, exactly.
template <class T> T int_to_scalar(const Int& q) {
  using std::ldexp;
  T r(0);
  const unsigned bits = q == 0 ? 0 : boost::multiprecision::msb(q) + 1;
  for (int shift = static_cast<int>((bits + 31) / 32) * 32 - 32; shift >= 0; shift -= 32) {
    const auto chunk = static_cast<std::uint32_t>((q >> static_cast<unsigned>(shift)) & 0xffffffffu);
    r = ldexp(r, 32) + T(chunk);
  }
  return r;
}

// The T nearest to x, ties to even; subnormal results keep only the precision T has there.
template <class T> T round_to_scalar(const Dyadic& x) {
  using std::ldexp;
  if (x.m == 0) return T(0);
  const bool negative = x.m < 0;
  const Int mag = negative ? Int(-x.m) : x.m;
  const long bits = static_cast<long>(boost::multiprecision::msb(mag)) + 1;
  long precision = std::numeric_limits<T>::digits;
  if constexpr (std::numeric_limits<T>::has_denorm == std::denorm_present) {
    const long exponent = x.e + bits;  // x in [2^(exponent-1), 2^exponent)
    const long min_exponent = std::numeric_limits<T>::min_exponent;
    if (exponent < min_exponent) precision -= min_exponent - exponent;
    if (precision < 0) return negative ? T(-0.0) : T(0);  // below half the least subnormal
  }
  Int q = mag;
  long e = x.e;
  if (bits > precision) {
    const auto shift = static_cast<unsigned>(bits - precision);
    q = mag >> shift;
    const Int rem = mag - (q << shift);
    const Int half = Int(1) << (shift - 1);
    if (rem > half || (rem == half && (q & 1) != 0)) ++q;
    e += static_cast<long>(shift);
  }
  const T r = ldexp(int_to_scalar<T>(q), static_cast<int>(e));
  return negative ? T(-r) : r;
}


// --- the exact solver.

// Enumerates the downward roots of p in [lo, hi] exactly (the semantics of
// visit_downward_roots, the turning-overlap rule included), each rounded to the nearest T,
// skipping the first `skip` of them (the ones a caller already visited before falling back here).
template <class T> class ExactSolver {
 public:
  ExactSolver(const Poly<T>& p, const T& lo, const T& hi) : p_(to_int_poly(p)), lo_(to_dyadic(lo)), hi_(to_dyadic(hi)) {}
  // A polynomial known exactly (a positive multiple of it), on [lo, hi].
  ExactSolver(IntPoly p, Dyadic lo, Dyadic hi) : p_(std::move(p)), lo_(std::move(lo)), hi_(std::move(hi)) {}

  template <class Visit> bool visit(StartRule rule, int skip, Visit& visit) {
    skip_ = skip;
    turned_ = false;
    if (p_.degree == 0) return false;
    const int s0 = sign_at(p_, lo_);
    const int rising = sign_just_after(derivative(p_), lo_);
    if (rising < 0 && (s0 == 0 || (s0 < 0 && rule == StartRule::OverlapCollides)))
      if (emit(visit, round_to_scalar<T>(lo_), s0 < 0)) return true;
    if (compare(lo_, hi_) >= 0) return false;
    chain_ = sturm_chain(p_);
    if (rule == StartRule::OverlapCollides && s0 < 0 && rising > 0 && turning_overlap(visit)) return true;
    return isolate(visit, lo_, hi_, chain_.variations(lo_), chain_.variations(hi_));
  }

  // The first downward root r of p in (lo, hi] (as StartRule::CrossingsOnly finds it) rounded
  // to T, and a point `right` with r <= right and p < 0 on (r, right] (`right` = r, `exact`
  // true, when r is a dyadic number found exactly). False if there is none.
  bool first_crossing(T& t, Dyadic& right, bool& exact) {
    if (p_.degree == 0 || compare(lo_, hi_) >= 0) return false;
    chain_ = sturm_chain(p_);
    bool found = false;
    auto take = [&](const T& x, bool) {
      t = x;
      found = true;
      return true;
    };
    isolate(take, lo_, hi_, chain_.variations(lo_), chain_.variations(hi_));
    right = right_;
    exact = right_exact_;
    return found;
  }

 private:
  // The turning-overlap rule of pge/roots.hpp, decided exactly: p < 0 at lo and rising. p rises
  // strictly up to its first local maximum r (the first downward root of p'; p' >= 0 before it),
  // so if p(r) <= 0 the pair turns back without ever separating and collides at r. p(r) is
  // decided without computing r: on (r, right] p falls, so with p(right) < 0 p has 0, 1 or 2
  // distinct roots in (lo, right] as p(r) is negative, zero (a double root at r) or positive,
  // and the Sturm chain counts them. Returns true if `visit` stopped the search; the roots that
  // follow r (p stays non-positive up to r, so there are none before it) are isolate's.
  template <class Visit> bool turning_overlap(Visit& visit) {
    ExactSolver slope(derivative(p_), lo_, hi_);
    T t{};
    Dyadic right;
    bool exact = false;
    if (!slope.first_crossing(t, right, exact)) return false;
    int at_max = 0;  // the sign of p(r)
    if (exact) {
      at_max = sign_at(p_, right);
    } else {
      if (sign_at(p_, right) >= 0) return false;  // p(r) > p(right) >= 0: apart before the turn
      const int roots = chain_.variations(lo_) - chain_.variations(right);
      at_max = roots == 0 ? -1 : (roots == 1 ? 0 : 1);
    }
    if (at_max > 0) return false;  // apart at the maximum: an ordinary crossing follows
    turned_ = true;
    if (emit(visit, t, at_max < 0)) return true;
    turned_ = false;
    return false;
  }

 public:
  // Whether the last root visited was the turning-overlap rule's (a local maximum of p, where p
  // is negative or, a double root, zero): its time is p''s crossing, not p's.
  bool turned() const { return turned_; }

 private:


  template <class Visit> bool emit(Visit& visit, const T& t, bool overlap) {
    if (skip_ > 0) { --skip_; return false; }
    return visit(t, overlap);
  }

  // Distinct roots in (a, b], va and vb the chain's variations at a and b, earliest first.
  template <class Visit> bool isolate(Visit& visit, const Dyadic& a, const Dyadic& b, int va, int vb) {
    const int n = va - vb;
    if (n <= 0) return false;
    if (n == 1) return one_root(visit, a, b);
    const Dyadic m = midpoint(a, b);
    const int vm = chain_.variations(m);
    return isolate(visit, a, m, va, vm) || isolate(visit, m, b, vm, vb);
  }

  // Exactly one distinct root r in (a, b].
  template <class Visit> bool one_root(Visit& visit, Dyadic a, Dyadic b) {
    const IntPoly& q = chain_.s[0];
    for (;;) {
      if (sign_at(q, b) == 0) return exact_root(visit, b);
      if (sign_at(q, a) != 0) break;
      // a is the previous root (or lo): move it right of a, but not past r, so that the sign of
      // p at a is the sign just before r.
      const Dyadic m = midpoint(a, b);
      if (chain_.variations(a) == chain_.variations(m)) a = m; else b = m;
    }
    // Now a < r < b with neither end a root of p: the signs of p at the ends are its signs
    // just before and just after r.
    if (!(sign_at(p_, a) > 0 && sign_at(p_, b) < 0)) return false;
    right_ = b;
    right_exact_ = false;
    const int sa = sign_at(q, a);
    for (;;) {
      const T ta = round_to_scalar<T>(a), tb = round_to_scalar<T>(b);
      if (ta == tb) return emit(visit, ta, false);  // rounding is monotone: r rounds to it too
      // When ta and tb are adjacent, r rounds to one of them and the tie point between them
      // decides which. Without this, a root exactly at a tie that is not on the bisection's
      // grid (found by pge fuzz: a dyadic root a third of the way into the bracket) keeps the
      // bracket straddling the tie forever.
      const Dyadic tie = midpoint(to_dyadic(ta), to_dyadic(tb));
      const T rt = round_to_scalar<T>(tie);
      if (rt == ta || rt == tb) {
        if (compare(tie, a) <= 0) return emit(visit, tb, false);  // r > a >= tie
        if (compare(tie, b) >= 0) return emit(visit, ta, false);  // r < b <= tie
        const int st = sign_at(q, tie);
        if (st == 0) return emit(visit, rt, false);  // exactly at the tie: ties to even
        return emit(visit, st == sa ? tb : ta, false);
      }
      const Dyadic m = midpoint(a, b);
      const int sm = sign_at(q, m);
      if (sm == 0) return emit(visit, round_to_scalar<T>(m), false);
      if (sm == sa) a = m; else b = m;
    }
  }

  // A root at the exact point r (> lo): the first non-zero derivative of p there gives the sign
  // after r, and its order's parity the sign before.
  template <class Visit> bool exact_root(Visit& visit, const Dyadic& r) {
    IntPoly d = p_;
    int order = 0, after = 0;
    while (after == 0 && d.degree > 0) {
      d = derivative(d);
      ++order;
      after = sign_at(d, r);
    }
    const int before = order % 2 == 0 ? after : -after;
    const bool at_hi = compare(r, hi_) == 0;
    if (before > 0 && (at_hi || after < 0)) {
      right_ = r;
      right_exact_ = true;
      return emit(visit, round_to_scalar<T>(r), false);
    }
    return false;
  }

  IntPoly p_;
  Dyadic lo_, hi_;
  SturmChain chain_;
  int skip_ = 0;
  bool turned_ = false;
  Dyadic right_;  // first_crossing's bracket end: the last root emitted (one_root, exact_root)
  bool right_exact_ = false;
};

}  // namespace exact
}  // namespace detail
}  // namespace pge
