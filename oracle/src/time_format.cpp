// Representable numbers of a binary floating-point format, exactly (see oracle_exact.hpp).
// A positive x in binade [2^k, 2^(k+1)) has quantum 2^(max(k, emin - 1) - digits + 1): the
// subnormals share the quantum of the first normal binade. The largest exponent is not
// modelled: times are far below any format's overflow.
#include "pge/oracle_exact.hpp"

#include <algorithm>

namespace pge::oracle {
namespace {

long bit_length(const mpz_class& m) { return static_cast<long>(mpz_sizeinbase(m.get_mpz_t(), 2)); }

// floor(log2 |x|) for x != 0.
long binade(const Dyadic& x) { return bit_length(x.mantissa()) - 1 + x.exponent(); }

long quantum_exponent(long k, const TimeFormat& f) {
  return std::max(k, static_cast<long>(f.min_exponent) - 1) - f.digits + 1;
}

mpz_class pow2(long k) {
  mpz_class r = 1;
  r <<= static_cast<mp_bitcnt_t>(k);
  return r;
}

}  // namespace

bool is_representable(const Dyadic& x, const TimeFormat& f) {
  if (x.is_zero()) return true;
  return x.exponent() >= quantum_exponent(binade(x), f);
}

Dyadic round_to_format(const Dyadic& x, const TimeFormat& f) {
  if (is_representable(x, f)) return x;
  const long q = quantum_exponent(binade(x), f);
  const long shift = q - x.exponent();  // > 0: bits below the quantum
  const mpz_class magnitude = ::abs(x.mantissa());
  mpz_class n, rem;
  mpz_fdiv_q_2exp(n.get_mpz_t(), magnitude.get_mpz_t(), static_cast<mp_bitcnt_t>(shift));
  mpz_fdiv_r_2exp(rem.get_mpz_t(), magnitude.get_mpz_t(), static_cast<mp_bitcnt_t>(shift));
  const int vs_half = cmp(rem, pow2(shift - 1));
  if (vs_half > 0 || (vs_half == 0 && mpz_odd_p(n.get_mpz_t()))) n += 1;
  // n == 2^digits (rounded up into the next binade) is still the right value n * 2^q.
  return Dyadic(x.sign() < 0 ? mpz_class(-n) : n, q);
}

mpz_class format_ordinal(const Dyadic& x, const TimeFormat& f) {
  if (!is_representable(x, f)) throw std::invalid_argument("format_ordinal: value not representable");
  if (x.is_zero()) return 0;
  const long kk = std::max(binade(x), static_cast<long>(f.min_exponent) - 1);
  const long q = kk - f.digits + 1;
  mpz_class n = ::abs(x.mantissa());
  n <<= static_cast<mp_bitcnt_t>(x.exponent() - q);
  n += mpz_class(kk - (f.min_exponent - 1)) * pow2(f.digits - 1);
  return x.sign() < 0 ? mpz_class(-n) : n;
}

Dyadic format_value(const mpz_class& ordinal, const TimeFormat& f) {
  if (ordinal < 0) return -format_value(mpz_class(-ordinal), f);
  const mpz_class half_binade = pow2(f.digits - 1);
  if (ordinal < 2 * half_binade) return Dyadic(ordinal, f.min_exponent - f.digits);
  const mpz_class j = ordinal / half_binade - 1;  // binades above the first normal one
  const long kk = f.min_exponent - 1 + j.get_si();
  return Dyadic(ordinal - j * half_binade, kk - f.digits + 1);
}

Dyadic format_step(const Dyadic& x, long k, const TimeFormat& f) {
  // A positive normal x moved by k quanta within its binade [2^b, 2^(b+1)], its end included (the
  // next binade's first value, k ordinals on): x + k 2^q, without the ordinals.
  if (x.sign() > 0 && is_representable(x, f)) {
    const long b = binade(x);
    if (b >= f.min_exponent - 1) {
      const Dyadic y = x + Dyadic(mpz_class(k), quantum_exponent(b, f));
      if (y.sign() > 0 && (binade(y) == b || (y.mantissa() == 1 && y.exponent() == b + 1))) return y;
    }
  }
  return format_value(format_ordinal(x, f) + k, f);
}

}  // namespace pge::oracle
