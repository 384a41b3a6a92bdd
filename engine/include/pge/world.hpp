// The event-driven world: bodies on closed-form paths, jumping from one predicted event to
// the next.
//
// Units are the scene's (pge/scene.hpp): seconds, metres, kilograms, m/s, m/s^2, joules; any
// consistent set works, as nothing is converted. The scalar T is float, double, long double or
// pge::Quad (the instantiations below); the scene's doubles are rounded to T once. Usage:
//
//   pge::World<double> world(scene);          // throws std::invalid_argument, UnsupportedScene
//   world.on_collision([&](const pge::CollisionInfo<double>& c) {
//     std::printf("%s hit %s at t = %g s\n", world.body_id(c.a).c_str(), world.body_id(c.b).c_str(), c.time);
//   });
//   world.run();                               // to the scene's run.until
//   const pge::BodySnapshot<double> s = world.snapshot(0);   // body 0's state at time()
//
// A whole program (a ball dropped on a floor, stepped with pge/step_loop.hpp) with its output:
// docs/api.md, "pge/world.hpp and pge/step_loop.hpp" (docs/examples/world.cpp). Link pge::engine.
#pragma once

#include "pge/constants.hpp"
#include "pge/event.hpp"
#include "pge/roots.hpp"
#include "pge/scalar.hpp"
#include "pge/scene.hpp"
#include "pge/tunnel.hpp"
#include "pge/vec2.hpp"

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace pge {

// Thrown when a scene is valid but uses something this engine does not simulate yet.
struct UnsupportedScene : std::runtime_error {
  int body;  // index into Scene::bodies of the body it is about; -1 for the scene as a whole
  UnsupportedScene(int body_, const std::string& what) : std::runtime_error(what), body(body_) {}
};

// Which pairs the world predicts after an event (DESIGN.md, "Scale"). AllPairs: the moving body
// against every body, O(n) per event. Grid: against the bodies in the cells around it
// (broad_phase.hpp), O(1) per event for bodies of similar size. Auto: the grid from
// kGridMinMovingBodies moving bodies on, unless the environment variable PGE_BROAD_PHASE says
// "grid" or "all-pairs" (how the test suites are run with either).
enum class BroadPhase : std::uint8_t { Auto, AllPairs, Grid };
std::string_view broad_phase_name(BroadPhase b);  // "auto", "all-pairs", "grid"
// Parses "auto", "all-pairs", "grid"; false if unknown.
bool parse_broad_phase(std::string_view text, BroadPhase& out);

// What a World takes from its caller instead of the scene's "run" block (every default: the
// scene's).
struct WorldOptions {
  double until = -1;              // horizon in seconds; < 0: the scene's run.until
  std::optional<SolverKind> solver;  // nothing: the scene's run.solver
  std::uint64_t max_events = 0;   // collision budget; 0: the scene's run.max_events
  double frames_per_second = -1;  // < 0: the scene's run.frames_per_second; 0: none
  BroadPhase broad_phase = BroadPhase::Auto;
  // Test every path a moving body takes, from one change of its motion to the next and the last
  // to the end of the run, against the fixed bodies (pge/tunnel.hpp), listing each body that
  // passed through one in tunnels(): a few box tests per motion change. Always on in
  // PGE_VALIDATE builds, where a solver that promises every collision (robust, certified) throws
  // TunnelError at the first.
  bool watch_tunnels = false;
};

// What a world has processed so far (World::counts()); cumulative from construction.
struct EventCounts {
  std::uint64_t collisions = 0;   // impulses applied (approaching contacts)
  std::uint64_t grazes = 0;       // predicted contacts found not approaching at the time
  std::uint64_t overlap_starts = 0;  // collisions by the overlap rule
  std::uint64_t timers = 0;
  std::uint64_t frames = 0;
  std::uint64_t stale = 0;        // queue entries dropped because a partner had changed
  std::uint64_t predictions = 0;  // pair predictions computed
  std::uint64_t exact_predictions = 0;  // of those, near-grazes decided from the exact paths
  std::uint64_t rests = 0;        // contacts that put a body to rest on a fixed face
  std::uint64_t leaves = 0;       // resting bodies that slid off a face's end
  std::uint64_t crossings = 0;    // broad phase: a moving body moved to another cell
  std::uint64_t global_bodies = 0;  // broad phase: bodies the grid does not hold (broad_phase.hpp)
  // certified, pairs with a rotating body: predicted contact times whose rounding could not be
  // decided (docs/rotation.md); each kept the robust placement, within a few ulps.
  std::uint64_t undecided_roundings = 0;
  // robust and certified, pairs with a rotating body: impulses grown by a few ulps because the
  // struck point's exact normal velocity after the rounded one still approached (docs/rotation.md).
  std::uint64_t impulse_lifts = 0;
};

// The closed-form path the engine holds for a body: p(t) = p0 + v0 (t - t0) + acc (t - t0)^2 / 2
// for t >= t0 until an event changes it. For fixed bodies v0 = acc = 0 and t0 = 0. This is the
// state an exact referee reads (it never calls the engine's algebra).
// A body resting on fixed faces (resting contact, DESIGN.md) slides along them: acc is then its
// field acceleration without the components the faces hold (zero in a V of two faces), and
// `supports` names the fixed bodies it rests on (kNoBody when unused): the body and a support
// touch all along the path, which is no contact event.
// A rotating body (World::rotates) turns as well: its angle is theta0 + omega (t - t0) (t0 = 0 for
// a fixed body, which spins about its position), p0, v0, acc are its pivot's path (a moving
// polygon's centroid, a moving segment's midpoint), and its vertex k is at
// p(t) + R(angle) World::pivot_vertices(i)[k]. Both are 0 for a body that does not rotate.
template <class T> struct BodyMotion {
  T t0{};
  Vec2<T> p0, v0, acc;
  std::array<BodyIndex, 2> supports{kNoBody, kNoBody};
  T theta0{}, omega{};
};

// A body's state at the world's current time: the position of its reference point (the scene's
// `position`, which turns with a rotating body), the velocity of its centre of mass (a rotating
// body's pivot; the reference point's for a body that does not rotate), its angle (rad) and
// angular velocity (rad/s), 0 and 0 for a body that does not rotate.
template <class T> struct BodySnapshot {
  Vec2<T> position;
  Vec2<T> velocity;
  T angle{};
  T angular_velocity{};
};

// One run of one scene. Movable, not copyable. A world is used from one thread; the callbacks
// run on it, inside step(). Body indices (BodyIndex) are positions in Scene::bodies; every
// accessor taking one throws std::out_of_range for an index >= body_count().
template <class T> class World {
 public:
  using CollisionCallback = std::function<void(const CollisionInfo<T>&)>;
  using TimerCallback = std::function<void(World&, T time)>;
  using FrameCallback = std::function<void(const World&, T time)>;
  // A body's motion changed at `time` other than by a collision: it slid off a face it rested
  // on, or set_velocity replaced its velocity.
  using MotionCallback = std::function<void(BodyIndex body, T time)>;

  // Throws std::invalid_argument for an invalid scene (see validate_scene) and
  // UnsupportedScene for shapes this version does not simulate.
  explicit World(const Scene& scene, const WorldOptions& options = {});
  ~World();
  World(World&&) noexcept;
  World& operator=(World&&) noexcept;
  World(const World&) = delete;
  World& operator=(const World&) = delete;

  // Each setter replaces the callback before it (one of each kind; an empty function: none).
  // on_collision: after every contact event, once the response is applied (CollisionInfo holds
  // the velocities before and after); also for a predicted contact found not approaching, with
  // impulse 0 (counted in EventCounts::grazes).
  void on_collision(CollisionCallback callback);
  // on_frame: at every frame event (WorldOptions::frames_per_second), which changes nothing.
  void on_frame(FrameCallback callback);
  void on_motion_change(MotionCallback callback);
  // Calls `callback` when simulated time reaches `time`, in seconds (ignored if before time() or
  // past the horizon). The callback may call set_velocity and stop().
  void add_timer(T time, TimerCallback callback);

  // Processes events until the horizon, the collision budget, a storm, or stop(); returns why it
  // stopped (also stop_reason()). Do not call run() or step() from a callback.
  StopReason run();
  // Processes the next event; false when the run is over (see stop_reason()). Calling it again
  // after false does nothing and returns false.
  bool step();
  void stop();  // from a callback: end the run after the current event

  // Simulated time, seconds: the last processed event's (collision, timer or frame); 0 before
  // the first step; the horizon once the run reached it.
  T time() const;
  T horizon() const;  // seconds: WorldOptions::until, else the scene's run.until
  StopReason stop_reason() const;  // meaningful once step() has returned false
  const StormInfo<T>& storm() const;  // when stop_reason() is EventStorm: where and when
  const EventCounts& counts() const;
  // The bodies that passed through a fixed body, each once, in the order found; the paths still
  // running are tested when the run ends (step() returns false). Empty unless watched
  // (WorldOptions::watch_tunnels or a PGE_VALIDATE build).
  const std::vector<Tunnel>& tunnels() const;

  std::size_t body_count() const;  // Scene::bodies.size()
  const std::string& body_id(BodyIndex i) const;  // the scene's id
  bool is_fixed(BodyIndex i) const;
  T mass(BodyIndex i) const;  // 0 for fixed bodies (infinite mass)
  BodySnapshot<T> snapshot(BodyIndex i) const;  // at time()
  BodyMotion<T> motion(BodyIndex i) const;
  // The acceleration of the body's field (its own plus gravity), which potential energy is
  // measured in; motion().acc differs from it while the body rests on a face. Zero when fixed.
  Vec2<T> field_acceleration(BodyIndex i) const;
  ShapeKind shape(BodyIndex i) const;
  T radius(BodyIndex i) const;       // circles; 0 otherwise
  T restitution(BodyIndex i) const;  // the body's own, or the world default it took
  // Shape vertices relative to the body's position, as given in the scene (segment: a, b).
  const std::vector<Vec2<T>>& local_vertices(BodyIndex i) const;
  // For fixed bodies, the world coordinates the engine predicts with (position + local vertex,
  // rounded once at construction); empty for moving bodies.
  const std::vector<Vec2<T>>& world_vertices(BodyIndex i) const;
  // Rotation (docs/rotation.md). Whether the body turns; its vertices about its pivot in its own
  // frame (empty if it does not rotate); its pivot relative to the scene's position at angle 0;
  // its moment of inertia about the pivot (kg m^2; 0 for fixed and non-rotating bodies).
  bool rotates(BodyIndex i) const;
  const std::vector<Vec2<T>>& pivot_vertices(BodyIndex i) const;
  Vec2<T> pivot(BodyIndex i) const;
  T inertia(BodyIndex i) const;
  SolverKind solver() const;
  BroadPhase broad_phase() const;  // AllPairs or Grid: what Auto chose
  // Bytes the world holds for its bodies, queues and grid (capacities; shapes' vertex lists
  // included), for the memory-per-body figures.
  std::size_t memory_bytes() const;
  // Replaces a moving body's velocity (m/s) at time() and reschedules it (for timer callbacks);
  // calls the motion-change callback. Throws std::invalid_argument for a fixed body.
  void set_velocity(BodyIndex i, Vec2<T> velocity);

  // Kinetic energy, potential energy of each body's constant acceleration field, and total
  // momentum of the moving bodies, at time(): joules (sum m |v|^2 / 2, plus I w^2 / 2 for a
  // rotating body; sum -m a . p with p the centre of mass, so m g y under gravity (0, -g)) and
  // kg m / s, in T's arithmetic.
  T kinetic_energy() const;
  T potential_energy() const;
  Vec2<T> momentum() const;

  // The largest overlap of any pair at time(): its depth, the depth as a fraction of the contact
  // distance (radius sum; a circle's radius against a wall or polygon; the smaller size of two
  // polygons or segments, a size being the larger side of the bounding box), and the depth in
  // units of the pair's rounding, epsilon(T) * (largest coordinate magnitude of the pair's
  // centres and vertices + |relative velocity| * |time| + contact distance): the second term is
  // how far the pair closes in the rounding of the clock. Polygon pairs are measured by the
  // separating-axis depth. The engine promises ulps <= kOverlapBoundUlps (constants.hpp) beyond
  // what the scene starts with (overlap_past_bound below).
  // O(n^2): for checks only.
  struct Overlap { T depth{}; T relative{}; T ulps{}; BodyIndex a = kNoBody, b = kNoBody; };
  Overlap largest_overlap() const;
  // The largest overlap seen at any collision so far (measured at the contact time).
  Overlap largest_contact_overlap() const;

  // A hash over the exact bits of time() and every body's position and velocity at time() (the
  // path's point: a rotating body's pivot, then its angle and angular velocity): two runs of one
  // scene and build give the same hash (what the golden-hash tests compare).
  std::uint64_t state_hash() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// The overlap invariant: an overlap is a failure when it is deeper than the scene's overlap at
// the start (World::largest_overlap() before the first step; PGE_VALIDATE builds and the fuzz invariants
// check overlaps this way) by more than kOverlapBoundUlps
// (in the pair's ulps: `ulps` is `depth` in those units). A scene may start overlapping by up to
// kStartOverlapTolerance of a contact distance, far more than the bound, and such an overlap
// stays until the pair separates: a body resting in a V it overlaps never does (found by
// fuzz_engine: fixtures/regressions/rest-in-v-overlapping-at-the-start.json). The engine must
// not make an overlap; it need not undo one it was given.
inline bool overlap_past_bound(double ulps, double depth, double start_depth) {
  return ulps > kOverlapBoundUlps && (depth - start_depth) * (ulps / depth) > kOverlapBoundUlps;
}

extern template class World<float>;
extern template class World<double>;
extern template class World<long double>;
extern template class World<Quad>;

}  // namespace pge
