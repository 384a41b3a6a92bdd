// Every tolerance and limit of the engine, named, with its unit and what it protects.
// Change one here and nowhere else.
#pragma once

#include <cstddef>
#include <cstdint>

namespace pge {

// Relative overlap two bodies may have in a scene file before it is rejected, as a fraction of
// the contact distance (radius sum, or radius for a circle against a wall). Dimensionless.
// Touching placements computed in decimal (a pool rack at sqrt(3) spacing) overlap by a few
// ulps; a real overlap is orders of magnitude larger. Raising it admits overlapping starts,
// which the overlap rule then resolves with a collision at t = 0.
inline constexpr double kStartOverlapTolerance = 1e-9;

// Supported range of scene values, checked by validate_scene. Every coordinate (positions,
// segment endpoints, polygon vertices), velocity, acceleration and gravity component is 0 or
// has magnitude in [kMinSceneScale, kMaxSceneMagnitude]; radii and masses lie in that range;
// the horizon (run.until, or pge run --until) is at most kMaxSceneMagnitude.
// SI units, but the bound is about floating point, not physics: a contact polynomial's
// coefficients are products of two such values and its highest term is (a t^2)^2, at most
// (1e30 * 1e60)^2 = 1e180; energies m v^2 stay below 1e90 and an impulse divides by
// n.n / m <= 1e60 * 1e30. So nothing the engine computes comes near overflow (1.8e308), and
// products of a few values stay far from the subnormals (below 2.2e-308), whose rounding error
// is absolute: the error bounds of the engine and the invariant checks are relative. Beyond
// this range a scene would silently produce infinities and NaNs (gravity 1e289 does within the
// first event); a clear error is better. Raising it towards
// 1e38 keeps that margin for double only; float runs already round such scenes badly.
inline constexpr double kMaxSceneMagnitude = 1e30;
inline constexpr double kMinSceneScale = 1e-30;

// Frame events in one run, at most (run.until * frames_per_second, whichever gives them):
// frames do not count against max_events, so without a bound a high frame rate would make a run
// that never ends (and a trace that fills the disk). 1e9 frames is already a trace of
// terabytes for a few bodies.
inline constexpr double kMaxFramesPerRun = 1e9;

// Event storm: a pair of bodies colliding more than kStormCollisions times while simulated time
// advances by less than kStormWindowRelative * max(1, |t|) seconds is reported as a storm and
// stops the run. Dimensionless counts and a relative time span. Too low a count would flag a
// legitimate cascade of simultaneous contacts (a long Newton's cradle resolves in about one
// collision per ball); too high delays the report of a real storm (a resting or Zeno contact).
inline constexpr std::uint32_t kStormCollisions = 1000;
inline constexpr double kStormWindowRelative = 1e-9;

// Resting contact (DESIGN.md): a body touching a fixed straight face (a segment, or an edge of a
// fixed polygon) while its acceleration presses it in, and whose bounce off the face would be
// rounding noise, stops bouncing: its normal speed is removed and it slides along the face, with
// the normal component of its acceleration removed, until it leaves the face's end or something
// hits it. Noise, for a contact with restitution < 1: a rise w^2 / (2 a_n) below kRestHeightUlps
// ulps of the body's coordinate scale (the rounding of its position), so a Zeno sequence of
// bounces ends after finitely many events; with restitution 1: a normal speed within
// kRestHeightUlps ulps of the body's speed (the rounding of its velocity), so that an elastic
// bounce keeps its energy. Dimensionless. A contact counts as on a face when its normal is
// within kRestNormalTolerance of the face's normal (1 - cos of the angle; dimensionless), and a
// polygon's vertex touches the face when it is within kRestVertexTolerance of the lowest vertex
// (relative to the polygon's size).
inline constexpr double kRestHeightUlps = 16;
// A body resting on a tilted face slides with its acceleration and velocity projected along the
// face; the projections' normal components are rounding (a few ulps of the unprojected
// magnitudes), and are lifted off the face by kRestLiftUlps ulps of those magnitudes so that
// the rounding can only carry the body off the face (a gap), never into it. Dimensionless.
inline constexpr double kRestLiftUlps = 8;
inline constexpr double kRestNormalTolerance = 1e-9;
inline constexpr double kRestVertexTolerance = 1e-9;

// Overlap bound: the largest overlap between two bodies, at a contact or between events, in
// units of epsilon(T) * (largest coordinate magnitude of the pair, vertices included, + the
// pair's relative speed * |t| + contact distance). A contact time is computed from coordinates
// rounded at that scale and is itself rounded to ulp(t), in which the pair closes |v_rel| ulp(t),
// so its overlap is a small multiple of it (measured on a 1,000-ball gas: about 150 for double,
// 50 for float; on the bundled games over 100,000 events, see docs/harness.md); a missed or late contact
// shows up as an overlap many orders of magnitude beyond this. Dimensionless.
inline constexpr double kOverlapBoundUlps = 1024;

// Corner contacts (polygons and segments): a vertex that crosses an edge's line within this
// many ulps of an end of the edge touches the corner there, a vertex against a vertex. Unit:
// epsilon(T) * the pair's coordinate scale (largest vertex coordinate magnitude), widened by
// (1 + cot of the crossing angle), which is how much a root time's rounding moves the contact
// point along the edge. Such a contact collides only if the two bodies start to overlap (see
// docs/events.md) and takes the corner's normal. Too small: a corner hit can
// fall between the two edges meeting there through rounding and the vertex pass into the body;
// too large: contacts near (not at) a corner get the corner normal. It stays far below
// kOverlapBoundUlps, so that a corner contact judged not entering overlaps less than the bound.
inline constexpr double kCornerSlackUlps = 64;

// Bounding circles: a pair involving a polygon or segment is skipped when the circles around
// its two bodies (each body's farthest vertex from its position, plus a circle's radius) do not
// meet before the horizon. The radius sum is widened by this fraction of (radius sum + the
// pair's coordinate scale) so that rounding never makes the test skip a pair that touches.
// Dimensionless; rounding is ~1e-16 of that scale, and a wider margin only costs predictions.
inline constexpr double kBoundingSlackRelative = 0x1p-20;

// Root refinement: at most this many safeguarded Halley/bisection iterations per bracketed
// root. Bisection alone halves the bracket each step, so 200 steps exhaust the exponent range
// of binary64 and reach adjacent floating-point numbers for every scalar up to binary128
// (113-bit significand from any starting bracket within the exponent range of double).
inline constexpr int kMaxRootIterations = 400;

// The turning-overlap rule in the robust solver (pge/roots.hpp): how far, in ulps of the turning
// time, robust's turning point (a root of p' from T coefficients) may lie from the exact local
// maximum of p. A negative p there must exceed what that distance can hide (|p'| d + |p''| d^2
// with d this many ulps) as well as p's rounding; anything closer is handed to the certified
// solver, which decides it exactly. Robust's well-conditioned roots are within a few ulps (the
// accuracy suite's random polynomials: at most 26 in double), so 64 leaves room; larger only
// sends more turns to certified (slower, never wrong), smaller lets robust's own error decide.
inline constexpr double kTurnErrorUlps = 64;

}  // namespace pge

