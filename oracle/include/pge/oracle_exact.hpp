// Exact numbers for the oracle. Every binary floating-point value (float, double, long double,
// binary128) is a dyadic rational m * 2^e, and sums, differences and products of dyadic
// rationals are dyadic again: the whole state of the engine and every contact polynomial built
// from it is exact in this type, with no division and no gcd. Conversion from a scalar peels
// its significand with frexp/ldexp, exactly; decimal text is never involved.
#pragma once

#include <gmpxx.h>

#include <bit>
#include <cmath>
#include <compare>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

namespace pge::oracle {

class Dyadic {
 public:
  Dyadic() = default;  // zero
  explicit Dyadic(long value);
  Dyadic(mpz_class mantissa, long exponent);  // mantissa * 2^exponent

  // The exact value of a finite scalar (float, double, long double, boost cpp_bin_float).
  // Throws std::invalid_argument for NaN or infinity.
  template <class T> static Dyadic from(const T& x);

  const mpz_class& mantissa() const { return m_; }  // odd, or 0
  long exponent() const { return e_; }
  int sign() const { return sgn(m_); }
  bool is_zero() const { return m_ == 0; }
  Dyadic scaled(long k) const;  // this * 2^k, exactly
  Dyadic abs() const;

  friend Dyadic operator+(const Dyadic& a, const Dyadic& b);
  friend Dyadic operator-(const Dyadic& a, const Dyadic& b);
  friend Dyadic operator*(const Dyadic& a, const Dyadic& b);
  Dyadic operator-() const;
  Dyadic& operator+=(const Dyadic& o) { return *this = *this + o; }
  Dyadic& operator-=(const Dyadic& o) { return *this = *this - o; }
  Dyadic& operator*=(const Dyadic& o) { return *this = *this * o; }

  friend int compare(const Dyadic& a, const Dyadic& b);  // -1, 0 or 1
  friend bool operator==(const Dyadic& a, const Dyadic& b) { return a.e_ == b.e_ && a.m_ == b.m_; }
  friend std::strong_ordering operator<=>(const Dyadic& a, const Dyadic& b) { return compare(a, b) <=> 0; }

  double to_double() const;  // nearest double, ties to even (exact when representable)
  mpq_class to_mpq() const;
  std::string to_string() const;  // exact: "m*2^e", or the integer when e >= 0 and small

 private:
  void normalize();
  mpz_class m_;
  long e_ = 0;
};

template <class T> Dyadic Dyadic::from(const T& x) {
  using std::floor;
  using std::frexp;
  using std::isfinite;
  using std::ldexp;
  if (!isfinite(x)) throw std::invalid_argument("Dyadic::from: NaN or infinity has no exact value");
  if (x == 0) return {};
  int e = 0;
  T f = frexp(x, &e);  // x = f * 2^e with 0.5 <= |f| < 1; exact
  const bool negative = f < 0;
  if (negative) f = -f;
  if constexpr (std::numeric_limits<T>::is_iec559 && std::numeric_limits<T>::radix == 2 &&
                std::numeric_limits<T>::digits <= std::numeric_limits<unsigned long>::digits) {
    // float, double, x87 long double: f * 2^digits is an integer below 2^digits (a subnormal's
    // significand has fewer bits), so scaling and converting it are exact.
    // Its trailing zeros go to the exponent here, where they are one instruction to count.
    constexpr int kDigits = std::numeric_limits<T>::digits;
    const auto bits = static_cast<unsigned long>(ldexp(f, kDigits));
    const int zeros = std::countr_zero(bits);
    mpz_class m(bits >> zeros);
    if (negative) mpz_neg(m.get_mpz_t(), m.get_mpz_t());
    return Dyadic(std::move(m), static_cast<long>(e) - kDigits + zeros);
  }
  mpz_class m = 0;
  long exponent = e;
  // Peel 32 bits at a time: scaling by a power of two, floor and subtracting the integer part
  // are all exact in T, and each digit fits an unsigned long.
  constexpr int kChunkBits = 32;
  while (f != 0) {
    f = ldexp(f, kChunkBits);
    const T digit = floor(f);
    f -= digit;
    m <<= kChunkBits;
    m += static_cast<unsigned long>(digit);
    exponent -= kChunkBits;
  }
  if (negative) m = -m;
  return Dyadic(std::move(m), exponent);
}

// Makes GMP (every Dyadic, mpz_class, mpq_class and the libraries over GMP in this process)
// keep the blocks of up to 16 limbs it frees, per thread, and hand them out again: the exact
// numbers of a judgement are short-lived and small, and the C library's malloc and free were
// about a fifth of the referee's time. Values are unchanged. Process-wide, so a program calls
// it once, at its start, if it wants it (pge does); returns false and changes nothing in an
// AddressSanitizer build (kept blocks would hide a use after free).
bool use_pooled_gmp_allocation();

// The multiples of 2^-bits nearest a rational from below and from above.
Dyadic grid_floor(const mpq_class& q, long bits);
Dyadic grid_ceil(const mpq_class& q, long bits);

struct ExactVec {
  Dyadic x, y;
  template <class V> static ExactVec from(const V& v) { return {Dyadic::from(v.x), Dyadic::from(v.y)}; }
};

// A binary floating-point format: the engine's time values are counted in its ulps.
// digits: significand bits including the hidden one (53 for double); min_exponent: as
// std::numeric_limits (-1021 for double: the smallest normal number is 2^(min_exponent - 1)).
struct TimeFormat {
  int digits = std::numeric_limits<double>::digits;
  int min_exponent = std::numeric_limits<double>::min_exponent;
  template <class T> static TimeFormat of() {
    return {std::numeric_limits<T>::digits, std::numeric_limits<T>::min_exponent};
  }
};

// Rounding to a format, and the position of a representable number in it. The ordinal of x >= 0
// counts the representable numbers in (0, x]; consecutive representable numbers differ by one,
// across binades and subnormals alike. Negative numbers have the negated ordinal of |x|.
Dyadic round_to_format(const Dyadic& x, const TimeFormat& f);  // nearest, ties to even
bool is_representable(const Dyadic& x, const TimeFormat& f);
mpz_class format_ordinal(const Dyadic& x, const TimeFormat& f);  // x must be representable
Dyadic format_value(const mpz_class& ordinal, const TimeFormat& f);
// x moved by k representable numbers (k < 0: down); x must be representable.
Dyadic format_step(const Dyadic& x, long k, const TimeFormat& f);

}  // namespace pge::oracle
