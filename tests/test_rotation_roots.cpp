// The rotating contact solver's building blocks (issue 25, item 4): rigorous enclosures of sin
// and cos (pge/detail/interval.hpp) and the earliest downward zero of a contact function that mixes
// polynomials with sin and cos of turning angles (pge/detail/roots_rotating.hpp).
//
// Expected values are independent of the code under test: sin and cos, acos and Newton's method
// in Boost.Multiprecision's 50-digit cpp_bin_float (its own series, not interval.hpp's), and
// closed forms for the contact times of a square spinning in place.
#include "pge/detail/roots_rotating.hpp"

#include <gtest/gtest.h>

#include <boost/math/constants/constants.hpp>
#include <boost/multiprecision/cpp_bin_float.hpp>

#include <cfenv>
#include <cmath>
#include <cstdint>
#include <iomanip>
#include <limits>
#include <optional>
#include <random>
#include <sstream>
#include <algorithm>
#include <vector>

namespace {

using pge::RootStatus;
using pge::StartRule;
using pge::detail::Interval;
using pge::detail::WaveSum;
using High = boost::multiprecision::cpp_bin_float_50;

template <class B> bool encloses(const Interval<B>& iv, const High& x) {
  return High(iv.lo()) <= x && x <= High(iv.hi());
}

template <class B> double width_in_eps(const Interval<B>& iv) {
  return static_cast<double>(iv.width() / std::numeric_limits<B>::epsilon());
}

// Points over many magnitudes, up to 1e6 rad (about 160,000 turns), and points next to
// multiples of pi/2, where the reduction cancels most.
template <class B> std::vector<B> trig_points(int n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::vector<B> out;
  for (int i = 0; i < n; ++i) {
    const double mag = std::pow(10.0, std::uniform_real_distribution<double>(-3, 6)(rng));
    out.push_back(B(std::uniform_real_distribution<double>(-mag, mag)(rng)));
    const int k = std::uniform_int_distribution<int>(-100000, 100000)(rng);
    out.push_back(static_cast<B>(High(k) * boost::math::constants::half_pi<High>()));
  }
  return out;
}

template <class B> void check_point_enclosures(int n, double max_width_eps) {
  double worst = 0;
  for (const B& x : trig_points<B>(n, 7)) {
    const auto sc = pge::detail::sin_cos(Interval<B>(x));
    ASSERT_TRUE(encloses(sc.sin, boost::multiprecision::sin(High(x)))) << static_cast<double>(x);
    ASSERT_TRUE(encloses(sc.cos, boost::multiprecision::cos(High(x)))) << static_cast<double>(x);
    worst = std::max({worst, width_in_eps(sc.sin), width_in_eps(sc.cos)});
  }
  // Tight as well as right: a few ulps of 1 (the reduction's last part and the Taylor sums).
  EXPECT_LE(worst, max_width_eps);
}

// The outward steps every interval bound takes: long double's own bit stepping (interval.hpp)
// against libm's nextafterl, at random values over many binades and at every power of two with
// its neighbours (the carries into and borrows from the exponent, subnormals, the extremes).
TEST(RotationTrig, LongDoubleStepsAreLibmsNextafter) {
  using LD = long double;
  const LD inf = std::numeric_limits<LD>::infinity();
  long checked = 0;
  const auto check = [&](const LD x) {
    ++checked;
    ASSERT_EQ(pge::detail::interval_next_up(x), std::nextafter(x, inf)) << static_cast<double>(x);
    ASSERT_EQ(pge::detail::interval_next_down(x), std::nextafter(x, -inf)) << static_cast<double>(x);
  };
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int i = 0; i < 100000; ++i) check(std::ldexp(LD(u(rng)), static_cast<int>(rng() % 400) - 200) + LD(u(rng)) * 1e-30L);
  for (int e = std::numeric_limits<LD>::min_exponent - 70; e <= std::numeric_limits<LD>::max_exponent; ++e) {
    const LD p = std::ldexp(LD(1), e - 1);
    for (const LD x : {p, LD(-p)})
      for (const LD y : {x, std::nextafter(x, LD(0)), std::nextafter(x, inf), std::nextafter(x, -inf)}) check(y);
  }
  for (const LD x : {LD(0), std::numeric_limits<LD>::max(), -std::numeric_limits<LD>::max(),
                     std::numeric_limits<LD>::denorm_min(), std::numeric_limits<LD>::min()})
    check(x);
  EXPECT_GT(checked, 200000);
}

