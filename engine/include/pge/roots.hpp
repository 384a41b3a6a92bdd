// Polynomials of degree <= 4 and the question every prediction asks of them: where, in
// [lo, hi], does p first cross zero going down?
#pragma once

#include <array>
#include <cstdint>
#include <string_view>

namespace pge {

// The root solver behind every prediction.
//   Fast: closed forms (quadratic formula, Cardano, Ferrari), as the original PGE: the baseline.
//   Robust (default): relative degree reduction, a walk over the pieces between inflection
//     points, stable closed forms for degree <= 2, safeguarded Halley steps elsewhere, a retry in
//     a wider type when a sign is within rounding.
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
#include "pge/detail/roots_fast.hpp"
#include "pge/detail/roots_certified.hpp"

namespace pge {

// Calls `visit(t, at_start_overlap)` for each downward root of p in [lo, hi], earliest first,
// until `visit` returns true. A downward root is a t where p(t) = 0 and p goes negative just
// after t (f' < 0, or the first non-zero derivative negative); a double root where p touches
// zero and comes back up (a graze) is not one. With StartRule::OverlapCollides, p(lo) <= 0 and
// decreasing at lo yields lo first. Returns true if some visit returned true.
// Precisely (what every solver computes, and the tests' exact referee checks):
//   at lo: p goes negative just after lo, and p(lo) = 0, or p(lo) < 0 under OverlapCollides;
//   at t in (lo, hi): p(t) = 0, p > 0 just before t and p < 0 just after t;
//   at hi (> lo): p(hi) = 0 and p > 0 just before hi (what follows hi is beyond the horizon).
// So a touch from below (p <= 0 around a double root) is not a root either: it never separates.
// The turning-overlap rule below is added on top of these by every solver alike; its turning
// point comes from the robust solver (not certified), and tests/tools/solver_reference.hpp does
// not model it.
// Contact code calls this, so that every contact category works with every solver.
namespace detail {
// The overlap rule, continued past lo (the same for every solver): a pair overlapping or
// touching at lo and receding (p(lo) <= 0, not decreasing) that turns to approach again before
// it is apart (a pair left overlapping by round-off and pressed back together by its relative
// acceleration) collides where it turns: at the first local maximum of p, if p is not positive
// there. Without this p never crosses zero from above and the bodies sink into each other
// unchecked (fixtures/regressions/overlap-then-pressed-back-in.json). Returns true if `visit`
// stopped the search; sets `after` to the turning point when there is one.
template <class T, class Visit>
bool visit_turning_overlap(const Poly<T>& p, const T& lo, const T& hi, StartRule rule, Visit& visit, T& after,
                           bool& turned) {
  turned = false;
  if (rule != StartRule::OverlapCollides || !(lo < hi)) return false;
  const T p_lo = p(lo);
  if (p_lo > T(0) || sign_just_after(p.derivative(), lo) < 0) return false;
  // The first local maximum: where p' first crosses zero going down.
  const RootOutcome<T> turn = [&] {
    RootOutcome<T> out;
    robust_visit_downward_roots(p.derivative(), lo, hi, StartRule::CrossingsOnly, [&](const T& t, bool) {
      out.status = RootStatus::Root;
      out.t = t;
      return true;
    });
    return out;
  }();
  if (turn.status != RootStatus::Root || turn.t <= lo) return false;
  const T p_turn = p(turn.t);
  if (p_turn > T(0)) return false;  // apart again before turning: an ordinary crossing follows
  turned = true;
  after = turn.t;
  return visit(turn.t, p_turn < T(0));
}
}  // namespace detail

template <class T, class Visit>
bool visit_downward_roots(SolverKind solver, const Poly<T>& p, const T& lo, const T& hi, StartRule rule,
                          Visit&& visit) {
  T after{};
  bool turned = false;
  if (detail::visit_turning_overlap(p, lo, hi, rule, visit, after, turned)) return true;
  if (turned) {
    // p stays non-positive and decreasing after the turn until it has risen again, so every
    // later downward root lies beyond it: continue from there, as crossings only.
    auto later = [&](const T& t, bool overlap) { return t > after && visit(t, overlap); };
    switch (solver) {
      case SolverKind::Fast: return fast_visit_downward_roots(p, after, hi, StartRule::CrossingsOnly, later);
      case SolverKind::Certified: return certified_visit_downward_roots(p, after, hi, StartRule::CrossingsOnly, later);
      case SolverKind::Robust: break;
    }
    return robust_visit_downward_roots(p, after, hi, StartRule::CrossingsOnly, later);
  }
  switch (solver) {
    case SolverKind::Fast: return fast_visit_downward_roots(p, lo, hi, rule, visit);
    case SolverKind::Certified: return certified_visit_downward_roots(p, lo, hi, rule, visit);
    case SolverKind::Robust: break;
  }
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
