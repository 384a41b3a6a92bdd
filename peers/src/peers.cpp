// Settings, the shared measures, and the run loops for PGE and the fixed-step peers.
#include "pge/peers.hpp"

#include "peer_sim.hpp"
#include "pge/detail/rigid.hpp"
#include "pge/step_loop.hpp"
#include "pge/tunnel.hpp"
#include "pge/world.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>

namespace pge::peers {
namespace {

using Clock = std::chrono::steady_clock;
using detail::field_acceleration;

// Steps per simulated second and (velocity, position) iterations offered by default: each peer's
// own default iteration count and a high one, at a game's 60 Hz, 240 Hz and 1 kHz.
constexpr double kRates[] = {60, 240, 1000};
constexpr int kBox2dDefault[2] = {8, 3}, kBox2dHigh[2] = {50, 20};
constexpr int kChipmunkDefault = 10, kChipmunkHigh = 50;
// Box2D v3 has no iteration counts but sub-steps per step: its default, 4, and a high one.
constexpr int kBox2d3Default = 4, kBox2d3High = 16;

constexpr double kInf = std::numeric_limits<double>::infinity();

// Totals are summed in a type wider than the state they measure (long double for float, double
// and long double states, quad for quad), the same for PGE and the peers: a float world's energy
// summed in float would hide drifts below float's resolution.
template <class T> using Wide = std::conditional_t<std::is_same_v<T, Quad>, Quad, long double>;

template <class U> struct Totals {
  U energy = U(0);
  Vec2<U> momentum;
};

// What the totals read of a moving body: its centre of mass (a body that does not turn: its
// position), the velocity of it, and I omega^2 (0 for a body that does not turn).
template <class P> struct MassState {
  Vec2<P> centre, v;
  P spin2{};
};

// Kinetic (I omega^2 / 2 included) + potential energy (potential -m a . c of each body's field
// at its centre of mass, as World measures it) and momentum of the moving bodies, in U. For a
// body that does not turn, spin2 is 0 and the sum is the translate-only one bit for bit.
template <class U, class P> Totals<U> totals(const Scene& scene, const std::vector<MassState<P>>& s) {
  Totals<U> t;
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    const BodyDesc& b = scene.bodies[i];
    if (b.fixed) continue;
    const U m(b.mass);
    const Vec2<U> vi = vec_cast<U>(s[i].v), ci = vec_cast<U>(s[i].centre), a = vec_cast<U>(field_acceleration(scene, b));
    t.energy += m * dot(vi, vi) / U(2) + U(s[i].spin2) / U(2) - m * dot(a, ci);
    t.momentum += vi * m;
  }
  return t;
}

// A peer's body at its reference point p and angle, moving at v and omega, as the totals read it.
MassState<double> mass_state(const RigidFrame& f, Vec2d p, double angle, Vec2d v, double omega) {
  if (!f.rotates) return {p, v, 0.0};
  return {p + rotated(angle, f.pivot), v, f.inertia * omega * omega};
}

double length(Vec2d v) { return std::hypot(v.x, v.y); }

// d / |base| as a double, computed in T (0 / 0 -> 0, d / 0 -> infinity).
template <class T> double relative_change(const T& d, const T& base) {
  if (base != T(0)) return to_double(d / (base < T(0) ? T(-base) : base));
  return d == T(0) ? 0.0 : kInf;
}

// Energy drift (signed) and momentum drift, in the type the totals were summed in (a quad run's
// drift of 1e-33 would vanish in double differences).
template <class U> void set_drifts(Outcome& o, const Totals<U>& start, const Totals<U>& end) {
  using std::sqrt;
  const Vec2<U> dp = end.momentum - start.momentum;
  o.energy_drift = relative_change(U(end.energy - start.energy), start.energy);
  o.momentum_drift = relative_change(U(sqrt(dot(dp, dp))), U(sqrt(dot(start.momentum, start.momentum))));
}

// A shape placed in the world: a circle, or a convex polygon (a segment: 2 vertices).
struct Placed {
  bool circle = false;
  Vec2d centre;
  double radius = 0;
  std::vector<Vec2d> v;
};

// The shape at reference point `at`, turned by `angle` about it (0: not turned, exactly).
Placed place(const BodyDesc& b, Vec2d at, double angle = 0) {
  const auto turn = [angle](Vec2d v) { return angle == 0 ? v : rotated(angle, v); };
  Placed s;
  switch (b.shape) {
    case ShapeKind::Circle: s.circle = true; s.centre = at; s.radius = b.radius; break;
    case ShapeKind::Segment: s.v = {turn(b.a) + at, turn(b.b) + at}; break;
    case ShapeKind::Polygon: for (const Vec2d& p : b.vertices) s.v.push_back(turn(p) + at); break;
  }
  return s;
}

// Distance from p to the segment [a, b].
double segment_distance(Vec2d p, Vec2d a, Vec2d b) {
  const Vec2d ab = b - a;
  const double len2 = dot(ab, ab);
  const double t = len2 > 0 ? std::clamp(dot(p - a, ab) / len2, 0.0, 1.0) : 0.0;
  return length(p - (a + ab * t));
}

// Signed distance from p to a convex polygon (counter-clockwise; negative inside) or a segment.
double signed_distance(Vec2d p, const std::vector<Vec2d>& v) {
  double outside = kInf;
  for (std::size_t k = 0; k < v.size(); ++k) outside = std::min(outside, segment_distance(p, v[k], v[(k + 1) % v.size()]));
  if (v.size() < 3) return outside;
  double inside = kInf;  // depth below the nearest side line, if inside every side
  for (std::size_t k = 0; k < v.size(); ++k) {
    const Vec2d e = v[(k + 1) % v.size()] - v[k];
    const double s = cross(e, p - v[k]) / length(e);  // > 0: on the inner side
    if (s < 0) return outside;
    inside = std::min(inside, s);
  }
  return -inside;
}

// Separating-axis depth of two convex vertex lists (segments included): the smallest overlap of
// their projections over the side normals of both; 0 if some axis separates them.
double sat_depth(const std::vector<Vec2d>& a, const std::vector<Vec2d>& b) {
  double depth = kInf;
  for (const auto* shape : {&a, &b})
    for (std::size_t k = 0; k < shape->size(); ++k) {
      const Vec2d e = (*shape)[(k + 1) % shape->size()] - (*shape)[k];
      const Vec2d n = perp(e) * (1 / length(e));
      double a0 = kInf, a1 = -kInf, b0 = kInf, b1 = -kInf;
      for (const Vec2d& p : a) a0 = std::min(a0, dot(p, n)), a1 = std::max(a1, dot(p, n));
      for (const Vec2d& p : b) b0 = std::min(b0, dot(p, n)), b1 = std::max(b1, dot(p, n));
      depth = std::min(depth, std::min(a1, b1) - std::max(a0, b0));
      if (depth <= 0) return 0;
    }
  return depth;
}

struct Box {
  Vec2d lo{kInf, kInf}, hi{-kInf, -kInf};
  void add(Vec2d p) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
  }
  bool contains(Vec2d p) const { return p.x >= lo.x && p.x <= hi.x && p.y >= lo.y && p.y <= hi.y; }
};

