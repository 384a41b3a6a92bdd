// pge::Quad (pge/scalar.hpp): GCC's __float128 with a correctly rounded square root and
// conversions from wider binary numbers rounded once. Expected values come from mathematics, not
// from the code under test: the square root from a 332-bit reference rounded to 113 bits (its
// distance from a Quad midpoint is never below 2^-230 relative, far above the reference's
// error), nearest-ness from exact differences in a 240-bit type.
#include "pge/scalar.hpp"

#include <gtest/gtest.h>

#include <random>

namespace {

using pge::Quad;
using High = boost::multiprecision::cpp_bin_float_100;  // 332 bits
using Wide = boost::multiprecision::number<boost::multiprecision::cpp_bin_float<240, boost::multiprecision::digit_base_2>,
                                           boost::multiprecision::et_off>;

Quad up(const Quad& x) { return Quad(nextafterq(x.backend().value(), std::numeric_limits<Quad>::infinity().backend().value())); }
Quad down(const Quad& x) { return Quad(nextafterq(x.backend().value(), -std::numeric_limits<Quad>::infinity().backend().value())); }

// A random Quad: a 113-bit significand from two 64-bit draws, an exponent in [lo, hi].
Quad random_quad(std::mt19937_64& rng, int lo, int hi) {
  const Quad top(rng() >> 7);                      // 57 bits
  const Quad low(rng() >> 8);                      // 56 bits
  const Quad m = ldexp(top, 56) + low;             // exact: < 2^113
  const int e = std::uniform_int_distribution<int>(lo, hi)(rng);
  return ldexp(m, e - 113);
}

// The Quad nearest v (ties to even), decided from exact differences: q is nearest when neither
// neighbour is closer, and of two equally close the one with an even significand.
bool is_nearest(const Wide& v, const Quad& q) {
  const Wide d = abs(v - Wide(q));
  for (const Quad& n : {up(q), down(q)}) {
    const Wide dn = abs(v - Wide(n));
    if (dn < d) return false;
    if (dn == d) {
      int e = 0;
      const Quad m = frexp(q, &e);  // q = m 2^e; its last significand bit is that of m 2^113
      if (fmod(ldexp(m, 113), Quad(2)) != 0) return false;
    }
  }
  return true;
}

Quad reference_sqrt(const Quad& x) {
  const High r = sqrt(High(x));
  return static_cast<Quad>(static_cast<pge::QuadSoftware>(r));  // the old type rounds once
}

TEST(QuadSqrt, CorrectlyRoundedOnRandomValuesOfEveryRange) {
  std::mt19937_64 rng(20261206);
  int checked = 0;
  const int ranges[][2] = {{-4, 4}, {-300, 300}, {-16000, 16000}, {-16494, -16300}};  // the last: subnormals too
  for (const auto& r : ranges) {
    for (int i = 0; i < 50'000; ++i) {
      const Quad x = random_quad(rng, r[0], r[1]);
      if (!(x > 0)) continue;
      ASSERT_EQ(sqrt(x), reference_sqrt(x)) << x;
      ++checked;
    }
  }
  EXPECT_GE(checked, 199'000);
}

// Squares of midpoints between Quads, rounded, and their neighbours: the inputs whose roots lie
// closest to a rounding boundary, where a faithful square root most often lands on the wrong side.
TEST(QuadSqrt, CorrectlyRoundedNextToMidpoints) {
  std::mt19937_64 rng(7);
  for (int i = 0; i < 20'000; ++i) {
    const Quad q = random_quad(rng, -50, 50);
    const Wide mid = (Wide(q) + Wide(up(q))) / 2;  // exact in 240 bits
    const Quad x = static_cast<Quad>(mid * mid);
    for (const Quad& y : {down(x), x, up(x)}) ASSERT_EQ(sqrt(y), reference_sqrt(y)) << y;
  }
}

TEST(QuadSqrt, ExactSquaresAndSpecialValues) {
  for (int k = 1; k < 1000; ++k) EXPECT_EQ(sqrt(Quad(k) * Quad(k)), Quad(k));
  EXPECT_EQ(sqrt(Quad(2)), reference_sqrt(Quad(2)));
  EXPECT_EQ(sqrt(Quad(0)), Quad(0));
  EXPECT_TRUE(signbit(sqrt(Quad(-0.0))));
  EXPECT_TRUE(isnan(sqrt(Quad(-1))));
  EXPECT_EQ(sqrt(std::numeric_limits<Quad>::infinity()), std::numeric_limits<Quad>::infinity());
  EXPECT_EQ(sqrt(std::numeric_limits<Quad>::max()), reference_sqrt(std::numeric_limits<Quad>::max()));
  EXPECT_EQ(sqrt(std::numeric_limits<Quad>::denorm_min()), ldexp(Quad(1), -8247));  // 2^-16494 = (2^-8247)^2
}

// Wider binary numbers convert to the nearest Quad, ties to even; among them values one part in
// 2^13 to 2^60 past a tie (Boost's generic conversion, adding 63-bit pieces one by one, rounds
// those twice and can land on the far side).
TEST(QuadConversion, WideBinaryNumbersRoundToNearestOnce) {
  std::mt19937_64 rng(3);
  for (int i = 0; i < 50'000; ++i) {
    const Quad q = random_quad(rng, -60, 60);
    const Wide half_ulp = (Wide(up(q)) - Wide(q)) / 2;
    const Wide tiny = ldexp(half_ulp, -std::uniform_int_distribution<int>(13, 60)(rng));
    for (const Wide& v : {Wide(q) + half_ulp, Wide(q) + half_ulp + tiny, Wide(q) + half_ulp - tiny,
                          Wide(q) + tiny, Wide(q) + half_ulp * Wide(rng() >> 11) / Wide(1ull << 52)}) {
      ASSERT_TRUE(is_nearest(v, static_cast<Quad>(v))) << v;
      ASSERT_TRUE(is_nearest(v, static_cast<Quad>(High(v)))) << v;
    }
  }
}

// Sums and quotients round to nearest, exponents far apart included (libgcc's software binary128;
// Boost 1.74's cpp_bin_float_quad, Quad before 2026-12, missed about one sum in 2,000 of these).
TEST(QuadArithmetic, SumsAndQuotientsRoundToNearest) {
  std::mt19937_64 rng(5);
  for (int i = 0; i < 100'000; ++i) {
    const int apart = std::uniform_int_distribution<int>(0, 120)(rng);
    const Quad a = random_quad(rng, 1, 3);
    const Quad b = (rng() & 1 ? 1 : -1) * random_quad(rng, 1 - apart, 3 - apart);
    ASSERT_TRUE(is_nearest(Wide(a) + Wide(b), a + b)) << a << " + " << b;  // exact in 240 bits
    const Wide q = Wide(a) / Wide(b);  // 240 bits: its error cannot move it across a midpoint...
    const Quad r = a / b;  // ...which a quotient of 113-bit values is never within 2^-227 of
    ASSERT_TRUE(is_nearest(q, r)) << a << " / " << b;
  }
}

// Quad to double and long double rounds to nearest (libgcc's conversions).
TEST(QuadConversion, NarrowingRoundsToNearest) {
  std::mt19937_64 rng(4);
  for (int i = 0; i < 50'000; ++i) {
    const Quad q = random_quad(rng, -100, 100);
    const double d = static_cast<double>(q);
    const Wide err = abs(Wide(q) - Wide(d));
    EXPECT_LE(err, abs(Wide(q) - Wide(std::nextafter(d, 1e300))));
    EXPECT_LE(err, abs(Wide(q) - Wide(std::nextafter(d, -1e300))));
    const long double l = static_cast<long double>(q);
    const Wide errl = abs(Wide(q) - Wide(l));
    EXPECT_LE(errl, abs(Wide(q) - Wide(std::nextafter(l, 1e300L))));
    EXPECT_LE(errl, abs(Wide(q) - Wide(std::nextafter(l, -1e300L))));
  }
}

// sign(a b - c) (pge/scalar.hpp's exact_product_minus_sign, in integers for Quad): against the
// exact product in 240 bits (two 113-bit significands need 226), on products rounded and their
// neighbours (where the sign is the rounding error's), unrelated values of either sign, zeros,
// and every range: subnormal factors and results, and products far past Dekker's splitting range
// (near overflow), where the integers must still be exact.
TEST(QuadProductSign, ExactOnEveryRange) {
  std::mt19937_64 rng(20261207);
  const auto exact_sign = [](const Quad& a, const Quad& b, const Quad& c) {
    const Wide d = Wide(a) * Wide(b) - Wide(c);
    return (d > 0) - (d < 0);
  };
  const int ranges[][2] = {{-4, 4}, {-200, 200}, {-8000, 8000}, {-16494, -16300}, {8100, 8190}};
  int checked = 0, nonzero_errors = 0;
  for (const auto& r : ranges) {
    for (int i = 0; i < 20'000; ++i) {
      Quad a = random_quad(rng, r[0], r[1]), b = random_quad(rng, r[0], r[1]);
      if (rng() % 2) a = -a;
      if (rng() % 2) b = -b;
      const Quad p = a * b;
      Quad other = random_quad(rng, r[0], r[1]);
      if (rng() % 2) other = -other;
      for (const Quad& c : {p, up(p), down(p), other, -p, Quad(0)}) {
        if (!isfinite(c)) continue;
        const int want = exact_sign(a, b, c);
        ASSERT_EQ(pge::detail::exact_product_minus_sign(a, b, c), want) << a << " * " << b << " - " << c;
        nonzero_errors += c == p && want != 0;
        ++checked;
      }
    }
  }
  for (const Quad& z : {Quad(0), Quad(-0.0)}) {
    EXPECT_EQ(pge::detail::exact_product_minus_sign(z, Quad(3), Quad(2)), -1);
    EXPECT_EQ(pge::detail::exact_product_minus_sign(Quad(3), z, Quad(-2)), 1);
    EXPECT_EQ(pge::detail::exact_product_minus_sign(z, z, z), 0);
  }
  EXPECT_GE(checked, 500'000);
  EXPECT_GE(nonzero_errors, 50'000);  // most rounded products are inexact: the error's sign is tested
}

}  // namespace
