// The oracle's certified root enclosures (src/root_enclosure.hpp) and the CGAL fallback behind
// them (src/roots_cgal.cpp): every answer here is known from algebra, and the cases are chosen
// so that the fast path must give up and defer to the exact one (a double root, two roots
// closer than the quadratic isolation, equal roots of different polynomials, a zero of another
// polynomial at the root, a root exactly on a rounding tie).
#include "pge/oracle_time.hpp"
#include "roots.hpp"

#include <gtest/gtest.h>

namespace pge::oracle::detail {
namespace {

IntPoly poly(std::initializer_list<long> c) {
  IntPoly p;
  for (long v : c) p.emplace_back(v);
  return p;
}

// (x - p/2^k)(x - q/2^k) 2^(2k), as an integer polynomial: roots p/2^k and q/2^k.
IntPoly dyadic_quadratic(const mpz_class& p, const mpz_class& q, long k) {
  mpz_class scale = 1;
  scale <<= static_cast<mp_bitcnt_t>(k);
  return {p * q, -(p + q) * scale, scale * scale};
}

TEST(OracleRoots, SquareRootOfTwoBracketsToAnyWidth) {
  // x^2 - 2: roots -sqrt(2) and sqrt(2), simple.
  const std::vector<RootWithMultiplicity> r = real_roots(poly({-2, 0, 1}));
  ASSERT_EQ(r.size(), 2u);
  EXPECT_EQ(r[1].multiplicity, 1);
  for (long bits : {10L, 64L, 300L}) {
    const auto [lo, hi] = bracket(*r[1].root, bits);
    EXPECT_LT(lo * lo, 2);  // lo < sqrt(2) < hi
    EXPECT_GT(hi * hi, 2);
    mpq_class width_scaled = (hi - lo);
    mpz_class two_bits = 1;
    two_bits <<= static_cast<mp_bitcnt_t>(bits);
    EXPECT_LE(width_scaled * two_bits, 1);
  }
  EXPECT_EQ(compare(*r[0].root, *r[1].root), -1);
  EXPECT_EQ(compare(*r[1].root, Dyadic(1)), 1);
  EXPECT_EQ(compare(*r[1].root, mpq_class(3, 2)), -1);    // 1.5^2 = 2.25 > 2
  EXPECT_EQ(compare(*r[1].root, mpq_class(141, 100)), 1);  // 1.41^2 = 1.9881 < 2
  EXPECT_EQ(sign_at(poly({-3, 2}), *r[1].root), -1);       // 2 sqrt(2) - 3 < 0
}

TEST(OracleRoots, DoubleRootDefersToCgal) {
  // (x - 3)^2: one root of multiplicity 2 (discriminant zero: no sign change to isolate).
  const std::vector<RootWithMultiplicity> r = real_roots(poly({9, -6, 1}));
  ASSERT_EQ(r.size(), 1u);
  EXPECT_EQ(r[0].multiplicity, 2);
  EXPECT_EQ(compare(*r[0].root, Dyadic(3)), 0);
}

TEST(OracleRoots, NearTangentRootsCloserThanTheIsolation) {
  // (x - 1)(x - 1 - 2^-60): two simple roots 2^-60 apart, closer than the quadratic isolation
  // (2^-40 relative): the fast path must give up and CGAL isolate them; the answers are exact.
  const mpz_class one = mpz_class(1) << 60;
  const std::vector<RootWithMultiplicity> r = real_roots(dyadic_quadratic(one, one + 1, 60));
  ASSERT_EQ(r.size(), 2u);
  EXPECT_EQ(r[0].multiplicity, 1);
  EXPECT_EQ(compare(*r[0].root, Dyadic(1)), 0);
  EXPECT_EQ(compare(*r[1].root, Dyadic(one + 1, -60)), 0);
  EXPECT_EQ(compare(*r[0].root, *r[1].root), -1);
  // Between the roots: below the second, above the first.
  const Dyadic between(2 * one + 1, -61);
  EXPECT_EQ(compare(*r[0].root, between), -1);
  EXPECT_EQ(compare(*r[1].root, between), 1);
}

TEST(OracleRoots, EqualRootsOfDifferentPolynomialsAreEqual) {
  // (3x - 1)(x - 2) and (3x - 1)(x + 4) share the root 1/3 (not dyadic: no evaluation at a
  // dyadic point can hit it, the enclosures overlap at every width, only a gcd decides).
  const std::vector<RootWithMultiplicity> a = real_roots(poly({2, -7, 3}));
  const std::vector<RootWithMultiplicity> b = real_roots(poly({-4, 11, 3}));
  ASSERT_EQ(a.size(), 2u);
  ASSERT_EQ(b.size(), 2u);
  const RealRoot& third_a = *a[0].root;  // 1/3 < 2
  const RealRoot& third_b = *b[1].root;  // -4 < 1/3
  EXPECT_EQ(compare(third_a, third_b), 0);
  EXPECT_EQ(compare(third_a, mpq_class(1, 3)), 0);
  EXPECT_EQ(compare(third_b, mpq_class(1, 3)), 0);
  EXPECT_EQ(compare(third_a, *b[0].root), 1);
  // 3x - 1 vanishes at the root: interval evaluation never excludes 0, CGAL's gcd says 0.
  EXPECT_EQ(sign_at(poly({-1, 3}), third_a), 0);
  EXPECT_EQ(sign_at(poly({-1, 3, 0, 1}), third_a), 1);  // 1/27 > 0
}

TEST(OracleRoots, RootOnARoundingTieRoundsToEven) {
  // (x - (1 + 2^-53))(x + 3): the root 1 + 2^-53 is the midpoint of the doubles 1 and
  // 1 + 2^-52; ties go to the even significand, 1. Found by an exact zero of the polynomial at
  // the midpoint.
  const mpz_class m = (mpz_class(1) << 53) + 1;
  const std::vector<RootWithMultiplicity> r = real_roots(dyadic_quadratic(m, -3 * (mpz_class(1) << 53), 53));
  ASSERT_EQ(r.size(), 2u);
  const ExactTime t(Dyadic(), r[1].root);
  EXPECT_EQ(t.round_to(TimeFormat::of<double>()), Dyadic(1));
  EXPECT_EQ(t.compare(Dyadic(m, -53)), 0);
}

TEST(OracleRoots, EnclosureInvariantChecked) {
  // No sign change at the ends: not an enclosure.
  EXPECT_FALSE(RootEnclosure::isolated(poly({-2, 0, 1}), Dyadic(2), Dyadic(3)));
  std::optional<RootEnclosure> e = RootEnclosure::isolated(poly({-2, 0, 1}), Dyadic(1), Dyadic(2));
  ASSERT_TRUE(e);
  e->narrow(100);
  EXPECT_LT(e->lo() * e->lo(), Dyadic(2));
  EXPECT_GT(e->hi() * e->hi(), Dyadic(2));
  EXPECT_LE(e->hi() - e->lo(), Dyadic(mpz_class(1), -100));
}

}  // namespace
}  // namespace pge::oracle::detail