// x y (or x / y, x + y) rounded by the FPU in `mode` (fesetround sets SSE's and the x87's
// rounding alike): the independent reference for the emulated directed rounding below. The
// volatile operands keep the operation between the mode changes.
template <class B> B directed(const B x, const B y, const int mode, const char op) {
  const int old = std::fegetround();
  std::fesetround(mode);
  volatile B a = x, b = y;
  volatile B r = op == '/' ? a / b : op == '+' ? a + b : a * b;
  std::fesetround(old);
  return r;
}

// Emulated bounds [down, up] of x op y against the FPU's directed roundings: the same where the
// emulation is tight, at most one value further out elsewhere.
template <class B> void expect_directed(const B x, const B y, const char op, const B down, const B up, const bool tight) {
  const B fpu_down = directed(x, y, FE_DOWNWARD, op), fpu_up = directed(x, y, FE_UPWARD, op);
  std::ostringstream what;
  what << std::setprecision(21) << static_cast<long double>(x) << ' ' << op << ' ' << static_cast<long double>(y);
  if (tight) {
    ASSERT_EQ(down, fpu_down) << what.str();
    ASSERT_EQ(up, fpu_up) << what.str();
    return;
  }
  ASSERT_LE(down, fpu_down) << what.str();
  ASSERT_GE(down, pge::detail::interval_next_down(fpu_down)) << what.str();
  ASSERT_GE(up, fpu_up) << what.str();
  ASSERT_LE(up, pge::detail::interval_next_up(fpu_up)) << what.str();
}

// A random positive value m 2^e for the rounding tests below: e uniform in [lo_exp, hi_exp], the
// significand m in [1, 2) a short one (exact products and quotients) one time in four, else random
// bits down to double's precision and, for a wider B, 53 bits more.
template <class B> B random_binade_value(std::mt19937_64& rng, int lo_exp, int hi_exp) {
  B m = B(1) + B(rng() >> 11) * B(0x1p-53) + (std::numeric_limits<B>::digits > 53 ? B(rng() >> 11) * B(0x1p-106) : B(0));
  if (rng() % 4 == 0) m = B(1) + B(rng() % 1024) / B(1024);
  return std::ldexp(m, lo_exp + static_cast<int>(rng() % static_cast<std::uint64_t>(hi_exp - lo_exp + 1)));
}

// The same with a random sign.
template <class B> B random_signed_value(std::mt19937_64& rng, int lo_exp, int hi_exp) {
  const B v = random_binade_value<B>(rng, lo_exp, hi_exp);
  return rng() % 2 ? v : B(-v);
}

// Interval products round each bound outward in round-to-nearest arithmetic (interval.hpp's
// Rounding: the product's error sign from a fused multiply-add in double, from the product in
// double for float, from the significands' integer product for two normal x87 long doubles, from
// Dekker's splitting otherwise). Where the
// product is an ordinary number they must be exactly the FPU's directed roundings; near
// underflow and overflow, where they widen by a value instead, at most one value further out.
// Factors: random significands over many binades with both signs, small integers (exact
// products), products next to powers of two, subnormal and huge factors.
template <class B> void check_products_round_as_the_fpu_does(std::uint64_t seed) {
  using R = pge::detail::Rounding<B>;
  std::mt19937_64 rng(seed);
  const int max_exp = std::numeric_limits<B>::max_exponent;
  const auto random_value = [&](int lo_exp, int hi_exp) { return random_signed_value<B>(rng, lo_exp, hi_exp); };
  long ordinary = 0, exact = 0, edge = 0;
  const auto check = [&](const B x, const B y) {
    const B down = R::mul_down(x, y), up = R::mul_up(x, y);
    const bool tight = R::ordinary(x * y);
    ordinary += tight;
    edge += !tight;
    exact += tight && down == up;
    expect_directed(x, y, '*', down, up, tight);
  };
  for (int i = 0; i < 200000; ++i) check(random_value(-60, 60), random_value(-60, 60));
  for (int i = 0; i < 50000; ++i) check(random_value(-max_exp + 8, max_exp - 8), random_value(-max_exp / 2, max_exp / 2));
  for (int i = 0; i < 20000; ++i) {  // one huge factor (Dekker could not split it) times a small one
    const B huge = random_value(max_exp - 60, max_exp - 2), small = random_value(-max_exp + 60, std::max(-max_exp + 60, -200));
    check(huge, small);
  }
  for (int i = 0; i < 20000; ++i) {  // subnormal and smallest normal factors, products near underflow
    const B tiny = std::ldexp(random_value(0, 0), std::numeric_limits<B>::min_exponent - 1 - static_cast<int>(rng() % 40));
    check(tiny, random_value(0, 120));
  }
  for (int k = 1; k < 2000; ++k) {  // next to powers of two: (1 + k eps)(1 - k eps) and the like
    const B eps = std::numeric_limits<B>::epsilon();
    check(B(1) + B(k) * eps, B(1) - B(k) * eps / B(2));
    check(std::nextafter(B(2), B(0)), B(1) + B(k) * eps);
  }
  for (const B z : {B(0), B(-0.0)}) check(z, random_value(-10, 10));
  EXPECT_GT(ordinary, 250000);
  EXPECT_GT(exact, 10000);
  EXPECT_GT(edge, 1000);
}

