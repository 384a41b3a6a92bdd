// A turned point at one instant, for the trace referee's poses (judge_scene.cpp): a rotating
// body's vertex is its pivot plus R(theta) r, and its pivot is a trace's reference point plus
// R(theta) of its offset. sin and cos of a double angle are transcendental, so the result is
// rounded: to the midpoint of an Arb ball narrower than 2^-kTurnBits of |r| (exact for theta = 0,
// where sin and cos are 0 and 1). Only turn.cpp and rotating.cpp include Arb.
#pragma once

#include "pge/oracle_exact.hpp"

#include <vector>

namespace pge::oracle::detail {

// Bits of R(theta) r kept (relative to |r|). A step trace's overlap test at an instant decides
// the sign of a separation from turned vertices: it can be wrong only where the pair is within
// about 2^-190 of its reach of touching. A corner of an outline turned by a non-zero dyadic angle
// is never exactly on a line through dyadic points (sin theta would be algebraic), so only such a
// near touch, far below every engine's rounding, is affected.
inline constexpr long kTurnBits = 192;

// R(theta) r = (cos theta x - sin theta y, sin theta x + cos theta y) for each r of `points`
// (one sine and cosine for all), each coordinate rounded as above.
std::vector<ExactVec> turned(const std::vector<ExactVec>& points, const Dyadic& theta);

}  // namespace pge::oracle::detail
