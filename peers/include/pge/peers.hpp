// Peers: the same scene run by Box2D (2.4.1) and Chipmunk (7.0.3), fixed-step engines, and by
// PGE, measured the same way (issue 11). The adapters are compiled only where the Debian packages
// libbox2d-dev and libchipmunk-dev are installed (PGE_HAVE_BOX2D, PGE_HAVE_CHIPMUNK); without them
// installed_peers() leaves them out and run_setting() returns an Outcome whose `error` says so.
// A third, "box2d3" (Box2D v3, its C API), is compiled when the build is pointed at a Box2D v3
// build (PGE_BOX2D3_INCLUDE_DIR and PGE_BOX2D3_LIBRARY; scripts/build-box2d3.sh sets both).
//
// How each peer is set up (the most favourable settings for accuracy; peers.cpp and the adapters
// say why for each):
//  - friction 0, linear and angular damping 0, no sleeping;
//  - rotation as PGE has it (pge-scene/2, docs/rotation.md): a body that rotates in PGE turns in
//    the peer, from its angle and angular velocity, about PGE's pivot (a moving polygon's area
//    centroid, a moving segment's midpoint) with PGE's moment of inertia (rigid_frame below): the
//    peer body's origin is the pivot and its centre of mass is there (Box2D SetMassData, centre 0;
//    Chipmunk's centre of gravity, 0), and positions are read back in the scene's terms (the
//    reference point, pivot - R(angle) pivot offset). A fixed body that spins is a kinematic body
//    turning at its constant rate. Every other body keeps fixed rotation (Box2D) / an infinite
//    moment (Chipmunk), exactly as before rotation existed;
//  - restitution per pair = the smaller of the two bodies' (PGE's rule), overriding Box2D's max and
//    Chipmunk's product in a pre-solve callback;
//  - gravity and each body's own acceleration applied as a constant force m (g + a) every step;
//  - fixed bodies are static bodies; segments are two-sided edges (Box2D) / segment shapes of
//    radius 0 (Chipmunk);
//  - Box2D: every moving body a bullet (continuous collision against moving bodies too),
//    restitution threshold 0 (restitution applies at every approach speed), and the scene scaled
//    into Box2D's metre range (a power of two: peers/src/peer_sim.hpp, box2d_length_scale), since its slop and speed cap are compile-time
//    lengths (and b2_maxRotation caps a turn at a quarter turn per step: 0.5 pi hz rad/s); Chipmunk: collision slop a small fraction of the smallest body (its default, 0.1, is
//    an absolute length), collision bias its default.
#pragma once

#include "pge/scene_io.hpp"
#include "pge/trace.hpp"
#include "pge/vec2.hpp"

#include <optional>
#include <string>
#include <vector>

