// Chipmunk 7.0.3 as a peer (peer_sim.hpp). Chipmunk computes in double (cpFloat, CP_USE_DOUBLES)
// and its lengths are set at run time, so the scene goes in unscaled. It has no continuous
// collision: a body that moves further than a thin body's thickness in one step can pass through.
#include "peer_sim.hpp"

#include <chipmunk/chipmunk.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <mutex>

namespace pge::peers::detail {
namespace {

// cpSpaceSetCollisionSlop: the overlap Chipmunk leaves uncorrected, an absolute length (default
// 0.1, as large as a whole gas ball). A thousandth of the smallest moving body: overlaps are
// corrected early, while a contact is still kept from one step to the next (slop 0 makes resting
// contacts flicker in and out).
constexpr double kSlopPerSize = 1e-3;
// Chipmunk's collision bias (the fraction of an overlap left after one second, default
// (1 - 0.1)^60) is left at its default: a faster correction pushes bodies apart harder and adds
// energy; a slower one leaves overlaps longer.

cpVect to_cp(Vec2d v) { return cpv(v.x, v.y); }

// Debian's libchipmunk is a debug build: the first cpSpaceNew of a process greets with printf
// ("Initializing cpSpace - Chipmunk v7.0.3 (Debug Enabled)" and a line on NDEBUG) on standard
// output, where pge writes its tables and JSON (`pge compare --json -`). pge's redirection of
// std::cout (cli/stdout.hpp) does not reach C's printf, so the first space of the process is made
// and freed here with file descriptor 1 pointed at standard error; later ones print nothing.
void greet_on_stderr() {
  static std::once_flag once;
  std::call_once(once, [] {
    std::fflush(stdout);
    const int saved = dup(STDOUT_FILENO);
    if (saved >= 0) dup2(STDERR_FILENO, STDOUT_FILENO);
    cpSpaceFree(cpSpaceNew());
    std::fflush(stdout);
    if (saved >= 0) {
      dup2(saved, STDOUT_FILENO);
      close(saved);
    }
  });
}

class ChipmunkSim final : public PeerSim {
 public:
  ChipmunkSim(const Scene& scene, const Setting& setting) : scene_(scene), space_(cpSpaceNew()) {
    cpSpaceSetIterations(space_, setting.velocity_iterations);
    cpSpaceSetGravity(space_, cpvzero);  // gravity comes as a force, with each body's own acceleration
    cpSpaceSetDamping(space_, 1.0);      // bodies keep all their velocity
    cpSpaceSetSleepTimeThreshold(space_, INFINITY);  // never sleep
    double smallest = std::numeric_limits<double>::infinity();
    for (const BodyDesc& d : scene.bodies)
      if (!d.fixed) smallest = std::min(smallest, body_size(d));
    if (std::isfinite(smallest)) cpSpaceSetCollisionSlop(space_, kSlopPerSize * smallest);
    cpCollisionHandler* handler = cpSpaceAddDefaultCollisionHandler(space_);
    handler->preSolveFunc = &ChipmunkSim::pre_solve;
    handler->userData = this;
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) add_body(i);
  }

  ~ChipmunkSim() override {
    for (cpShape* s : shapes_) {
      cpSpaceRemoveShape(space_, s);
      cpShapeFree(s);
    }
    for (cpBody* b : bodies_)
      if (b != cpSpaceGetStaticBody(space_)) {
        cpSpaceRemoveBody(space_, b);
        cpBodyFree(b);
      }
    cpSpaceFree(space_);
  }
  ChipmunkSim(const ChipmunkSim&) = delete;
  ChipmunkSim& operator=(const ChipmunkSim&) = delete;

  void step(double dt) override {
    for (std::size_t i = 0; i < bodies_.size(); ++i) {
      const BodyDesc& d = scene_.bodies[i];
      if (!d.fixed) cpBodySetForce(bodies_[i], to_cp(field_acceleration(scene_, d) * d.mass));
    }
    touching_.clear();
    cpSpaceStep(space_, dt);
  }

  Vec2d position(std::size_t i) const override {
    if (scene_.bodies[i].fixed) return scene_.bodies[i].position;
    const cpVect p = cpBodyGetPosition(bodies_[i]);
    return scene_position(frames_[i], {p.x, p.y}, angle(i));
  }
  Vec2d velocity(std::size_t i) const override {
    if (scene_.bodies[i].fixed) return {};
    const cpVect v = cpBodyGetVelocity(bodies_[i]);
    return {v.x, v.y};
  }
  double angle(std::size_t i) const override { return cpBodyGetAngle(bodies_[i]); }
  double angular_velocity(std::size_t i) const override { return cpBodyGetAngularVelocity(bodies_[i]); }

