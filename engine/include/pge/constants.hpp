// Every tolerance and limit of the engine, named, with its unit and what it protects.
// Change one here and nowhere else.
#pragma once

#include <cstdint>

namespace pge {

// Relative overlap two bodies may have in a scene file before it is rejected, as a fraction of
// the contact distance (radius sum, or radius for a circle against a wall). Dimensionless.
// Touching placements computed in decimal (a pool rack at sqrt(3) spacing) overlap by a few
// ulps; a real overlap is orders of magnitude larger. Raising it admits overlapping starts,
// which the overlap rule then resolves with a collision at t = 0.
inline constexpr double kStartOverlapTolerance = 1e-9;

// Event storm: a pair of bodies colliding more than kStormCollisions times while simulated time
// advances by less than kStormWindowRelative * max(1, |t|) seconds is reported as a storm and
// stops the run. Dimensionless counts and a relative time span. Too low a count would flag a
// legitimate cascade of simultaneous contacts (a long Newton's cradle resolves in about one
// collision per ball); too high delays the report of a real storm (a resting or Zeno contact).
inline constexpr std::uint32_t kStormCollisions = 1000;
inline constexpr double kStormWindowRelative = 1e-9;

// Overlap bound: the largest overlap between two bodies, at a contact or between events, in
// units of epsilon(T) * (largest coordinate magnitude of the pair + contact distance). A contact
// time is computed from coordinates rounded at that scale, so its overlap is a small multiple of
// it (measured on a 1,000-ball gas: about 150 for double, 50 for float); a missed or late contact
// shows up as an overlap many orders of magnitude beyond this. Dimensionless.
inline constexpr double kOverlapBoundUlps = 1024;

// Root refinement: at most this many safeguarded Newton/bisection iterations per bracketed
// root. Bisection alone halves the bracket each step, so 200 steps exhaust the exponent range
// of binary64 and reach adjacent floating-point numbers for every scalar up to binary128
// (113-bit significand from any starting bracket within the exponent range of double).
inline constexpr int kMaxRootIterations = 400;

}  // namespace pge