void add_shape(Box& box, const BodyDesc& b, Vec2d at, double angle) {
  const Placed s = place(b, at, angle);
  if (s.circle) {
    box.add(s.centre - Vec2d{s.radius, s.radius});
    box.add(s.centre + Vec2d{s.radius, s.radius});
  }
  for (const Vec2d& p : s.v) box.add(p);
}

// The point of a moving body the end test of tunnelling follows: its reference point, or for a
// turning polygon its centre of mass (inside it at every angle; the reference point turns with
// the body and may lie outside it), from the body at reference point p and angle.
Vec2d followed_point(const BodyDesc& b, const RigidFrame& f, Vec2d p, double angle) {
  return f.rotates && b.shape == ShapeKind::Polygon ? p + rotated(angle, f.pivot) : p;
}

// The end test of tunnelling, for every engine: a moving body whose followed point started
// inside the bounding box of the fixed bodies and ended outside it, or ended inside a fixed
// polygon or circle that does not turn.
bool escaped(const Scene& scene, const Box& fixed_box, Vec2d start, Vec2d end) {
  if (fixed_box.contains(start) && !fixed_box.contains(end)) return true;
  for (const BodyDesc& f : scene.bodies) {
    if (!f.fixed || f.rotates) continue;
    const Placed s = place(f, f.position);
    if (s.circle ? length(end - s.centre) < s.radius : (s.v.size() > 2 && signed_distance(end, s.v) < 0)) return true;
  }
  return false;
}

