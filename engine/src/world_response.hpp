// World<T>::Impl, part of world_impl.hpp. Response: the impulse of a collision, the storm count,
// and the overlap measures of a contact.
#pragma once

#include "world_impl.hpp"

namespace pge {

template <class T> inline auto World<T>::Impl::approaching(const Scheduled<T>& s) const -> bool {
  const Body& a = bodies[s.lo];
  const Body& b = bodies[s.hi];
  if (a.rotates || b.rotates) return rotating_approaching(s);
  const Kinematics<T> ka = kinematics(a, s.time), kb = kinematics(b, s.time);
  const PredictedContact<T> contact{s.time, s.contact, s.feature_a, s.feature_b, s.at_start_overlap, s.corner};
  const ContactGeometry<T> g = contact_geometry(contact, a.shape, ka, b.shape, kb);
  return dot(kb.v - ka.v, g.normal) < T(0) && dot(g.normal, g.normal) > T(0);
}

template <class T> inline auto World<T>::Impl::note_storm(BodyIndex i, BodyIndex partner) -> void {
  Body& b = bodies[i];
  using std::abs;
  const T window = T(kStormWindowRelative) * std::max(T(1), abs(now));
  if (b.storm_count > 0 && now - b.storm_start <= window) {
    ++b.storm_count;
  } else {
    b.storm_start = now;
    b.storm_count = 1;
  }
  if (b.storm_count > kStormCollisions && !finished) {
    storm = {now, std::min(i, partner), std::max(i, partner), b.storm_count};
    reason = StopReason::EventStorm;
    finished = true;
  }
}

template <class T> inline auto World<T>::Impl::collide(const Scheduled<T>& s) -> void {
  Body& a = bodies[s.lo];
  Body& b = bodies[s.hi];
  // Both bodies' candidates are requested before either is predicted again (their cells'
  // records were requested when this event reached the top).
  if (grid_on && prefetching) {
    if (!a.fixed) prefetch_candidates(s.lo);
    if (!b.fixed) prefetch_candidates(s.hi);
  }
  if (a.rotates || b.rotates) {
    collide_rotating(s);
    return;
  }
  rebase(a, now);
  rebase(b, now);
  const Kinematics<T> ka = kinematics(a, now), kb = kinematics(b, now);
  const PredictedContact<T> contact{now, s.contact, s.feature_a, s.feature_b, s.at_start_overlap, s.corner};
  const ContactGeometry<T> g = contact_geometry(contact, a.shape, ka, b.shape, kb);

  CollisionInfo<T> info = collision_info(s, ka, kb);
  info.point = g.point;
  info.gap = g.gap;

  // Impulse along the (unnormalised) normal n: j = -(1 + e) (v_rel . n) / (n . n (1/ma + 1/mb)).
  // An axis-aligned normal is replaced by the exact unit vector along it first: equal masses
  // along an axis then swap their velocities exactly, as a Newton's cradle must, where
  // v.n / n.n * n with a normal such as (0.2000000000000000111, 0) left a rounding residue that
  // set resting balls moving (fixtures/scenes/simultaneous/cradle-10-decimal.json). Other
  // normals keep their length: a diagonal one such as (-1, 1) is exact as it is, and its
  // unit vector would not be.
  using std::sqrt;
  Vec2<T> n = g.normal;
  if (n.y == T(0) && n.x != T(0)) n = Vec2<T>{n.x > T(0) ? T(1) : T(-1), T(0)};
  if (n.x == T(0) && n.y != T(0)) n = Vec2<T>{T(0), n.y > T(0) ? T(1) : T(-1)};
  const T nn = dot(n, n);
  const T vn = dot(kb.v - ka.v, n);
  const T n_len = sqrt(nn);
  info.normal = n_len > T(0) ? n * (T(1) / n_len) : n;
  info.approach_speed = n_len > T(0) ? -vn / n_len : T(0);
  const T inv_sum = a.inv_mass + b.inv_mass;
  if (vn < T(0) && nn > T(0) && inv_sum > T(0)) {
    const T e = std::min(a.restitution, b.restitution);
    const T j = -(T(1) + e) * vn / (nn * inv_sum);
    a.v0 -= n * (j * a.inv_mass);
    b.v0 += n * (j * b.inv_mass);
    info.impulse = j * n_len;
    ++counts.collisions;
    if (s.at_start_overlap) ++counts.overlap_starts;
  } else {
    ++counts.grazes;  // predicted, but not approaching at the contact: no impulse is due
  }
  // Resting contact: faces that stop holding a body, and a face that starts to.
  if (!a.fixed) update_rest(s.lo, s.hi, -g.normal, g.point);
  if (!b.fixed) update_rest(s.hi, s.lo, g.normal, g.point);
  info.va_after = a.v0;
  info.vb_after = b.v0;

  finish_collision(s, info, measure_overlap(-g.gap, g.contact_distance, rounding_scale(a.shape, ka, b.shape, kb, now), s.lo, s.hi));
}

template <class T>
inline auto World<T>::Impl::collision_info(const Scheduled<T>& s, const Kinematics<T>& ka, const Kinematics<T>& kb) const
    -> CollisionInfo<T> {
  CollisionInfo<T> info;
  info.time = now;
  info.a = s.lo;
  info.b = s.hi;
  info.contact = s.contact;
  // The edge's public index (event.hpp): a segment's one edge is 0, struck from either side,
  // where a predictor may name its far side edge 1 (the rotating one, an outline of two vertices
  // having two edges). In a circle-edge contact the edge is the circle's partner's.
  const bool circle_lo = bodies[s.lo].shape.kind == ShapeKind::Circle;
  const bool edge_on_lo = s.contact == ContactKind::EdgeVertex || (s.contact == ContactKind::CircleEdge && !circle_lo);
  const bool edge_on_hi = s.contact == ContactKind::VertexEdge || (s.contact == ContactKind::CircleEdge && circle_lo);
  info.feature_a = edge_on_lo ? public_edge(bodies[s.lo].shape, s.feature_a) : s.feature_a;
  info.feature_b = edge_on_hi ? public_edge(bodies[s.hi].shape, s.feature_b) : s.feature_b;
  info.corner = s.corner;
  info.at_start_overlap = s.at_start_overlap;
  info.va_before = ka.v;
  info.vb_before = kb.v;
  return info;
}

template <class T>
inline auto World<T>::Impl::finish_collision(const Scheduled<T>& s, const CollisionInfo<T>& info, const Overlap& o) -> void {
  Body& a = bodies[s.lo];
  Body& b = bodies[s.hi];
  if (o.ulps > worst_contact.ulps) worst_contact = o;
  ++a.version;
  ++b.version;
  if (!a.fixed) note_storm(s.lo, s.hi);
  if (!b.fixed) note_storm(s.hi, s.lo);
  if (!a.fixed) reschedule(s.lo);
  if (!b.fixed) reschedule(s.hi);
  if (on_collision) on_collision(info);
  if (max_events > 0 && counts.collisions + counts.grazes >= max_events && !finished) {
    reason = StopReason::MaxEvents;
    finished = true;
  }
}

template <class T>
inline auto World<T>::Impl::rounding_scale(const BodyShape<T>& sa, const Kinematics<T>& ka, const BodyShape<T>& sb,
    const Kinematics<T>& kb, const T& t)
    -> T {
  using std::abs;
  using std::sqrt;
  const Vec2<T> dv = kb.v - ka.v;
  return pair_scale(sa, ka.p, sb, kb.p) + sqrt(dot(dv, dv)) * abs(t);
}

template <class T>
inline auto World<T>::Impl::measure_overlap(const T& depth, const T& contact_distance, const T& scale, BodyIndex a,
    BodyIndex b)
    -> Overlap {
  if (!(depth > T(0))) return {};
  const T unit = std::numeric_limits<T>::epsilon() * (scale + contact_distance);
  return {depth, depth / contact_distance, depth / unit, a, b};
}

}  // namespace pge