TEST(RotationTrig, ProductsRoundOutwardAsTheFpuDoes) {
  check_products_round_as_the_fpu_does<float>(4);
  check_products_round_as_the_fpu_does<double>(5);
  check_products_round_as_the_fpu_does<long double>(6);
}

// Interval sums (Rounding::add_down, add_up: the rounded sum stepped by its TwoSum error's sign,
// in integers without a branch on it for float and double) round outward alike: exactly the
// FPU's directed roundings where the sum is an ordinary number, at most one value further out
// elsewhere. Addends: random significands over many binades with both signs, near
// cancellations, sums next to powers of two on either side (where a step crosses into the next
// binade), huge and tiny ones.
template <class B> void check_sums_round_as_the_fpu_does(std::uint64_t seed) {
  using R = pge::detail::Rounding<B>;
  std::mt19937_64 rng(seed);
  const int max_exp = std::numeric_limits<B>::max_exponent, min_exp = std::numeric_limits<B>::min_exponent;
  const B eps = std::numeric_limits<B>::epsilon();
  const auto random_value = [&](int lo_exp, int hi_exp) { return random_signed_value<B>(rng, lo_exp, hi_exp); };
  long ordinary = 0, exact = 0, inexact = 0;  // inexact: one bound stepped from the rounded sum
  const auto check = [&](const B x, const B y) {
    const B down = R::add_down(x, y), up = R::add_up(x, y);
    const bool tight = R::ordinary(x + y);
    ordinary += tight;
    exact += tight && down == up;
    inexact += tight && down != up;
    expect_directed(x, y, '+', down, up, tight);
  };
  for (int i = 0; i < 100000; ++i) check(random_value(-60, 60), random_value(-60, 60));
  for (int i = 0; i < 20000; ++i) check(random_value(-max_exp + 8, max_exp - 8), random_value(-max_exp + 8, max_exp - 8));
  for (int i = 0; i < 20000; ++i) {  // near cancellation: x and about -x
    const B x = random_value(-60, 60);
    check(x, B(-x) * (B(1) + B(static_cast<int>(rng() % 64) - 32) * eps));
  }
  for (int e = -80; e <= 80; ++e) {  // next to powers of two, from below and above, both signs
    const B p = std::ldexp(B(1), e);
    for (int k = 1; k < 64; ++k)
      for (const B sign : {B(1), B(-1)}) {
        const B small = std::ldexp(B(1) + B(k) / B(64), e - std::numeric_limits<B>::digits - static_cast<int>(rng() % 3));
        check(sign * p, sign * small);
        check(sign * p, B(-sign) * small);
        check(sign * std::nextafter(p, B(0)), sign * small);
        check(sign * std::nextafter(p, B(2) * p), B(-sign) * small);
      }
  }
  for (int i = 0; i < 10000; ++i) {  // near underflow and overflow, where the bounds widen by a value
    check(std::ldexp(random_value(0, 0), min_exp - 1 - static_cast<int>(rng() % 40)), random_value(min_exp - 20, min_exp + 60));
    check(random_value(max_exp - 4, max_exp - 1), random_value(max_exp - 60, max_exp - 1));
  }
  EXPECT_GT(ordinary, 150000);
  EXPECT_GT(exact, 5000);
  EXPECT_GT(inexact, 50000);
}

TEST(RotationTrig, SumsRoundOutwardAsTheFpuDoes) {
  check_sums_round_as_the_fpu_does<float>(1);
  check_sums_round_as_the_fpu_does<double>(2);
  check_sums_round_as_the_fpu_does<long double>(3);
}

