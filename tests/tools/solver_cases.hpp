// Polynomials for the root-solver tests and benchmarks: random collision-derived ones (the
// contact functions of two discs in relative motion) and the hard set of
// fixtures/polynomials/hard.json. Shared by tests/test_solvers_accuracy.cpp and bench/.
#pragma once

#include "pge/roots.hpp"

#include <boost/math/special_functions/next.hpp>

#include <nlohmann/json.hpp>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace pge::cases {

struct Case {
  std::string name;  // empty for random cases
  Poly<double> p;
  double lo = 0;
  double hi = 1;
  StartRule rule = StartRule::OverlapCollides;
};

template <class T> Poly<T> convert(const Poly<double>& p) {
  Poly<T> q;
  q.degree = p.degree;
  for (int k = 0; k <= p.degree; ++k) q.c[k] = T(p.c[k]);
  return q;
}

// Default seed of the random cases; PGE_SOLVER_SEED overrides it (decimal).
inline constexpr std::uint64_t kDefaultSeed = 20240604;

inline std::uint64_t seed_from_env() {
  const char* s = std::getenv("PGE_SOLVER_SEED");
  return s ? std::strtoull(s, nullptr, 10) : kDefaultSeed;
}

// Two discs of radius sum r, centre offset d, relative velocity v and relative acceleration a
// (zero for quadratics): |d + v t + a t^2 / 2|^2 - r^2 on [0, horizon], coefficients rounded as
// the engine rounds them. Scales are log-uniform over the ranges of a lively scene; half of the
// velocities aim at the other disc, so that about half of the cases have a root.
inline Case random_collision_case(std::mt19937_64& rng, bool quartic) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double two_pi = 6.283185307179586;
  auto log_uniform = [&](double lo_exp, double hi_exp) { return std::pow(10.0, lo_exp + (hi_exp - lo_exp) * unit(rng)); };
  const double r = log_uniform(-2, 0);
  const double gap = r * log_uniform(-6, 1);
  const double angle = two_pi * unit(rng);
  const double dx = (r + gap) * std::cos(angle), dy = (r + gap) * std::sin(angle);
  const double speed = log_uniform(-2, 1);
  const double heading = unit(rng) < 0.5 ? angle + 3.141592653589793 + (unit(rng) - 0.5) : two_pi * unit(rng);
  const double vx = speed * std::cos(heading), vy = speed * std::sin(heading);
  double ax = 0, ay = 0;
  if (quartic) {
    const double accel = log_uniform(-1, 1.3);
    const double dir = two_pi * unit(rng);
    ax = accel * std::cos(dir);
    ay = accel * std::sin(dir);
  }
  Case c;
  c.p.c[0] = (dx * dx + dy * dy) - r * r;
  c.p.c[1] = 2.0 * (dx * vx + dy * vy);
  c.p.c[2] = (vx * vx + vy * vy) + (dx * ax + dy * ay);
  c.p.c[3] = vx * ax + vy * ay;
  c.p.c[4] = (ax * ax + ay * ay) / 4.0;
  c.p.degree = quartic ? 4 : 2;
  c.lo = 0;
  c.hi = log_uniform(-1, 1);
  return c;
}

inline std::vector<Case> random_cases(std::uint64_t seed, std::size_t count, bool quartic) {
  std::mt19937_64 rng(seed);
  std::vector<Case> out;
  out.reserve(count);
  for (std::size_t i = 0; i < count; ++i) out.push_back(random_collision_case(rng, quartic));
  return out;
}

// The turning family: p(0) < 0 and rising, with its first local maximum within a few ulps of
// zero, above or below, so that the turning-overlap rule (pge/roots.hpp) hangs on the sign of p
// there. p is -A (t - m)^2, A (t - m)^2 (t - c) or -A (t - m)^2 (t - c)(t - d) (m < c < d), whose
// maximum at m is 0, expanded in T (so the maximum moves by the coefficients' rounding) and then
// nudged by k in [-8, 8] ulps of its constant term. Time scales 1e-3 to 1e3, amplitudes 1e-6 to
// 1e6; the window [0, hi] reaches past m, sometimes past the later roots. In T's own precision,
// so that every scalar meets maxima within its own ulps.
template <class T> struct TurningCase {
  Poly<T> p;
  T lo{0}, hi{1};
};

template <class T> TurningCase<T> turning_case(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  auto log_uniform = [&](double lo_exp, double hi_exp) { return std::pow(10.0, lo_exp + (hi_exp - lo_exp) * unit(rng)); };
  const double scale = log_uniform(-3, 3);
  const T m = T(scale * (0.1 + 0.9 * unit(rng)));
  const T c = m + T(scale * (0.5 + 2.5 * unit(rng)));
  const T d = c + T(scale * (0.5 + 2.5 * unit(rng)));
  const T a = T(log_uniform(-6, 6));
  const int degree = 2 + static_cast<int>(unit(rng) * 3.0);
  // (t - m)^2 = m^2 - 2 m t + t^2, times the other factors, in T.
  std::array<T, 5> q{m * m, T(-2) * m, T(1), T(0), T(0)};
  const auto times_root = [&](const T& r) {  // q *= (t - r)
    for (int k = 4; k >= 0; --k) q[k] = (k > 0 ? q[k - 1] : T(0)) - r * q[k];
  };
  if (degree >= 3) times_root(c);
  if (degree >= 4) times_root(d);
  const T sign = degree == 3 ? T(1) : T(-1);  // negative around m: the maximum is 0
  TurningCase<T> out;
  out.p.degree = degree;
  for (int k = 0; k <= degree; ++k) out.p.c[k] = sign * a * q[k];
  const int nudge = static_cast<int>(unit(rng) * 17.0) - 8;
  for (int i = 0; i < (nudge < 0 ? -nudge : nudge); ++i)
    out.p.c[0] = nudge > 0 ? boost::math::float_next(out.p.c[0]) : boost::math::float_prior(out.p.c[0]);
  out.hi = unit(rng) < 0.5 ? T(m * T(1.0 + unit(rng))) : T(d * T(1.0 + unit(rng)));
  return out;
}

inline StartRule parse_rule(const std::string& s) {
  if (s == "overlap-collides") return StartRule::OverlapCollides;
  if (s == "crossings-only") return StartRule::CrossingsOnly;
  throw std::runtime_error("hard polynomials: unknown rule \"" + s + "\"");
}

inline const char* rule_name(StartRule r) { return r == StartRule::OverlapCollides ? "overlap-collides" : "crossings-only"; }

// The hard set, with its stored expectations (the earliest downward root as the nearest
// double, or none) in `expected`.
struct HardCase {
  Case c;
  nlohmann::json expected;
};

inline std::vector<HardCase> load_hard_set(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open " + path);
  const nlohmann::json doc = nlohmann::json::parse(in);
  std::vector<HardCase> out;
  for (const auto& j : doc.at("cases")) {
    HardCase h;
    h.c.name = j.at("name").get<std::string>();
    const auto& coeffs = j.at("coefficients");
    h.c.p.degree = static_cast<int>(coeffs.size()) - 1;
    for (std::size_t k = 0; k < coeffs.size(); ++k) h.c.p.c[k] = coeffs[k].get<double>();
    h.c.lo = j.at("lo").get<double>();
    h.c.hi = j.at("hi").get<double>();
    h.c.rule = parse_rule(j.at("rule").get<std::string>());
    h.expected = j.at("expected");
    out.push_back(h);
  }
  return out;
}

}  // namespace pge::cases