// The box of the fixed bodies; a fixed body that turns adds its shape at every angle (the box
// of its circle of reach about its position, its pivot).
Box fixed_bounds(const Scene& scene) {
  Box box;
  for (const BodyDesc& b : scene.bodies) {
    if (!b.fixed) continue;
    if (!b.rotates) {
      add_shape(box, b, b.position, 0);
      continue;
    }
    double reach = b.radius;
    for (const Vec2d& v : place(b, {}).v) reach = std::max(reach, length(v));
    box.add(b.position - Vec2d{reach, reach});
    box.add(b.position + Vec2d{reach, reach});
  }
  return box;
}

// Where each body starts, as the end test of tunnelling follows it (followed_point).
std::vector<Vec2d> followed_starts(const Scene& scene) {
  std::vector<Vec2d> out;
  for (const BodyDesc& b : scene.bodies) out.push_back(followed_point(b, rigid_frame(b), b.position, b.rotates ? b.angle : 0));
  return out;
}

double resolve_horizon(const Scene& scene, double horizon) { return horizon > 0 ? horizon : scene.run.until; }

template <class T>
Outcome run_pge_as(const Scene& scene, SolverKind solver, double horizon, const std::vector<Vec2d>& reference) {
  Outcome o;
  WorldOptions wo;
  wo.until = horizon;
  wo.max_events = std::numeric_limits<std::uint64_t>::max();  // to the horizon, as the peers run
  wo.frames_per_second = 0;
  wo.solver = solver;
  // Tunnelling is measured as for the peers (run_peer): a path of a body's interior point through
  // a fixed body, here along the engine's own arcs between motion changes.
  wo.watch_tunnels = true;
  World<T> world(scene, wo);
  const std::size_t n = scene.bodies.size();
  std::vector<Vec2<T>> p(n);
  std::vector<T> angle(n);
  std::vector<MassState<T>> m(n);
  const auto state = [&] {
    for (std::size_t i = 0; i < n; ++i) {
      const auto bi = static_cast<BodyIndex>(i);
      const BodySnapshot<T> b = world.snapshot(bi);
      p[i] = b.position;
      angle[i] = b.angle;
      m[i] = {b.position, b.velocity, T(0)};
      if (world.rotates(bi) && !world.is_fixed(bi))
        m[i] = {b.position + rotated(b.angle, world.pivot(bi)), b.velocity, world.inertia(bi) * b.angular_velocity * b.angular_velocity};
    }
    return totals<Wide<T>>(scene, m);
  };
  // state() leaves p and angle at the end positions and angles: the end measures below read them.
  const auto stepped = step_to_end(world, [&](const World<T>&) { return state(); });
  o.wall_seconds = stepped.wall_seconds;
  if (stepped.stop == StopReason::EventStorm) o.error = "event storm";
  set_drifts(o, stepped.start, stepped.end);
  std::vector<char> crossed(n, 0);
  for (const Tunnel& t : world.tunnels()) crossed[t.body] = 1;
  o.penetration = to_double(world.largest_contact_overlap().relative);
  std::vector<Vec2d> end(n);
  const Box box = fixed_bounds(scene);
  const std::vector<Vec2d> starts = followed_starts(scene);
  for (std::size_t i = 0; i < n; ++i) {
    end[i] = {to_double(p[i].x), to_double(p[i].y)};
    const BodyDesc& b = scene.bodies[i];
    if (!b.fixed && (crossed[i] || escaped(scene, box, starts[i], followed_point(b, rigid_frame(b), end[i], to_double(angle[i])))))
      ++o.tunnelled;
  }
  o.final_error = rms_error(scene, end, reference, scene_extent(scene));
  return o;
}

