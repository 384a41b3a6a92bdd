// Every tolerance of the oracle, named, with its unit and reason. The oracle decides with exact
// arithmetic; its only tolerance is how it names a time difference that exists.
#pragma once

namespace pge::oracle {

// Agreement of an engine time with the exact time, in ulps of the engine's scalar type (the
// exact time rounded to that type counts as 0). Dimensionless count. A solver that returns the
// double nearest the exact root of the polynomial it built scores 0; rounding of the state
// (positions rebased at every event) and of the polynomial's coefficients moves well-conditioned
// roots by a few ulps. Beyond this an error is reported as a time error; and a different pair
// touching exactly earlier by more than this is a miss rather than a misorder. Lowering it turns
// rounding-level reorderings of near-simultaneous contacts into misses; raising it hides real
// errors.
inline constexpr long kAgreeUlps = 4;

}  // namespace pge::oracle
