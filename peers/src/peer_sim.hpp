// What peers.cpp needs from a fixed-step engine: step, read back, list touching and reported pairs. One
// implementation per peer (box2d_sim.cpp, chipmunk_sim.cpp), compiled only where it is installed.
#pragma once

#include "pge/peers.hpp"
#include "pge/scene.hpp"

#include <algorithm>
#include <cstddef>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace pge::peers::detail {

// A scene a peer cannot take (what() says which body and why).
struct PeerUnsupported : std::runtime_error {
  using std::runtime_error::runtime_error;
};

class PeerSim {
 public:
  virtual ~PeerSim() = default;
  // One step of dt simulated seconds, each moving body pushed by the constant force m (g + a).
  virtual void step(double dt) = 0;
  // Scene units, body i of the scene (fixed bodies: where they were put).
  virtual Vec2d position(std::size_t i) const = 0;
  virtual Vec2d velocity(std::size_t i) const = 0;
  // The body's angle (rad) and angular velocity (rad/s) as the peer holds them: a body with fixed
  // rotation or an infinite moment stays at 0, 0.
  virtual double angle(std::size_t i) const = 0;
  virtual double angular_velocity(std::size_t i) const = 0;
  // The pairs of scene bodies the engine holds as touching after the last step (lower index first).
  virtual void touching_pairs(std::vector<std::pair<std::size_t, std::size_t>>& out) const = 0;
  // The pairs the engine reported in contact during the last step, lower index first, each once:
  // what a step trace lists for the referee (pge/judge.hpp). Box2D: contacts that began in the
  // step (BeginContact, its continuous sub-steps included) or touch after it; Chipmunk: the
  // arbiters its collision handler pre-solved in the step.
  virtual void reported_pairs(std::vector<std::pair<std::size_t, std::size_t>>& out) const = 0;
};

// The acceleration field of a moving body: world gravity if it takes it, plus its own.
inline Vec2d field_acceleration(const Scene& scene, const BodyDesc& b) {
  return (b.gravity ? scene.world.gravity : Vec2d{}) + b.acceleration;
}
// Throws PeerUnsupported when polygon `d` has more vertices than the peer takes (`limit`: the
// peer's name for its bound, e.g. "Box2D takes at most b2_maxPolygonVertices").
inline void require_vertices_at_most(const BodyDesc& d, std::size_t most, const std::string& limit) {
  if (d.vertices.size() > most)
    throw PeerUnsupported("body \"" + d.id + "\": a polygon of " + std::to_string(d.vertices.size()) + " vertices; " +
                          limit + " = " + std::to_string(most));
}

// `out` with `more` appended, sorted and each pair once: what reported_pairs returns for a peer
// that reports the pairs touching after a step and those that began in it.
inline void add_pairs_once(std::vector<std::pair<std::size_t, std::size_t>>& out,
                           const std::vector<std::pair<std::size_t, std::size_t>>& more) {
  out.insert(out.end(), more.begin(), more.end());
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
}

// A body's restitution as PGE resolves it (< 0: the world's).
inline double restitution_of(const Scene& scene, const BodyDesc& b) {
  return b.restitution < 0 ? scene.world.restitution : b.restitution;
}

// A scene body as a peer is given it (peers.hpp, RigidFrame): the world position of the peer
// body's origin at the start (a turning body's pivot at the scene's angle, position + R(angle)
// pivot; any other body's position) and the shape's points about that origin, unturned (a
// polygon's vertices or a segment's two ends; none for a circle).
struct PeerBody {
  RigidFrame frame;
  Vec2d origin;
  std::vector<Vec2d> points;
};
PeerBody peer_body(const BodyDesc& d);

// The scene's position of a body (its reference point) from its peer origin and angle: the
// origin itself for a body that does not turn, origin - R(angle) pivot for one that does.
inline Vec2d scene_position(const RigidFrame& f, Vec2d origin, double angle) {
  return f.rotates ? origin - rotated(angle, f.pivot) : origin;
}

// Each throws PeerUnsupported for a scene the peer cannot take.
std::unique_ptr<PeerSim> make_box2d(const Scene& scene, const Setting& setting);
std::unique_ptr<PeerSim> make_chipmunk(const Scene& scene, const Setting& setting);
std::unique_ptr<PeerSim> make_box2d3(const Scene& scene, const Setting& setting);

// Box2D's lengths are compile-time constants in metres (box2d/b2_common.h, b2_lengthUnitsPerMeter
// = 1): b2_linearSlop 0.005 (overlap the solver leaves alone), b2_polygonRadius 0.01 (a skin
// around polygons and edges), b2_maxTranslation 2 (no body moves more per step: a speed cap of
// 2 hz), b2_aabbExtension 0.1. The scene is therefore scaled by a power of two (exact in binary)
// chosen so that the smallest moving body has a radius of about 1 (slop and skin then are 0.5%
// and 1% of it) unless that would let the fastest body move more than 1 (half the cap) per step.
// The fastest speed is estimated from energy: sqrt(|v|^2 + 2 |field acceleration| * extent).
// Every polygon side must stay at least b2_linearSlop long (Box2D welds closer vertices): where
// that needs a larger scale, the shape wins and the speed cap shows in the measures. Box2D v3
// (box2d3_sim.cpp) has the same slop at one length unit per metre and takes the same scale; its
// speed cap, a world setting (400 units/s by default), is raised to 2.4.1's 2 units per step.
double box2d_length_scale(const Scene& scene, double hz, double linear_slop);

}  // namespace pge::peers::detail
