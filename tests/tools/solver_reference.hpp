// The tests' exact referee for root solvers: the downward roots of a polynomial with scalar
// coefficients, computed with CGAL's Algebraic_kernel_d_1 (Descartes isolation over GMP
// integers) and multiplicities, and each rounded to the nearest scalar by exact comparison with
// the midpoints of neighbouring scalars. Independent of the engine: it shares no code with the
// certified solver (whose fallback uses Sturm sequences in Boost.Multiprecision), and converts
// scalars to rationals with its own frexp/ldexp decomposition.
#pragma once

#include "pge/roots.hpp"

#include <CGAL/Algebraic_kernel_d_1.h>
#include <CGAL/Gmpq.h>
#include <CGAL/Gmpz.h>

#include <boost/math/special_functions/next.hpp>

#include <cmath>
#include <algorithm>
#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

namespace pge::reference {

using Kernel = CGAL::Algebraic_kernel_d_1<CGAL::Gmpz>;
using Polynomial = Kernel::Polynomial_1;
using Algebraic = Kernel::Algebraic_real_1;
using Rational = CGAL::Gmpq;

// x as an exact rational: the significand is peeled off 16 bits at a time (exact steps).
template <class T> Rational to_rational(const T& x) {
  using std::floor;
  using std::frexp;
  using std::ldexp;
  if (x == T(0)) return Rational(0);
  int e = 0;
  T f = frexp(x < T(0) ? T(-x) : x, &e);
  CGAL::Gmpz m(0);
  while (f != T(0)) {
    f = ldexp(f, 16);
    const T chunk = floor(f);
    f -= chunk;
    m = m * 65536 + CGAL::Gmpz(static_cast<long>(static_cast<std::uint32_t>(chunk)));
    e -= 16;
  }
  mpq_t q;
  mpq_init(q);
  mpq_set_z(q, m.mpz());
  if (e < 0) mpq_div_2exp(q, q, static_cast<mp_bitcnt_t>(-e));
  else mpq_mul_2exp(q, q, static_cast<mp_bitcnt_t>(e));
  const Rational r(q);
  mpq_clear(q);
  return x < T(0) ? -r : r;
}

// The exact polynomial times the product of its coefficients' denominators (a positive factor:
// the same roots and signs), with integer coefficients.
template <class T> Polynomial to_polynomial(const Poly<T>& p, std::vector<Rational>& exact) {
  exact.clear();
  for (int k = 0; k <= p.degree; ++k) exact.push_back(to_rational(p.c[k]));
  while (exact.size() > 1 && exact.back() == 0) exact.pop_back();
  CGAL::Gmpz common(1);
  for (const Rational& q : exact) common = common * q.denominator();
  std::vector<CGAL::Gmpz> ints;
  for (const Rational& q : exact) ints.push_back((q * Rational(common)).numerator());
  return Polynomial(ints.begin(), ints.end());
}

inline int sign_of(const Rational& q) { return q < 0 ? -1 : (q > 0 ? 1 : 0); }

inline Rational evaluate(const std::vector<Rational>& c, const Rational& x) {
  Rational r(0);
  for (auto it = c.rbegin(); it != c.rend(); ++it) r = r * x + *it;
  return r;
}

inline std::vector<Rational> differentiate(const std::vector<Rational>& c) {
  std::vector<Rational> d;
  for (std::size_t k = 1; k < c.size(); ++k) d.push_back(c[k] * Rational(static_cast<long>(k)));
  if (d.empty()) d.push_back(Rational(0));
  return d;
}

// One root in [lo, hi]: either a rational point known exactly (lo by the start rule, or a root at
// lo or hi), or an algebraic number isolated by CGAL in [low, high] where p has no other root,
// with odd multiplicity, p of sign `after` just right of it and -after just left.
struct ExactRoot {
  bool overlap = false;
  bool rational = false;
  Rational value;      // when rational
  Rational low, high;  // otherwise
  int after = 0;
  // The integer polynomial whose root this is, when it is not p's own (the turning-overlap
  // rule's root of p'); empty otherwise.
  std::vector<CGAL::Gmpz> of;
};

// The exact answer for one polynomial: its downward roots in [lo, hi] by the definition in
// roots.hpp, earliest first, and its other real roots in [lo, hi] (grazes, upward crossings: to
// judge what an inexact solver's answer stands for).
struct Solved {
  std::vector<CGAL::Gmpz> poly;  // the integer polynomial, low degree first
  std::vector<ExactRoot> downward;
  std::vector<ExactRoot> other_roots;
};

// Sign of the integer polynomial c at the rational x = n / d: sign of sum c_k n^k d^(deg-k)
// (d > 0), in GMP integers.
inline int sign_at(const std::vector<CGAL::Gmpz>& c, const Rational& x) {
  const CGAL::Gmpz n = x.numerator(), d = x.denominator();
  CGAL::Gmpz r = c.back(), dpow = 1;
  for (std::size_t k = c.size() - 1; k-- > 0;) {
    dpow = dpow * d;
    r = r * n + c[k] * dpow;
  }
  return r < 0 ? -1 : (r > 0 ? 1 : 0);
}

// The roots of an integer polynomial in [lo, hi] with the sign it has just after each (from the
// first derivative that does not vanish there, as CGAL's multiplicity says).
struct SignedRoot {
  Algebraic root;
  int multiplicity = 0;
  int after = 0;
};
inline std::vector<SignedRoot> roots_in(const Polynomial& poly, const Rational& lo, const Rational& hi) {
  Kernel kernel;
  std::vector<std::pair<Algebraic, Kernel::Multiplicity_type>> roots;
  kernel.solve_1_object()(poly, std::back_inserter(roots));
  const auto compare = kernel.compare_1_object();
  const auto sign_at_root = kernel.sign_at_1_object();
  std::vector<SignedRoot> out;
  for (const auto& [r, multiplicity] : roots) {
    if (compare(r, lo) == CGAL::SMALLER || compare(r, hi) == CGAL::LARGER) continue;
    Polynomial d = poly;
    for (int k = 0; k < static_cast<int>(multiplicity); ++k) d = CGAL::differentiate(d);
    out.push_back({r, static_cast<int>(multiplicity), static_cast<int>(sign_at_root(d, r))});
  }
  return out;
}

// The turning-overlap rule of pge/roots.hpp, from its definition: p(lo) < 0 and p rising after
// lo; r the first root of p' in (lo, hi] where p' goes from positive to negative (at hi: positive
// before it); if p(r) <= 0 (CGAL's exact sign at the algebraic r), r is a downward root with the
// overlap flag p(r) < 0.
inline std::optional<ExactRoot> turning_root(const Polynomial& poly, const Rational& lo, const Rational& hi) {
  if (CGAL::degree(poly) < 2) return std::nullopt;
  const Polynomial slope = CGAL::differentiate(poly);
  Kernel kernel;
  const auto compare = kernel.compare_1_object();
  for (const SignedRoot& r : roots_in(slope, lo, hi)) {
    if (compare(r.root, lo) == CGAL::EQUAL) continue;
    const bool at_hi = compare(r.root, hi) == CGAL::EQUAL;
    const int before = r.multiplicity % 2 == 0 ? r.after : -r.after;
    if (!(before > 0 && (r.after < 0 || at_hi))) continue;
    const int at_max = static_cast<int>(kernel.sign_at_1_object()(poly, r.root));
    if (at_max > 0) return std::nullopt;
    ExactRoot root;
    root.overlap = at_max < 0;
    root.low = r.root.low();
    root.high = r.root.high();
    if (at_hi) {
      root.rational = true;
      root.value = hi;
    }
    root.after = r.after;
    for (int k = 0; k <= CGAL::degree(slope); ++k) root.of.push_back(slope[k]);
    return root;
  }
  return std::nullopt;
}

template <class T> Solved solve(const Poly<T>& p, const T& lo_t, const T& hi_t, StartRule rule) {
  Solved solved;
  std::vector<ExactRoot>& out = solved.downward;
  std::vector<Rational> c;
  const Polynomial poly = to_polynomial(p, c);
  if (c.size() <= 1) return solved;
  for (int k = 0; k <= CGAL::degree(poly); ++k) solved.poly.push_back(poly[k]);
  const Rational lo = to_rational(lo_t), hi = to_rational(hi_t);
  const int s_lo = sign_of(evaluate(c, lo));
  int after = 0;  // the sign of p just after lo: its first non-zero derivative there
  for (std::vector<Rational> d = c; after == 0 && d.size() > 1;) {
    d = differentiate(d);
    after = sign_of(evaluate(d, lo));
  }
  if (after < 0 && (s_lo == 0 || (s_lo < 0 && rule == StartRule::OverlapCollides))) {
    ExactRoot r;
    r.overlap = s_lo < 0;
    r.rational = true;
    r.value = lo;
    out.push_back(r);
  }
  if (!(lo < hi)) return solved;
  if (rule == StartRule::OverlapCollides && s_lo < 0 && after > 0)
    if (const std::optional<ExactRoot> turn = turning_root(poly, lo, hi)) out.push_back(*turn);

  Kernel kernel;
  const auto compare = kernel.compare_1_object();
  for (const SignedRoot& sr : roots_in(poly, lo, hi)) {
    const Algebraic& r = sr.root;
    const int multiplicity = sr.multiplicity;
    ExactRoot root;
    root.low = r.low();
    root.high = r.high();
    const bool at_lo = compare(r, lo) == CGAL::EQUAL, at_hi = compare(r, hi) == CGAL::EQUAL;
    if (at_lo || at_hi) {
      root.rational = true;
      root.value = at_lo ? lo : hi;
    }
    if (at_lo) {  // lo's own rule decided above
      solved.other_roots.push_back(root);
      continue;
    }
    root.after = sr.after;
    const int before = multiplicity % 2 == 0 ? root.after : -root.after;
    if (before > 0 && (root.after < 0 || at_hi)) out.push_back(root);
    else solved.other_roots.push_back(root);
  }
  return solved;
}

// Compares the root with a rational x: -1 if root < x, 0 if equal, 1 if root > x. Needs odd
// multiplicity (a sign change), which every downward root that is not rational has.
inline const std::vector<CGAL::Gmpz>& poly_of(const Solved& s, const ExactRoot& root) {
  return root.of.empty() ? s.poly : root.of;
}

inline int compare(const Solved& s, const ExactRoot& root, const Rational& x) {
  if (root.rational) return root.value < x ? -1 : (root.value > x ? 1 : 0);
  if (x < root.low) return 1;
  if (x > root.high) return -1;
  const int sx = sign_at(poly_of(s, root), x);
  if (sx == 0) return 0;
  return sx == root.after ? -1 : 1;  // p at x has the sign it has right of the root: x is right
}

// The T nearest to a rational, approximately (callers correct by comparison).
template <class T> T approximate(const Rational& q) {
  using std::ldexp;
  if (q == 0) return T(0);
  const bool negative = q < 0;
  const Rational a = negative ? -q : q;
  // a = n / d; scale by 2^s so that the integer quotient has digits + 8 bits.
  const long bits_n = static_cast<long>(mpz_sizeinbase(a.numerator().mpz(), 2));
  const long bits_d = static_cast<long>(mpz_sizeinbase(a.denominator().mpz(), 2));
  const long s = std::numeric_limits<T>::digits + 8 - (bits_n - bits_d);
  mpz_t num, quotient;
  mpz_init_set(num, a.numerator().mpz());
  mpz_init(quotient);
  if (s >= 0) mpz_mul_2exp(num, num, static_cast<mp_bitcnt_t>(s));
  mpz_tdiv_q(quotient, num, a.denominator().mpz());
  if (s < 0) mpz_tdiv_q_2exp(quotient, quotient, static_cast<mp_bitcnt_t>(-s));
  // Keep the top digits bits so that the conversion below is exact.
  long shift = static_cast<long>(mpz_sizeinbase(quotient, 2)) - std::numeric_limits<T>::digits;
  if (shift < 0) shift = 0;
  mpz_tdiv_q_2exp(quotient, quotient, static_cast<mp_bitcnt_t>(shift));
  T r(0);
  const std::size_t words = mpz_sizeinbase(quotient, 2) / 16 + 1;
  for (std::size_t w = words; w-- > 0;) {
    mpz_t chunk;
    mpz_init(chunk);
    mpz_tdiv_q_2exp(chunk, quotient, static_cast<mp_bitcnt_t>(16 * w));
    mpz_fdiv_r_2exp(chunk, chunk, 16);
    r = ldexp(r, 16) + T(static_cast<unsigned>(mpz_get_ui(chunk)));
    mpz_clear(chunk);
  }
  mpz_clear(num);
  mpz_clear(quotient);
  r = ldexp(r, static_cast<int>(shift - s));
  return negative ? T(-r) : r;
}

// A starting guess for the root in T: bracketed Newton steps in T from the isolating interval.
template <class T> T guess(const Solved& s, const ExactRoot& root) {
  if (root.rational) return approximate<T>(root.value);
  T a = approximate<T>(root.low), b = approximate<T>(root.high);
  if (!(a < b)) return a;
  // The coefficients over the largest one, so that none overflows T.
  CGAL::Gmpz largest(0);
  for (const CGAL::Gmpz& k : poly_of(s, root)) largest = std::max(largest, k < 0 ? CGAL::Gmpz(-k) : k);
  std::vector<T> c;
  for (const CGAL::Gmpz& k : poly_of(s, root)) c.push_back(approximate<T>(Rational(k, largest)));
  T x = a + (b - a) / T(2);
  for (int it = 0; it < 60; ++it) {
    T v = c.back(), dv(0);
    for (std::size_t k = c.size() - 1; k-- > 0;) {
      dv = dv * x + v;
      v = v * x + c[k];
    }
    if (v == T(0)) break;
    if ((v > T(0)) == (root.after > 0)) b = x; else a = x;  // p has the after-sign right of the root
    T next = dv != T(0) ? T(x - v / dv) : T(a + (b - a) / T(2));
    if (!(next > a && next < b)) next = a + (b - a) / T(2);
    if (next == x) break;
    x = next;
  }
  return x;
}

// The root to about double precision (not necessarily the nearest double).
inline double approximate_double(const Solved& s, const ExactRoot& root) { return guess<double>(s, root); }

// The T nearest to the root (ties to even), by exact comparison with the midpoints between
// neighbouring T values, walking from the guess with doubling steps.
template <class T> T nearest(const Solved& s, const ExactRoot& root) {
  if (root.rational) {
    // lo and hi are T values: exact.
    return approximate<T>(root.value);
  }
  auto mid = [](const T& u, const T& v) { return (to_rational(u) + to_rational(v)) / Rational(2); };
  // root's cell relative to x: 1 above x's rounding cell, -1 below, 0 inside (2: a tie above,
  // -2: a tie below).
  auto cell = [&](const T& x) {
    const int above = compare(s, root, mid(x, boost::math::float_next(x)));
    if (above > 0) return 1;
    const int below = compare(s, root, mid(boost::math::float_prior(x), x));
    if (below < 0) return -1;
    return above == 0 ? 2 : (below == 0 ? -2 : 0);
  };
  T x = guess<T>(s, root);
  int c = cell(x);
  if (c == 1 || c == -1) {
    // Bisection over T between ends that bracket the root, starting from the isolating interval.
    T lo = approximate<T>(root.low), hi = approximate<T>(root.high);
    while (compare(s, root, to_rational(lo)) < 0) lo = lo - (hi - lo) - T(1);  // approximate may land inside
    while (compare(s, root, to_rational(hi)) > 0) hi = hi + (hi - lo) + T(1);
    while (boost::math::float_next(lo) < hi) {
      const T m = lo + (hi - lo) / T(2);
      if (!(m > lo && m < hi)) break;
      if (compare(s, root, to_rational(m)) > 0) lo = m; else hi = m;
    }
    x = compare(s, root, mid(lo, hi)) > 0 ? hi : lo;
    c = cell(x);
  }
  if (c == 2 || c == -2) {  // a tie: the neighbour with the even significand
    using std::fmod;
    using std::frexp;
    using std::ldexp;
    int e = 0;
    const T scaled = ldexp(frexp(x, &e), std::numeric_limits<T>::digits);
    if (fmod(scaled, T(2)) != T(0)) x = c == 2 ? boost::math::float_next(x) : boost::math::float_prior(x);
  }
  return x;
}

}  // namespace pge::reference