// Quotients by a positive value (Rounding::div_down, div_up: the error's sign as that of r d - a)
// round outward the same way: exactly the FPU's directed roundings where the quotient and the
// dividend are ordinary numbers and Dekker can split the quotient and the divisor (float's
// quotients past about 5e30 it cannot), at most one value further out elsewhere. A dividend near
// underflow was wrong: with r ordinary, r d - a can be non-zero yet below the smallest
// subnormal, and the fused multiply-add (double) or Dekker's error terms rounded it to zero, so
// r came back as an exact bound. In double 2^-1026 / (2^-106 (1 + 2^-52)): r = 2^-920 (1 - 2^-52),
// r d - a = -2^-1130, while the true quotient is above r.
template <class B> void check_quotients_round_as_the_fpu_does(std::uint64_t seed) {
  using R = pge::detail::Rounding<B>;
  std::mt19937_64 rng(seed);
  constexpr int digits = std::numeric_limits<B>::digits, max_exp = std::numeric_limits<B>::max_exponent,
                min_exp = std::numeric_limits<B>::min_exponent;
  const B eps = std::numeric_limits<B>::epsilon();
  const auto value = [&](int lo_exp, int hi_exp) { return random_binade_value<B>(rng, lo_exp, hi_exp); };
  long ordinary = 0, edge = 0;
  const auto check = [&](const B a, const B d) {
    const bool tight = R::ordinary(a / d) && R::ordinary(a) && R::splittable(a / d, d);
    ordinary += tight;
    edge += !tight;
    expect_directed(a, d, '/', R::div_down(a, d), R::div_up(a, d), tight);
  };
  const auto sign = [&](const B v) { return rng() % 2 ? v : B(-v); };
  for (int i = 0; i < 100000; ++i) check(sign(value(-60, 60)), value(-60, 60));
  for (int i = 0; i < 20000; ++i) check(sign(value(-max_exp + 8, max_exp - 8)), value(-max_exp / 2, max_exp / 2));
  for (int i = 0; i < 20000; ++i)  // dividends near and below underflow, quotients mostly ordinary
    check(sign(std::ldexp(value(0, 0), min_exp - 1 - static_cast<int>(rng() % 60))), value(-2 * digits - 10, -digits));
  check(std::ldexp(B(1), min_exp - 5), std::ldexp(B(1) + eps, -2 * digits));
  for (const B z : {B(0), B(-0.0)}) check(z, value(-10, 10));
  EXPECT_GT(ordinary, 100000);
  EXPECT_GT(edge, 10000);
}

TEST(RotationTrig, QuotientsRoundOutwardAsTheFpuDoes) {
  check_quotients_round_as_the_fpu_does<float>(7);
  check_quotients_round_as_the_fpu_does<double>(8);
  check_quotients_round_as_the_fpu_does<long double>(9);
}

TEST(RotationTrig, PointEnclosuresHoldTheTrueValueAndAreTight) {
  check_point_enclosures<double>(20000, 6);
  check_point_enclosures<long double>(5000, 6);
  check_point_enclosures<pge::Quad>(300, 6);
}

TEST(RotationTrig, FloatReducesWithinItsRangeAndGivesUpPastIt) {
  // float's reduction is exact for |x| below 2^10; past that the enclosures are [-1, 1].
  const auto near = pge::detail::sin_cos(Interval<float>(1000.0f));
  EXPECT_TRUE(encloses(near.sin, boost::multiprecision::sin(High(1000.0f))));
  EXPECT_LE(width_in_eps(near.sin), 6);
  const auto far = pge::detail::sin_cos(Interval<float>(1.0e5f));
  EXPECT_EQ(far.sin.lo(), -1.0f);
  EXPECT_EQ(far.sin.hi(), 1.0f);
}

TEST(RotationTrig, IntervalEnclosuresHoldTheRangeIncludingExtrema) {
  std::mt19937_64 rng(11);
  for (int i = 0; i < 20000; ++i) {
    const double a = std::uniform_real_distribution<double>(-50, 50)(rng);
    const double w = std::pow(10.0, std::uniform_real_distribution<double>(-12, 0.8)(rng));
    const Interval<double> x(a, a + w);
    const auto sc = pge::detail::sin_cos(x);
    // The true range from dense samples and the extrema inside (the samples' hull is inside the
    // range, so each must be enclosed; the extremum values are exact).
    for (int k = 0; k <= 16; ++k) {
      const High t = High(a) + (High(a + w) - High(a)) * k / 16;
      ASSERT_TRUE(encloses(sc.sin, boost::multiprecision::sin(t))) << a << " + " << w;
      ASSERT_TRUE(encloses(sc.cos, boost::multiprecision::cos(t))) << a << " + " << w;
    }
    const High half_pi = boost::math::constants::half_pi<High>();
    const long long k_lo = static_cast<long long>(boost::multiprecision::ceil(High(a) / half_pi));
    const long long k_hi = static_cast<long long>(boost::multiprecision::floor(High(a + w) / half_pi));
    for (long long k = k_lo; k <= k_hi; ++k) {
      const int q = static_cast<int>(((k % 4) + 4) % 4);
      if (q == 0) {
        ASSERT_EQ(sc.cos.hi(), 1.0);
      }
      if (q == 1) {
        ASSERT_EQ(sc.sin.hi(), 1.0);
      }
      if (q == 2) {
        ASSERT_EQ(sc.cos.lo(), -1.0);
      }
      if (q == 3) {
        ASSERT_EQ(sc.sin.lo(), -1.0);
      }
    }
  }
}