// Robust solver, relative degree reduction: a leading term c_d t^d is dropped when, for some
// lower non-zero coefficient c_k, |c_d| m^(d-k) <= kNegligibleTermEpsilons * epsilon(T) * |c_k|
// with m = max(|lo|, |hi|). In units of epsilon(T) (dimensionless). Then the dropped term is below
// an eighth of one rounding of the kept terms anywhere in [lo, hi], far under the Horner error
// bound (2d epsilon), so no sign the solver can compute changes. Raising it towards 1 and beyond
// starts to move roots by more than rounding; 0 only drops exact zeros (closed forms then meet
// huge spurious roots and ill-conditioned critical points).
inline constexpr double kNegligibleTermEpsilons = 0.125;

namespace pge {

// Certified events: contacts scheduled within this relative distance of the earliest one are
// re-derived from the exact paths before it is processed (engine/src/world_impl.hpp,
// refine_near_top). Predictions from rounded states were seen 924 ulps (1e-13 relative) from
// the exact time; 2^-30 (9e-10) leaves a margin of four orders of magnitude.
inline constexpr double kRefineWindowRelative = 0x1p-30;
// ... and never narrower than this many ulps of the scalar: in float, 2^-30 is below one ulp
// (2^-23 at 1), so only exact ties were re-derived and every sibling search bounded by the
// window (world_refine.hpp, off_feature_contact) was empty (a ball at a segment's end in float,
// its vertex contact kept 1 ulp after the edge's exact crossing: scripts/edge-end-sweep.py seed
// 2, end-179; 64 ulps were not enough). Double and wider keep 2^-30 (256 ulps of double are
// 5.7e-14).
inline constexpr double kRefineWindowUlps = 256;

// Robust and certified: a line contact (a circle or a vertex against an edge: a distance to a
// line, quadratic in time) whose rounded function has a local minimum within this fraction of
// the magnitude of the terms it is computed from ((coordinates + radius + displacement) times
// the edge's length) is a near-graze: whether the exact paths cross there, or only come within
// rounding, is decided from them (engine/src/refine.hpp, exact_line_graze), not by the rounding
// (a ball or box touching a ceiling at the apex of its bounce: a phantom or a miss). Dimensionless;
// the value of refine.hpp's kNearGrazeRelative for two circles: far above the rounding of the
// coefficients (a few hundred ulps of their scale), far below any real miss. Larger only sends
// more predictions to the exact signs (slower, never wrong); smaller leaves more to the rounding.
inline constexpr double kLineGrazeRelative = 0x1p-36;

}  // namespace pge

