// Polynomials of degree <= 4 and the question every prediction asks of them: where, in
// [lo, hi], does p first cross zero going down?
#pragma once

#include <array>
#include <cstdint>
#include <optional>
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

// Whether a solver promises never to miss a collision (docs/solvers.md): robust and certified
// find every earliest root (the oracle finds no miss on any bundled scene), so a body of theirs
// that passes through a fixed body is a bug, which PGE_VALIDATE builds stop at (pge/tunnel.hpp).
// Fast keeps the closed forms, which lose roots: it can tunnel, and that is measured (pge run
// exit 11, the report's tunnelled count), not an engine failure.
constexpr bool promises_every_collision(SolverKind kind) { return kind != SolverKind::Fast; }

// The largest error of an event's time, in ulps of the scalar, that a solver promises against the
// exact contact time of the state the engine holds (README "Root solvers", "Exact event times"):
// certified rounds every root correctly, and robust and certified both re-derive each event's
// time from the exact paths before processing it, so their times are the exact times correctly
// rounded: 0 ulps. Fast keeps the closed forms and promises nothing (nothing: contrast only).
// `pge check` fails a run whose event time is further off than its solver's promise.
constexpr std::optional<long long> promised_time_error_ulps(SolverKind kind) {
  if (kind == SolverKind::Fast) return std::nullopt;
  return 0;
}
// The same for a pair with a rotating body (docs/rotation.md): robust places a crossing within a
// few ulps of the exact time (measured within 3.43 on random turning pairs), so 4, the referee's
// agreement bound; certified rounds it correctly (0), or keeps robust's placement where the
// rounding stays undecided (WorldStats::undecided_roundings, which pge check reports).
constexpr std::optional<long long> promised_rotating_time_error_ulps(SolverKind kind) {
  if (kind == SolverKind::Fast) return std::nullopt;
  return kind == SolverKind::Robust ? 4 : 0;
}
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
//   at hi (> lo): p(hi) = 0 and p > 0 just before hi (what follows hi is beyond the horizon);
//   the turning-overlap rule, under OverlapCollides: p(lo) < 0 and p rising just after lo (so
//   not the rule at lo), with r the first downward root of p' in (lo, hi] (p's first local
//   maximum): if p(r) <= 0, r, with the overlap flag when p(r) < 0. A pair left overlapping by
//   round-off and pressed back together by its relative acceleration collides where it turns:
//   without this p never crosses zero from above and the bodies sink into each other unchecked
//   (fixtures/regressions/overlap-then-pressed-back-in.json). Every root after it lies past r.
// So a touch from below (p <= 0 around a double root) is not a root either: it never separates.
// Certified decides every part of this exactly (roots_certified.hpp, roots_exact.hpp). Robust
// and fast apply the turning rule below around their own walks; robust hands a turn whose sign
// is within rounding to certified, so that a wrong sign (a missed or invented collision) cannot
// come from it. Contact code calls this, so that every contact category works with every solver.
namespace detail {
enum class Turning : std::uint8_t { None, Turned, Stopped, Doubt };

// The turning-overlap rule in T for fast and robust: Stopped if `visit` stopped the search at the
// turn, Turned (with `after` the turning point) if it declined it, None if the rule does not
// apply; Doubt (only when `guarded`, robust's) if the sign of p at the turn is within rounding
// (a p(lo) within rounding of zero does not end the search when guarded: the turn decides).
template <class T, class Visit>
Turning visit_turning_overlap(const Poly<T>& p, const T& lo, const T& hi, StartRule rule, Visit& visit, T& after,
                              bool guarded) {
  if (rule != StartRule::OverlapCollides || !(lo < hi)) return Turning::None;
  // Apart at lo: p(lo) > 0, or (guarded) certainly so, by its error bound; at lo = 0 (every
  // prediction) p(lo) is c0, exactly.
  const Evaluation<T> at_lo =
      guarded && lo != T(0) ? evaluate_with_bound(p, lo) : Evaluation<T>{p(lo), T(0)};
  if (at_lo.value > at_lo.bound) return Turning::None;
  const Poly<T> d1 = p.derivative();
  if (sign_just_after(d1, lo) < 0) return Turning::None;
  // The first local maximum: where p' first crosses zero going down.
  bool found = false;
  T turn{};
  robust_visit_downward_roots(d1, lo, hi, StartRule::CrossingsOnly, [&](const T& t, bool) {
    found = true;
    turn = t;
    return true;
  });
  if (!found || turn <= lo) return Turning::None;
  const T p_turn = p(turn);
  if (guarded) {
    // p(turn) <= p(r) near the true maximum r, so a value certainly positive decides; a negative
    // one must also clear what the turn's own error (kTurnErrorUlps) can hide: |p'| d + |p''| d^2.
    const Evaluation<T> e = evaluate_with_bound(p, turn);
    const T d = T(kTurnErrorUlps) * std::numeric_limits<T>::epsilon() * abs_of(turn);
    const T hidden = e.bound + abs_of(d1(turn)) * d + abs_of(d1.derivative()(turn)) * d * d;
    const bool positive = e.value > e.bound, negative = e.value < -hidden;
    if (!positive && !negative) return Turning::Doubt;
    if (positive) return Turning::None;
  } else if (p_turn > T(0)) {
    return Turning::None;  // apart again before turning: an ordinary crossing follows
  }
  after = turn;
  return visit(turn, p_turn < T(0)) ? Turning::Stopped : Turning::Turned;
}
}  // namespace detail

template <class T, class Visit>
bool visit_downward_roots(SolverKind solver, const Poly<T>& p, const T& lo, const T& hi, StartRule rule,
                          Visit&& visit) {
  if (solver == SolverKind::Certified) return certified_visit_downward_roots(p, lo, hi, rule, visit);
  T after{};
  switch (detail::visit_turning_overlap(p, lo, hi, rule, visit, after, solver == SolverKind::Robust)) {
    case detail::Turning::Stopped: return true;
    case detail::Turning::Doubt: return certified_visit_downward_roots(p, lo, hi, rule, visit);
    case detail::Turning::Turned: {
      // p stays non-positive and decreasing after the turn until it has risen again, so every
      // later downward root lies beyond it: continue from there, as crossings only.
      auto later = [&](const T& t, bool overlap) { return t > after && visit(t, overlap); };
      if (solver == SolverKind::Fast) return fast_visit_downward_roots(p, after, hi, StartRule::CrossingsOnly, later);
      return robust_visit_downward_roots(p, after, hi, StartRule::CrossingsOnly, later);
    }
    case detail::Turning::None: break;
  }
  if (solver == SolverKind::Fast) return fast_visit_downward_roots(p, lo, hi, rule, visit);
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
