// Box2D v3 (its C API, version 3.2, built from a checkout by scripts/build-box2d3.sh) as a peer
// (peer_sim.hpp), engine name "box2d3". Set up as the 2.4.1 adapter (box2d_sim.cpp) is, in v3's
// terms: friction 0, no damping, no sleeping, continuous collision with every moving body a
// bullet, restitution per pair the smaller of the two (a mixing callback) at every approach speed
// (threshold 0), gravity and each body's own acceleration as a force every step, a body that
// turns in PGE turning about PGE's pivot with PGE's inertia (centre of mass at its origin), every
// other body with its rotation locked; the scene scaled by the same power of two as for 2.4.1
// (v3's linear slop is 2.4.1's, 0.005 length units). A setting's iterations are v3's sub-steps
// per step (4 is its default). Box2D computes in float unless the checkout was built with
// BOX2D_DOUBLE_PRECISION (positions then in double; b2Pos holds both).
#include "peer_sim.hpp"

#include <box2d/box2d.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace pge::peers::detail {
namespace {

using Pair = std::pair<std::size_t, std::size_t>;

// v3's default linear slop at one length unit per metre (include/box2d/constants.h, B2_LINEAR_SLOP).
constexpr double kBox2d3LinearSlop = 0.005;

// PGE's rule for a pair: the smaller restitution (v3's default mix is the larger).
float smaller_restitution(float a, std::uint64_t, float b, std::uint64_t) { return std::min(a, b); }

b2Vec2 to_vec(Vec2d v, double scale) { return {static_cast<float>(v.x * scale), static_cast<float>(v.y * scale)}; }

b2Pos to_pos(Vec2d v, double scale) {
  b2Pos p;
  p.x = static_cast<decltype(p.x)>(v.x * scale);
  p.y = static_cast<decltype(p.y)>(v.y * scale);
  return p;
}

std::size_t index_of(b2ShapeId shape) {
  return static_cast<std::size_t>(reinterpret_cast<std::uintptr_t>(b2Shape_GetUserData(shape)) - 1);
}

Pair pair_of(b2ShapeId a, b2ShapeId b) { return std::minmax(index_of(a), index_of(b)); }

class Box2d3Sim final : public PeerSim {
 public:
  Box2d3Sim(const Scene& scene, const Setting& setting)
      : scene_(scene), setting_(setting), scale_(box2d_length_scale(scene, setting.hz, kBox2d3LinearSlop)) {
    b2WorldDef wd = b2DefaultWorldDef();
    wd.gravity = {0.0f, 0.0f};  // gravity comes as a force, with each body's own acceleration
    wd.restitutionThreshold = 0.0f;
    wd.restitutionCallback = smaller_restitution;
    wd.enableSleep = false;
    wd.enableContinuous = true;
    // 2.4.1's cap, 2 length units per step (box2d_length_scale keeps bodies within half of it).
    wd.maximumLinearSpeed = std::max(wd.maximumLinearSpeed, static_cast<float>(2 * setting.hz));
    wd.workerCount = 1;  // one thread, as every engine here
    world_ = b2CreateWorld(&wd);
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) add_body(i);
  }
  ~Box2d3Sim() override { b2DestroyWorld(world_); }
  Box2d3Sim(const Box2d3Sim&) = delete;
  Box2d3Sim& operator=(const Box2d3Sim&) = delete;

  void step(double dt) override {
    for (std::size_t i = 0; i < bodies_.size(); ++i) {
      const BodyDesc& d = scene_.bodies[i];
      if (d.fixed) continue;
      const Vec2d f = field_acceleration(scene_, d) * (d.mass * scale_);
      if (f.x != 0 || f.y != 0) b2Body_ApplyForceToCenter(bodies_[i], to_vec(f, 1.0), true);
    }
    b2World_Step(world_, static_cast<float>(dt), setting_.velocity_iterations);
    // The contacts that began in this step (read now: the events last until the next step).
    begun_.clear();
    const b2ContactEvents events = b2World_GetContactEvents(world_);
    for (int k = 0; k < events.beginCount; ++k)
      begun_.push_back(pair_of(events.beginEvents[k].shapeIdA, events.beginEvents[k].shapeIdB));
  }

  Vec2d position(std::size_t i) const override {
    const b2Pos p = b2Body_GetPosition(bodies_[i]);
    return scene_position(frames_[i], {static_cast<double>(p.x) / scale_, static_cast<double>(p.y) / scale_}, angle(i));
  }
  Vec2d velocity(std::size_t i) const override {
    const b2Vec2 v = b2Body_GetLinearVelocity(bodies_[i]);
    return {static_cast<double>(v.x) / scale_, static_cast<double>(v.y) / scale_};
  }
  // atan2 of the rotation's cosine and sine: v3's own b2Rot_GetAngle is an approximation
  // (about 1e-3 rad off), as is b2MakeRot, so neither is used.
  double angle(std::size_t i) const override {
    const b2Rot q = b2Body_GetRotation(bodies_[i]);
    return std::atan2(static_cast<double>(q.s), static_cast<double>(q.c));
  }
  double angular_velocity(std::size_t i) const override { return static_cast<double>(b2Body_GetAngularVelocity(bodies_[i])); }