// The memo of sin_cos (interval.hpp: SinCosMemo) answers exactly what the computation gives, bit
// for bit, whatever was asked before: arguments asked three times over in shuffled orders (so that
// slots are taken and retaken), among them points and ranges, +0 and -0, and long doubles that
// differ only past their first 8 bytes (x and 2x share the x87 significand; the sign and
// exponent are bytes 8 and 9), which a key of the head alone would take for one another.
template <class B> void check_memo_is_exact() {
  std::mt19937_64 rng(5);
  std::vector<Interval<B>> args;
  for (const B& x : trig_points<B>(400, 13)) {
    args.emplace_back(x);
    args.emplace_back(B(2) * x);
    args.emplace_back(-x);
    args.emplace_back(x, x + B(0.25));
  }
  args.emplace_back(B(0));
  args.emplace_back(-B(0));
  const auto same = [](const Interval<B>& u, const Interval<B>& v) {
    return u.lo() == v.lo() && u.hi() == v.hi() && std::signbit(u.lo()) == std::signbit(v.lo()) &&
           std::signbit(u.hi()) == std::signbit(v.hi());
  };
  for (int round = 0; round < 3; ++round) {
    std::shuffle(args.begin(), args.end(), rng);
    for (const Interval<B>& x : args) {
      const auto memo = pge::detail::sin_cos(x);
      const auto computed = pge::detail::sin_cos_computed(x);
      ASSERT_TRUE(same(memo.sin, computed.sin) && same(memo.cos, computed.cos))
          << static_cast<double>(x.lo()) << " " << static_cast<double>(x.hi()) << " round " << round;
    }
  }
}

TEST(RotationTrig, MemoAnswersExactlyWhatItComputes) {
  static_assert(pge::detail::SinCosMemo<float>::enabled && pge::detail::SinCosMemo<double>::enabled);
  check_memo_is_exact<float>();
  check_memo_is_exact<double>();
  check_memo_is_exact<long double>();
}

// --- contact functions --------------------------------------------------------------------------

using I = Interval<double>;

// The vertex (h, -h) of a square centred at c_x spinning at w from angle 0, against the fixed
// wall x = d (d > c_x + h, the square clear of it): the gap d - x(t), x(t) = c_x + h cos wt +
// h sin wt. The coefficients are built as the engine would build them from the stored values,
// with interval arithmetic: d - c_x.
WaveSum<double> square_to_wall(double c_x, double h, double w, double d) {
  WaveSum<double> f;
  f.base.c[0] = I(d) - I(c_x);
  f.wave_count = 1;
  f.waves[0].omega = I(w);
  f.waves[0].phase = I(0);
  f.waves[0].cos_part.c[0] = I(-h);
  f.waves[0].sin_part.c[0] = I(-h);
  return f;
}

// x(t) = h sqrt(2) cos(wt - pi/4) reaches d first at wt = pi/4 - acos(d' / (h sqrt 2)), with
// d' = d - c_x exactly (the doubles as given).
High square_to_wall_time(double c_x, double h, double w, double d) {
  const High pi = boost::math::constants::pi<High>();
  const High reach = (High(d) - High(c_x)) / (High(h) * boost::multiprecision::sqrt(High(2)));
  return (pi / 4 - boost::multiprecision::acos(reach)) / High(w);
}

double ulps_off(double t, const High& exact) {
  const double ulp = std::nextafter(t, INFINITY) - t;
  return static_cast<double>(boost::multiprecision::abs(High(t) - exact) / High(ulp));
}

