// Peers: the same scene run by Box2D (2.4.1) and Chipmunk (7.0.3), fixed-step engines, and by
// PGE, measured the same way (issue 11). The adapters are compiled only where the Debian packages
// libbox2d-dev and libchipmunk-dev are installed (PGE_HAVE_BOX2D, PGE_HAVE_CHIPMUNK); without them
// installed_peers() leaves them out and run_setting() returns an Outcome whose `error` says so.
//
// How each peer is set up (the most favourable settings for accuracy; peers.cpp and the adapters
// say why for each):
//  - friction 0, linear damping 0, no sleeping, fixed rotation (PGE bodies translate only);
//  - restitution per pair = the smaller of the two bodies' (PGE's rule), overriding Box2D's max and
//    Chipmunk's product in a pre-solve callback;
//  - gravity and each body's own acceleration applied as a constant force m (g + a) every step;
//  - fixed bodies are static bodies; segments are two-sided edges (Box2D) / segment shapes of
//    radius 0 (Chipmunk);
//  - Box2D: every moving body a bullet (continuous collision against moving bodies too),
//    restitution threshold 0 (restitution applies at every approach speed), and the scene scaled
//    into Box2D's metre range (a power of two: peers/src/peer_sim.hpp, box2d_length_scale), since its slop and speed cap are compile-time
//    lengths; Chipmunk: collision slop a small fraction of the smallest body (its default, 0.1, is
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
  std::string engine;          // "box2d", "chipmunk", "pge"
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
  double energy_drift = 0;     // (E_end - E_start) / |E_start| (kinetic + potential), signed
  double momentum_drift = 0;   // |P_end - P_start| / |P_start| (moving bodies; 0/0 -> 0)
  double penetration = 0;      // largest overlap seen at any step end, as a fraction of the smaller body's size
  int tunnelled = 0;           // moving bodies that passed through a fixed body (pge/tunnel.hpp), or ended
                               // inside one or outside the box of the fixed bodies they started in
  double final_error = 0;      // RMS of final position errors against the reference, / the scene's extent
  std::string reference;       // "pge certified double"
  std::string error;           // non-empty: not run (why)
  // Peers run with Record::StepTrace: the run as a step trace (pge/trace.hpp, steps mode: each
  // step's end time, every moving body's state then, the pairs the engine reported in the step;
  // engine = the setting's label), for the referee (pge/judge.hpp). It is recorded between the
  // timed Step calls, so wall_seconds does not include it, but for Box2D's note of each contact
  // that begins (a callback inside Step: one vector append per beginning contact, recorded
  // whether a trace is asked for or not). Empty otherwise.
  std::optional<Trace> trace;
};

// Whether run_setting records a peer's run as a step trace too.
enum class Record : bool { Nothing, StepTrace };

// Subset of {"box2d", "chipmunk"}: the peers this build was compiled with.
std::vector<std::string> installed_peers();
// Whether `engine` ("box2d", "chipmunk", "pge") can run in this build.
bool available(const std::string& engine);
// The Debian package that provides a peer ("libbox2d-dev", "libchipmunk-dev").
std::string peer_package(const std::string& engine);

// Box2D: 60, 240 and 1000 Hz x 8+3 (its default) and 50+20 iterations; Chipmunk: the same rates x
// 10 (its default) and 50 iterations; pge: robust and certified, double. Empty for other names.
std::vector<Setting> default_settings(const std::string& engine);
// A PGE setting: solver "fast" | "robust" | "certified", scalar "float" | "double" |
// "long-double" | "quad"; labelled "pge SOLVER/SCALAR".
Setting pge_setting(const std::string& solver, const std::string& scalar);

// Runs `s` on the scene to `horizon` (<= 0: the scene's run.until) and measures it against the
// reference (computed here; pass one from reference_positions to share it between settings).
Outcome run_setting(const LoadedScene& scene, const Setting& s, double horizon);
Outcome run_setting(const LoadedScene& scene, const Setting& s, double horizon,
                    const std::vector<Vec2d>& reference, Record record = Record::Nothing);

// The reference final state: every body's position at the horizon from PGE, certified solver,
// double, with no collision budget. On the scenes with exact answers (head-on, Newton's cradle, a
// bullet against an axis-parallel wall) this is the exact answer: their inputs are small dyadic
// numbers, every operation on them is exact, and the certified solver rounds each event time
// correctly (fixtures/scenes/simultaneous/cradle-5.json and scale/thin-wall-1e-4.json assert it
// against the exact oracle).
std::vector<Vec2d> reference_positions(const Scene& scene, double horizon);

// The measures, exposed for tests. Overlap depth of two bodies at the given positions (0 when
// apart): circles by centre distance, a circle against a polygon or segment by the signed
// distance of its centre, polygons and segments by separating-axis depth.
double overlap_depth(const BodyDesc& a, Vec2d pa, const BodyDesc& b, Vec2d pb);
// The size a penetration is measured in: a circle's radius, a polygon's inradius (the smallest
// distance from its vertex centroid to a side line), a segment's: infinite (it has no thickness).
double body_size(const BodyDesc& b);
// The diagonal of the bounding box of every body's shape at its start position.
double scene_extent(const Scene& scene);
// RMS over moving bodies of |p_i - q_i|, divided by `extent`.
double rms_error(const Scene& scene, const std::vector<Vec2d>& p, const std::vector<Vec2d>& q, double extent);

}  // namespace pge::peers