Outcome run_pge(const Scene& scene, const Setting& s, double horizon, const std::vector<Vec2d>& reference) {
  SolverKind solver{};
  if (!parse_solver_kind(s.solver, solver)) throw std::invalid_argument("unknown PGE solver \"" + s.solver + "\"");
  ScalarKind scalar = ScalarKind::Double;
  if (!s.scalar.empty() && !parse_scalar_kind(s.scalar, scalar))
    throw std::invalid_argument("unknown PGE scalar \"" + s.scalar + "\"");
  return with_scalar(scalar, [&](auto type) {
    return run_pge_as<typename decltype(type)::type>(scene, solver, horizon, reference);
  });
}

// A step trace of a peer's run (pge/trace.hpp), its header filled: the moving bodies, in order.
Trace step_trace_header(const Scene& scene, const Setting& s, const std::vector<std::size_t>& moving, std::uint64_t steps) {
  Trace t;
  t.mode = TraceMode::Steps;
  t.engine = s.label;
  t.scene = scene.name;
  for (std::size_t i : moving) t.bodies.push_back(scene.bodies[i].id);
  t.steps.reserve(static_cast<std::size_t>(steps));
  return t;
}

// Appends the step that ended at t: the moving bodies' states (positions and angles already read
// into p and angle; in a scene with rotation each body's angle and angular velocity too, as the
// peer holds them: 0, 0 for a body with fixed rotation) and the pairs the peer reported in it.
void record_step(Trace& trace, const Scene& scene, const detail::PeerSim& sim, double t, const std::vector<std::size_t>& moving,
                 const std::vector<Vec2d>& p, const std::vector<double>& angle, bool rotation,
                 std::vector<std::pair<std::size_t, std::size_t>>& scratch) {
  TraceStep& step = trace.steps.emplace_back();
  step.t = t;
  step.bodies.reserve(moving.size());
  for (std::size_t i : moving) step.bodies.push_back({p[i], sim.velocity(i)});
  if (rotation)
    for (std::size_t i : moving)
      step.turns.push_back({scene.bodies[i].rotates ? angle[i] : sim.angle(i), sim.angular_velocity(i)});
  sim.reported_pairs(scratch);
  for (const auto& [a, b] : scratch) step.contacts.push_back({scene.bodies[a].id, scene.bodies[b].id});
}

