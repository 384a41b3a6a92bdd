#include "judging.hpp"
#include "roots.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace pge::oracle::detail {
namespace {

// Large enough for any real time error, small enough to be exact in a long long.
constexpr long kUlpsClamp = 1L << 62;

Dyadic representable(const Dyadic& t, const TimeFormat& f) { return round_to_format(t, f); }

long long abs_ll(long long v) { return v < 0 ? -v : v; }

// |n / d| (d != 0) as mpq_class's get_d gives it (rounded towards zero). Without a fraction in
// lowest terms where the answer is a normal double: q = floor(|N| 2^k / |D|) for mantissas N, D
// has at least 54 bits, and truncating q to 53 bits truncates the exact quotient (the 53-bit grid
// there is made of integers, so no grid point lies between q and the quotient).
double quotient_magnitude(const Dyadic& n, const Dyadic& d) {
  const long nb = static_cast<long>(mpz_sizeinbase(n.mantissa().get_mpz_t(), 2));
  const long db = static_cast<long>(mpz_sizeinbase(d.mantissa().get_mpz_t(), 2));
  const long k = std::max(0L, db - nb + 54);
  mpz_class quot;
  mpz_mul_2exp(quot.get_mpz_t(), n.mantissa().get_mpz_t(), static_cast<mp_bitcnt_t>(k));
  mpz_tdiv_q(quot.get_mpz_t(), quot.get_mpz_t(), d.mantissa().get_mpz_t());
  long exp = 0;
  const double top = std::abs(mpz_get_d_2exp(&exp, quot.get_mpz_t()));  // in [0.5, 1), truncated to 53 bits
  const long scale = exp + n.exponent() - d.exponent() - k;         // |n / d| truncated = top * 2^scale
  if (scale - 1 >= -1022 && scale - 1 <= 1023) return std::ldexp(top, static_cast<int>(scale));
  mpq_class q(::abs(n.mantissa()), ::abs(d.mantissa()));
  q.canonicalize();
  const long shift = n.exponent() - d.exponent();
  if (shift >= 0) mpq_mul_2exp(q.get_mpq_t(), q.get_mpq_t(), static_cast<mp_bitcnt_t>(shift));
  else mpq_div_2exp(q.get_mpq_t(), q.get_mpq_t(), static_cast<mp_bitcnt_t>(-shift));
  return q.get_d();
}

// The exact time rounded to format f (ties to even), tried first in the rounding cell of `guess`
// (the engine's time, right nearly always): two exact comparisons with the cell's ends, strictly
// inside, instead of refining the time to the format's precision; round_to decides otherwise.
Dyadic rounded(const ExactTime& exact, const Dyadic& guess, const TimeFormat& f) {
  const Dyadic below = format_step(guess, -1, f), above = format_step(guess, 1, f);
  if (exact.compare((below + guess).scaled(-1)) > 0 && exact.compare((guess + above).scaled(-1)) < 0) return guess;
  return exact.round_to(f);
}

}  // namespace

long long ulps_from(const Dyadic& engine, const ExactTime& exact, const TimeFormat& f) {
  const Dyadic e = representable(engine, f);
  const Dyadic r = rounded(exact, e, f);
  if (r == e) return 0;  // the common answer, without the two ordinals
  const mpz_class d = format_ordinal(e, f) - format_ordinal(r, f);
  if (d > kUlpsClamp) return kUlpsClamp;
  if (d < -kUlpsClamp) return -kUlpsClamp;
  return d.get_si();
}

double relative_error(const Dyadic& engine, const ExactTime& exact) {
  if (exact.compare(Dyadic()) == 0) return engine.is_zero() ? 0.0 : std::numeric_limits<double>::infinity();
  if (exact.compare(engine) == 0) return 0.0;
  // The exact time is refined until its bracket is below 2^-kSlackBits of its distance to the
  // engine's time: the quotient from any point of it is then within about 2^-kSlackBits of the
  // exact |engine - exact| / exact, relatively, far below the double it is reported in (a
  // bracket of a fixed absolute width would leave an error of 1 ulp at 2^-28 relative).
  constexpr long kSlackBits = 64;
  // The engine's time is near the exact one: one Newton step from it usually brackets the
  // exact time that finely at once (a hint; the loop below checks).
  refine_near(*exact.offset(), engine - exact.base(), kSlackBits + 8);
  std::optional<mpq_class> e_q;
  for (long bits = 80;; bits += kSlackBits) {
    if (const auto b = dyadic_bracket(*exact.offset(), bits)) {
      // The same test and quotient as below, in dyadic numbers: exact, so the same answer.
      const Dyadic lo = b->first + exact.base(), hi = b->second + exact.base();
      const Dyadic gap = engine < lo ? lo - engine : (engine > hi ? engine - hi : Dyadic());
      if (gap.sign() > 0 && (hi - lo).scaled(kSlackBits) <= gap) {
        const Dyadic mid = (lo + hi).scaled(-1);
        if (mid.is_zero()) return std::numeric_limits<double>::infinity();
        return quotient_magnitude(engine - mid, mid);
      }
      continue;
    }
    if (!e_q) e_q = engine.to_mpq();
    const mpq_class& e = *e_q;
    const auto [lo, hi] = exact.bracket(bits);
    const mpq_class gap = e < lo ? mpq_class(lo - e) : (e > hi ? mpq_class(e - hi) : mpq_class(0));
    mpz_class scale = 1;
    scale <<= static_cast<mp_bitcnt_t>(kSlackBits);
    if (gap > 0 && (hi - lo) * scale <= gap) {
      const mpq_class mid = (lo + hi) / 2;
      if (mid == 0) return std::numeric_limits<double>::infinity();  // a time below any bracket's width
      return mpq_class(abs(mpq_class((e - mid) / mid))).get_d();
    }
  }
}

Verdict decide(const std::optional<ExactTime>& own, std::optional<long long> own_ulps, const NextEvent& earliest,
               const Dyadic& engine_time, const TimeFormat& f, long agree_ulps) {
  const auto within = [&](const ExactTime& t) { return abs_ll(ulps_from(engine_time, t, f)) <= agree_ulps; };
  const auto own_within = [&] { return own_ulps ? abs_ll(*own_ulps) <= agree_ulps : within(*own); };
  if (own && earliest.time && own->compare(*earliest.time) == 0) {
    if (!own_within()) return Verdict::TimeError;
    return earliest.pairs.size() > 1 ? Verdict::Tie : Verdict::Agree;
  }
  if (earliest.time && earliest.time->compare(engine_time) < 0 && !within(*earliest.time)) return Verdict::Miss;
  if (own && own_within()) return Verdict::Misorder;
  return Verdict::Phantom;
}

}  // namespace pge::oracle::detail
