// The three root solvers on hand-derived cases, for every scalar: the semantics of a downward
// root (roots.hpp), the visitor's order, the certified solver's exact fallback, and the world
// running with each solver. Every expected value is derived in the comment beside it.
#include "pge/roots.hpp"
#include "pge/scalar.hpp"
#include "pge/world.hpp"

#include <boost/math/special_functions/next.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <type_traits>
#include <utility>
#include <vector>

namespace pge {
namespace {

template <class T> Poly<T> poly(std::vector<double> c) {
  Poly<T> p;
  p.degree = static_cast<int>(c.size()) - 1;
  for (std::size_t k = 0; k < c.size(); ++k) p.c[k] = T(c[k]);
  return p;
}

template <class T>
std::vector<std::pair<T, bool>> all_roots(SolverKind s, const Poly<T>& p, double lo, double hi,
                                          StartRule rule = StartRule::OverlapCollides) {
  std::vector<std::pair<T, bool>> out;
  visit_downward_roots(s, p, T(lo), T(hi), rule, [&](const T& t, bool overlap) {
    out.emplace_back(t, overlap);
    return false;
  });
  return out;
}

template <class T> class Solvers : public ::testing::Test {};
using Scalars = ::testing::Types<float, double, long double, Quad>;
TYPED_TEST_SUITE(Solvers, Scalars);

constexpr SolverKind kAll[] = {SolverKind::Fast, SolverKind::Robust, SolverKind::Certified};
constexpr SolverKind kSound[] = {SolverKind::Robust, SolverKind::Certified};

// (t-1)(t-2) = 2 - 3t + t^2: positive at 0, down through 1 (p'(1) = -1), up through 2.
TYPED_TEST(Solvers, SimpleCrossing) {
  using T = TypeParam;
  for (SolverKind s : kAll) {
    const RootOutcome<T> r = earliest_downward_root(s, poly<T>({2, -3, 1}), T(0), T(5));
    ASSERT_EQ(r.status, RootStatus::Root) << solver_name(s);
    EXPECT_EQ(r.t, T(1)) << solver_name(s);
    EXPECT_FALSE(r.at_start_overlap);
  }
}

// 1 - t^4 (declared quartic, middle coefficients zero): the only positive root is 1.
TYPED_TEST(Solvers, ZeroMiddleCoefficients) {
  using T = TypeParam;
  for (SolverKind s : kAll) EXPECT_EQ(earliest_downward_root(s, poly<T>({1, 0, 0, 0, -1}), T(0), T(2)).t, T(1)) << solver_name(s);
}

// (t-1)^2: touches zero at 1 and comes back: a graze, no root. (t-1)^2 (t-3)(t-4): the graze at 1
// is skipped, the crossing at 3 (p goes from + to -) counts.
TYPED_TEST(Solvers, GrazeIsNotARoot) {
  using T = TypeParam;
  for (SolverKind s : kSound) {
    EXPECT_EQ(earliest_downward_root(s, poly<T>({1, -2, 1}), T(0), T(3)).status, RootStatus::None) << solver_name(s);
    const RootOutcome<T> r = earliest_downward_root(s, poly<T>({12, -31, 27, -9, 1}), T(0), T(5));
    ASSERT_EQ(r.status, RootStatus::Root) << solver_name(s);
    EXPECT_EQ(r.t, T(3)) << solver_name(s);
  }
}

// (t-1)(t-2) from 1.25: p(1.25) = -0.1875 < 0, p'(1.25) = -0.5: overlapping and approaching, so
// lo itself with the overlap flag; a one-sided function (CrossingsOnly) has no root (the next
// crossing, at 2, goes up). From 1.5 (p' = 0, p'' > 0): receding, no root.
TYPED_TEST(Solvers, OverlapRule) {
  using T = TypeParam;
  for (SolverKind s : kAll) {
    const RootOutcome<T> r = earliest_downward_root(s, poly<T>({2, -3, 1}), T(1.25), T(3));
    ASSERT_EQ(r.status, RootStatus::Root) << solver_name(s);
    EXPECT_EQ(r.t, T(1.25));
    EXPECT_TRUE(r.at_start_overlap);
    EXPECT_EQ(earliest_downward_root(s, poly<T>({2, -3, 1}), T(1.25), T(3), StartRule::CrossingsOnly).status,
              RootStatus::None) << solver_name(s);
  }
  for (SolverKind s : kSound)
    EXPECT_EQ(earliest_downward_root(s, poly<T>({2, -3, 1}), T(1.5), T(3)).status, RootStatus::None) << solver_name(s);
}

// The turning-overlap rule. -(t-1)^2 (t-3)(t-5) = -15 + 38t - 32t^2 + 10t^3 - t^4 (expanded by
// hand; every coefficient exact in every scalar): p(0) = -15 < 0, p'(0) = 38 > 0, and p' =
// -(t-1)(4t^2 - 26t + 38) vanishes first at t = 1 (4 - 26 + 38 = 16 > 0, so p' changes sign
// there), where p(1) = 0: the pair touches at its maximum, the rule collides at 1 without the
// overlap flag. With c0 = -15 - e (e = 2^-49, one ulp of 15 in double) p' is the same and
// p(1) = -e < 0: a turn at 1 with the overlap flag. With c0 = -15 + e the maximum is +e > 0: the
// pair separates; with h = t - 1, p = -8 h^2 + 6 h^3 - h^4 + e is 6 2^-78 - 2^-104 > 0 at
// h0 = 2^-26 and falls there with slope -16 h0 + 18 h0^2 (about -2^-22), so it crosses down at
// h0 + d with d about 6 2^-78 / 2^-22 = 1.5 2^-54: in (1 + 2^-26, 1 + 2^-26 + 2^-52), nearest
// double 1 + 2^-26 (d is below half an ulp of 1). Certified's times are exact; robust's within
// a few ulps (kRobustUlps) where the root is well conditioned. Float has no 15 + 2^-49; the touching case holds there too.
constexpr double kRobustUlps = 16;

template <class T> double ulps_between(const T& a, const T& b) {
  using std::abs;
  return abs(static_cast<double>(boost::math::float_distance(a, b)));
}

TYPED_TEST(Solvers, TurningOverlapRule) {
  using T = TypeParam;
  const double e = std::ldexp(1.0, -49);
  const auto expect_time = [](SolverKind s, const T& got, const T& want) {
    if (s == SolverKind::Certified) EXPECT_EQ(got, want);
    else EXPECT_LE(ulps_between(got, want), kRobustUlps) << solver_name(s);
  };
  for (SolverKind s : kSound) {
    const RootOutcome<T> touch = earliest_downward_root(s, poly<T>({-15, 38, -32, 10, -1}), T(0), T(2));
    ASSERT_EQ(touch.status, RootStatus::Root) << solver_name(s);
    expect_time(s, touch.t, T(1));
    EXPECT_FALSE(touch.at_start_overlap) << solver_name(s);
  }
  if constexpr (std::numeric_limits<T>::digits >= 53) {
    const T h0 = T(std::ldexp(1.0, -26));
    for (SolverKind s : kSound) {
      const RootOutcome<T> turn = earliest_downward_root(s, poly<T>({-15 - e, 38, -32, 10, -1}), T(0), T(2));
      ASSERT_EQ(turn.status, RootStatus::Root) << solver_name(s);
      expect_time(s, turn.t, T(1));
      EXPECT_TRUE(turn.at_start_overlap) << solver_name(s);
      const RootOutcome<T> apart = earliest_downward_root(s, poly<T>({-15 + e, 38, -32, 10, -1}), T(0), T(2));
      ASSERT_EQ(apart.status, RootStatus::Root) << solver_name(s);
      EXPECT_FALSE(apart.at_start_overlap) << solver_name(s);
      if (s == SolverKind::Certified) {
        EXPECT_GE(apart.t, T(1) + h0);
        EXPECT_LE(apart.t, T(1) + h0 + T(std::ldexp(1.0, -52)));
        if constexpr (std::is_same_v<T, double>) {
          EXPECT_EQ(apart.t, 1.0 + std::ldexp(1.0, -26));
        }
      } else {
        // A root this close to a double root is ill-conditioned (rounding of p moves it by
        // about u 15 / 2^-22); robust must find this crossing, not the turn at 1.
        EXPECT_LT(detail::abs_of(apart.t - (T(1) + h0)), h0 / T(4)) << solver_name(s);
      }
    }
  }
}

// The case that found the rule deciding in floating point: p = -(t-1)(t-1-2^-30)(t-3)(t-5),
// coefficients expanded exactly in double (as hex below). p(0) < 0 and rising; with h = t - 1,
// p = -h (h - 2^-30)(h - 2)(h - 4) is 2^-62 (2 - 2^-31)(4 - 2^-31), about 8 2^-62 > 0, at
// h = 2^-31 between its first two roots: the pair separates for an instant before its maximum,
// so the earliest downward root is the simple root 1 + 2^-30, exact in double and wider
// scalars. fast may still take the turn (the baseline).
TYPED_TEST(Solvers, TurningOverlapNearDoubleRoot) {
  using T = TypeParam;
  if constexpr (std::numeric_limits<T>::digits >= 53) {
    const Poly<T> p = poly<T>({-0x1.e000000780000p+3, 0x1.30000002e0000p+5, -0x1.0000000120000p+5,
                               0x1.4000000080000p+3, -0x1.0000000000000p+0});
    const T root = T(1) + T(std::ldexp(1.0, -30));
    for (SolverKind s : kSound) {
      const RootOutcome<T> r = earliest_downward_root(s, p, T(0), T(10));
      ASSERT_EQ(r.status, RootStatus::Root) << solver_name(s);
      EXPECT_FALSE(r.at_start_overlap) << solver_name(s);
      if (s == SolverKind::Certified || std::is_same_v<T, double>) {
        EXPECT_EQ(r.t, root) << solver_name(s);
      } else {  // robust in wider scalars: the root, not the turn 2^-31 before it (ill-conditioned)
        EXPECT_LT(detail::abs_of(r.t - root), T(std::ldexp(1.0, -33))) << solver_name(s);
      }
    }
  }
}

// -(t-1)(t-2)(t-3) = 6 - 11t + 6t^2 - t^3: p(0) = 6, down at 1, up at 2, down at 3. The visitor
// sees 1 then 3; returning true at the first stops the walk.
TYPED_TEST(Solvers, VisitsEveryDownwardRootInOrder) {
  using T = TypeParam;
  for (SolverKind s : kSound) {
    const auto roots = all_roots<T>(s, poly<T>({6, -11, 6, -1}), 0, 4);
    ASSERT_EQ(roots.size(), 2u) << solver_name(s);
    EXPECT_EQ(roots[0].first, T(1));
    EXPECT_EQ(roots[1].first, T(3));
    int calls = 0;
    EXPECT_TRUE(visit_downward_roots(s, poly<T>({6, -11, 6, -1}), T(0), T(4), StartRule::OverlapCollides, [&](const T&, bool) {
      ++calls;
      return true;
    }));
    EXPECT_EQ(calls, 1);
  }
}

// Ends and degenerate input: a root exactly at hi counts (p arrives from above); lo == hi is a
// root only by the start rule; lo > hi and constants have none.
TYPED_TEST(Solvers, EndsAndDegenerateInput) {
  using T = TypeParam;
  for (SolverKind s : kSound) {
    EXPECT_EQ(earliest_downward_root(s, poly<T>({2, -3, 1}), T(0), T(1)).t, T(1)) << solver_name(s);
    const RootOutcome<T> at = earliest_downward_root(s, poly<T>({2, -3, 1}), T(1), T(1));
    EXPECT_EQ(at.status, RootStatus::Root) << solver_name(s);  // p(1) = 0, p'(1) = -1
    EXPECT_EQ(earliest_downward_root(s, poly<T>({2, -3, 1}), T(2), T(1)).status, RootStatus::None);
    EXPECT_EQ(earliest_downward_root(s, poly<T>({-1, 0, 0}), T(0), T(1)).status, RootStatus::None);
    EXPECT_EQ(earliest_downward_root(s, poly<T>({0, 0, 0, 0, 0}), T(0), T(1)).status, RootStatus::None);
    // 0 * t^4 + t^2 - 3t + 2 declared as a quartic: leading zeros are trimmed.
    EXPECT_EQ(earliest_downward_root(s, poly<T>({2, -3, 1, 0, 0}), T(0), T(5)).t, T(1)) << solver_name(s);
  }
}

// t^2 - 2t + (1 + 2^-52): complex roots 1 +- 2^-26 i, a near touch: no root. t^2 - 2t + (1 - 2^-52):
// real roots 1 -+ 2^-26 exactly; the earliest is 1 - 2^-26 (representable in every scalar but float,
// where the coefficients round to (t-1)^2, a graze).
TEST(SolversDouble, NearDoubleRoots) {
  const double u = std::ldexp(1.0, -52);
  for (SolverKind s : kSound) {
    EXPECT_EQ(earliest_downward_root(s, poly<double>({1 + u, -2, 1}), 0.0, 2.0).status, RootStatus::None) << solver_name(s);
    const RootOutcome<double> r = earliest_downward_root(s, poly<double>({1 - u, -2, 1}), 0.0, 2.0);
    ASSERT_EQ(r.status, RootStatus::Root) << solver_name(s);
    EXPECT_EQ(r.t, 1 - std::ldexp(1.0, -26)) << solver_name(s);
  }
}

// Certified on t^2 - 2t + (1 - 2^-53): roots 1 -+ 2^-26.5, which no double holds; the nearest
// double to 1 - 2^-26.5 = 1 - 1.0536712127723509e-08 is found by comparing with the midpoints
// around the long double value (64-bit significand: 11 bits to spare).
TEST(SolversDouble, CertifiedRoundsCorrectly) {
  const double c0 = 1 - std::ldexp(1.0, -53);
  const long double exact = 1.0L - std::sqrt(std::ldexp(1.0L, -53));
  const double nearest = static_cast<double>(exact);  // round to nearest, 11 guard bits
  const RootOutcome<double> r = earliest_downward_root(SolverKind::Certified, poly<double>({c0, -2, 1}), 0.0, 2.0);
  ASSERT_EQ(r.status, RootStatus::Root);
  EXPECT_EQ(r.t, nearest);
}

// The exact fallback on its own: Sturm isolation of the square-free part and exact rounding.
// (t-1)^2 (t-3)(t-4): graze at 1 skipped, 3 counted. 3 t^2 - 1 (root 1/sqrt(3)) on [-1, 1]:
// p(-1) = 2 > 0, down through -1/sqrt(3) (nearest double: -0.57735026918962573), up through
// 1/sqrt(3).
TEST(SolversExact, SturmAndRounding) {
  using detail::exact::ExactSolver;
  std::vector<double> seen;
  auto collect = [&](const double& t, bool) {
    seen.push_back(t);
    return false;
  };
  ExactSolver<double>(poly<double>({12, -31, 27, -9, 1}), 0.0, 5.0).visit(StartRule::OverlapCollides, 0, collect);
  EXPECT_EQ(seen, std::vector<double>({3.0}));
  seen.clear();
  ExactSolver<double>(poly<double>({-1, 0, 3}), -1.0, 1.0).visit(StartRule::OverlapCollides, 0, collect);
  EXPECT_EQ(seen, std::vector<double>({-0.57735026918962573}));
  // Skipping: -(t-1)(t-2)(t-3) has downward roots 1 and 3; skip one, see 3.
  seen.clear();
  ExactSolver<double>(poly<double>({6, -11, 6, -1}), 0.0, 4.0).visit(StartRule::OverlapCollides, 1, collect);
  EXPECT_EQ(seen, std::vector<double>({3.0}));
}

// A derivative with a root exactly at a double stays in floating point (regression: such a root
// sent the whole call to the exact solver, which made certified 10x slower than robust on the
// 1,000-disc gas under gravity 1). A disc of radius 1/2 at (-2, 1) from a fixed corner, moving at
// (1, 1/2) under gravity (0, -1): p(t) = |d(t)|^2 - 1/4 with d(t) = (-2 + t, 1 + t/2 - t^2/2), so
// p = t^4/4 - t^3/2 + t^2/4 - 3 t + 19/4 and p'''(t) = 6 t - 3 vanishes at t = 1/2 exactly. The
// expected root comes from the exact solver on its own (Sturm isolation, exact rounding).
TEST(SolversCertified, ExactDerivativeRootStaysInFloatingPoint) {
  const Poly<double> p = poly<double>({4.75, -3, 0.25, -0.5, 0.25});
  std::vector<double> exact_roots;
  auto collect = [&](const double& t, bool) {
    exact_roots.push_back(t);
    return true;
  };
  detail::exact::ExactSolver<double>(p, 0.0, 4.0).visit(StartRule::OverlapCollides, 0, collect);
  ASSERT_EQ(exact_roots.size(), 1u);
  const std::uint64_t before = detail::certified_exact_fallbacks;
  const RootOutcome<double> r = earliest_downward_root(SolverKind::Certified, p, 0.0, 4.0);
  EXPECT_EQ(detail::certified_exact_fallbacks, before) << "the certified solver fell back to exact arithmetic";
  ASSERT_EQ(r.status, RootStatus::Root);
  EXPECT_EQ(r.t, exact_roots[0]);
}

// Dyadic conversion is exact and rounding is to nearest, ties to even: 1 + 2^-53 lies halfway
// between 1 and 1 + 2^-52 and rounds to 1 (even); 1 + 3 2^-53 lies halfway between 1 + 2^-52 and
// 1 + 2^-51 and rounds to 1 + 2^-51.
TEST(SolversExact, DyadicRounding) {
  using namespace detail::exact;
  EXPECT_EQ(round_to_scalar<double>(to_dyadic(1.0)), 1.0);
  Dyadic tie_low;  // 1 + 2^-53 = (2^53 + 1) 2^-53
  tie_low.m = (Int(1) << 53) + 1;
  tie_low.e = -53;
  EXPECT_EQ(round_to_scalar<double>(tie_low), 1.0);
  Dyadic tie_high;  // 1 + 3 2^-53
  tie_high.m = (Int(1) << 53) + 3;
  tie_high.e = -53;
  EXPECT_EQ(round_to_scalar<double>(tie_high), 1.0 + std::ldexp(1.0, -51));
  EXPECT_EQ(compare(midpoint(to_dyadic(1.0), to_dyadic(1.0 + std::ldexp(1.0, -52))), tie_low), 0);
  const long double x = 0.1L;
  EXPECT_EQ(round_to_scalar<long double>(to_dyadic(x)), x);
  EXPECT_EQ(round_to_scalar<float>(to_dyadic(0.1)), 0.1f);  // 0.1 (double) rounds to 0.1f
  const Quad q = Quad(1) / Quad(3);
  EXPECT_EQ(round_to_scalar<Quad>(to_dyadic(q)), q);
}

// The world runs with every solver: two unit discs 10 apart closing at 2 collide when the gap of
// 8 is closed, at t = 4 exactly, whichever solver predicts it.
TYPED_TEST(Solvers, WorldRunsWithEverySolver) {
  using T = TypeParam;
  Scene scene;
  scene.name = "head-on";
  for (int i = 0; i < 2; ++i) {
    BodyDesc b;
    b.id = i == 0 ? "a" : "b";
    b.shape = ShapeKind::Circle;
    b.radius = 1;
    b.position = {i == 0 ? 0.0 : 10.0, 0};
    b.velocity = {i == 0 ? 1.0 : -1.0, 0};
    b.mass = 1;
    scene.bodies.push_back(b);
  }
  scene.run.until = 5;
  for (SolverKind s : kAll) {
    WorldOptions options;
    options.solver = s;
    World<T> world(scene, options);
    EXPECT_EQ(world.solver(), s);
    std::vector<T> times;
    world.on_collision([&](const CollisionInfo<T>& c) { times.push_back(c.time); });
    world.run();
    ASSERT_EQ(times.size(), 1u) << solver_name(s);
    EXPECT_EQ(times[0], T(4)) << solver_name(s);
  }
}


// detail::approaching_parabola_root, the short form the engine takes for two circles apart and
// approaching without relative acceleration, against the general robust solver it stands in
// for: where it answers, the same root bit for bit (or the same absence of one). The expected
// values are the general solver's (earliest_downward_root, robust). Pairs drawn like a gas's:
// centres 0.5 to 2 apart, radius sums around 1, speeds 1e-3 to 10; a quarter placed so that
// they pass within 1e-6 to 1e-15 of touching (signs at the vertex within rounding: the general
// path's doubts), and windows from 1e-12 s (the degree reduction) to 100 s.
TYPED_TEST(Solvers, ApproachingParabolaShortFormIsTheRobustWalk) {
  using T = TypeParam;
  std::mt19937_64 rng(27);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int answered = 0, roots = 0, left = 0;
  for (int i = 0; i < 20000; ++i) {
    const double angle = 6.283185307179586 * unit(rng), dist = 0.5 + 1.5 * unit(rng);
    const double speed = std::pow(10.0, -3 + 4 * unit(rng));
    double miss = (unit(rng) - 0.5) * 2.5 * dist;  // impact parameter
    const double r = 0.3 + 0.7 * unit(rng);
    if (i % 4 == 0) miss = r * (1 + (unit(rng) - 0.5) * std::pow(10.0, -6 - 9 * unit(rng)));
    const double dx = dist * std::cos(angle), dy = dist * std::sin(angle);
    // velocity towards the other centre, offset sideways so that the closest approach is `miss`
    const double ux = -dx / dist, uy = -dy / dist;
    const double side = miss / dist;
    const double vx = speed * (ux * std::sqrt(std::max(0.0, 1 - side * side)) - uy * side);
    const double vy = speed * (uy * std::sqrt(std::max(0.0, 1 - side * side)) + ux * side);
    const double hi = std::pow(10.0, -12 + 14 * unit(rng));
    // |d + dv t|^2 - r^2, as the engine's distance_poly builds it without acceleration
    Poly<T> p;
    p.degree = 2;
    p.c[0] = (T(dx) * T(dx) + T(dy) * T(dy)) - T(r) * T(r);
    p.c[1] = T(2) * (T(dx) * T(vx) + T(dy) * T(vy));
    p.c[2] = T(vx) * T(vx) + T(vy) * T(vy);
    T root{};
    const detail::ParabolaRoot fast = detail::approaching_parabola_root(p, T(hi), root);
    if (fast == detail::ParabolaRoot::Unsure) {
      ++left;
      continue;
    }
    ++answered;
    const RootOutcome<T> general = earliest_downward_root(SolverKind::Robust, p, T(0), T(hi));
    if (fast == detail::ParabolaRoot::None) {
      EXPECT_EQ(general.status, RootStatus::None) << i;
      continue;
    }
    ++roots;
    ASSERT_EQ(general.status, RootStatus::Root) << i;
    EXPECT_EQ(general.t, root) << i;
    EXPECT_FALSE(general.at_start_overlap) << i;
  }
  // Most draws are taken (the test compares something), some with a root, and the near grazes
  // leave some to the general path.
  EXPECT_GT(answered, 4000);
  EXPECT_GT(roots, 400);
  EXPECT_GT(left, 10) << answered << " answered, " << roots << " roots";
}

}  // namespace
}  // namespace pge
