// The earliest contact of one feature pair: exact, and the certified filter in front of it.
#pragma once

#include "features.hpp"
#include "roots.hpp"

#include <functional>
#include <optional>

namespace pge::oracle::detail {

struct Contact {
  RootHandle tau;             // time since the frame's `now`
  bool overlap_rule = false;  // found overlapping: at tau = 0 and approaching, or at a turn
};

// The integer polynomial with the same roots and signs (scaled by a positive power of two).
IntPoly to_int_poly(const Poly<Dyadic>& p);

// The earliest tau in [0, tau_hi] at which the feature pair collides (DESIGN.md):
//   at tau = 0: f(0) <= 0 and approaching (the first non-zero derivative negative), on the
//     feature; if f(0) < 0 this is the overlap rule and also needs `overlap_applies()`;
//   the turning-overlap rule: f(0) < 0 and rising, and f not positive at its first local
//     maximum m in (0, tau_hi] (the pair turns back before it separates): a contact at m, on
//     the feature at m and with `overlap_applies()`, found overlapping if f(m) < 0;
//   after 0: a root where f crosses from positive to negative (odd multiplicity, negative just
//     after; a double root touching zero is a graze), on the feature at the root.
// "On the feature" is decided by exact signs at the root: the projection in [0, e.e] for edge
// interiors, cross(P - A, e) > 0 for a circle against a one-sided edge. A vertex meeting an
// edge exactly at an end (projection 0: end 0, e.e: end 1) meets a corner, and collides only if
// `corner_enters(root, end)` (see corner.hpp).
using CornerTest = std::function<bool(const RealRoot& root, int end)>;
std::optional<Contact> earliest_contact(const ContactPolys<Dyadic>& c, const Dyadic& tau_hi,
                                        const std::function<bool()>& overlap_applies, const CornerTest& corner_enters);

// False only if the feature pair certainly has no contact in tau in [0, window.hi()]: the
// contact function is positive throughout, or increasing throughout (so neither approaching at
// 0 nor crossing down later), or the point never projects onto the edge, or (one-sided circle)
// never lies outside the edge line.
bool may_touch(const ContactPolys<Interval>& c, const Interval& window);

}  // namespace pge::oracle::detail
