// Accuracy of the three root solvers against an exact referee (CGAL, tests/tools/
// solver_reference.hpp), for every scalar, on the hard set (fixtures/polynomials/hard.json) and on
// random collision-derived polynomials. Asserts: certified visits exactly the downward roots, each
// the nearest scalar to the exact root; robust misses no earliest root and invents none. Fast's
// errors are recorded, not asserted. Prints a table of the errors (and writes it as JSON to
// $PGE_SOLVER_REPORT if set). $PGE_SOLVER_CASES (default 100000) and $PGE_SOLVER_SEED choose the
// random cases; $PGE_TURNING_CASES (default 20000 per scalar) the turning-overlap family's.
#include "solver_cases.hpp"
#include "solver_reference.hpp"

#include "pge/roots.hpp"
#include "pge/scalar.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <limits>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

#ifndef PGE_HARD_POLYNOMIALS
#error "PGE_HARD_POLYNOMIALS must name fixtures/polynomials/hard.json"
#endif

namespace pge {
namespace {

std::size_t random_count() {
  const char* s = std::getenv("PGE_SOLVER_CASES");
  return s ? static_cast<std::size_t>(std::strtoull(s, nullptr, 10)) : 100000;
}

template <class T> struct Found {
  std::vector<T> t;
  std::vector<bool> overlap;
};

template <class T> Found<T> run_solver(SolverKind solver, const Poly<T>& p, const T& lo, const T& hi, StartRule rule) {
  Found<T> f;
  visit_downward_roots(solver, p, lo, hi, rule, [&](const T& t, bool overlap) {
    f.t.push_back(t);
    f.overlap.push_back(overlap);
    return false;
  });
  return f;
}

template <class T> bool representable(const cases::Case& c) {
  using std::isfinite;
  for (int k = 0; k <= c.p.degree; ++k)
    if (!isfinite(T(c.p.c[k]))) return false;
  return isfinite(T(c.lo)) && isfinite(T(c.hi));
}

// The exact answer for a case in scalar T. Double, long double and quad share their
// coefficients (doubles convert exactly), so CGAL solves each case once for all three; float
// rounds the coefficients and gets its own solve.
// Cases live in static vectors for the whole run, so their addresses are stable keys.
const reference::Solved& solved_for(const cases::Case& c, bool float_coefficients) {
  static std::map<std::pair<const cases::Case*, bool>, reference::Solved> cache;
  const auto key = std::make_pair(&c, float_coefficients);
  auto it = cache.find(key);
  if (it == cache.end()) {
    reference::Solved s = float_coefficients
                              ? reference::solve(cases::convert<float>(c.p), float(c.lo), float(c.hi), c.rule)
                              : reference::solve(c.p, c.lo, c.hi, c.rule);
    it = cache.emplace(key, std::move(s)).first;
  }
  return it->second;
}

template <class T> const reference::Solved& solved(const cases::Case& c) { return solved_for(c, std::is_same_v<T, float>); }

template <class T> struct Exact {
  Found<T> downward;
  std::vector<double> other_roots;  // approximations: enough to tell which root an answer stands for
};

template <class T> Exact<T> exact_roots(const reference::Solved& s) {
  Exact<T> e;
  for (const auto& r : s.downward) {
    e.downward.t.push_back(reference::nearest<T>(s, r));
    e.downward.overlap.push_back(r.overlap);
  }
  for (const auto& r : s.other_roots) e.other_roots.push_back(reference::approximate_double(s, r));
  return e;
}

template <class T> Exact<T> reference_roots(const cases::Case& c) { return exact_roots<T>(solved<T>(c)); }

// Errors of one solver on one set, for one scalar.
struct Tally {
  std::size_t cases = 0, with_root = 0, misses = 0, invented = 0, wrong = 0;  // wrong: certified's exactness failures
  std::vector<double> ulps;
  std::vector<std::string> examples;  // the first few failures, to reproduce