TEST(RotationRoots, SquareSpinningInPlaceReachesAWallAtTheAcosTime) {
  std::mt19937_64 rng(3);
  double worst = 0;
  for (int i = 0; i < 500; ++i) {
    const double h = std::uniform_real_distribution<double>(0.1, 2)(rng);
    const double w = std::pow(10.0, std::uniform_real_distribution<double>(-2, 3)(rng));
    // The wall between the square's side (h) and its corner circle (h sqrt 2).
    const double d = h * std::uniform_real_distribution<double>(1.0001, 1.4141)(rng);
    for (const double c_x : {0.0, 1.0e6}) {
      const double wall = c_x + d;
      const auto r = pge::detail::earliest_wave_root(square_to_wall(c_x, h, w, wall), 0.0, 10.0 / w,
                                                     StartRule::CrossingsOnly, 100000);
      ASSERT_EQ(r.status, RootStatus::Root) << h << " " << w << " " << d;
      EXPECT_FALSE(r.tangent);
      worst = std::max(worst, ulps_off(r.t, square_to_wall_time(c_x, h, w, wall)));
    }
  }
  // Far from the origin the gap d - c_x loses nothing (the wall's position is a double near
  // 1e6: its ulp, 1e-10, is part of the stored geometry and of the closed form alike).
  EXPECT_LE(worst, 4);
}

// A rod of half-length L spinning at W about a centre moving towards the wall x = L + G at v:
// f(t) = (L + G) - v t - L cos(W t + pi) = (L + G) - v t + L cos(W t), closest each half turn
// plus a whole one, t_k = (k + 1/2) T. v closes G over 1000 turns: the approaches k = 0..999 miss
// by G (1 - (k + 1/2) / 1000) in (5e-16, 1e-12], the 1001st hits.
struct NearMisses {
  double L = 0.01, G = 1e-12, W = 2 * 3.141592653589793;
  double T = 2 * 3.141592653589793 / W;
  double D = L + G;
  double v = G / (1000 * T);

  WaveSum<double> function() const {
    WaveSum<double> f;
    f.base.degree = 1;
    f.base.c[0] = I(D);
    f.base.c[1] = -I(v);
    f.wave_count = 1;
    f.waves[0].omega = I(W);
    f.waves[0].phase = I(0);
    f.waves[0].cos_part.c[0] = I(L);
    return f;
  }
  // Newton's method in 50 digits from the approach's falling side.
  High contact() const {
    auto f = [&](const High& t) { return High(D) - High(v) * t + High(L) * boost::multiprecision::cos(High(W) * t); };
    auto df = [&](const High& t) { return -High(v) - High(L) * High(W) * boost::multiprecision::sin(High(W) * t); };
    const High pi = boost::math::constants::pi<High>();
    const High t_min = (2 * 1000 + 1) * pi / High(W);  // where cos(W t) = -1 on approach 1000
    High t = t_min - High(1e-6);
    for (int i = 0; i < 100; ++i) t -= f(t) / df(t);
    EXPECT_LT(t, t_min);
    EXPECT_LT(boost::multiprecision::abs(f(t)), High(1e-40));
    return t;
  }
};

TEST(RotationRoots, ThousandNearMissesThenTheHitWithBoundedWork) {
  const NearMisses s;
  const auto r = pge::detail::earliest_wave_root(s.function(), 0.0, 2000.0, StartRule::CrossingsOnly,
                                                 1000000);
  ASSERT_EQ(r.status, RootStatus::Root);
  EXPECT_LE(ulps_off(r.t, s.contact()), 4);
  // Work: a bounded number of boxes per turn (measured 38 boxes in all).
  EXPECT_LE(r.boxes, 100u * 1001u);
}

TEST(RotationRoots, ABudgetStopsTheSearchWithProgressAndResumingFindsTheSameRoot) {
  const NearMisses s;
  const WaveSum<double> f = s.function();
  const auto whole = pge::detail::earliest_wave_root(f, 0.0, 2000.0, StartRule::CrossingsOnly, 1000000);
  // A caller with a small budget: it resumes from where each call stopped, and grows the budget
  // when a call could not resolve any part of its interval (t == from).
  double from = 0;
  std::uint64_t budget = 2;
  int stopped = 0;
  for (int calls = 0;; ++calls) {
    ASSERT_LT(calls, 1000);
    const auto r = pge::detail::earliest_wave_root(f, from, 2000.0, StartRule::CrossingsOnly, budget);
    if (r.status == RootStatus::Root) {
      EXPECT_EQ(r.t, whole.t);
      break;
    }
    ASSERT_EQ(r.status, RootStatus::Undecided);
    ++stopped;
    ASSERT_GE(r.t, from);
    ASSERT_LE(r.t, whole.t);  // no crossing before t: the root is not passed
    if (r.t == from) budget *= 2;
    from = r.t;
  }
  EXPECT_GE(stopped, 2);
}