Outcome run_peer(const Scene& scene, const Setting& s, double horizon, const std::vector<Vec2d>& reference, Record record) {
  Outcome o;
  if (!(s.hz > 0)) throw std::invalid_argument("a peer setting needs a step rate (hz > 0)");
  std::unique_ptr<detail::PeerSim> sim;
#ifdef PGE_HAVE_BOX2D
  if (s.engine == "box2d") sim = detail::make_box2d(scene, s);
#endif
#ifdef PGE_HAVE_CHIPMUNK
  if (s.engine == "chipmunk") sim = detail::make_chipmunk(scene, s);
#endif
#ifdef PGE_HAVE_BOX2D3
  if (s.engine == "box2d3") sim = detail::make_box2d3(scene, s);
#endif
  if (!sim) throw std::logic_error("no adapter for engine \"" + s.engine + "\"");
  const std::size_t n = scene.bodies.size();
  std::vector<Vec2d> p(n);
  std::vector<double> angle(n, 0.0);
  std::vector<RigidFrame> frames(n);
  std::vector<std::size_t> moving, turning;  // turning: moving or fixed
  std::vector<MassState<double>> m(n);
  for (std::size_t i = 0; i < n; ++i) {
    const BodyDesc& b = scene.bodies[i];
    frames[i] = rigid_frame(b);
    p[i] = b.position;
    if (frames[i].rotates) angle[i] = b.angle, turning.push_back(i);
    if (b.fixed) continue;
    moving.push_back(i);
    m[i] = mass_state(frames[i], p[i], angle[i], b.velocity, frames[i].rotates ? b.angular_velocity : 0.0);
  }
  const Totals<long double> start = totals<long double>(scene, m);
  const auto steps = static_cast<std::uint64_t>(std::max(1.0, std::round(horizon * s.hz)));
  const double dt = horizon / static_cast<double>(steps);
  const FixedBodies fixed(scene);
  std::vector<char> crossed(n, 0);
  std::vector<std::pair<std::size_t, std::size_t>> touching;
  if (record == Record::StepTrace) o.trace = step_trace_header(scene, s, moving, steps);
  std::vector<Vec2d> prev = followed_starts(scene);
  double wall = 0;
  for (std::uint64_t k = 0; k < steps; ++k) {
    const auto t0 = Clock::now();
    sim->step(dt);
    wall += std::chrono::duration<double>(Clock::now() - t0).count();
    for (std::size_t i : turning) angle[i] = sim->angle(i);
    for (std::size_t i : moving) p[i] = sim->position(i);
    // Untimed, as the measures below: the trace costs the timed run nothing.
    if (o.trace) record_step(*o.trace, scene, *sim, dt * static_cast<double>(k + 1), moving, p, angle, !turning.empty(), touching);
    sim->touching_pairs(touching);
    for (const auto& [a, b] : touching) {
      const double depth = overlap_depth(scene.bodies[a], p[a], angle[a], scene.bodies[b], p[b], angle[b]);
      if (depth > 0) o.penetration = std::max(o.penetration, depth / std::min(body_size(scene.bodies[a]), body_size(scene.bodies[b])));
    }
    // A turning polygon's centre of mass is followed (followed_point), a turning segment not at
    // all (it has no interior point, as a moving segment that does not turn: pge/tunnel.hpp).
    for (std::size_t i : moving) {
      const BodyDesc& b = scene.bodies[i];
      const Vec2d at = followed_point(b, frames[i], p[i], angle[i]);
      if (!crossed[i]) {
        const PositionPath path = straight_path(prev[i], at);
        const BodyIndex hit = !frames[i].rotates                  ? fixed.passed_through(static_cast<BodyIndex>(i), path)
                              : b.shape == ShapeKind::Polygon ? fixed.point_passed_through({}, path)
                                                               : kNoBody;
        if (hit != kNoBody) crossed[i] = 1;
      }
      prev[i] = at;
    }
  }
  o.wall_seconds = wall;
  for (std::size_t i : moving) m[i] = mass_state(frames[i], p[i], angle[i], sim->velocity(i), sim->angular_velocity(i));
  set_drifts(o, start, totals<long double>(scene, m));
  const Box box = fixed_bounds(scene);
  const std::vector<Vec2d> starts = followed_starts(scene);
  for (std::size_t i : moving)
    if (crossed[i] || escaped(scene, box, starts[i], followed_point(scene.bodies[i], frames[i], p[i], angle[i]))) ++o.tunnelled;
  o.final_error = rms_error(scene, p, reference, scene_extent(scene));
  return o;
}

std::string iterations_label(const Setting& s) {
  if (s.engine == "box2d") return std::to_string(s.velocity_iterations) + "+" + std::to_string(s.position_iterations) + " iterations";
  if (s.engine == "box2d3") return std::to_string(s.velocity_iterations) + " sub-steps";
  return std::to_string(s.velocity_iterations) + " iterations";
}

Setting peer_setting(const std::string& engine, double hz, int vi, int pi) {
  Setting s;
  s.engine = engine;
  s.hz = hz;
  s.velocity_iterations = vi;
  s.position_iterations = pi;
  s.label = engine + " " + std::to_string(static_cast<int>(hz)) + " Hz, " + iterations_label(s);
  return s;
}

}  // namespace

std::vector<std::string> installed_peers() {
  std::vector<std::string> out;
#ifdef PGE_HAVE_BOX2D
  out.emplace_back("box2d");
#endif
#ifdef PGE_HAVE_CHIPMUNK
  out.emplace_back("chipmunk");
#endif
#ifdef PGE_HAVE_BOX2D3
  out.emplace_back("box2d3");
#endif
  return out;
}

bool available(const std::string& engine) {
  if (engine == "pge") return true;
  const auto peers = installed_peers();
  return std::find(peers.begin(), peers.end(), engine) != peers.end();
}

