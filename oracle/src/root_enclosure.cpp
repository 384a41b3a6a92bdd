#include "root_enclosure.hpp"

#include <algorithm>
#include <cmath>

namespace pge::oracle::detail {
namespace {

long bit_length(const mpz_class& m) { return static_cast<long>(mpz_sizeinbase(m.get_mpz_t(), 2)); }

// floor(log2 |x|) for x != 0.
long log2_floor(const Dyadic& x) { return bit_length(x.mantissa()) - 1 + x.exponent(); }

Dyadic power_of_two(long k) { return Dyadic(mpz_class(1), k); }

// p(x) = value * 2^exponent, exactly. With x = m 2^e and e < 0 (s = -e), Horner on integers:
// p(x) 2^(s n) = sum c_k m^k 2^(s (n - k)).
struct Scaled {
  mpz_class value;
  long exponent = 0;
};
Scaled evaluate_scaled(const IntPoly& p, const Dyadic& x) {
  Scaled r;
  if (p.empty()) return r;
  const long n = static_cast<long>(p.size()) - 1;
  if (x.exponent() >= 0) {
    mpz_class xi = x.mantissa();
    xi <<= static_cast<mp_bitcnt_t>(x.exponent());
    r.value = p[static_cast<std::size_t>(n)];
    for (long k = n - 1; k >= 0; --k) r.value = r.value * xi + p[static_cast<std::size_t>(k)];
    return r;
  }
  const long s = -x.exponent();
  r.value = p[static_cast<std::size_t>(n)];
  mpz_class term;
  for (long k = n - 1; k >= 0; --k) {
    r.value *= x.mantissa();
    mpz_mul_2exp(term.get_mpz_t(), p[static_cast<std::size_t>(k)].get_mpz_t(), static_cast<mp_bitcnt_t>(s * (n - k)));
    r.value += term;
  }
  r.exponent = -s * n;
  return r;
}

IntPoly derivative_of(const IntPoly& p) {
  IntPoly d;
  for (std::size_t k = 1; k < p.size(); ++k) d.push_back(p[k] * static_cast<unsigned long>(k));
  return d;
}

// An exact interval of dyadic numbers.
struct Range {
  Dyadic lo, hi;
};
Range times(const Range& a, const Range& b) {
  const Dyadic p[4] = {a.lo * b.lo, a.lo * b.hi, a.hi * b.lo, a.hi * b.hi};
  return {*std::min_element(p, p + 4), *std::max_element(p, p + 4)};
}

// How many bits finer than the current width sign_of and compare narrow before giving up (a
// zero of q at the root, or two equal roots, never separates), and in how many rounds. Any
// value is correct (the exact fallback decides the rest); this only trades Newton steps spent
// on true zeros and ties against CGAL calls for roots that merely lie close.
constexpr long kNarrowRoundBits = 48;
constexpr int kNarrowRounds = 4;

// Newton's correction is a double quotient (about 2^-51 relative error) and the step's own
// quadratic error: the root is bracketed by probes this many bits below the step's size once
// the iteration converges. Any value is correct (probes that miss still shrink the enclosure).
constexpr long kProbeBits = 44;

// Quadratic roots are first isolated at this relative width: far below any time's resolution
// question that follows (those are one exact evaluation each), far above the double rounding
// of the closed form that proposes them. Roots closer than this go to CGAL.
constexpr long kQuadraticIsolationBits = 40;

}  // namespace

int sign_at(const IntPoly& p, const Dyadic& x) { return sgn(evaluate_scaled(p, x).value); }

RootEnclosure RootEnclosure::point(const Dyadic& x) {
  RootEnclosure r;
  r.lo_ = r.hi_ = x;
  r.point_ = true;
  return r;
}

std::optional<RootEnclosure> RootEnclosure::isolated(IntPoly p, const Dyadic& lo, const Dyadic& hi) {
  if (!(lo < hi) || p.size() < 2) return std::nullopt;
  const int s_lo = sign_at(p, lo), s_hi = sign_at(p, hi);
  if (s_lo == 0 || s_hi != -s_lo) return std::nullopt;
  RootEnclosure r;
  r.dp_ = derivative_of(p);
  r.p_ = std::move(p);
  r.lo_ = lo;
  r.hi_ = hi;
  r.sign_lo_ = s_lo;
  return r;
}

void RootEnclosure::probe(const Dyadic& z) {
  if (point_ || !(lo_ < z && z < hi_)) return;
  const int s = sign_at(p_, z);
  if (s == 0) {
    *this = point(z);
  } else if (s == sign_lo_) {
    lo_ = z;  // p has p(lo)'s sign on (lo, root) only
  } else {
    hi_ = z;
  }
}

int RootEnclosure::compare(const Dyadic& x) {
  if (point_) return lo_ < x ? -1 : (x < lo_ ? 1 : 0);
  if (!(lo_ < x)) return 1;  // root > lo >= x
  if (!(x < hi_)) return -1;
  probe(x);
  if (point_) return 0;
  return lo_ == x ? 1 : -1;
}

int RootEnclosure::compare(const mpq_class& x) {
  const mpz_class& den = x.get_den();
  if (mpz_popcount(den.get_mpz_t()) == 1)  // a dyadic number
    return compare(Dyadic(x.get_num(), -static_cast<long>(mpz_scan1(den.get_mpz_t(), 0))));
  if (point_) return ::cmp(lo_.to_mpq(), x) < 0 ? -1 : 1;  // a dyadic root is never x
  if (::cmp(x, lo_.to_mpq()) <= 0) return 1;
  if (::cmp(x, hi_.to_mpq()) >= 0) return -1;
  // p(n / d) d^deg = sum c_k n^k d^(deg - k): the sign of p at x, exactly.
  mpz_class v = p_.back();
  for (std::size_t k = p_.size() - 1; k-- > 0;) {
    v *= x.get_num();
    mpz_class term = p_[k];
    for (std::size_t j = k; j < p_.size() - 1; ++j) term *= den;
    v += term;
  }
  const int s = sgn(v);
  if (s == 0) return 0;
  return s == sign_lo_ ? 1 : -1;
}

std::optional<double> RootEnclosure::newton_quotient(const Dyadic& x) {
  const Scaled f = evaluate_scaled(p_, x);
  const int s = sgn(f.value);
  if (s == 0) {
    *this = point(x);
    return std::nullopt;
  }
  if (lo_ < x && x < hi_) (s == sign_lo_ ? lo_ : hi_) = x;
  const Scaled d = evaluate_scaled(dp_, x);
  if (d.value == 0) return std::nullopt;
  long ef = 0, ed = 0;
  const double mf = mpz_get_d_2exp(&ef, f.value.get_mpz_t());
  const double md = mpz_get_d_2exp(&ed, d.value.get_mpz_t());
  const long e = ef - ed + f.exponent - d.exponent;
  if (e > 1000 || e < -1000) return std::nullopt;
  const double q = std::ldexp(mf / md, static_cast<int>(e));
  if (!std::isfinite(q) || q == 0) return std::nullopt;
  return q;
}

void RootEnclosure::narrow(long bits) {
  const Dyadic target = power_of_two(-bits);
  Dyadic x = midpoint();
  while (!point_ && hi_ - lo_ > target) {
    const Dyadic before = hi_ - lo_;
    const std::optional<double> q = newton_quotient(x);
    if (point_) return;
    std::optional<Dyadic> next;
    if (q) {
      const Dyadic step = Dyadic::from(*q);
      const Dyadic y = x - step;
      if (lo_ < y && y < hi_) {
        const Dyadic delta = power_of_two(std::max(log2_floor(step) + 1 - kProbeBits, -bits - 2));
        probe(y - delta);
        probe(y + delta);
        if (point_) return;
        if (lo_ < y && y < hi_) next = y;
      }
    }
    // Newton may stall far from the root: bisect whenever the width did not halve.
    if ((hi_ - lo_).scaled(1) > before) probe(midpoint());
    x = next ? *next : midpoint();
  }
}

void RootEnclosure::newton_from(const Dyadic& x0, long bits) {
  if (point_ || bits < 1) return;
  // Newton steps from x0 with quotients good to bits + 8 bits, until a step is below 2^-(bits +
  // 2) of the first: the error left is then about the square of that step over the root's
  // scale, far below the probes' distance 2^-bits of the first step (|x0 - root|).
  constexpr int kMaxSteps = 4;
  Dyadic x = x0;
  long first = 0;  // floor(log2) of the first step
  for (int k = 0; k < kMaxSteps; ++k) {
    const Scaled f = evaluate_scaled(p_, x);
    if (f.value == 0) {
      if (lo_ < x && x < hi_) *this = point(x);  // else x is another root of p: no hint
      return;
    }
    const Scaled d = evaluate_scaled(dp_, x);
    if (d.value == 0) return;
    // step = f / d to bits + 8 significant bits: q = floor(f 2^s / d), step = q 2^(ef - ed - s).
    const long shift = bits + 8 + bit_length(d.value) - bit_length(f.value);
    mpz_class num = f.value, den = d.value, q;
    if (shift >= 0) num <<= static_cast<mp_bitcnt_t>(shift);
    else den <<= static_cast<mp_bitcnt_t>(-shift);
    mpz_tdiv_q(q.get_mpz_t(), num.get_mpz_t(), den.get_mpz_t());
    if (q == 0) break;
    const Dyadic step(q, f.exponent - d.exponent - shift);
    x = x - step;
    if (k == 0) first = log2_floor(step);
    else if (log2_floor(step) < first - bits - 2) break;
  }
  const Dyadic delta = power_of_two(first + 1 - bits);
  probe(x - delta);
  probe(x + delta);
}

std::optional<int> RootEnclosure::sign_of(const IntPoly& q) {
  if (q.empty()) return 0;
  for (int round = 0;; ++round) {
    if (point_) return sign_at(q, lo_);
    const Range x{lo_, hi_};
    Range r{Dyadic(q.back(), 0), Dyadic(q.back(), 0)};
    for (std::size_t k = q.size() - 1; k-- > 0;) {
      r = times(r, x);
      const Dyadic c(q[k], 0);
      r = {r.lo + c, r.hi + c};
    }
    if (r.lo.sign() > 0) return 1;
    if (r.hi.sign() < 0) return -1;
    if (round == kNarrowRounds) return std::nullopt;
    narrow(kNarrowRoundBits - log2_floor(hi_ - lo_));
  }
}

std::optional<int> compare(RootEnclosure& a, RootEnclosure& b) {
  for (int round = 0;; ++round) {
    if (b.is_point()) return a.compare(b.lo());
    if (a.is_point()) return -b.compare(a.lo());
    if (!(b.lo() < a.hi())) return -1;  // a < a.hi <= b.lo < b
    if (!(a.lo() < b.hi())) return 1;
    if (round == kNarrowRounds) return std::nullopt;
    const long bits = kNarrowRoundBits - std::min(log2_floor(a.hi() - a.lo()), log2_floor(b.hi() - b.lo()));
    a.narrow(bits);
    b.narrow(bits);
  }
}

std::optional<std::pair<RootEnclosure, RootEnclosure>> quadratic_roots(const IntPoly& p) {
  if (p.size() != 3 || p[0] == 0 || p[2] == 0) return std::nullopt;
  const mpz_class disc = p[1] * p[1] - 4 * p[0] * p[2];
  if (sgn(disc) <= 0) return std::nullopt;
  // Proposals from the closed form in GMP floats (any exponent range): q = -(b + sign(b)
  // sqrt(D)) / 2, roots q / a and c / q. Their accuracy does not matter for correctness.
  constexpr mp_bitcnt_t kPrecision = 64;
  const mpf_class a(p[2], kPrecision), b(p[1], kPrecision), c(p[0], kPrecision), d(disc, kPrecision);
  const mpf_class root_d = sqrt(d);
  const mpf_class q = -(b + (sgn(p[1]) < 0 ? mpf_class(-root_d) : root_d)) / 2;
  if (sgn(q) == 0) return std::nullopt;
  mpf_class x[2] = {q / a, c / q};
  if (x[1] < x[0]) std::swap(x[0], x[1]);
  Dyadic lo[2], hi[2];
  for (int k = 0; k < 2; ++k) {
    if (sgn(x[k]) == 0) return std::nullopt;
    long e = 0;
    const double m = mpf_get_d_2exp(&e, x[k].get_mpf_t());  // x = m 2^e, 0.5 <= |m| < 1
    const Dyadic centre = Dyadic::from(m).scaled(e);
    const Dyadic delta = power_of_two(e - kQuadraticIsolationBits);
    lo[k] = centre - delta;
    hi[k] = centre + delta;
  }
  // Two disjoint intervals, each with a sign change of p at its ends (isolated checks them),
  // hold at least one root each; a quadratic has two: exactly one each.
  if (!(hi[0] < lo[1])) return std::nullopt;
  std::optional<RootEnclosure> r0 = RootEnclosure::isolated(p, lo[0], hi[0]);
  std::optional<RootEnclosure> r1 = RootEnclosure::isolated(p, lo[1], hi[1]);
  if (!r0 || !r1) return std::nullopt;
  return std::pair(std::move(*r0), std::move(*r1));
}

}  // namespace pge::oracle::detail
