// Box2D 2.4.1 as a peer (peer_sim.hpp). Box2D computes in float: the scene's doubles are rounded
// once on the way in and the state read back as float, which bounds its accuracy near 6e-8 of
// the scene's coordinates however small the step.
#include "peer_sim.hpp"

#include <box2d/box2d.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace pge::peers::detail {
namespace {

using Pair = std::pair<std::size_t, std::size_t>;

// The scene indices of a contact's two bodies, lower first (fixture user data: index + 1).
Pair pair_of(b2Contact* c) {
  const auto a = static_cast<std::size_t>(c->GetFixtureA()->GetUserData().pointer - 1);
  const auto b = static_cast<std::size_t>(c->GetFixtureB()->GetUserData().pointer - 1);
  return std::minmax(a, b);
}

// Restitution of a pair = the smaller of the two (PGE's rule; Box2D's own mix is the larger),
// applied at every approach speed (threshold 0; Box2D's default, 1 m/s, makes slower contacts
// perfectly inelastic). And a note of every contact that begins, for the step trace: one that
// begins and ends inside a step (in a continuous sub-step) is no longer touching after it.
class Listener : public b2ContactListener {
 public:
  void PreSolve(b2Contact* contact, const b2Manifold*) override {
    contact->SetRestitution(std::min(contact->GetFixtureA()->GetRestitution(), contact->GetFixtureB()->GetRestitution()));
    contact->SetRestitutionThreshold(0.0f);
  }
  void BeginContact(b2Contact* contact) override { begun.push_back(pair_of(contact)); }
  std::vector<Pair> begun;  // since the start of the step
};

b2Vec2 to_b2(Vec2d v, double scale) {
  return {static_cast<float>(v.x * scale), static_cast<float>(v.y * scale)};
}

class Box2dSim final : public PeerSim {
 public:
  Box2dSim(const Scene& scene, const Setting& setting)
      : scene_(scene), setting_(setting), scale_(box2d_length_scale(scene, setting.hz, static_cast<double>(b2_linearSlop))), world_(b2Vec2(0.0f, 0.0f)) {
    world_.SetAllowSleeping(false);
    world_.SetContinuousPhysics(true);
    world_.SetSubStepping(false);
    world_.SetWarmStarting(true);
    world_.SetContactListener(&listener_);
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) add_body(i);
  }

  void step(double dt) override {
    for (std::size_t i = 0; i < bodies_.size(); ++i) {
      const BodyDesc& d = scene_.bodies[i];
      if (d.fixed) continue;
      const Vec2d f = field_acceleration(scene_, d) * (d.mass * scale_);
      if (f.x != 0 || f.y != 0) bodies_[i]->ApplyForceToCenter(to_b2(f, 1.0), true);
    }
    listener_.begun.clear();
    world_.Step(static_cast<float>(dt), setting_.velocity_iterations, setting_.position_iterations);
  }

  Vec2d position(std::size_t i) const override {
    const b2Vec2 p = bodies_[i]->GetPosition();
    return scene_position(frames_[i], {static_cast<double>(p.x) / scale_, static_cast<double>(p.y) / scale_}, angle(i));
  }
  Vec2d velocity(std::size_t i) const override {
    const b2Vec2 v = bodies_[i]->GetLinearVelocity();
    return {static_cast<double>(v.x) / scale_, static_cast<double>(v.y) / scale_};
  }
  double angle(std::size_t i) const override { return static_cast<double>(bodies_[i]->GetAngle()); }
  double angular_velocity(std::size_t i) const override { return static_cast<double>(bodies_[i]->GetAngularVelocity()); }

  void touching_pairs(std::vector<Pair>& out) const override {
    out.clear();
    for (b2Contact* c = world_.GetContactList(); c; c = c->GetNext())
      if (c->IsTouching()) out.push_back(pair_of(c));
  }

  void reported_pairs(std::vector<Pair>& out) const override {
    touching_pairs(out);
    add_pairs_once(out, listener_.begun);
  }

