// Polynomials of degree <= 4 and the question every prediction asks of them: where, in
// [lo, hi], does p first cross zero going down?
#pragma once

#include <array>
#include <cstdint>

namespace pge {

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

// Calls `visit(t, at_start_overlap)` for each downward root of p in [lo, hi], earliest first,
// until `visit` returns true. A downward root is a t where p(t) = 0 and p goes negative just
// after t (f' < 0, or the first non-zero derivative negative); a double root where p touches
// zero and comes back up (a graze) is not one. With StartRule::OverlapCollides, p(lo) <= 0 and
// decreasing at lo yields lo first. Returns true if some visit returned true.
// This is the robust solver: it brackets every root between the roots of the derivative and
// refines it by safeguarded Newton iteration.
template <class T, class Visit>
bool visit_downward_roots(const Poly<T>& p, const T& lo, const T& hi, StartRule rule, Visit&& visit);

template <class T>
RootOutcome<T> earliest_downward_root(const Poly<T>& p, const T& lo, const T& hi,
                                      StartRule rule = StartRule::OverlapCollides);

}  // namespace pge

#include "pge/detail/roots_robust.hpp"