TEST(RotationRoots, ATangentialGrazeIsReportedAtTheMinimumAsATangency) {
  // f(t) = L - L cos(W t): zero at t = 0 and again at 2 pi / W, a minimum each time (a corner
  // touching a wall tangentially, never crossing it).
  const double L = 0.5, W = 3.0;
  WaveSum<double> f;
  f.base.c[0] = I(L);
  f.wave_count = 1;
  f.waves[0].omega = I(W);
  f.waves[0].cos_part.c[0] = I(-L);
  const auto r = pge::detail::earliest_wave_root(f, 0.25, 10.0, StartRule::CrossingsOnly, 100000);
  ASSERT_EQ(r.status, RootStatus::Root);
  EXPECT_TRUE(r.tangent);
  const High exact = 2 * boost::math::constants::pi<High>() / High(W);
  // At the minimum to the precision f' can be told: f'' = L W^2, so within |f'| rounding /
  // f'' of it, a few ulps.
  EXPECT_LE(ulps_off(r.t, exact), 8);
}

TEST(RotationRoots, ANearMissJustAboveRoundingIsNoContact) {
  // The same with the minimum lifted by 1e-13 (far above f's rounding, about 1e-16): no root.
  const double L = 0.5, W = 3.0;
  WaveSum<double> f;
  f.base.c[0] = I(L + 1e-13);
  f.wave_count = 1;
  f.waves[0].omega = I(W);
  f.waves[0].cos_part.c[0] = I(-L);
  const auto r = pge::detail::earliest_wave_root(f, 0.25, 10.0, StartRule::CrossingsOnly, 100000);
  EXPECT_EQ(r.status, RootStatus::None);
}

TEST(RotationRoots, OverlapAtTheStartCollidesOnlyUnderTheOverlapRule) {
  // Negative at 0 and falling: f(t) = -0.01 - t + 0.1 sin(t) (f' = -1 + 0.1 cos t < 0).
  WaveSum<double> f;
  f.base.degree = 1;
  f.base.c[0] = I(-0.01);
  f.base.c[1] = I(-1);
  f.wave_count = 1;
  f.waves[0].omega = I(1);
  f.waves[0].sin_part.c[0] = I(0.1);
  const auto overlap = pge::detail::earliest_wave_root(f, 0.0, 5.0, StartRule::OverlapCollides, 1000);
  ASSERT_EQ(overlap.status, RootStatus::Root);
  EXPECT_TRUE(overlap.at_start_overlap);
  EXPECT_EQ(overlap.t, 0.0);
  const auto crossings = pge::detail::earliest_wave_root(f, 0.0, 5.0, StartRule::CrossingsOnly, 1000);
  EXPECT_EQ(crossings.status, RootStatus::None);
}

