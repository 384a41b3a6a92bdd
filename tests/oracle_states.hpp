// Hand-made oracle states for tests: bodies given in doubles, converted exactly.
#pragma once

#include "pge/oracle.hpp"
#include "pge/vec2.hpp"

#include <vector>

namespace pge::oracle::testing {

inline ExactVec ev(double x, double y) { return {Dyadic::from(x), Dyadic::from(y)}; }
inline ExactVec ev(Vec2d v) { return ev(v.x, v.y); }

inline ExactMotion motion(Vec2d p, Vec2d v = {}, Vec2d acc = {}, double t0 = 0) {
  return {Dyadic::from(t0), ev(p), ev(v), ev(acc)};
}

inline ExactBody moving_circle(double r, Vec2d p, Vec2d v, double mass = 1, Vec2d acc = {}) {
  ExactBody b;
  b.shape = ShapeKind::Circle;
  b.radius = Dyadic::from(r);
  b.mass = Dyadic::from(mass);
  b.restitution = Dyadic(1);
  b.motion = motion(p, v, acc);
  b.field_acc = b.motion.acc;  // not resting: the path's acceleration is the field's
  return b;
}

inline ExactBody fixed_circle(double r, Vec2d p) {
  ExactBody b = moving_circle(r, p, {}, 0);
  b.fixed = true;
  return b;
}

inline ExactBody fixed_segment(Vec2d a, Vec2d b) {
  ExactBody s;
  s.shape = ShapeKind::Segment;
  s.fixed = true;
  s.restitution = Dyadic(1);
  s.local = {ev(a), ev(b)};
  s.world = {ev(a), ev(b)};  // position (0, 0): world = local, exactly
  s.motion = motion({});
  return s;
}

// A moving polygon: counter-clockwise vertices relative to position p.
inline ExactBody moving_polygon(std::vector<Vec2d> local, Vec2d p, Vec2d v, double mass = 1, Vec2d acc = {}) {
  ExactBody b;
  b.shape = ShapeKind::Polygon;
  b.mass = Dyadic::from(mass);
  b.restitution = Dyadic(1);
  for (Vec2d q : local) b.local.push_back(ev(q));
  b.motion = motion(p, v, acc);
  b.field_acc = b.motion.acc;  // not resting: the path's acceleration is the field's
  return b;
}

inline ExactBody fixed_polygon(std::vector<Vec2d> world) {
  ExactBody b = moving_polygon(world, {}, {}, 0);
  b.fixed = true;
  b.mass = Dyadic();
  b.world = b.local;
  return b;
}

inline ExactBody moving_segment(Vec2d a, Vec2d b, Vec2d p, Vec2d v) {
  ExactBody s = moving_polygon({a, b}, p, v);
  s.shape = ShapeKind::Segment;
  return s;
}

inline std::vector<Vec2d> square(double h) { return {{-h, -h}, {h, -h}, {h, h}, {-h, h}}; }
inline std::vector<Vec2d> diamond(double h) { return {{0, -h}, {h, 0}, {0, h}, {-h, 0}}; }

inline ExactState state_of(std::vector<ExactBody> bodies, double horizon = 100) {
  ExactState s;
  s.bodies = std::move(bodies);
  s.now = Dyadic();
  s.horizon = Dyadic::from(horizon);
  s.format = TimeFormat::of<double>();
  return s;
}

// An engine event between a < b at time t with unchanged velocities (what a judge needs when
// conservation is not the point of the test).
inline ExactEvent event_at(const ExactState& s, BodyIndex a, BodyIndex b, double t, ContactKind kind,
                           int fa = 0, int fb = 0) {
  ExactEvent e;
  e.time = Dyadic::from(t);
  e.a = a;
  e.b = b;
  e.contact = kind;
  e.feature_a = static_cast<std::uint16_t>(fa);
  e.feature_b = static_cast<std::uint16_t>(fb);
  e.va_before = e.va_after = s.bodies[a].motion.v0;
  e.vb_before = e.vb_after = s.bodies[b].motion.v0;
  return e;
}

inline bool has_feature(const PairContact& p, ContactKind kind, int fa, int fb) {
  for (const FeaturePair& f : p.features)
    if (f == FeaturePair{kind, static_cast<std::uint16_t>(fa), static_cast<std::uint16_t>(fb)}) return true;
  return false;
}

}  // namespace pge::oracle::testing
