#include "pge/oracle_exact.hpp"

#include <algorithm>
#include <cstdlib>

namespace pge::oracle {

Dyadic::Dyadic(long value) : m_(value) { normalize(); }

Dyadic::Dyadic(mpz_class mantissa, long exponent) : m_(std::move(mantissa)), e_(exponent) { normalize(); }

// Canonical form: an odd mantissa (or zero with exponent 0), so that equal values have equal
// representations and mantissas stay as short as the value allows.
void Dyadic::normalize() {
  if (m_ == 0) {
    e_ = 0;
    return;
  }
  const mp_bitcnt_t zeros = mpz_scan1(m_.get_mpz_t(), 0);
  if (zeros > 0) {
    mpz_fdiv_q_2exp(m_.get_mpz_t(), m_.get_mpz_t(), zeros);
    e_ += static_cast<long>(zeros);
  }
}

Dyadic Dyadic::scaled(long k) const {
  Dyadic r = *this;
  if (!r.is_zero()) r.e_ += k;
  return r;
}

// In place on the copy: one allocation, not a copy and a temporary.
Dyadic Dyadic::abs() const {
  Dyadic r = *this;
  mpz_abs(r.m_.get_mpz_t(), r.m_.get_mpz_t());
  return r;
}

Dyadic Dyadic::operator-() const {
  Dyadic r = *this;
  mpz_neg(r.m_.get_mpz_t(), r.m_.get_mpz_t());
  return r;
}

namespace {

// a + sign * b, exactly: the operand with the larger exponent is shifted onto the other's grid
// in place of the result (one allocation, not a copy and a shift of each). The result is given
// its limbs for the sum first (the shifted operand's, one for the shift's carry and one for the
// sum's), so that neither the shift nor the addition grows it again.
void add_into(mpz_class& r, long& e, const Dyadic& a, const Dyadic& b, int sign) {
  const auto limbs = [](const Dyadic& x) { return mpz_size(x.mantissa().get_mpz_t()); };
  const bool a_shifts = a.exponent() >= b.exponent();
  const std::size_t shift_limbs = static_cast<std::size_t>(std::abs(a.exponent() - b.exponent())) / GMP_NUMB_BITS;
  const std::size_t shifted = (a_shifts ? limbs(a) : limbs(b)) + shift_limbs + 1;
  const std::size_t other = a_shifts ? limbs(b) : limbs(a);
  mpz_realloc2(r.get_mpz_t(), (std::max(shifted, other) + 1) * GMP_NUMB_BITS);
  if (a_shifts) {
    mpz_mul_2exp(r.get_mpz_t(), a.mantissa().get_mpz_t(), static_cast<mp_bitcnt_t>(a.exponent() - b.exponent()));
    (sign > 0 ? mpz_add : mpz_sub)(r.get_mpz_t(), r.get_mpz_t(), b.mantissa().get_mpz_t());
    e = b.exponent();
  } else {
    mpz_mul_2exp(r.get_mpz_t(), b.mantissa().get_mpz_t(), static_cast<mp_bitcnt_t>(b.exponent() - a.exponent()));
    if (sign < 0) mpz_neg(r.get_mpz_t(), r.get_mpz_t());
    mpz_add(r.get_mpz_t(), r.get_mpz_t(), a.mantissa().get_mpz_t());
    e = a.exponent();
  }
}

long top_bit(const Dyadic& x) {  // floor(log2 |x|), x != 0
  return static_cast<long>(mpz_sizeinbase(x.mantissa().get_mpz_t(), 2)) - 1 + x.exponent();
}

}  // namespace

Dyadic operator+(const Dyadic& a, const Dyadic& b) {
  if (a.is_zero()) return b;
  if (b.is_zero()) return a;
  Dyadic r;
  add_into(r.m_, r.e_, a, b, 1);
  r.normalize();
  return r;
}

Dyadic operator-(const Dyadic& a, const Dyadic& b) {
  if (b.is_zero()) return a;
  if (a.is_zero()) return -b;
  Dyadic r;
  add_into(r.m_, r.e_, a, b, -1);
  r.normalize();
  return r;
}

Dyadic operator*(const Dyadic& a, const Dyadic& b) {
  if (a.is_zero() || b.is_zero()) return {};
  Dyadic r;
  r.m_ = a.m_ * b.m_;  // odd times odd is odd: already canonical
  r.e_ = a.e_ + b.e_;
  return r;
}

int compare(const Dyadic& a, const Dyadic& b) {
  const int sa = a.sign(), sb = b.sign();
  if (sa != sb) return sa < sb ? -1 : 1;
  if (sa == 0) return 0;
  // Same sign: magnitudes in different binades are ordered by the binade alone.
  const long ta = top_bit(a), tb = top_bit(b);
  if (ta != tb) return (ta > tb ? 1 : -1) * sa;
  if (a.e_ == b.e_) return cmp(a.m_, b.m_) < 0 ? -1 : (a.m_ == b.m_ ? 0 : 1);
  return (a - b).sign();
}

double Dyadic::to_double() const {
  // A mantissa of at most 53 bits on the grid of the subnormals and below the overflow is a
  // double already (every double converted exactly is one): m, then the scaling, are exact.
  const long bits = static_cast<long>(mpz_sizeinbase(m_.get_mpz_t(), 2));
  if (bits <= 53 && e_ >= -1074 && bits - 1 + e_ <= 1023) return std::ldexp(m_.get_d(), static_cast<int>(e_));
  if (bits > 53 && bits - 1 + e_ >= -1022 && bits - 1 + e_ <= 1022) {
    // A normal double's 53 bits: |m| / 2^shift rounded to nearest, ties to even. m is odd, so
    // below the half bit there is a set bit (the rest is above half) unless the half bit is
    // bit 0 itself (exactly half: a tie).
    const long shift = bits - 53;
    mpz_class n;
    mpz_tdiv_q_2exp(n.get_mpz_t(), m_.get_mpz_t(), static_cast<mp_bitcnt_t>(shift));  // |n| = floor(|m| / 2^shift)
    // Bit shift - 1 of |m|: of m's two's complement for m > 0, its complement for m < 0 above bit 0.
    const bool half = shift == 1 || (mpz_tstbit(m_.get_mpz_t(), static_cast<mp_bitcnt_t>(shift - 1)) != 0) == (sgn(m_) > 0);
    if (half && (shift >= 2 || mpz_odd_p(n.get_mpz_t()))) n += sgn(m_);
    return std::ldexp(n.get_d(), static_cast<int>(e_ + shift));  // |n| <= 2^53: exact, and so is the scaling
  }
  const Dyadic r = round_to_format(*this, TimeFormat::of<double>());
  // r has at most 53 significant bits, so both conversions below are exact.
  return std::ldexp(r.m_.get_d(), static_cast<int>(std::clamp(r.e_, -2200L, 2200L)));
}

mpq_class Dyadic::to_mpq() const {
  mpq_class q(m_);
  if (e_ >= 0) {
    mpz_class scale = 1;
    scale <<= static_cast<mp_bitcnt_t>(e_);
    q *= scale;
  } else {
    mpz_class scale = 1;
    scale <<= static_cast<mp_bitcnt_t>(-e_);
    q /= scale;
  }
  q.canonicalize();
  return q;
}

namespace {

template <class Divide> Dyadic on_grid(const mpq_class& q, long bits, Divide divide) {
  mpz_class scaled = q.get_num();
  scaled <<= static_cast<mp_bitcnt_t>(bits);
  mpz_class n;
  divide(n.get_mpz_t(), scaled.get_mpz_t(), q.get_den_mpz_t());
  return Dyadic(n, -bits);
}

}  // namespace

Dyadic grid_floor(const mpq_class& q, long bits) { return on_grid(q, bits, mpz_fdiv_q); }
Dyadic grid_ceil(const mpq_class& q, long bits) { return on_grid(q, bits, mpz_cdiv_q); }

std::string Dyadic::to_string() const {
  if (e_ == 0) return m_.get_str();
  return m_.get_str() + "*2^" + std::to_string(e_);
}

}  // namespace pge::oracle
