// Writes fixtures/polynomials/hard.json: the hard polynomials for the root solvers, each with
// its downward roots computed exactly by CGAL (tests/tools/solver_reference.hpp) and rounded to
// the nearest double. Usage: make_hard_polynomials OUT.json
// The cases are built here from exact roots (expanded in rationals, then each coefficient
// rounded to the nearest double: the exact polynomial is the one with those doubles, whose roots
// the reference computes, not the roots the case was built from).
#include "solver_cases.hpp"
#include "solver_reference.hpp"

#include <mpfr.h>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

namespace {

using pge::reference::Rational;

struct Spec {
  std::string name, why;
  std::vector<double> coefficients;  // c0 .. cn
  double lo, hi;
  pge::StartRule rule = pge::StartRule::OverlapCollides;
};

// lead * prod (t - r) as doubles: each coefficient rounded once from its exact value.
std::vector<double> from_roots(const std::vector<Rational>& roots, const Rational& lead = Rational(1)) {
  std::vector<Rational> c{lead};  // c[k] is the coefficient of t^k
  for (const Rational& r : roots) {
    std::vector<Rational> next(c.size() + 1, Rational(0));
    for (std::size_t k = 0; k < c.size(); ++k) {
      next[k + 1] += c[k];
      next[k] -= c[k] * r;
    }
    c = next;
  }
  std::vector<double> out;
  for (const Rational& q : c) out.push_back(CGAL::to_double(q));
  return out;
}

Rational q(double x) { return pge::reference::to_rational(x); }
Rational pow2(int e) { return q(std::ldexp(1.0, e)); }

std::vector<double> multiply(const std::vector<double>& a, const std::vector<double>& b) {
  // Exact product of two double polynomials, rounded once per coefficient.
  std::vector<Rational> c(a.size() + b.size() - 1, Rational(0));
  for (std::size_t i = 0; i < a.size(); ++i)
    for (std::size_t j = 0; j < b.size(); ++j) c[i + j] += q(a[i]) * q(b[j]);
  std::vector<double> out;
  for (const Rational& x : c) out.push_back(CGAL::to_double(x));
  return out;
}

// The root to 40 significant digits: the exact isolating interval narrowed by bisection on the
// sign of p until its ends agree to that many digits.
std::string decimal(const pge::reference::Solved& solved, const pge::reference::ExactRoot& r) {
  Rational value = r.value;
  if (!r.rational) {
    Rational a = r.low, b = r.high;
    for (int it = 0; it < 200 && b - a > Rational(0); ++it) {
      const Rational m = (a + b) / Rational(2);
      const int c = pge::reference::compare(solved, r, m);
      if (c == 0) { a = b = m; break; }
      if (c > 0) a = m; else b = m;
    }
    value = (a + b) / Rational(2);
  }
  mpfr_t x;
  mpfr_init2(x, 256);
  mpfr_set_q(x, value.mpq(), MPFR_RNDN);
  char buf[128];
  mpfr_snprintf(buf, sizeof buf, "%.40Rg", x);
  mpfr_clear(x);
  return buf;
}

std::vector<Spec> specs() {
  const pge::StartRule crossings = pge::StartRule::CrossingsOnly;
  const double u = std::ldexp(1.0, -52);
  std::vector<Spec> s;
  auto add = [&](std::string name, std::string why, std::vector<double> c, double lo, double hi,
                 pge::StartRule rule = pge::StartRule::OverlapCollides) {
    s.push_back({std::move(name), std::move(why), std::move(c), lo, hi, rule});
  };
  add("simple-quadratic", "(t-1)(t-2): the first crossing", from_roots({q(1), q(2)}), 0, 5);
  add("graze-double-root", "(t-1)^2: touches and comes back, no root", from_roots({q(1), q(1)}), 0, 2);
  add("triple-root-crossing", "-(t-1)^3: crosses down through a triple root", from_roots({q(1), q(1), q(1)}, q(-1)), 0, 3);
  add("quadruple-root-graze", "(t-1)^4: a graze of order four", from_roots({q(1), q(1), q(1), q(1)}), 0, 3);
  add("graze-then-crossing", "(t-1)^2 (t-3)(t-4): the graze at 1 is skipped, the crossing at 3 counts",
      from_roots({q(1), q(1), q(3), q(4)}), 0, 5);
  add("near-double-real", "t^2 - 2t + (1 - 2^-53): roots 1 -+ 2^-26.5, a near-double root that is real",
      {1 - u / 2, -2, 1}, 0, 2);
  add("near-double-real-rational", "t^2 - 2t + (1 - 2^-52): roots exactly 1 -+ 2^-26", {1 - u, -2, 1}, 0, 2);
  add("near-touch-none", "t^2 - 2t + (1 + 2^-52): complex roots 2^-26 off the axis", {1 + u, -2, 1}, 0, 2);
  add("near-double-1-and-1+2^-52", "3 (t-1)(t-1-2^-52), coefficients rounded: roots 1 and 1 + 2^-49/6",
      from_roots({q(1), q(1) + pow2(-52)}, q(3)), 0, 2);
  add("near-double-quartic", "(t-1)(t-1-2^-52)(t-3)(t-4), coefficients rounded: is the near-double pair still real?",
      from_roots({q(1), q(1) + pow2(-52), q(3), q(4)}), 0, 5);
  add("near-double-quartic-exact", "((t-1)^2 - 2^-52)(t^2 + 1): roots 1 -+ 2^-26 and +-i, all exact",
      multiply({1 - u, -2, 1}, {1, 0, 1}), 0, 2);
  add("near-touch-quartic", "((t-1)^2 + 2^-52)(t^2 + 1): no real root, a near touch at 1",
      multiply({1 + u, -2, 1}, {1, 0, 1}), 0, 2);
  add("clustered-1e-3", "(t-1)(t-1.001)(t-1.002)(t-1.003) rounded", from_roots({q(1), q(1.001), q(1.002), q(1.003)}), 0, 2);
  add("clustered-1e-6", "four roots within 3e-6 of 1, rounded",
      from_roots({q(1), q(1) + q(1e-6), q(1) + q(2e-6), q(1) + q(3e-6)}), 0, 2);
  add("clustered-cubic-1e-5", "-(t-1)(t-1.00001)(t-1.00002): a triple cluster crossing down",
      from_roots({q(1), q(1.00001), q(1.00002)}, q(-1)), 0, 2);
  add("wide-1e-8-1e8", "(t - 1e-8)(t - 1e8)", from_roots({q(1e-8), q(1e8)}), 0, 1e9);
  add("wide-quartic-1e-8-1e8", "(t - 1e-8)(t - 1)(t - 1e4)(t - 1e8)", from_roots({q(1e-8), q(1), q(1e4), q(1e8)}), 0, 1e9);
  add("wide-1e-20-1e20", "(t - 1e-20)(t - 1e20)", from_roots({q(1e-20), q(1e20)}), 0, 1e21);
  add("wide-first-root-late", "(t - 1e6)(t - 2e6)(t + 1e-8)(t + 1): the first root is large",
      from_roots({q(1e6), q(2e6), q(-1e-8), q(-1)}), 0, 1e9);
  add("wide-pair-merged", "(t - 1e8)(t - 1e8 - 1)(t + 1e-8)(t + 1) rounded: the pair at 1e8 becomes complex",
      from_roots({q(1e8), q(1e8 + 1), q(-1e-8), q(-1)}), 0, 1e9);
  add("huge-coefficients", "1e100 (t-3)(t-7): beyond float's range", from_roots({q(3), q(7)}, q(1e100)), 0, 10);
  add("tiny-coefficients", "1e-100 (t-3)(t-7): below float's range", from_roots({q(3), q(7)}, q(1e-100)), 0, 10);
  add("zero-middle-coefficients", "1 - t^4: c1 = c2 = c3 = 0", {1, 0, 0, 0, -1}, 0, 2);
  add("zero-leading-coefficients", "t^2 - 3t + 2 declared as a quartic with c3 = c4 = 0", {2, -3, 1, 0, 0}, 0, 5);
  add("tiny-leading-negligible", "2^-60 t^4 + t^2 - 3t + 2: the quartic term is below rounding on [0, 10]",
      {2, -3, 1, 0, std::ldexp(1.0, -60)}, 0, 10);
  add("tiny-leading-relevant", "1e-12 t^4 - t + 1 on [0, 2e3]: small, but not negligible at the far end",
      {1, -1, 0, 0, 1e-12}, 0, 2e3);
  add("tiny-leading-creates-root", "1e-14 t^4 - 1e-6 t^2 + 1 on [0, 1e4]: the tiny term brings roots in",
      {1, 0, -1e-6, 0, 1e-14}, 0, 1e4);
  add("root-at-zero", "t^2 - t: p(0) = 0 and decreasing: the root is lo", {0, -1, 1}, 0, 2);
  add("root-at-zero-upward", "t^2 + t: p(0) = 0 and increasing: no root", {0, 1, 1}, 0, 2);
  add("root-at-zero-quartic", "t (t-1)(t-2)(t-3): p(0) = 0, increasing; down at 1", from_roots({q(0), q(1), q(2), q(3)}), 0, 4);
  add("root-at-hi", "(t-1)(t-2) on [0, 1]: the root is the end of the interval", from_roots({q(1), q(2)}), 0, 1);
  add("graze-at-hi", "(t-2)^2 on [0, 2]: arriving from above at hi counts (beyond hi is past the horizon)",
      from_roots({q(2), q(2)}), 0, 2);
  add("overlap-start", "(t-1)(t-2) from 1.25: negative and decreasing: lo, overlapping", from_roots({q(1), q(2)}), 1.25, 3);
  add("overlap-start-crossings-only", "(t-1)(t-2) from 1.25, a one-sided function: no root", from_roots({q(1), q(2)}), 1.25,
      3, crossings);
  add("negative-start-up-then-down", "(t-1)(t-2)(t-3): up at 1, down at 2", from_roots({q(1), q(2), q(3)}), 0, 4, crossings);
  add("receding-overlap", "(t-1)(t-2)(t-3) from 0, overlap rule: negative but increasing at lo; down at 2",
      from_roots({q(1), q(2), q(3)}), 0, 4);
  add("lo-equals-hi", "(t-1)(t-2) on [1, 1]: a root exactly at lo = hi", from_roots({q(1), q(2)}), 1, 1);
  add("touch-from-below", "-(t-1)^2 on [0, 2]: negative, touches zero at 1: never separates, no root",
      from_roots({q(1), q(1)}, q(-1)), 0, 2, crossings);
  add("no-real-root", "t^2 + 1", {1, 0, 1}, 0, 10);
  add("negative-interval", "(t+2)(t-1) on [-3, -1]", from_roots({q(-2), q(1)}), -3, -1);
  add("tangent-pass", "a disc passing tangentially: |(-1 + t, 1)|^2 - 1 = (t-1)^2", {1, -2, 1}, 0, 3);
  add("tangent-pass-with-gravity", "|(-1 + t, 1 - 2^-40 t^2)|^2 - 1: a near-tangent pass under a small acceleration",
      {1, -2, 1 - std::ldexp(1.0, -39), 0, std::ldexp(1.0, -80)}, 0, 3);
  add("wilkinson-4", "(t-1)(t-2)(t-3)(t-4)", from_roots({q(1), q(2), q(3), q(4)}), 0, 5);
  add("descending-cubic-far", "-(t - 1e6) (t^2 + 1e-12)", multiply({1e6, -1}, {1e-12, 0, 1}), 0, 2e6);
  add("linear", "2 - 4t", {2, -4}, 0, 1);
  add("linear-irrational-ish", "0.1 - 0.3t: the root 1/3 of the rounded coefficients", {0.1, -0.3}, 0, 1);
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: make_hard_polynomials OUT.json\n";
    return 2;
  }
  nlohmann::json doc;
  doc["format"] = "pge-polynomials/1";
  doc["reference"] =
      "Exact: CGAL 5.5 Algebraic_kernel_d_1<Gmpz> (Descartes isolation over GMP integers) on the polynomial whose "
      "coefficients are exactly these doubles; a root counts by the rule in engine/include/pge/roots.hpp, decided "
      "from its multiplicity and the sign of the next derivative there; each root is rounded to the nearest double "
      "by exact comparison with the midpoints of neighbouring doubles. Written by tests/tools/make_hard_polynomials.";
  doc["cases"] = nlohmann::json::array();
  for (const Spec& s : specs()) {
    pge::Poly<double> p;
    p.degree = static_cast<int>(s.coefficients.size()) - 1;
    for (int k = 0; k <= p.degree; ++k) p.c[k] = s.coefficients[k];
    const auto solved = pge::reference::solve(p, s.lo, s.hi, s.rule);
    nlohmann::json expected = nlohmann::json::array();
    for (const auto& r : solved.downward)
      expected.push_back(
          {{"t", pge::reference::nearest<double>(solved, r)}, {"decimal", decimal(solved, r)}, {"overlap", r.overlap}});
    doc["cases"].push_back({{"name", s.name},
                            {"why", s.why},
                            {"coefficients", s.coefficients},
                            {"lo", s.lo},
                            {"hi", s.hi},
                            {"rule", pge::cases::rule_name(s.rule)},
                            {"expected", {{"downward_roots", expected}}}});
  }
  std::ofstream out(argv[1]);
  out << doc.dump(1) << "\n";
  std::cout << "wrote " << doc["cases"].size() << " cases to " << argv[1] << "\n";
  return 0;
}