namespace pge {

// Bodies a World accepts. Without the broad phase (BroadPhase::AllPairs) the first schedule
// predicts every pair once: n (n - 1) / 2 predictions, 5e9 for 1e5 bodies (about two minutes)
// but 5e11 for a million (hours, a hang to any user). With the grid the cost is linear, and the
// limit is memory: about 0.75 KB per circle (World::memory_bytes: 733 to 749 bytes measured by
// bench_scale), 0.75 GB for a million. Larger
// scenes are refused with UnsupportedScene.
inline constexpr std::size_t kMaxBodiesWithoutBroadPhase = 100000;
inline constexpr std::size_t kMaxBodies = 1000000;

// Vertices of one polygon, at most. Predicting a pair of polygons tests every vertex of each
// against every edge of the other (engine/src/contact_polygon.hpp): 2 n m quadratics, about
// 20 ns each. Measured (pge run, robust, double, two moving regular n-gons passing 1e-7 inside
// their bounding circles, which makes exactly one prediction of the pair): one prediction takes
// 0.04 to 0.08 s at n = m = 1024, 0.26 s at 2048 and 1.6 to 1.9 s at 4096 (run time less that
// of the same scene ending before the pair can meet; the cost grows faster than n^2 once the
// pair's data leaves the cache); a collision of two polygons costs a few
// predictions, and two 100,000-gons took 40 minutes. 1024 keeps one prediction well under a
// tenth of a second; a body rounder than that is better modelled as a circle. The limit also
// keeps every feature index (a vertex or edge number, below n) inside the 16-bit feature
// fields of pge/event.hpp: a 70,000-gon had reported its edge 68,055 as 2,519. validate_scene
// refuses a larger polygon (field "polygon.vertices").
inline constexpr std::size_t kMaxPolygonVertices = 1024;

// BroadPhase::Auto uses the grid from this many moving bodies on. Measured (bench_scale,
// gas_grid/N against gas_all_pairs/N, robust, double): the grid is already faster at 16 discs
// (8.6 against 9.3 us per event) and at 128 twice as fast; smaller scenes keep all pairs, where
// the difference is noise and no cell bookkeeping is simpler to follow.
inline constexpr std::size_t kGridMinMovingBodies = 16;

// Rotation (pge-scene/2). The rigorous sine and cosine (detail/interval.hpp) reduce an angle
// exactly only below 2^25 rad (3.4e7) in double; past it their enclosure is [-1, 1] and no
// contact of the body can be decided. A starting angle is at most kMaxAngle in magnitude and a
// rate at most kMaxAngularVelocity (1,600 turns a second), so that a body starting at the limit
// turns for 54 minutes of simulated time without an event before it reaches 2^25. Both are 0 or of
// magnitude at least kMinSceneScale, like every other value. A body's inertia lies in
// [kMinSceneScale, kMaxSceneMagnitude] like its mass.
inline constexpr double kMaxAngle = 1e6;
inline constexpr double kMaxAngularVelocity = 1e4;

// A rotating pair's search window (engine/src/world_rotation.hpp), in multiples of the pair's
// reaches' sum closed at its present closing speed; past it the pair is predicted again. Larger:
// longer searches (each costs about a box per turn or near miss in its window, and the features
// too far from their edges to touch within it are not searched at all), fewer re-predictions;
// smaller: the reverse. Nothing is missed either way: the next window starts where this one
// ended. Measured on the 20-polygon spinning gas (docs/rotation.md, before the support test
// of predict_rotating.hpp): 8 reaches 486 events/s (5,417 predictions), 4: 571 (5,722), 2: 672
// (6,833), 1: 747 (9,668), the same state hash each time. On the 1,000-polygon spinning gas
// (bench_scale spinning_polygons/1000, 2026-12-07, release builds alternated): 2 reaches 1,670-
// 1,690 events/s, 1: 2,190-2,270, 0.7: 2,400-2,450, 0.5: 2,410-2,550, 0.35: 2,500-2,510 (19.8
// predictions per event at 1, 27.5 at 0.5): robust and certified take 0.5. Certified's contact
// times are correctly rounded, so its events do not depend on the window; robust's are placed
// within a few ulps by a narrowing whose last ulps depend on the bracket it starts from, so a
// chaotic gas may go another way (docs/rotation.md). The fast solver keeps 1: its conservative
// advancement costs differently, and its contrast runs stay as they were.
inline constexpr double kRotatingWindowReaches = 0.5;
inline constexpr double kFastRotatingWindowReaches = 1;

// How many times a rotating collision's impulse may grow (by an ulp, then 4, 16, ... times
// more) while the struck point's exact normal velocity after it still approaches
// (engine/src/world_rotation.hpp, collide_rotating): 4^12 ulps is far past any rounding of the
// impulse's terms.
inline constexpr int kMaxImpulseLifts = 12;

}  // namespace pge
