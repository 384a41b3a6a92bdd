// Polynomials of degree <= 4 and the question every prediction asks of them: where, in
// [lo, hi], does p first cross zero going down?
#pragma once

#include <array>
#include <cstdint>
#include <string_view>

namespace pge {

// The root solver behind every prediction.
//   Fast: closed forms (quadratic formula, Cardano, Ferrari), as the original PGE: the baseline.
//   Robust (default): bracketing between the roots of the derivative, stable closed forms for
//     degree <= 2, safeguarded Newton elsewhere.
//   Certified: a rigorous error bound around robust's work, exact rational arithmetic where the
//     bound cannot decide; returns the double nearest the exact earliest root.
enum class SolverKind : std::uint8_t { Fast, Robust, Certified };

std::string_view solver_name(SolverKind kind);                  // "fast", "robust", "certified"
bool parse_solver_kind(std::string_view text, SolverKind& out);  // false if unknown

// p(t) = c[0] + c[1] t + ... + c[4] t^4. `degree` is the index of the highest coefficient the
// producer set (the polynomial may still have leading zeros; solvers trim them).
template <class T> struct Poly {
  std::array<T, 5> c{};
  int degree = 0;

  T operator()(const T& t) const {
    T r = c[degree];
    for (int k = degree - 1; k >= 0; --k) r = r * t + c[k];
    return r;
  }
  Poly derivative() const {
    Poly d;
    d.degree = degree > 0 ? degree - 1 : 0;
    for (int k = 1; k <= degree; ++k) d.c[k - 1] = c[k] * T(k);
    return d;
  }
};

enum class RootStatus : std::uint8_t {
  Root,       // a downward crossing (or the overlap rule) at `t`
  None,       // no downward crossing in [lo, hi]
  Undecided,  // the solver could not decide (only solvers that know their limits say this)
};

template <class T> struct RootOutcome {
  RootStatus status = RootStatus::None;
  T t{};
  bool at_start_overlap = false;  // true when the root is `lo` by the overlap rule
};

// Whether a negative value at `lo` counts: the overlap rule of DESIGN.md (a contact function
// found negative and decreasing at lo collides at lo) applies to functions that measure real
// separation; a one-sided distance to a line is negative on the other side and must not.
enum class StartRule : std::uint8_t { OverlapCollides, CrossingsOnly };

}  // namespace pge

#include "pge/detail/roots_robust.hpp"

namespace pge {

// Calls `visit(t, at_start_overlap)` for each downward root of p in [lo, hi], earliest first,
// until `visit` returns true. A downward root is a t where p(t) = 0 and p goes negative just
// after t (f' < 0, or the first non-zero derivative negative); a double root where p touches
// zero and comes back up (a graze) is not one. With StartRule::OverlapCollides, p(lo) <= 0 and
// decreasing at lo yields lo first. Returns true if some visit returned true.
// Contact code calls this, so that every contact category works with every solver.
template <class T, class Visit>
bool visit_downward_roots(SolverKind solver, const Poly<T>& p, const T& lo, const T& hi, StartRule rule,
                          Visit&& visit) {
  (void)solver;  // only the robust solver exists so far; World rejects the others
  return robust_visit_downward_roots(p, lo, hi, rule, visit);
}

// The earliest downward root (see visit_downward_roots), or None.
template <class T>
RootOutcome<T> earliest_downward_root(SolverKind solver, const Poly<T>& p, const T& lo, const T& hi,
                                      StartRule rule = StartRule::OverlapCollides) {
  RootOutcome<T> out;
  visit_downward_roots(solver, p, lo, hi, rule, [&](const T& t, bool overlap) {
    out.status = RootStatus::Root;
    out.t = t;
    out.at_start_overlap = overlap;
    return true;
  });
  return out;
}

}  // namespace pge