std::string peer_package(const std::string& engine) {
  if (engine == "box2d") return "libbox2d-dev";
  if (engine == "chipmunk") return "libchipmunk-dev";
  if (engine == "box2d3") return "a Box2D v3 build: scripts/build-box2d3.sh CHECKOUT";
  return "";
}

Setting pge_setting(const std::string& solver, const std::string& scalar) {
  Setting s;
  s.engine = "pge";
  s.solver = solver;
  s.scalar = scalar;
  s.label = "pge " + solver + "/" + scalar;
  return s;
}

std::vector<Setting> default_settings(const std::string& engine) {
  std::vector<Setting> out;
  if (engine == "pge") {
    for (const char* solver : {"robust", "certified"}) out.push_back(pge_setting(solver, "double"));
  } else if (engine == "box2d") {
    for (double hz : kRates)
      for (const int* it : {kBox2dDefault, kBox2dHigh}) out.push_back(peer_setting(engine, hz, it[0], it[1]));
  } else if (engine == "chipmunk") {
    for (double hz : kRates)
      for (int it : {kChipmunkDefault, kChipmunkHigh}) out.push_back(peer_setting(engine, hz, it, 0));
  } else if (engine == "box2d3") {
    for (double hz : kRates)
      for (int it : {kBox2d3Default, kBox2d3High}) out.push_back(peer_setting(engine, hz, it, 0));
  }
  return out;
}

std::vector<Vec2d> reference_positions(const Scene& scene, double horizon) {
  WorldOptions wo;
  wo.until = resolve_horizon(scene, horizon);
  wo.max_events = std::numeric_limits<std::uint64_t>::max();
  wo.frames_per_second = 0;
  wo.solver = SolverKind::Certified;
  World<double> world(scene, wo);
  world.run();
  std::vector<Vec2d> out(scene.bodies.size());
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = world.snapshot(static_cast<BodyIndex>(i)).position;
  return out;
}

Outcome run_setting(const LoadedScene& scene, const Setting& s, double horizon) {
  const double h = resolve_horizon(scene.scene, horizon);
  if (!available(s.engine)) {
    Outcome o;
    o.setting = s;
    o.scene = scene.path;
    o.horizon = h;
    o.error = s.engine + " is not installed (Debian: " + peer_package(s.engine) + ")";
    return o;
  }
  return run_setting(scene, s, h, reference_positions(scene.scene, h));
}

Outcome run_setting(const LoadedScene& scene, const Setting& s, double horizon, const std::vector<Vec2d>& reference,
                    Record record) {
  const double h = resolve_horizon(scene.scene, horizon);
  Outcome o;
  try {
    if (s.engine == "pge") {
      o = run_pge(scene.scene, s, h, reference);
    } else if (!available(s.engine)) {
      o.error = s.engine.empty() ? "no engine named" : s.engine + " is not installed (Debian: " + peer_package(s.engine) + ")";
    } else {
      o = run_peer(scene.scene, s, h, reference, record);
    }
  } catch (const detail::PeerUnsupported& e) {
    o = Outcome{};
    o.error = s.engine + " cannot take this scene: " + e.what();
  }
  o.setting = s;
  o.scene = scene.path;
  o.horizon = h;
  o.reference = "pge certified double";
  return o;
}

RigidFrame rigid_frame(const BodyDesc& b) {
  RigidFrame f;
  f.rotates = b.rotates;
  if (!b.rotates || b.fixed) return f;  // a fixed body turns about its position, with no inertia
  if (b.shape == ShapeKind::Circle) {   // no outline: no pivot offset, no lamina
    f.inertia = b.inertia > 0 ? b.inertia : 0.0;
    return f;
  }
  const pge::detail::TurningMass<double> m = pge::detail::turning_mass(
      b.shape == ShapeKind::Segment ? std::vector<Vec2d>{b.a, b.b} : b.vertices, b.mass, b.inertia);
  f.pivot = m.pivot;
  f.inertia = m.inertia;
  return f;
}