 private:
  // A body that turns in PGE has its origin at PGE's pivot, its shape about it, and is given
  // its angle and spin; a fixed one that turns is kinematic (it spins at its constant rate,
  // pushed by nothing). Every other body: fixed rotation, origin at the scene's position.
  void add_body(std::size_t i) {
    const BodyDesc& d = scene_.bodies[i];
    const PeerBody pb = peer_body(d);
    const bool turns = pb.frame.rotates;
    frames_.push_back(pb.frame);
    b2BodyDef bd;
    bd.type = !d.fixed ? b2_dynamicBody : turns ? b2_kinematicBody : b2_staticBody;
    bd.position = to_b2(pb.origin, scale_);
    bd.linearVelocity = d.fixed ? b2Vec2(0.0f, 0.0f) : to_b2(d.velocity, scale_);
    if (turns) {
      bd.angle = static_cast<float>(d.angle);
      bd.angularVelocity = static_cast<float>(d.angular_velocity);
    }
    bd.fixedRotation = !turns;
    bd.bullet = !d.fixed;      // continuous collision against moving bodies as well as static ones
    bd.allowSleep = false;
    bd.linearDamping = 0.0f;
    bd.angularDamping = 0.0f;
    bd.gravityScale = 0.0f;    // gravity comes as a force, with each body's own acceleration
    b2Body* body = world_.CreateBody(&bd);
    bodies_.push_back(body);

    b2FixtureDef fd;
    fd.friction = 0.0f;
    fd.restitution = static_cast<float>(restitution_of(scene_, d));
    fd.restitutionThreshold = 0.0f;
    fd.density = 0.0f;  // the mass is set below, as the scene gives it
    fd.userData.pointer = static_cast<std::uintptr_t>(i + 1);
    b2CircleShape circle;
    b2PolygonShape polygon;
    b2EdgeShape edge;
    switch (d.shape) {
      case ShapeKind::Circle:
        circle.m_radius = static_cast<float>(d.radius * scale_);
        fd.shape = &circle;
        break;
      case ShapeKind::Polygon: {
        require_vertices_at_most(d, static_cast<std::size_t>(b2_maxPolygonVertices), "Box2D takes at most b2_maxPolygonVertices");
        std::vector<b2Vec2> v;
        for (const Vec2d& p : pb.points) v.push_back(to_b2(p, scale_));
        polygon.Set(v.data(), static_cast<int32>(v.size()));
        if (polygon.m_count != static_cast<int32>(v.size()))
          throw PeerUnsupported("body \"" + d.id + "\": Box2D merged vertices of this polygon closer than its "
                                "b2_linearSlop at the chosen scale");
        fd.shape = &polygon;
        break;
      }
      case ShapeKind::Segment:
        edge.SetTwoSided(to_b2(pb.points[0], scale_), to_b2(pb.points[1], scale_));
        fd.shape = &edge;
        break;
    }
    body->CreateFixture(&fd);
    if (!d.fixed) {
      // The centre of mass at the origin: the reference point of a body that does not turn
      // (forces act there, nothing turns), the pivot of one that does, with PGE's inertia about
      // it (a length squared: scaled by scale^2).
      b2MassData md;
      md.mass = static_cast<float>(d.mass);
      md.center = b2Vec2(0.0f, 0.0f);
      md.I = turns ? static_cast<float>(pb.frame.inertia * scale_ * scale_) : 0.0f;
      body->SetMassData(&md);
      if (turns) {  // as given, whatever SetMassData did to the velocities
        body->SetLinearVelocity(to_b2(d.velocity, scale_));
        body->SetAngularVelocity(static_cast<float>(d.angular_velocity));
      }
    }
  }

  const Scene& scene_;
  Setting setting_;
  double scale_;
  mutable b2World world_;  // mutable: b2Fixture::GetUserData has no const overload
  Listener listener_;
  std::vector<b2Body*> bodies_;
  std::vector<RigidFrame> frames_;  // per scene body
};

}  // namespace

std::unique_ptr<PeerSim> make_box2d(const Scene& scene, const Setting& setting) {
  return std::make_unique<Box2dSim>(scene, setting);
}

}  // namespace pge::peers::detail