  void touching_pairs(std::vector<std::pair<std::size_t, std::size_t>>& out) const override { out = touching_; }
  // Chipmunk pre-solves each pair of shapes at most once a step, and a scene body has one shape.
  void reported_pairs(std::vector<std::pair<std::size_t, std::size_t>>& out) const override { out = touching_; }

 private:
  static std::size_t index_of(const cpShape* s) {
    return static_cast<std::size_t>(reinterpret_cast<std::uintptr_t>(cpShapeGetUserData(s)));
  }

  // Restitution of a pair = the smaller of the two (PGE's rule; Chipmunk multiplies them), and a
  // note of the touching pair for the penetration measure.
  static cpBool pre_solve(cpArbiter* arb, cpSpace*, cpDataPointer self) {
    cpShape* a = nullptr;
    cpShape* b = nullptr;
    cpArbiterGetShapes(arb, &a, &b);
    cpArbiterSetRestitution(arb, std::min(cpShapeGetElasticity(a), cpShapeGetElasticity(b)));
    const std::size_t ia = index_of(a), ib = index_of(b);
    static_cast<ChipmunkSim*>(self)->touching_.emplace_back(std::min(ia, ib), std::max(ia, ib));
    return cpTrue;
  }

  void add_body(std::size_t i) {
    const BodyDesc& d = scene_.bodies[i];
    const PeerBody pb = peer_body(d);
    frames_.push_back(pb.frame);
    cpBody* body = nullptr;
    // Fixed shapes that do not turn go on the space's static body in world coordinates; another
    // body's shape is relative to its origin (centre of gravity at 0): a body that does not turn,
    // its reference point, with an infinite moment; one that turns, PGE's pivot, with PGE's
    // moment of inertia (a fixed one: kinematic, spinning at its constant rate).
    Vec2d offset;
    if (d.fixed && !pb.frame.rotates) {
      body = cpSpaceGetStaticBody(space_);
      offset = d.position;
    } else {
      body = cpSpaceAddBody(space_, d.fixed ? cpBodyNewKinematic() : cpBodyNew(d.mass, pb.frame.rotates ? pb.frame.inertia : INFINITY));
      cpBodySetPosition(body, to_cp(pb.origin));
      if (!d.fixed) cpBodySetVelocity(body, to_cp(d.velocity));
      if (pb.frame.rotates) {
        cpBodySetAngle(body, d.angle);
        cpBodySetAngularVelocity(body, d.angular_velocity);
      }
    }
    bodies_.push_back(body);
    cpShape* shape = nullptr;
    switch (d.shape) {
      case ShapeKind::Circle: shape = cpCircleShapeNew(body, d.radius, to_cp(offset)); break;
      case ShapeKind::Segment:
        shape = cpSegmentShapeNew(body, to_cp(pb.points[0] + offset), to_cp(pb.points[1] + offset), 0.0);
        break;
      case ShapeKind::Polygon: {
        std::vector<cpVect> v;
        for (const Vec2d& p : pb.points) v.push_back(to_cp(p + offset));
        // Raw: the scene's polygons are already convex and counter-clockwise, as Chipmunk wants.
        shape = cpPolyShapeNewRaw(body, static_cast<int>(v.size()), v.data(), 0.0);
        break;
      }
    }
    cpShapeSetElasticity(shape, restitution_of(scene_, d));
    cpShapeSetFriction(shape, 0.0);
    cpShapeSetUserData(shape, reinterpret_cast<cpDataPointer>(static_cast<std::uintptr_t>(i)));
    shapes_.push_back(cpSpaceAddShape(space_, shape));
  }

  const Scene& scene_;
  cpSpace* space_;
  std::vector<cpBody*> bodies_;
  std::vector<RigidFrame> frames_;  // per scene body
  std::vector<cpShape*> shapes_;
  std::vector<std::pair<std::size_t, std::size_t>> touching_;
};

}  // namespace

std::unique_ptr<PeerSim> make_chipmunk(const Scene& scene, const Setting& setting) {
  greet_on_stderr();
  return std::make_unique<ChipmunkSim>(scene, setting);
}

}  // namespace pge::peers::detail