  double median() const {
    if (ulps.empty()) return 0;
    std::vector<double> v = ulps;
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
    return v[v.size() / 2];
  }
  double largest() const { return ulps.empty() ? 0 : *std::max_element(ulps.begin(), ulps.end()); }
  void note(const std::string& what) {
    if (examples.size() < 5) examples.push_back(what);
  }
};

template <class T> double ulp_distance(const T& a, const T& b) {
  using std::abs;
  if (a == b) return 0;
  return abs(static_cast<double>(boost::math::float_distance(a, b)));
}

std::string describe(const cases::Case& c, std::size_t index) {
  std::ostringstream os;
  os.precision(17);
  os << (c.name.empty() ? "random #" + std::to_string(index) : c.name) << " p=[";
  for (int k = 0; k <= c.p.degree; ++k) os << (k ? ", " : "") << c.p.c[k];
  os << "] on [" << c.lo << ", " << c.hi << "] " << cases::rule_name(c.rule);
  return os.str();
}

// Scores the earliest root a solver found against the exact answer. The solver's root stands for
// the exact real root nearest to it (a graze, an upward crossing, or a downward root): a miss if
// the solver has none while the exact answer has one, or if its root stands for a later downward
// root; invented if the exact answer has none, or its root stands for a root that is not
// downward. Otherwise its error in ulps from the exact earliest root is recorded.
template <class T, class What>
void score_earliest(Tally& tally, const Exact<T>& ref, const Found<T>& got, const What& what) {
  const Found<T>& exact = ref.downward;
  ++tally.cases;
  if (!exact.t.empty()) ++tally.with_root;
  if (exact.t.empty() && got.t.empty()) return;
  if (exact.t.empty()) { ++tally.invented; tally.note("invented: " + what()); return; }
  if (got.t.empty()) { ++tally.misses; tally.note("missed: " + what()); return; }
  const double first = ulp_distance(got.t[0], exact.t[0]);
  for (std::size_t j = 1; j < exact.t.size(); ++j) {
    if (ulp_distance(got.t[0], exact.t[j]) < first) { ++tally.misses; tally.note("skipped the first root: " + what()); return; }
  }
  if (!exact.overlap[0] && first > 0) {
    using std::abs;
    const double t = static_cast<double>(got.t[0]), t0 = static_cast<double>(exact.t[0]);
    for (const double r : ref.other_roots) {
      if (abs(t - r) < abs(t - t0)) {
        ++tally.invented;
        tally.note("stands for a root that is not downward: " + what());
        return;
      }
    }
  }
  if (got.overlap[0] != exact.overlap[0]) { ++tally.misses; tally.note("overlap flag: " + what()); return; }
  tally.ulps.push_back(first);
  if (std::getenv("PGE_SOLVER_VERBOSE") && first > 4) std::cout << first << " ulps: " << what() << "\n";
}

// Certified must reproduce the exact list: same roots, same order, same flags, every time the
// nearest T.
template <class T, class What> void score_exact(Tally& tally, const Found<T>& exact, const Found<T>& got, const What& what) {
  const bool same = exact.t == got.t && exact.overlap == got.overlap;
  if (!same) { ++tally.wrong; tally.note("not exact: " + what()); }
}

using Report = std::map<std::string, Tally>;  // key: scalar/solver/set

template <class T> void evaluate_set(Report& report, const std::string& set, const std::vector<cases::Case>& cs) {
  const std::string scalar(ScalarTraits<T>::name);
  for (std::size_t i = 0; i < cs.size(); ++i) {
    const cases::Case& c = cs[i];
    if (!representable<T>(c)) continue;
    const Exact<T> exact = reference_roots<T>(c);
    const Poly<T> p = cases::convert<T>(c.p);
    for (SolverKind solver : {SolverKind::Fast, SolverKind::Robust, SolverKind::Certified}) {
      const Found<T> got = run_solver(solver, p, T(c.lo), T(c.hi), c.rule);
      const std::string key = scalar + "/" + std::string(solver_name(solver)) + "/" + set;
      Tally& tally = report[key];
      const auto what = [&] { return key + ": " + describe(c, i); };
      score_earliest(tally, exact, got, what);
      if (solver == SolverKind::Certified) score_exact(tally, exact.downward, got, what);
    }
  }
}

Report& global_report() {
  static Report report;
  return report;
}

const std::vector<cases::HardCase>& hard_set() {
  static const std::vector<cases::HardCase> set = cases::load_hard_set(PGE_HARD_POLYNOMIALS);
  return set;
}

const std::vector<cases::Case>& hard_cases() {
  static const std::vector<cases::Case> set = [] {
    std::vector<cases::Case> cs;
    for (const auto& h : hard_set()) cs.push_back(h.c);
    return cs;
  }();
  return set;
}

// The random set: half quartics (accelerating discs), half quadratics (coasting discs).
const std::vector<cases::Case>& random_set() {
  static const std::vector<cases::Case> set = [] {
    const std::size_t n = random_count();
    std::vector<cases::Case> quartics = cases::random_cases(cases::seed_from_env(), n - n / 2, true);
    const std::vector<cases::Case> quadratics = cases::random_cases(cases::seed_from_env() + 1, n / 2, false);
    quartics.insert(quartics.end(), quadratics.begin(), quadratics.end());
    return quartics;
  }();
  return set;
}

// The stored expectations are what the referee computes today (the fixture and the referee
// check each other: a change in either shows here).
TEST(SolverFixtures, HardSetMatchesReference) {
  ASSERT_GE(hard_set().size(), 30u);
  for (const auto& h : hard_set()) {
    const Found<double> exact = reference_roots<double>(h.c).downward;  // h.c lives in the static set
    const auto& stored = h.expected.at("downward_roots");
    ASSERT_EQ(stored.size(), exact.t.size()) << h.c.name;
    for (std::size_t j = 0; j < exact.t.size(); ++j) {
      EXPECT_EQ(stored[j].at("t").get<double>(), exact.t[j]) << h.c.name << " root " << j;
      EXPECT_EQ(stored[j].at("overlap").get<bool>(), static_cast<bool>(exact.overlap[j])) << h.c.name << " root " << j;
    }
  }
}

// The referee itself, on answers derived by hand.
TEST(SolverFixtures, ReferenceOnHandDerivedCases) {
  auto first = [](std::vector<double> c, double lo, double hi, StartRule rule) {
    cases::Case k;
    k.p.degree = static_cast<int>(c.size()) - 1;
    for (std::size_t i = 0; i < c.size(); ++i) k.p.c[i] = c[i];
    k.lo = lo;
    k.hi = hi;
    k.rule = rule;
    return reference::solve(k.p, k.lo, k.hi, k.rule);
  };
  auto nearest = [](const reference::Solved& s) {
    std::vector<double> t;
    for (const auto& r : s.downward) t.push_back(reference::nearest<double>(s, r));
    return t;
  };
  EXPECT_EQ(nearest(first({2, -3, 1}, 0, 5, StartRule::OverlapCollides)), std::vector<double>({1.0}));  // (t-1)(t-2)
  EXPECT_TRUE(first({1, -2, 1}, 0, 5, StartRule::OverlapCollides).downward.empty());                   // graze
  EXPECT_TRUE(first({-2, 0, 1}, 0, 5, StartRule::OverlapCollides).downward.empty());                   // t^2 - 2: upward
  // 2 - t^2: sqrt(2), which the library's correctly rounded sqrt gives.
  EXPECT_EQ(nearest(first({2, 0, -1}, 0, 5, StartRule::OverlapCollides)), std::vector<double>({std::sqrt(2.0)}));
  EXPECT_TRUE(first({2, -3, 1}, 1.5, 5, StartRule::OverlapCollides).downward.empty());  // p'(1.5) = 0: not decreasing
  const auto start = first({2, -3, 1}, 1.25, 5, StartRule::OverlapCollides);
  ASSERT_EQ(start.downward.size(), 1u);
  EXPECT_EQ(nearest(start), std::vector<double>({1.25}));
  EXPECT_TRUE(start.downward[0].overlap);
  // -(t-1)(t-2)(t-3) from 0 under CrossingsOnly: p(0) = 6, down at 1, up at 2, down at 3.
  EXPECT_EQ(nearest(first({6, -11, 6, -1}, 0, 4, StartRule::CrossingsOnly)), std::vector<double>({1.0, 3.0}));
}

template <class T> class SolverAccuracy : public ::testing::Test {};
using Scalars = ::testing::Types<float, double, long double, Quad>;
TYPED_TEST_SUITE(SolverAccuracy, Scalars);

// The assertions of the issue: certified exact (correctly rounded, nothing missed or invented),
// robust missing and inventing nothing. Fast is recorded only.
template <class T> void expect_sound(const std::string& set) {
  Report& report = global_report();
  const std::string scalar(ScalarTraits<T>::name);
  const Tally& certified = report[scalar + "/certified/" + set];
  const Tally& robust = report[scalar + "/robust/" + set];
  auto first = [](const Tally& t) { return t.examples.empty() ? std::string() : t.examples[0]; };
  EXPECT_EQ(certified.wrong + certified.misses + certified.invented, 0u) << first(certified);
  EXPECT_EQ(robust.misses, 0u) << first(robust);
  EXPECT_EQ(robust.invented, 0u) << first(robust);
}

TYPED_TEST(SolverAccuracy, HardSet) {
  evaluate_set<TypeParam>(global_report(), "hard", hard_cases());
  expect_sound<TypeParam>("hard");
}

TYPED_TEST(SolverAccuracy, RandomCollisionPolynomials) {
  using T = TypeParam;
  evaluate_set<T>(global_report(), "random", random_set());
  const Tally& certified = global_report()[std::string(ScalarTraits<T>::name) + "/certified/random"];
  EXPECT_EQ(certified.cases, random_set().size());
  EXPECT_GT(certified.with_root, certified.cases / 5) << "the generator should give many roots";
  expect_sound<T>("random");
}

// Certified's quick path (roots_certified.hpp, quick_earliest_root) decides the common case from
// robust's candidate and cheap proofs. Whatever it decides must be the referee's answer: no root,
// or the earliest downward root correctly rounded (never the overlap rule: it proves p(lo) > 0).
// It must also decide nearly all random cases, or certified pays for its walk after all (the walk
// costs about four times the quick path: on random double quartics 280 of 4,096 left to it cost
// certified 1.6x robust's time, 11 of 4,096 1.46x, bench_solvers).
TYPED_TEST(SolverAccuracy, QuickPathAgreesWithReferee) {
  using T = TypeParam;
  std::size_t decided = 0, random_seen = 0;
  for (const auto* set : {&random_set(), &hard_cases()}) {
    const std::size_t n = std::min<std::size_t>(set->size(), 10000);
    for (std::size_t i = 0; i < n; ++i) {
      const cases::Case& c = (*set)[i];
      if (!representable<T>(c)) continue;
      Poly<T> p = cases::convert<T>(c.p);
      p.degree = detail::trimmed_degree(p);
      if (p.degree == 0) continue;
      T t{};
      const detail::Quick q = detail::quick_earliest_root(p, T(c.lo), T(c.hi), t);
      random_seen += set == &random_set();
      if (q == detail::Quick::Undecided) continue;
      decided += set == &random_set();
      const Found<T> exact = reference_roots<T>(c).downward;
      if (q == detail::Quick::None) {
        EXPECT_TRUE(exact.t.empty()) << describe(c, i) << ": quick path says no root";
      } else {
        ASSERT_FALSE(exact.t.empty()) << describe(c, i) << ": quick path invents " << t;
        EXPECT_EQ(t, exact.t[0]) << describe(c, i);
        EXPECT_FALSE(exact.overlap[0]) << describe(c, i);
      }
    }
  }
  EXPECT_GT(decided, random_seen * 99 / 100) << "the quick path should decide nearly all random cases: " << decided
                                             << " of " << random_seen;
}

// Roots within a tiny fraction of an ulp of a midpoint of T, where a wrong sign at the midpoint
// would round the wrong way. With P = digits(T), b odd and 2k + 1 = e / b mod 2^(P+1) (e = 1 or
// -1), the integer a = ((2k + 1) b - e) / 2^(P+1) makes a / b = m - e / (b 2^(P+1)) for the
// midpoint m = (2k + 1) / 2^(P+1) of k / 2^P and (k + 1) / 2^P: a / b lies 2^-(P+1) / b from m,
// below it for e = 1 (nearest k / 2^P) and above it for e = -1 (nearest (k + 1) / 2^P); a and
// b < 2^P are exact in T.
// Only m >= 1/2 (2k + 1 >= 2^P), where T's spacing is 2^-P. p = a - b t, and (a - b t)(1 + t^2) =
// a - b t + a t^2 - b t^3 (the same single root), on [0, 1].
// In float the wider type (double) evaluates a - b m exactly, so the quick path decides every
// linear case itself; elsewhere it may leave them to the walk, but never answer wrongly.
TYPED_TEST(SolverAccuracy, RootsNextToMidpoints) {
  using T = TypeParam;
  using detail::exact::Int;
  constexpr int P = std::numeric_limits<T>::digits;
  const Int modulus = Int(1) << (P + 1), mask = modulus - 1;
  std::mt19937_64 rng(cases::seed_from_env() + 3);
  auto random_bits = [&](int bits) {
    Int r = 0;
    for (int have = 0; have < bits; have += 64) r = (r << 64) + Int(rng());
    return r & ((Int(1) << bits) - 1);
  };
  std::size_t linear = 0, linear_decided = 0;
  for (int i = 0; i < 800; ++i) {
    const Int b = random_bits(P) | (Int(1) << (P - 1)) | 1;  // odd, in [2^(P-1), 2^P)
    Int inverse = b;  // Newton's iteration for 1/b mod 2^(P+1): each step doubles the correct bits
    for (int step = 0; step < 7; ++step) inverse = (inverse * ((modulus + 2 - ((b * inverse) & mask)) & mask)) & mask;
    const bool below = i % 2 == 0;
    const Int odd = below ? inverse : Int((modulus - inverse) & mask);  // 2k + 1
    const Int a = (odd * b - (below ? 1 : -1)) >> (P + 1);
    ASSERT_EQ(a * modulus, odd * b - (below ? 1 : -1));
    if (odd < (Int(1) << P)) continue;  // m < 1/2: k / 2^P and (k + 1) / 2^P are not adjacent in T
    const Int k = odd >> 1;
    using std::ldexp;
    const T expected = ldexp(static_cast<T>(below ? k : Int(k + 1)), -P);
    const T ta = static_cast<T>(a), tb = static_cast<T>(b);
    for (const Poly<T>& p : {Poly<T>{{ta, T(-tb)}, 1}, Poly<T>{{ta, T(-tb), ta, T(-tb)}, 3}}) {
      const RootOutcome<T> r = earliest_downward_root(SolverKind::Certified, p, T(0), T(1));
      ASSERT_EQ(r.status, RootStatus::Root) << "a = " << a << ", b = " << b;
      EXPECT_EQ(r.t, expected) << "a = " << a << ", b = " << b << ", degree " << p.degree;
      T t{};
      const detail::Quick q = detail::quick_earliest_root(p, T(0), T(1), t);
      EXPECT_NE(q, detail::Quick::None);
      if (q == detail::Quick::Root) {
        EXPECT_EQ(t, expected) << "a = " << a << ", b = " << b << ", degree " << p.degree;
        linear_decided += p.degree == 1;
      }
      linear += p.degree == 1;
    }
  }
  EXPECT_GT(linear, 300u);
  if (std::is_same_v<T, float>) {
    EXPECT_EQ(linear_decided, linear);
  }
}

std::size_t turning_count() {
  const char* s = std::getenv("PGE_TURNING_CASES");
  return s ? static_cast<std::size_t>(std::strtoull(s, nullptr, 10)) : 20000;
}

// The turning family (cases::turning_case): an overlapping start whose first local maximum lies
// within a few ulps of zero, generated in each scalar's own precision, judged against the CGAL
// referee's turning rule (solver_reference.hpp, turning_root). Certified must be exact and robust
// must miss and invent nothing, as everywhere; the family must really hold both signs at the
// maximum (turns taken and turns that separate first).
TYPED_TEST(SolverAccuracy, TurningOverlapFamily) {
  using T = TypeParam;
  const std::string scalar(ScalarTraits<T>::name);
  std::mt19937_64 rng(cases::seed_from_env() + 2);
  std::size_t turns = 0, separations = 0;
  for (std::size_t i = 0, n = turning_count(); i < n; ++i) {
    const cases::TurningCase<T> c = cases::turning_case<T>(rng);
    const reference::Solved solved = reference::solve(c.p, c.lo, c.hi, StartRule::OverlapCollides);
    const Exact<T> exact = exact_roots<T>(solved);
    const bool turned = !solved.downward.empty() && !solved.downward[0].of.empty();
    (turned ? turns : separations) += 1;
    for (SolverKind solver : {SolverKind::Fast, SolverKind::Robust, SolverKind::Certified}) {
      const Found<T> got = run_solver(solver, c.p, c.lo, c.hi, StartRule::OverlapCollides);
      const std::string key = scalar + "/" + std::string(solver_name(solver)) + "/turning";
      Tally& tally = global_report()[key];
      const auto what = [&] {
        std::ostringstream os;
        os.precision(std::numeric_limits<T>::max_digits10);
        os << key << ": turning #" << i << " p=[";
        for (int k = 0; k <= c.p.degree; ++k) os << (k ? ", " : "") << c.p.c[k];
        os << "] on [" << c.lo << ", " << c.hi << "]";
        return os.str();
      };
      score_earliest(tally, exact, got, what);
      if (solver == SolverKind::Certified) score_exact(tally, exact.downward, got, what);
    }
  }
  EXPECT_GT(turns, turning_count() / 10) << "the family should often turn";
  EXPECT_GT(separations, turning_count() / 10) << "the family should often separate before its maximum";
  expect_sound<T>("turning");
}

// Runs last (gtest runs suites in declaration order): prints and writes the table.
TEST(SolverReport, Print) {
  nlohmann::json out = nlohmann::json::array();
  std::cout << "scalar/solver/set: cases, with root, misses, invented, certified wrong, median ulps, largest ulps\n";
  for (const auto& [key, t] : global_report()) {
    std::cout << key << ": " << t.cases << ", " << t.with_root << ", " << t.misses << ", " << t.invented << ", "
              << t.wrong << ", " << t.median() << ", " << t.largest() << "\n";
    for (const std::string& e : t.examples) std::cout << "    " << e << "\n";
    out.push_back({{"key", key}, {"cases", t.cases}, {"with_root", t.with_root}, {"misses", t.misses},
                   {"invented", t.invented}, {"certified_wrong", t.wrong}, {"median_ulps", t.median()},
                   {"largest_ulps", t.largest()}});
  }
  if (const char* path = std::getenv("PGE_SOLVER_REPORT")) {
    std::ofstream f(path);
    f << out.dump(1) << "\n";
    ASSERT_TRUE(f.good()) << "cannot write " << path;
  }
}

}  // namespace
}  // namespace pge