// Random contact functions of the engine's shape (a quadratic path against a spinning feature,
// two waves, the second at a difference of rates), against a reference that is independent of
// interval arithmetic: samples every 1/64 of the fastest half-turn in 50 digits, each local
// minimum between samples located by bisection on f' and its value checked, and Newton polishing
// the first downward crossing. Functions whose reference comes within 1e-9 of a tangency (the
// minimum's value) are skipped: the two methods need not agree on a graze's side.
TEST(RotationRoots, RandomFunctionsAgreeWithAHighPrecisionScan) {
  std::mt19937_64 rng(5);
  auto uni = [&](double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); };
  int compared = 0, roots = 0;
  for (int n = 0; n < 300; ++n) {
    WaveSum<double> f;
    f.base.degree = 2;
    f.base.c[0] = I(uni(0.05, 1.0));
    f.base.c[1] = I(uni(-1, 0.2));
    f.base.c[2] = I(uni(-0.5, 0.1));
    f.wave_count = 2;
    const double w0 = uni(0.5, 20), w1 = uni(-20, 20);
    f.waves[0].omega = I(w0);
    f.waves[0].phase = I(uni(-3, 3));
    f.waves[0].cos_part.c[0] = I(uni(-0.3, 0.3));
    f.waves[0].sin_part.degree = 1;
    f.waves[0].sin_part.c[0] = I(uni(-0.3, 0.3));
    f.waves[0].sin_part.c[1] = I(uni(-0.05, 0.05));
    f.waves[1].omega = I(w1);
    f.waves[1].phase = I(uni(-3, 3));
    f.waves[1].cos_part.c[0] = I(uni(-0.1, 0.1));
    const double hi = 4.0;

    auto value = [&](const High& t, int order) {
      // f^(order)(t) for order 0, 1: direct formulas in 50 digits.
      High v = 0;
      const auto& b = f.base;
      if (order == 0) v = High(b.c[0].lo()) + High(b.c[1].lo()) * t + High(b.c[2].lo()) * t * t;
      else v = High(b.c[1].lo()) + 2 * High(b.c[2].lo()) * t;
      for (int j = 0; j < 2; ++j) {
        const auto& w = f.waves[static_cast<std::size_t>(j)];
        const High om = High(w.omega.lo());
        const High arg = om * t + High(w.phase.lo());
        const High c = High(w.cos_part.c[0].lo());
        const High s = High(w.sin_part.c[0].lo()) + (w.sin_part.degree > 0 ? High(w.sin_part.c[1].lo()) * t : High(0));
        const High ds = w.sin_part.degree > 0 ? High(w.sin_part.c[1].lo()) : High(0);
        if (order == 0) v += c * cos(arg) + s * sin(arg);
        else v += -c * om * sin(arg) + ds * sin(arg) + s * om * cos(arg);
      }
      return v;
    };
    const double fastest = std::max(std::abs(w0), std::abs(w1));
    const int steps = static_cast<int>(hi * fastest / 3.14159 * 64) + 64;
    std::optional<High> expected;
    bool doubtful = false;
    High prev_t = 0, prev_f = value(prev_t, 0), prev_d = value(prev_t, 1);
    if (prev_f <= 0) continue;
    for (int k = 1; k <= steps && !expected && !doubtful; ++k) {
      const High t = High(hi) * k / steps;
      const High ft = value(t, 0), dt = value(t, 1);
      if (ft < 0) {  // a crossing in (prev_t, t): polish by bisection (f changes sign once here)
        High a = prev_t, b = t;
        for (int i = 0; i < 200; ++i) {
          const High m = (a + b) / 2;
          (value(m, 0) > 0 ? a : b) = m;
        }
        expected = a;
      } else if (prev_d < 0 && dt > 0) {  // a minimum in between: its value
        High a = prev_t, b = t;
        for (int i = 0; i < 200; ++i) {
          const High m = (a + b) / 2;
          (value(m, 1) < 0 ? a : b) = m;
        }
        const High fm = value(a, 0);
        if (boost::multiprecision::abs(fm) < High(1e-9)) doubtful = true;
        else if (fm < 0) {
          High lo = prev_t, hi2 = a;
          for (int i = 0; i < 200; ++i) {
            const High m = (lo + hi2) / 2;
            (value(m, 0) > 0 ? lo : hi2) = m;
          }
          expected = lo;
        }
      }
      prev_t = t;
      prev_f = ft;
      prev_d = dt;
    }
    if (doubtful) continue;
    const auto r = pge::detail::earliest_wave_root(f, 0.0, hi, StartRule::CrossingsOnly, 1000000);
    ++compared;
    if (!expected) {
      EXPECT_EQ(r.status, RootStatus::None) << "function " << n << " t " << r.t;
      continue;
    }
    ++roots;
    ASSERT_EQ(r.status, RootStatus::Root) << "function " << n;
    EXPECT_FALSE(r.tangent) << n;
    EXPECT_LE(ulps_off(r.t, *expected), 8) << "function " << n << " got " << r.t << " expected "
                                            << expected->str(20);
  }
  EXPECT_GE(compared, 200);
  EXPECT_GE(roots, 50);
}

// A search resumed past a tangency or a crossing at t steps 1, 2, 4, ... ulps of t, but never
// less than the smallest double: at t = 0 Quad's ulp is 2^-16494 and doubling from it to the end
// of a window took about 16,500 evaluations of the function in software arithmetic per call (a
// box lying still on a floor, whose gap is 0 throughout: 258 s to build the world in quad; CTest
// cli_rotation_quad_resting runs it). float and double step exactly as before.
TEST(RotationRoots, StepsPastAResolvedRootStartAtAnUlpButNotBelowTheSmallestDouble) {
  using pge::Quad;
  using pge::detail::first_step_past;
  const double smallest = std::numeric_limits<double>::denorm_min();
  EXPECT_EQ(first_step_past(0.0), smallest);
  EXPECT_EQ(first_step_past(1.0), std::nextafter(1.0, 2.0) - 1.0);
  EXPECT_EQ(first_step_past(0.0f), std::numeric_limits<float>::denorm_min());
  EXPECT_EQ(first_step_past(Quad(0)), Quad(smallest));
  EXPECT_EQ(first_step_past(Quad(1)), ldexp(Quad(1), -112));  // Quad's ulp at 1: 113-bit significand
  EXPECT_EQ(first_step_past(0.0L), static_cast<long double>(smallest));
  // The function 0 throughout (a gap that neither opens nor closes): past the tangency at 0 is the
  // end of the window, as before.
  const WaveSum<Quad> zero;
  EXPECT_EQ(pge::detail::past_tangency(zero, Quad(0), Quad(1)), std::optional<Quad>(Quad(1)));
}

}  // namespace
