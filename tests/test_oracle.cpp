// The oracle on cases whose answers are known exactly. Every expected value is derived in the
// comment above it, or computed independently with GMP integers; none comes from a run of the
// oracle.
#include "judging.hpp"
#include "oracle_states.hpp"

#include <gtest/gtest.h>

#include <boost/multiprecision/cpp_bin_float.hpp>

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <string>
#include <vector>

namespace pge::oracle {
namespace {

using namespace testing;

mpz_class pow10(int k) {
  mpz_class r = 1;
  for (int i = 0; i < k; ++i) r *= 10;
  return r;
}

// ---------------------------------------------------------------- exact numbers and formats

TEST(OracleNumbers, DoubleFloatLongDoubleQuadConvertExactly) {
  // IEEE 754: 0.1 rounds to 3602879701896397 * 2^-55 in binary64 (an odd significand).
  EXPECT_EQ(Dyadic::from(0.1), Dyadic(mpz_class(3602879701896397L), -55));
  // binary32: 0.1f = 0x3DCCCCCD = 13421773 * 2^-27.
  EXPECT_EQ(Dyadic::from(0.1f), Dyadic(mpz_class(13421773L), -27));
  // x87 extended: 0.1L = 0xCCCCCCCCCCCCCCCD * 2^-67 (64-bit significand, rounded up).
  EXPECT_EQ(Dyadic::from(0.1L), Dyadic(mpz_class("CCCCCCCCCCCCCCCD", 16), -67));
  // binary128 holds 1 + 2^-112 exactly; it is (2^112 + 1) * 2^-112.
  using Quad = boost::multiprecision::cpp_bin_float_quad;
  const Quad q = 1 + ldexp(Quad(1), -112);
  mpz_class m = 1;
  m <<= 112;
  EXPECT_EQ(Dyadic::from(q), Dyadic(m + 1, -112));
  EXPECT_EQ(Dyadic::from(-0.0), Dyadic());
  EXPECT_THROW(Dyadic::from(std::numeric_limits<double>::quiet_NaN()), std::invalid_argument);
  // The ends of each binary format: the smallest subnormal is 2^-1074 (binary64), 2^-149
  // (binary32), 2^-16445 (x87: 2^-16382 with 63 fraction bits); the largest finite value is
  // (2^53 - 1) 2^971, (2^24 - 1) 2^104, (2^64 - 1) 2^16320; and negatives.
  const auto ones = [](int bits) -> mpz_class { return (mpz_class(1) << static_cast<mp_bitcnt_t>(bits)) - 1; };
  EXPECT_EQ(Dyadic::from(std::numeric_limits<double>::denorm_min()), Dyadic(mpz_class(1), -1074));
  EXPECT_EQ(Dyadic::from(std::numeric_limits<float>::denorm_min()), Dyadic(mpz_class(1), -149));
  EXPECT_EQ(Dyadic::from(std::numeric_limits<long double>::denorm_min()), Dyadic(mpz_class(1), -16445));
  EXPECT_EQ(Dyadic::from(-std::numeric_limits<double>::max()), Dyadic(-ones(53), 971));
  EXPECT_EQ(Dyadic::from(std::numeric_limits<float>::max()), Dyadic(ones(24), 104));
  EXPECT_EQ(Dyadic::from(-std::numeric_limits<long double>::max()), Dyadic(-ones(64), 16320));
  // Random doubles of every binade, subnormals included, against GMP's exact mpq_class(double).
  std::mt19937_64 rng(1206);
  std::uniform_real_distribution<double> mant(-1.0, 1.0);
  std::uniform_int_distribution<int> expo(-1080, 1023);
  for (int k = 0; k < 2000; ++k) {
    const double x = std::ldexp(mant(rng), expo(rng));
    EXPECT_EQ(Dyadic::from(x).to_mpq(), mpq_class(x)) << x;
    const auto f = static_cast<float>(std::ldexp(x, std::ilogb(x) / 8 - std::ilogb(x)));  // 2^-135 to 2^127
    EXPECT_EQ(Dyadic::from(f).to_mpq(), mpq_class(static_cast<double>(f))) << f;
  }
}

TEST(OracleNumbers, ArithmeticIsExact) {
  // Sums, differences and products of the doubles 0.1 and 0.2 against GMP's rational arithmetic
  // on the same two values (an independent exact computation).
  const Dyadic a = Dyadic::from(0.1), b = Dyadic::from(0.2);
  EXPECT_EQ((a + b).to_mpq(), a.to_mpq() + b.to_mpq());
  EXPECT_EQ((a * b).to_mpq(), a.to_mpq() * b.to_mpq());
  EXPECT_EQ((a - b).to_mpq(), a.to_mpq() - b.to_mpq());
  EXPECT_LT(compare(a, b), 0);
  EXPECT_EQ(Dyadic(12), Dyadic(mpz_class(3), 2));  // canonical form: 12 = 3 * 2^2
}

// Dyadic::to_double rounds to nearest, ties to even; IEEE arithmetic rounds the exact sum and
// product of two doubles the same way, so a + b and a * b are what the exact values must round
// to: random doubles of every sign and binade (normal, subnormal and overflowing results), and
// sums that are ties (a double plus half an ulp of it, or an odd multiple of a quarter ulp).
TEST(OracleNumbers, ToDoubleRoundsToNearestEven) {
  std::mt19937_64 rng(27);
  std::uniform_real_distribution<double> mant(-1.0, 1.0);
  std::uniform_int_distribution<int> expo(-1100, 1023);  // |a| < 2^1023: finite
  int checked = 0;
  for (int k = 0; k < 20000; ++k) {
    const double a = std::ldexp(mant(rng), expo(rng)), b = std::ldexp(mant(rng), k % 4 == 0 ? expo(rng) : expo(rng) / 16);
    const Dyadic x = Dyadic::from(a), y = Dyadic::from(b);
    if (std::isfinite(a * b)) {
      EXPECT_EQ((x * y).to_double(), a * b) << a << " * " << b;
    }
    if (std::isfinite(a + b)) {
      EXPECT_EQ((x + y).to_double(), a + b) << a << " + " << b;
    }
    const double ulp = std::nextafter(std::abs(a), std::numeric_limits<double>::infinity()) - std::abs(a);
    if (!(ulp >= 0x1p-1000) || !std::isfinite(ulp)) continue;
    for (const double frac : {0.5, 0.25, 0.75}) {  // h = ulp * frac is exact: a tie, below and above it
      const double h = ulp * frac;
      if (std::isfinite(a + h)) {
        EXPECT_EQ((x + Dyadic::from(h)).to_double(), a + h) << a << " + " << h;
      }
      ++checked;
    }
  }
  EXPECT_GT(checked, 10000);
}

TEST(OracleNumbers, FormatOrdinalsAndRounding) {
  const TimeFormat d = TimeFormat::of<double>();
  // The smallest subnormal is the first positive double; 2^-1022 (the smallest normal) is the
  // 2^52-th (2^52 - 1 subnormals precede it); 1.0 is 2^52 * 1023 (1022 binades above it).
  EXPECT_EQ(format_ordinal(Dyadic::from(std::numeric_limits<double>::denorm_min()), d), 1);
  EXPECT_EQ(format_ordinal(Dyadic::from(std::numeric_limits<double>::min()), d), mpz_class(1L << 52));
  EXPECT_EQ(format_ordinal(Dyadic(1), d), mpz_class(1L << 52) * 1023);
  // Neighbours of 1: 1 + 2^-52 above, 1 - 2^-53 below.
  EXPECT_EQ(format_step(Dyadic(1), 1, d).to_double(), std::nextafter(1.0, 2.0));
  EXPECT_EQ(format_step(Dyadic(1), -1, d).to_double(), std::nextafter(1.0, 0.0));
  // 1 + 2^-53 is halfway between 1 and 1 + 2^-52: ties to even gives 1. 1 + 3 * 2^-54 is nearer
  // to 1 + 2^-52.
  EXPECT_EQ(round_to_format(Dyadic(1) + Dyadic(mpz_class(1), -53), d), Dyadic(1));
  EXPECT_EQ(round_to_format(Dyadic(1) + Dyadic(mpz_class(3), -54), d), Dyadic::from(std::nextafter(1.0, 2.0)));
  EXPECT_EQ(format_value(format_ordinal(Dyadic::from(0.1), d), d), Dyadic::from(0.1));
}

// format_step(x, k) is x's k-th neighbour in the format: std::nextafter applied |k| times (an
// independent count), for float, double and long double, from random values, from powers of
// two (binade ends, either way) and around the smallest normal and the subnormals.
template <class T> void expect_steps_are_nextafter(std::uint64_t seed) {
  const TimeFormat f = TimeFormat::of<T>();
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.5, 1.0);
  std::uniform_int_distribution<int> expo(std::numeric_limits<T>::min_exponent - 4, 60);
  std::vector<T> starts = {T(1), T(2), T(0.5), std::numeric_limits<T>::min(), std::numeric_limits<T>::denorm_min(),
                           std::nextafter(std::numeric_limits<T>::min(), T(0)), std::nextafter(T(1), T(0))};
  for (int n = 0; n < 500; ++n) starts.push_back(std::ldexp(static_cast<T>(unit(rng)), expo(rng)));
  for (const T x : starts)
    for (long k = -3; k <= 3; ++k) {
      T y = x;
      const T towards = (k < 0 ? -1 : 1) * std::numeric_limits<T>::infinity();
      for (long j = 0; j < (k < 0 ? -k : k); ++j) y = std::nextafter(y, towards);
      EXPECT_EQ(format_step(Dyadic::from(x), k, f), Dyadic::from(y)) << x << " + " << k;
    }
}

TEST(OracleNumbers, FormatStepIsNextafterRepeated) {
  expect_steps_are_nextafter<float>(1);
  expect_steps_are_nextafter<double>(2);
  expect_steps_are_nextafter<long double>(3);
}

// ---------------------------------------------------------------- known contact times

// Circles of radius 1 at x = 0 and x = 3 closing at speed 2: the gap 1 closes at t = 1/2
// ((3 - 2t)^2 = 4 has roots 1/2 and 5/2; the first is the downward crossing).
ExactState half_state() {
  return state_of({moving_circle(1, {0, 0}, {1, 0}), moving_circle(1, {3, 0}, {-1, 0})});
}

// The pooled GMP allocation (oracle/src/gmp_pool.cpp) changes no value: a sequence of random
// operations on numbers of 1 to 40 limbs (products, sums, shifts that grow and shrink, copies and
// frees in random order) gives the same numbers with the pool as with GMP's default functions,
// including numbers made before the pool was installed and freed after it.
TEST(OracleNumbers, PooledGmpAllocationKeepsEveryValue) {
  void* (*default_alloc)(size_t) = nullptr;
  void* (*default_realloc)(void*, size_t, size_t) = nullptr;
  void (*default_free)(void*, size_t) = nullptr;
  mp_get_memory_functions(&default_alloc, &default_realloc, &default_free);
  const auto workload = [](std::vector<mpz_class>& live) {
    std::mt19937_64 rng(20261206);
    std::vector<std::string> seen;
    for (int step = 0; step < 20000; ++step) {
      const std::size_t i = rng() % live.size(), j = rng() % live.size();
      switch (rng() % 6) {
        case 0: live[i] = live[i] * live[j]; break;
        case 1: live[i] += live[j]; break;
        case 2: live[i] <<= static_cast<mp_bitcnt_t>(rng() % 200); break;
        case 3: live[i] >>= static_cast<mp_bitcnt_t>(rng() % 300); break;
        case 4: live[i] = mpz_class(static_cast<unsigned long>(rng())) - live[j]; break;
        default: live.erase(live.begin() + static_cast<long>(i)); live.push_back(mpz_class(static_cast<long>(rng() % 1000)) + 1);
      }
      if (mpz_sizeinbase(live[i].get_mpz_t(), 2) > 40 * 64) live[i] >>= 39 * 64;  // at most about 40 limbs
      if (step % 97 == 0) seen.push_back(live[i].get_str(16));
    }
    for (const mpz_class& v : live) seen.push_back(v.get_str(16));
    return seen;
  };
  const auto start = [] {
    std::vector<mpz_class> v;
    for (long k = 1; k <= 64; ++k) v.push_back(mpz_class(k) << static_cast<mp_bitcnt_t>(k * 37 % 500));
    return v;
  };
  std::vector<mpz_class> plain = start();
  const std::vector<std::string> expected = workload(plain);
  std::vector<mpz_class> made_before = start();  // allocated by GMP's default functions
  if (!use_pooled_gmp_allocation()) GTEST_SKIP() << "no pool in an AddressSanitizer build";
  const std::vector<std::string> got = workload(made_before);
  // A block given back is handed out again for the same size: the pool is in use.
  void* (*alloc)(size_t) = nullptr;
  void (*release)(void*, size_t) = nullptr;
  mp_get_memory_functions(&alloc, nullptr, &release);
  void* block = alloc(3 * sizeof(mp_limb_t));
  release(block, 3 * sizeof(mp_limb_t));
  EXPECT_EQ(alloc(3 * sizeof(mp_limb_t)), block);
  release(block, 3 * sizeof(mp_limb_t));
  made_before.clear();  // given back to the pool, whether GMP's default functions or the pool made them
  mp_set_memory_functions(default_alloc, default_realloc, default_free);
  EXPECT_EQ(got, expected);
}

TEST(OracleKnown, TwoCirclesMeetAtExactlyOneHalf) {
  const NextEvent next = next_event(half_state());
  ASSERT_TRUE(next.time);
  EXPECT_EQ(next.time->compare(Dyadic(mpz_class(1), -1)), 0);
  EXPECT_EQ(next.time->decimal(5), "0.50000");
  EXPECT_EQ(next.time->to_double(), 0.5);
  ASSERT_EQ(next.pairs.size(), 1u);
  EXPECT_EQ(next.pairs[0].a, 0u);
  EXPECT_EQ(next.pairs[0].b, 1u);
  EXPECT_TRUE(has_feature(next.pairs[0], ContactKind::CircleCircle, 0, 0));
  EXPECT_FALSE(next.pairs[0].overlap_rule);
}

// A ball (radius 1/2) released at rest at (1/2, 3) under gravity (0, -4) onto a fixed peg of
// radius 1/2 at the origin. Centre distance squared: 1/4 + (3 - 2 t^2)^2, a quartic in t; it
// equals 1 when (3 - 2 t^2)^2 = 3/4, first at 3 - 2 t^2 = sqrt(3)/2, so
//   t = sqrt(3/2 - sqrt(3)/4) = sqrt((6 - sqrt 3) / 4) ~ 1.0329.
// floor(10^100 t) = isqrt(floor(10^200 (6 - sqrt 3) / 4)) (isqrt(floor X) = floor(sqrt X)), and
// with S = isqrt(3 * 10^400) < 10^200 sqrt 3 < S + 1 and M = 6 * 10^200 - S, the inner floor is
// floor((M - 1) / 4) (an integer cannot lie strictly inside ((M - 1)/4, M/4) unless M/4 is one,
// and then the floor is M/4 - 1 all the same).
TEST(OracleKnown, QuarticRootMatchesClosedFormTo100Digits) {
  const ExactState s = state_of({fixed_circle(0.5, {0, 0}), moving_circle(0.5, {0.5, 3}, {0, 0}, 1, {0, -4})});
  const NextEvent next = next_event(s);
  ASSERT_TRUE(next.time);
  mpz_class s3, n;
  mpz_class three_e400 = 3 * pow10(400);
  mpz_sqrt(s3.get_mpz_t(), three_e400.get_mpz_t());
  const mpz_class m = 6 * pow10(200) - s3;
  mpz_class inner;
  mpz_class m1 = m - 1;
  mpz_fdiv_q_ui(inner.get_mpz_t(), m1.get_mpz_t(), 4);
  mpz_sqrt(n.get_mpz_t(), inner.get_mpz_t());
  std::string digits = n.get_str();  // 101 digits: "10329..."
  ASSERT_EQ(digits.size(), 101u);
  EXPECT_EQ(next.time->decimal(100), digits.substr(0, 1) + "." + digits.substr(1));
  // And the isolating interval, refined to 2^-340 < 10^-100, holds the closed form exactly:
  // lo <= t iff lo <= 0 or (6 - 4 lo^2 >= 0 and 3 <= (6 - 4 lo^2)^2); likewise t <= hi.
  const auto [lo, hi] = next.time->bracket(340);
  EXPECT_LE(mpq_class(hi - lo), mpq_class(mpz_class(1), pow10(100)));
  const mpq_class a = 6 - 4 * lo * lo, b = 6 - 4 * hi * hi;
  EXPECT_TRUE(a >= 0 && 3 <= a * a);
  EXPECT_TRUE(b < 0 || 3 >= b * b);
}

// A ball of radius 1 passing a fixed peg of radius 1: centre at (-5 + t, y0), so the squared
// centre distance is (t - 5)^2 + y0^2, least at t = 5. Contact needs it to reach 4.
ExactState pass_state(double y0) { return state_of({fixed_circle(1, {0, 0}), moving_circle(1, {-5, y0}, {1, 0})}); }

TEST(OracleKnown, NearDoubleRootGrazeIsNoCollision) {
  // y0 = 2 + 2^-40: at the closest approach the gap is y0 - 2 = 2^-40 > 0 exactly (computed
  // here in rationals, independently of the oracle), and f = (t - 5)^2 + y0^2 - 4 > 0 always.
  const double y0 = 2 + std::ldexp(1.0, -40);
  const mpq_class gap = Dyadic::from(y0).to_mpq() - 2;
  EXPECT_GT(gap, 0);
  EXPECT_FALSE(next_event(pass_state(y0)).time);
  // y0 = 2: an exact double root at t = 5, f touches 0 and comes back: a graze, no collision.
  EXPECT_FALSE(next_event(pass_state(2)).time);
  // y0 = 2 - 2^-40: two close roots 5 -+ sqrt(4 - y0^2); the collision is the first, just before 5.
  const NextEvent hit = next_event(pass_state(2 - std::ldexp(1.0, -40)));
  ASSERT_TRUE(hit.time);
  EXPECT_LT(hit.time->compare(Dyadic(5)), 0);
  EXPECT_GT(hit.time->compare(Dyadic::from(5 - std::ldexp(1.0, -18))), 0);
}

// A ball (radius 1/2) at rest at x = 2 accelerating at 1 towards a peg (radius 1/2) at the
// origin: the centre distance 2 - t^2 / 2 reaches 1 at t = sqrt 2.
TEST(OracleKnown, TimeRoundsToTheNearestRepresentable) {
  const ExactState s = state_of({fixed_circle(0.5, {0, 0}), moving_circle(0.5, {2, 0}, {0, 0}, 1, {-1, 0})});
  const NextEvent next = next_event(s);
  ASSERT_TRUE(next.time);
  // IEEE 754 sqrt is correctly rounded in every format: the nearest representable sqrt 2.
  EXPECT_EQ(next.time->round_to(TimeFormat::of<double>()), Dyadic::from(std::sqrt(2.0)));
  EXPECT_EQ(next.time->round_to(TimeFormat::of<float>()), Dyadic::from(std::sqrt(2.0f)));
  EXPECT_EQ(next.time->round_to(TimeFormat::of<long double>()), Dyadic::from(std::sqrt(2.0L)));
}

// ---------------------------------------------------------------- verdicts on engine events

Judgement judge_one(const ExactState& s, const ExactEvent& e) {
  Referee r(s);
  return r.judge(e, s.bodies[e.a].motion, s.bodies[e.b].motion);
}

TEST(OracleVerdict, ExactTimeAgreesAndLateTimeIsATimeError) {
  const ExactState s = half_state();
  const Judgement ok = judge_one(s, event_at(s, 0, 1, 0.5, ContactKind::CircleCircle));
  EXPECT_EQ(ok.verdict, Verdict::Agree);
  EXPECT_EQ(ok.ulps, 0);
  EXPECT_EQ(ok.relative_error, 0);
  EXPECT_TRUE(ok.features_match);
  // 100 representable doubles after 1/2 (ulp 2^-53 there): 100 ulps late, relative 100 * 2^-52.
  double late = 0.5;
  for (int k = 0; k < 100; ++k) late = std::nextafter(late, 1.0);
  const Judgement bad = judge_one(s, event_at(s, 0, 1, late, ContactKind::CircleCircle));
  EXPECT_EQ(bad.verdict, Verdict::TimeError);
  EXPECT_EQ(bad.ulps, 100);
  EXPECT_DOUBLE_EQ(bad.relative_error, 100 * std::ldexp(1.0, -52));
}

// An irrational contact time (the quartic's above, t = sqrt((6 - sqrt 3) / 4)) and an engine
// time 3 doubles past its rounding: the ulps and the relative error, the latter against the
// exact time bracketed to 2^-300 in rationals (|e - t| / t to far below a double's precision).
TEST(OracleVerdict, RelativeErrorOfAnIrrationalTime) {
  const ExactState s = state_of({fixed_circle(0.5, {0, 0}), moving_circle(0.5, {0.5, 3}, {0, 0}, 1, {0, -4})});
  const NextEvent next = next_event(s);
  ASSERT_TRUE(next.time);
  double t = next.time->to_double();
  for (int k = 0; k < 3; ++k) t = std::nextafter(t, 2.0);
  const Judgement j = judge_one(s, event_at(s, 0, 1, t, ContactKind::CircleCircle));
  ASSERT_TRUE(j.pair_time);
  EXPECT_EQ(j.ulps, 3);
  const auto [lo, hi] = j.pair_time->bracket(300);
  const mpq_class exact = (lo + hi) / 2, e = Dyadic::from(t).to_mpq();
  const double expected = mpq_class(abs(mpq_class((e - exact) / exact))).get_d();
  EXPECT_GT(expected, 2 * std::ldexp(1.0, -53));
  EXPECT_DOUBLE_EQ(j.relative_error, expected);
}

// The relative error |e - t| / t of an engine time e against an exact time t is reported
// rounded towards zero, as GMP's mpq_class::get_d rounds the exact quotient (an independent
// computation): dyadic times of every size, e within a few ulps of t up to far from it, and
// quotients below the normal doubles (where the answer takes another path).
TEST(OracleVerdict, RelativeErrorIsTheExactQuotientRoundedTowardsZero) {
  std::mt19937_64 rng(1206);
  std::uniform_real_distribution<double> unit(0.5, 1.0);
  std::uniform_int_distribution<int> binade(-60, 60), apart(-1150, 10);
  for (int k = 0; k < 3000; ++k) {
    const Dyadic t = Dyadic::from(std::ldexp(unit(rng), binade(rng)));
    const int up = k % 3 == 0 ? 1 : -1;
    const Dyadic e = t + Dyadic::from(up * std::ldexp(unit(rng), apart(rng))) * t;
    if (e.sign() <= 0) continue;
    const double expected = mpq_class(abs(mpq_class((e.to_mpq() - t.to_mpq()) / t.to_mpq()))).get_d();
    EXPECT_EQ(detail::relative_error(e, ExactTime::at(t)), expected) << e.to_string() << " against " << t.to_string();
  }
}

// Two pairs far apart: A (x = 0, speed 1) reaches B (x = 3, at rest) at t = 1; D (speed 1) reaches
// E, at rest 3 + `extra` away, at t = 1 + extra. F sits far off and is touched by nobody.
ExactState two_pairs(double extra) {
  return state_of({moving_circle(1, {0, 0}, {1, 0}), moving_circle(1, {3, 0}, {0, 0}),
                   moving_circle(1, {0, 100}, {1, 0}), moving_circle(1, {3 + extra, 100}, {0, 0}),
                   moving_circle(1, {50, 50}, {0, 0})});
}

TEST(OracleVerdict, SkippedCollisionIsAMiss) {
  // The faked engine processes D-E at t = 4 (its exact time: extra = 3) and skips A-B at t = 1.
  const ExactState s = two_pairs(3);
  const Judgement j = judge_one(s, event_at(s, 2, 3, 4, ContactKind::CircleCircle));
  EXPECT_EQ(j.verdict, Verdict::Miss);
  ASSERT_TRUE(j.earliest_time);
  EXPECT_EQ(j.earliest_time->compare(Dyadic(1)), 0);
  ASSERT_EQ(j.earliest.size(), 1u);
  EXPECT_EQ(j.earliest[0].a, 0u);
  EXPECT_EQ(j.earliest[0].b, 1u);
  EXPECT_EQ(j.ulps, 0);  // its own pair's time is right
}

TEST(OracleVerdict, EventBetweenBodiesThatNeverTouchIsAPhantom) {
  // A moves along y = 0 and F sits at (50, 50): their distance never drops below 50. The faked
  // event is at t = 1/2, before anything touches.
  const ExactState s = two_pairs(3);
  const Judgement j = judge_one(s, event_at(s, 0, 4, 0.5, ContactKind::CircleCircle));
  EXPECT_EQ(j.verdict, Verdict::Phantom);
  EXPECT_FALSE(j.pair_time);
  EXPECT_GT(j.gap, 40);
}

TEST(OracleVerdict, NearSimultaneousPairsInTheOtherOrderAreAMisorder) {
  // D-E touches 2^-51 (two ulps of 1; one ulp of E's position 3) after A-B; the engine takes
  // D-E first, at its exact time.
  const double extra = std::ldexp(1.0, -51);
  const ExactState s = two_pairs(extra);
  const Judgement j = judge_one(s, event_at(s, 2, 3, 1 + extra, ContactKind::CircleCircle));
  EXPECT_EQ(j.verdict, Verdict::Misorder);
  // 2^-30 apart is far beyond a few ulps: a miss.
  const double far = std::ldexp(1.0, -30);
  const ExactState s2 = two_pairs(far);
  EXPECT_EQ(judge_one(s2, event_at(s2, 2, 3, 1 + far, ContactKind::CircleCircle)).verdict, Verdict::Miss);
}

TEST(OracleVerdict, SameExactTimeIsATie) {
  // B (x = -3) and C (x = 3) close on A at the origin at speed 1 from both sides: both gaps of 1
  // close at t = 1 exactly.
  const ExactState s = state_of({moving_circle(1, {0, 0}, {0, 0}), moving_circle(1, {-3, 0}, {1, 0}),
                                 moving_circle(1, {3, 0}, {-1, 0})});
  const Judgement j = judge_one(s, event_at(s, 0, 1, 1, ContactKind::CircleCircle));
  EXPECT_EQ(j.verdict, Verdict::Tie);
  EXPECT_EQ(j.earliest.size(), 2u);
}

TEST(OracleVerdict, ConservationIsExact) {
  // Equal masses, head on, elastic: the velocities swap; kinetic energy and momentum are
  // unchanged exactly, and the positions do not move, so the potential (no field) is 0.
  ExactState s = half_state();
  ExactEvent e = event_at(s, 0, 1, 0.5, ContactKind::CircleCircle);
  e.va_after = ev(-1, 0);
  e.vb_after = ev(1, 0);
  Referee r(s);
  const ExactMotion a_after = motion({0.5, 0}, {-1, 0}, {}, 0.5), b_after = motion({2.5, 0}, {1, 0}, {}, 0.5);
  const Judgement j = r.judge(e, a_after, b_after);
  EXPECT_TRUE(j.conservation.both_moving);
  EXPECT_TRUE(j.conservation.elastic);
  EXPECT_TRUE(j.conservation.energy_change.is_zero());
  EXPECT_TRUE(j.conservation.momentum_change.x.is_zero());
  EXPECT_DOUBLE_EQ(j.conservation.kinetic_before, 1.0);
  // A second event where b leaves at 1 + 2^-40 instead of 1: energy grows by
  // ((1 + 2^-40)^2 - 1) / 2 = 2^-40 + 2^-81 and momentum by 2^-40, exactly.
  ExactState s2 = half_state();
  ExactEvent e2 = e;
  e2.vb_after = ev(1 + std::ldexp(1.0, -40), 0);
  Referee r2(s2);
  const Judgement j2 = r2.judge(e2, a_after, motion({2.5, 0}, {1 + std::ldexp(1.0, -40), 0}, {}, 0.5));
  EXPECT_EQ(j2.conservation.energy_change, Dyadic(mpz_class(1), -40) + Dyadic(mpz_class(1), -81));
  EXPECT_EQ(j2.conservation.momentum_change.x, Dyadic(mpz_class(1), -40));
}

TEST(OracleVerdict, PotentialEnergyUsesExactPositions) {
  // A body under gravity (0, -2) at height 1, at rest at t0 = 0; at t = 1 it is at height 0
  // exactly (1 - t^2) with speed 2. If the engine rebased it to height 2^-30 instead, the
  // potential after, m g h = 2 * 2^-30, is the whole energy change (velocities unchanged).
  ExactState s = state_of({moving_circle(0.25, {0, 1}, {0, 0}, 1, {0, -2}), moving_circle(0.25, {10, 0}, {0, 0})});
  ExactEvent e = event_at(s, 0, 1, 1, ContactKind::CircleCircle);
  e.va_before = e.va_after = ev(0, -2);
  Referee r(s);
  const Judgement j = r.judge(e, motion({0, std::ldexp(1.0, -30)}, {0, -2}, {0, -2}, 1), s.bodies[1].motion);
  EXPECT_EQ(j.conservation.energy_change, Dyadic(mpz_class(1), -29));
}

}  // namespace
}  // namespace pge::oracle