namespace pge::peers {

struct Setting {               // one way of running a scene
  std::string engine;          // "box2d", "chipmunk", "box2d3", "pge"
  std::string label;           // e.g. "box2d 240 Hz, 8+3 iterations" or "pge robust/double"
  double hz = 0;               // steps per simulated second (peers)
  int velocity_iterations = 0, position_iterations = 0;  // Box2D; Chipmunk uses velocity_iterations as its iterations
  std::string solver, scalar;  // pge rows: "robust" | "certified" | "fast"; "float" | "double" | "long-double" | "quad"
};

struct Outcome {
  Setting setting;
  std::string scene;
  double horizon = 0;          // simulated seconds
  double wall_seconds = 0;     // the stepping alone (peers: Step calls; PGE: world.step() loop)
  double energy_drift = 0;     // (E_end - E_start) / |E_start| (kinetic, I omega^2 / 2 included, + potential), signed
  double momentum_drift = 0;   // |P_end - P_start| / |P_start| (moving bodies; 0/0 -> 0)
  double penetration = 0;      // largest overlap seen at any step end, as a fraction of the smaller body's size
  int tunnelled = 0;           // moving bodies that passed through a fixed body (pge/tunnel.hpp), or ended
                               // inside one or outside the box of the fixed bodies they started in
  double final_error = 0;      // RMS of final position errors against the reference, / the scene's extent
  std::string reference;       // "pge certified double"
  std::string error;           // non-empty: not run (why)
  // Peers run with Record::StepTrace: the run as a step trace (pge/trace.hpp, steps mode: each
  // step's end time, every moving body's state then (in a scene with rotation its angle and
  // angular velocity too), the pairs the engine reported in the step; engine = the setting's
  // label), for the referee (pge/judge.hpp, which follows a turning body from each recorded angle and angular velocity). It is recorded between the
  // timed Step calls, so wall_seconds does not include it, but for Box2D's note of each contact
  // that begins (a callback inside Step: one vector append per beginning contact, recorded
  // whether a trace is asked for or not). Empty otherwise.
  std::optional<Trace> trace;
};

// Whether run_setting records a peer's run as a step trace too.
enum class Record : bool { Nothing, StepTrace };

// Subset of {"box2d", "chipmunk", "box2d3"}: the peers this build was compiled with.
std::vector<std::string> installed_peers();
// Whether `engine` ("box2d", "chipmunk", "pge") can run in this build.
bool available(const std::string& engine);
// The Debian package that provides a peer ("libbox2d-dev", "libchipmunk-dev"); for box2d3 (Box2D
// v3, not packaged in Debian 12) the script that builds it from a checkout.
std::string peer_package(const std::string& engine);

// Box2D: 60, 240 and 1000 Hz x 8+3 (its default) and 50+20 iterations; Chipmunk: the same rates x
// 10 (its default) and 50 iterations; Box2D v3: the same rates x 4 (its default) and 16 sub-steps
// (velocity_iterations holds them); pge: robust and certified, double. Empty for other names.
std::vector<Setting> default_settings(const std::string& engine);
// A PGE setting: solver "fast" | "robust" | "certified", scalar "float" | "double" |
// "long-double" | "quad"; labelled "pge SOLVER/SCALAR".
Setting pge_setting(const std::string& solver, const std::string& scalar);

// Runs `s` on the scene to `horizon` (<= 0: the scene's run.until) and measures it against the
// reference (computed here; pass one from reference_positions to share it between settings).
Outcome run_setting(const LoadedScene& scene, const Setting& s, double horizon);
Outcome run_setting(const LoadedScene& scene, const Setting& s, double horizon,
                    const std::vector<Vec2d>& reference, Record record = Record::Nothing);

// The reference final state: every body's position (the scene's terms: a turning body's
// reference point) at the horizon from PGE, certified solver, double, with no collision budget. On the scenes with exact answers (head-on, Newton's cradle, a
// bullet against an axis-parallel wall) this is the exact answer: their inputs are small dyadic
// numbers, every operation on them is exact, and the certified solver rounds each event time
// correctly (fixtures/scenes/simultaneous/cradle-5.json and scale/thin-wall-1e-4.json assert it
// against the exact oracle).
std::vector<Vec2d> reference_positions(const Scene& scene, double horizon);

// How a peer holds body b, PGE's way (docs/rotation.md): whether it turns (BodyDesc::rotates),
// the point it turns about relative to its position at angle 0 (a moving polygon's area
// centroid, a moving segment's midpoint, 0 for a fixed body), and its moment of inertia about
// that point (the scene's `inertia`, else a uniform lamina's, a segment a thin rod's, of its mass,
// from the engine's own pge/detail/rigid.hpp). A body that does not turn, and a fixed body's
// inertia (infinite): 0.
struct RigidFrame {
  bool rotates = false;
  Vec2d pivot;
  double inertia = 0;
};
RigidFrame rigid_frame(const BodyDesc& b);

// The measures, exposed for tests. Overlap depth of two bodies at the given positions (0 when
// apart): circles by centre distance, a circle against a polygon or segment by the signed
// distance of its centre, polygons and segments by separating-axis depth. The second form turns
// each body's shape by its angle (radians, about its position: a turning body's reference point,
// which turns with it) first.
double overlap_depth(const BodyDesc& a, Vec2d pa, const BodyDesc& b, Vec2d pb);
double overlap_depth(const BodyDesc& a, Vec2d pa, double angle_a, const BodyDesc& b, Vec2d pb, double angle_b);
// The size a penetration is measured in: a circle's radius, a polygon's inradius (the smallest
// distance from its vertex centroid to a side line), a segment's: infinite (it has no thickness).
double body_size(const BodyDesc& b);
// The diagonal of the bounding box of every body's shape at its start position.
double scene_extent(const Scene& scene);
// RMS over moving bodies of |p_i - q_i|, divided by `extent`.
double rms_error(const Scene& scene, const std::vector<Vec2d>& p, const std::vector<Vec2d>& q, double extent);

}  // namespace pge::peers
