// What the oracle reads: the engine's state and events, converted exactly to dyadic rationals.
// Only state is read (World's motion, shape and mass accessors, CollisionInfo); the oracle
// never calls the engine's algebra.
#pragma once

#include "pge/event.hpp"
#include "pge/oracle_exact.hpp"
#include "pge/scene.hpp"
#include "pge/world.hpp"

#include <array>
#include <cstdint>
#include <vector>

namespace pge::oracle {

// p(t) = p0 + v0 (t - t0) + acc (t - t0)^2 / 2, exactly as the engine states it. A rotating body
// (ExactBody::rotates) turns as well: its angle is theta0 + omega (t - t0) and p is its pivot.
struct ExactMotion {
  Dyadic t0;
  ExactVec p0, v0, acc;
  // Fixed bodies the body rests on (BodyMotion::supports): touching all along the path, which is
  // a contact state, not an event; the search skips these pairs.
  std::array<BodyIndex, 2> supports{kNoBody, kNoBody};
  Dyadic theta0{}, omega{};  // rad, rad/s; 0 for a body that does not rotate
};

struct ExactBody {
  ShapeKind shape = ShapeKind::Circle;
  bool fixed = false;
  Dyadic radius;       // circles
  Dyadic mass;         // 0 for fixed bodies
  Dyadic restitution;
  std::vector<ExactVec> local;  // vertices relative to the position (segment: a, b)
  std::vector<ExactVec> world;  // fixed bodies: the world vertices the engine predicts with
  ExactMotion motion;           // fixed bodies: p0 is the position, v0 = acc = 0
  ExactVec field_acc;           // the field potential energy is measured in (World::field_acceleration)
  // A rotating body (World::rotates): `local` holds its vertices about its pivot at angle 0
  // (World::pivot_vertices), vertex k is at p(t) + R(theta(t)) local[k], `world` is empty, and a
  // fixed one spins about its position at the constant rate motion.omega. Its contact functions
  // hold sin and cos of the angle: the certified transcendental search judges them
  // (oracle/README.md, "Rotation").
  bool rotates = false;
  Dyadic inertia;  // about the pivot, kg m^2 (World::inertia); 0 for fixed and non-rotating bodies
};

struct ExactState {
  std::vector<ExactBody> bodies;
  Dyadic now;      // the time the state holds from: the last event that changed it
  Dyadic horizon;  // contacts after it do not count
  TimeFormat format;  // the engine's scalar: time errors are counted in its ulps
};

// One engine event (a collision, or a predicted contact found not approaching: impulse 0).
struct ExactEvent {
  Dyadic time;
  BodyIndex a = kNoBody, b = kNoBody;  // a < b
  ContactKind contact = ContactKind::CircleCircle;
  std::uint16_t feature_a = 0, feature_b = 0;
  ExactVec va_before, vb_before, va_after, vb_after;
  Dyadic wa_before, wb_before, wa_after, wb_after;  // angular velocities (rad/s); 0 without rotation
  bool impulse = false;       // a non-zero impulse was applied
  bool overlap_rule = false;  // the engine collided the pair by the overlap rule
};

template <class T> ExactMotion exact_motion(const BodyMotion<T>& m) {
  return {Dyadic::from(m.t0),  ExactVec::from(m.p0),    ExactVec::from(m.v0), ExactVec::from(m.acc),
          m.supports,          Dyadic::from(m.theta0), Dyadic::from(m.omega)};
}

template <class T> ExactBody exact_body(const World<T>& w, BodyIndex i) {
  ExactBody b;
  b.shape = w.shape(i);
  b.fixed = w.is_fixed(i);
  b.radius = Dyadic::from(w.radius(i));
  b.mass = Dyadic::from(w.mass(i));
  b.restitution = Dyadic::from(w.restitution(i));
  b.rotates = w.rotates(i);
  if (b.rotates) {
    for (const auto& v : w.pivot_vertices(i)) b.local.push_back(ExactVec::from(v));
    b.inertia = Dyadic::from(w.inertia(i));
  } else {
    for (const auto& v : w.local_vertices(i)) b.local.push_back(ExactVec::from(v));
    for (const auto& v : w.world_vertices(i)) b.world.push_back(ExactVec::from(v));
  }
  b.motion = exact_motion(w.motion(i));
  b.field_acc = ExactVec::from(w.field_acceleration(i));
  return b;
}

// The state a World holds now (call before its first step, or between steps).
template <class T> ExactState exact_state(const World<T>& w) {
  ExactState s;
  for (BodyIndex i = 0; i < w.body_count(); ++i) s.bodies.push_back(exact_body(w, i));
  s.now = Dyadic::from(w.time());
  s.horizon = Dyadic::from(w.horizon());
  s.format = TimeFormat::of<T>();
  return s;
}

template <class T> ExactEvent exact_event(const CollisionInfo<T>& c) {
  ExactEvent e;
  e.time = Dyadic::from(c.time);
  e.a = c.a;
  e.b = c.b;
  e.contact = c.contact;
  e.feature_a = c.feature_a;
  e.feature_b = c.feature_b;
  e.va_before = ExactVec::from(c.va_before);
  e.vb_before = ExactVec::from(c.vb_before);
  e.va_after = ExactVec::from(c.va_after);
  e.vb_after = ExactVec::from(c.vb_after);
  e.wa_before = Dyadic::from(c.wa_before);
  e.wb_before = Dyadic::from(c.wb_before);
  e.wa_after = Dyadic::from(c.wa_after);
  e.wb_after = Dyadic::from(c.wb_after);
  e.impulse = c.impulse != T(0);
  e.overlap_rule = c.at_start_overlap;
  return e;
}

}  // namespace pge::oracle
