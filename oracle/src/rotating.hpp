// The referee for pairs with a rotating body (oracle/README.md, "Rotation"). Their contact
// functions hold sin and cos of the angles, so there is no polynomial to isolate: the oracle
// derives its own functions from the stored paths (pivot on its quadratic path, angle
// theta0 + omega (t - t0), every double read exactly) and isolates their roots with Arb's
// rigorous ball arithmetic. Only rotating.cpp includes Arb.
#pragma once

#include "judging.hpp"
#include "search.hpp"

#include <optional>

namespace pge::oracle::detail {

// Whether the pair has a rotating body: its contacts are searched here, not by the polynomial
// path (which is untouched for every other pair).
inline bool rotating_pair(const Frame& fr, BodyIndex a, BodyIndex b) {
  return fr.exact_body(a).rotates || fr.exact_body(b).rotates;
}

// The pair's earliest contact in tau in [0, tau_hi], with every feature pair touching then
// (features whose times agree to kTranscendentalTieBits are reported together). Throws
// UndecidedTime where a possible contact cannot be decided within the precision cap (a tangency
// to 2^-kRotatingTangencyBits, a contact at an edge's very end, a sign at the cap).
std::optional<PairResult> rotating_pair_contact(Frame& fr, BodyIndex a, BodyIndex b, const Dyadic& tau_hi,
                                                SearchCounters& n);

// The earliest exact graze the pair's search meets in [0, tau_hi]: a time (tau) where a contact
// function and its derivative are both exactly zero and the function turns back (a tangency
// placed at a dyadic time, such as a corner turning exactly onto a wall's line). No contact.
std::optional<Dyadic> rotating_graze(Frame& fr, BodyIndex a, BodyIndex b, const Dyadic& tau_hi);

// False only when the pair certainly does not touch in [0, tau_hi]: a separating axis keeps the
// outlines apart all through the window (each body's outline enclosed over it in double
// intervals), or the discs the bodies sweep as they turn stay apart (the filter in front of
// rotating_pair_contact).
bool rotating_may_touch(Frame& fr, BodyIndex a, BodyIndex b, const Dyadic& tau_hi);

// The pair's coordinate scale at tau (length units): the larger of each body's largest centre
// coordinate plus its reach, what rounding the bodies' coordinates is relative to.
double rotating_pair_scale(Frame& fr, BodyIndex a, BodyIndex b, const Dyadic& tau);

// The engine's features at tau, as measure_gap (judging.hpp).
GapMeasure rotating_gap(Frame& fr, BodyIndex a, BodyIndex b, const FeaturePair& id, const Dyadic& tau);

// An interval of time narrower than 2^-kRotatingTangencyBits (relative to the time, from 1 s
// on) on which a contact function and its derivative both still hold zero is a tangency the
// referee cannot resolve: undecided.
inline constexpr long kRotatingTangencyBits = 100;
// Intervals narrower than 2^-kQuickBits (relative, as above) are tested in Arb's balls only: in
// double intervals the rounding of the functions' terms (about 2^-52 of them) would hide the
// Taylor forms' shrinking there.
inline constexpr long kQuickBits = 36;
// The highest working precision (bits) a sign is decided at before it is undecided.
inline constexpr long kRotatingMaxPrecision = 4096;

}  // namespace pge::oracle::detail