namespace detail {
PeerBody peer_body(const BodyDesc& d) {
  PeerBody out;
  out.frame = rigid_frame(d);
  out.origin = d.position;
  if (d.shape == ShapeKind::Segment) out.points = {d.a, d.b};
  if (d.shape == ShapeKind::Polygon) out.points = d.vertices;
  if (!out.frame.rotates) return out;
  out.origin = d.position + rotated(d.angle, out.frame.pivot);
  for (Vec2d& v : out.points) v -= out.frame.pivot;
  return out;
}

double box2d_length_scale(const Scene& scene, double hz, double linear_slop) {
  const double inf = std::numeric_limits<double>::infinity();
  double smallest = inf, fastest = 0, shortest_side = inf;
  const double extent = scene_extent(scene);
  for (const BodyDesc& b : scene.bodies) {
    for (std::size_t k = 0; k < b.vertices.size(); ++k)
      shortest_side = std::min(shortest_side, std::hypot(b.vertices[(k + 1) % b.vertices.size()].x - b.vertices[k].x,
                                                         b.vertices[(k + 1) % b.vertices.size()].y - b.vertices[k].y));
    if (b.fixed) continue;
    smallest = std::min(smallest, b.shape == ShapeKind::Segment ? std::hypot(b.b.x - b.a.x, b.b.y - b.a.y) : body_size(b));
    fastest = std::max(fastest, std::sqrt(dot(b.velocity, b.velocity) + 2 * std::hypot(field_acceleration(scene, b).x,
                                                                                      field_acceleration(scene, b).y) * extent));
  }
  double scale = std::isfinite(smallest) && smallest > 0 ? 1 / smallest : 1.0;
  if (fastest > 0) scale = std::min(scale, hz / fastest);  // at most 1 length unit per step
  // But every polygon side at least the linear slop: Box2D welds closer vertices (and asserts on
  // the degenerate hull). The shape wins over the speed: a faster body is then capped by
  // Box2D's speed limit, which the measures show.
  scale = std::exp2(std::floor(std::log2(scale)));
  if (std::isfinite(shortest_side) && scale * shortest_side < linear_slop)
    scale = std::exp2(std::ceil(std::log2(linear_slop / shortest_side)));
  return scale;
}
}  // namespace detail

double overlap_depth(const BodyDesc& a, Vec2d pa, const BodyDesc& b, Vec2d pb) { return overlap_depth(a, pa, 0, b, pb, 0); }

double overlap_depth(const BodyDesc& a, Vec2d pa, double angle_a, const BodyDesc& b, Vec2d pb, double angle_b) {
  const Placed sa = place(a, pa, angle_a), sb = place(b, pb, angle_b);
  double depth = 0;
  if (sa.circle && sb.circle) depth = sa.radius + sb.radius - length(sa.centre - sb.centre);
  else if (sa.circle) depth = sa.radius - signed_distance(sa.centre, sb.v);
  else if (sb.circle) depth = sb.radius - signed_distance(sb.centre, sa.v);
  else depth = sat_depth(sa.v, sb.v);
  return std::max(0.0, depth);
}

double body_size(const BodyDesc& b) {
  switch (b.shape) {
    case ShapeKind::Circle: return b.radius;
    case ShapeKind::Segment: return kInf;
    case ShapeKind::Polygon: {
      Vec2d c;
      for (const Vec2d& p : b.vertices) c += p;
      c = c * (1.0 / static_cast<double>(b.vertices.size()));
      return -signed_distance(c, b.vertices);
    }
  }
  return kInf;
}

double scene_extent(const Scene& scene) {
  Box box;
  for (const BodyDesc& b : scene.bodies) add_shape(box, b, b.position, b.rotates ? b.angle : 0);
  return box.lo.x <= box.hi.x ? length(box.hi - box.lo) : 0.0;
}

double rms_error(const Scene& scene, const std::vector<Vec2d>& p, const std::vector<Vec2d>& q, double extent) {
  double sum = 0;
  std::size_t n = 0;
  for (std::size_t i = 0; i < scene.bodies.size() && i < p.size() && i < q.size(); ++i) {
    if (scene.bodies[i].fixed) continue;
    const Vec2d d = p[i] - q[i];
    sum += dot(d, d);
    ++n;
  }
  if (n == 0) return 0;
  const double rms = std::sqrt(sum / static_cast<double>(n));
  return extent > 0 ? rms / extent : rms;
}

}  // namespace pge::peers