  // v3 holds a pair as touching when its manifold has points (speculative ones, up to four slops
  // apart, included: that is when it sends its begin-touch event).
  void touching_pairs(std::vector<Pair>& out) const override {
    out.clear();
    for (std::size_t i = 0; i < bodies_.size(); ++i) {
      if (scene_.bodies[i].fixed) continue;  // every contact has a moving body
      const int capacity = b2Body_GetContactCapacity(bodies_[i]);
      if (capacity == 0) continue;
      contacts_.resize(static_cast<std::size_t>(capacity));
      const int n = b2Body_GetContactData(bodies_[i], contacts_.data(), capacity);
      for (int k = 0; k < n; ++k)
        if (contacts_[static_cast<std::size_t>(k)].manifold.pointCount > 0)
          out.push_back(pair_of(contacts_[static_cast<std::size_t>(k)].shapeIdA, contacts_[static_cast<std::size_t>(k)].shapeIdB));
    }
    add_pairs_once(out, {});
  }

  void reported_pairs(std::vector<Pair>& out) const override {
    touching_pairs(out);
    add_pairs_once(out, begun_);
  }

 private:
  void add_body(std::size_t i) {
    const BodyDesc& d = scene_.bodies[i];
    const PeerBody pb = peer_body(d);
    const bool turns = pb.frame.rotates;
    frames_.push_back(pb.frame);
    b2BodyDef bd = b2DefaultBodyDef();
    bd.type = !d.fixed ? b2_dynamicBody : turns ? b2_kinematicBody : b2_staticBody;
    bd.position = to_pos(pb.origin, scale_);
    if (!d.fixed) bd.linearVelocity = to_vec(d.velocity, scale_);
    if (turns) {
      bd.rotation = {static_cast<float>(std::cos(d.angle)), static_cast<float>(std::sin(d.angle))};
      bd.angularVelocity = static_cast<float>(d.angular_velocity);
    }
    bd.motionLocks.angularZ = !turns;
    bd.isBullet = !d.fixed;
    bd.enableSleep = false;
    bd.linearDamping = 0.0f;
    bd.angularDamping = 0.0f;
    bd.gravityScale = 0.0f;
    const b2BodyId body = b2CreateBody(world_, &bd);
    bodies_.push_back(body);

    b2ShapeDef sd = b2DefaultShapeDef();
    sd.material.friction = 0.0f;
    sd.material.restitution = static_cast<float>(restitution_of(scene_, d));
    sd.density = 0.0f;  // the mass is set below, as the scene gives it
    sd.enableContactEvents = true;
    sd.userData = reinterpret_cast<void*>(static_cast<std::uintptr_t>(i + 1));
    switch (d.shape) {
      case ShapeKind::Circle: {
        b2Circle circle{};
        circle.radius = static_cast<float>(d.radius * scale_);
        b2CreateCircleShape(body, &sd, &circle);
        break;
      }
      case ShapeKind::Polygon: {
        require_vertices_at_most(d, B2_MAX_POLYGON_VERTICES, "Box2D v3 takes at most B2_MAX_POLYGON_VERTICES");
        std::vector<b2Vec2> v;
        for (const Vec2d& p : pb.points) v.push_back(to_vec(p, scale_));
        const b2Hull hull = b2ComputeHull(v.data(), static_cast<int>(v.size()));
        if (hull.count != static_cast<int>(v.size()))
          throw PeerUnsupported("body \"" + d.id + "\": Box2D v3 merged vertices of this polygon closer than its "
                                "linear slop at the chosen scale");
        const b2Polygon polygon = b2MakePolygon(&hull, 0.0f);
        b2CreatePolygonShape(body, &sd, &polygon);
        break;
      }
      case ShapeKind::Segment: {
        const b2Segment segment{to_vec(pb.points[0], scale_), to_vec(pb.points[1], scale_)};
        b2CreateSegmentShape(body, &sd, &segment);
        break;
      }
    }
    if (!d.fixed) {
      b2MassData md{};
      md.mass = static_cast<float>(d.mass);
      md.center = {0.0f, 0.0f};
      md.rotationalInertia = turns ? static_cast<float>(pb.frame.inertia * scale_ * scale_) : 0.0f;
      b2Body_SetMassData(body, md);
      b2Body_SetLinearVelocity(body, to_vec(d.velocity, scale_));  // as given, whatever the mass change did
      if (turns) b2Body_SetAngularVelocity(body, static_cast<float>(d.angular_velocity));
    }
  }

  const Scene& scene_;
  Setting setting_;
  double scale_;
  b2WorldId world_{};
  std::vector<b2BodyId> bodies_;
  std::vector<RigidFrame> frames_;  // per scene body
  std::vector<Pair> begun_;         // the contacts that began in the last step
  mutable std::vector<b2ContactData> contacts_;  // scratch for touching_pairs
};

}  // namespace

std::unique_ptr<PeerSim> make_box2d3(const Scene& scene, const Setting& setting) {
  return std::make_unique<Box2d3Sim>(scene, setting);
}

}  // namespace pge::peers::detail
