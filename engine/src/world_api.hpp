// World<T>::Impl, part of world_impl.hpp. World's other public members: queries of the state,
// energies, the state hash, and set_velocity.
#pragma once

#include "world_impl.hpp"

namespace pge {

template <class T> void World<T>::stop() { impl_->stop_requested = true; }
template <class T> T World<T>::time() const { return impl_->now; }
template <class T> T World<T>::horizon() const { return impl_->horizon; }
template <class T> StopReason World<T>::stop_reason() const { return impl_->reason; }
template <class T> const StormInfo<T>& World<T>::storm() const { return impl_->storm; }
template <class T> const EventCounts& World<T>::counts() const { return impl_->counts; }
template <class T> const std::vector<Tunnel>& World<T>::tunnels() const {
  static const std::vector<Tunnel> kNone;
  return impl_->tunnel_watch ? impl_->tunnel_watch->tunnels() : kNone;
}
template <class T> std::size_t World<T>::body_count() const { return impl_->bodies.size(); }
template <class T> const std::string& World<T>::body_id(BodyIndex i) const { return impl_->bodies.at(i).id; }
template <class T> bool World<T>::is_fixed(BodyIndex i) const { return impl_->bodies.at(i).fixed; }
template <class T> T World<T>::mass(BodyIndex i) const { return impl_->bodies.at(i).mass; }

template <class T> BodySnapshot<T> World<T>::snapshot(BodyIndex i) const {
  const auto& b = impl_->bodies.at(i);
  const Kinematics<T> k = impl_->kinematics(b, impl_->now);
  if (!b.rotates) return {k.p, k.v};
  const auto& r = impl_->spin_of(b);
  const T angle = impl_->angle_at(b, impl_->now);
  return {k.p - rotated(angle, r.pivot), k.v, angle, r.omega};
}

template <class T> BodyMotion<T> World<T>::motion(BodyIndex i) const {
  const auto& b = impl_->bodies.at(i);
  BodyMotion<T> m;
  m.p0 = b.p0;
  if (b.rotates) {
    m.theta0 = impl_->spin_of(b).theta0;
    m.omega = impl_->spin_of(b).omega;
  }
  if (b.fixed) return m;
  m.t0 = b.t0;
  m.v0 = b.v0;
  m.acc = b.acc;
  for (int k = 0; k < b.supports; ++k) m.supports[static_cast<std::size_t>(k)] = b.support[static_cast<std::size_t>(k)].body;
  return m;
}
template <class T> bool World<T>::rotates(BodyIndex i) const { return impl_->bodies.at(i).rotates; }
template <class T> const std::vector<Vec2<T>>& World<T>::pivot_vertices(BodyIndex i) const {
  static const std::vector<Vec2<T>> kNone;
  const auto& b = impl_->bodies.at(i);
  return b.rotates ? impl_->spin_of(b).vertices : kNone;
}
template <class T> Vec2<T> World<T>::pivot(BodyIndex i) const {
  const auto& b = impl_->bodies.at(i);
  return b.rotates ? impl_->spin_of(b).pivot : Vec2<T>{};
}
template <class T> T World<T>::inertia(BodyIndex i) const {
  const auto& b = impl_->bodies.at(i);
  return b.rotates ? impl_->spin_of(b).inertia : T(0);
}
template <class T> Vec2<T> World<T>::field_acceleration(BodyIndex i) const {
  const auto& b = impl_->bodies.at(i);
  return b.fixed ? Vec2<T>{} : b.field_acc;
}
template <class T> ShapeKind World<T>::shape(BodyIndex i) const { return impl_->bodies.at(i).shape.kind; }
template <class T> T World<T>::radius(BodyIndex i) const { return impl_->bodies.at(i).shape.radius; }
template <class T> T World<T>::restitution(BodyIndex i) const { return impl_->bodies.at(i).restitution; }
template <class T> const std::vector<Vec2<T>>& World<T>::local_vertices(BodyIndex i) const {
  return impl_->bodies.at(i).shape.local;
}
template <class T> const std::vector<Vec2<T>>& World<T>::world_vertices(BodyIndex i) const {
  return impl_->bodies.at(i).shape.world;
}
template <class T> SolverKind World<T>::solver() const { return impl_->solver; }
template <class T> BroadPhase World<T>::broad_phase() const {
  return impl_->grid_on ? BroadPhase::Grid : BroadPhase::AllPairs;
}

template <class T> std::size_t World<T>::memory_bytes() const {
  const Impl& w = *impl_;
  std::size_t bytes = sizeof(Impl) + w.bodies.capacity() * sizeof(typename Impl::Body);
  for (const auto& b : w.bodies) {
    const auto& s = b.shape;
    bytes += b.id.capacity() > 15 ? b.id.capacity() + 1 : 0;
    bytes += (s.local.capacity() + s.world.capacity() + s.edges.capacity()) * sizeof(Vec2<T>) +
             s.edge_length.capacity() * sizeof(T);
  }
  for (const auto& r : w.spins)
    bytes += r.vertices.capacity() * sizeof(Vec2<T>) + r.memos.capacity() * sizeof(typename Impl::RotatingMemo);
  bytes += w.spins.capacity() * sizeof(typename Impl::Spin);
  bytes += w.moving.capacity() * sizeof(BodyIndex) + w.heap.memory_bytes();
  bytes += w.seen.capacity() * sizeof(std::uint32_t) +
           w.globals.capacity() * sizeof(BodyIndex) + w.grid.memory_bytes();
  return bytes;
}

template <class T> void World<T>::set_velocity(BodyIndex i, Vec2<T> velocity) {
  Impl& w = *impl_;
  auto& b = w.bodies.at(i);
  if (b.fixed) throw std::invalid_argument("set_velocity: body \"" + b.id + "\" is fixed");
  w.watch_path(i);
  w.rebase(b, w.now);
  b.v0 = velocity;
  // A new velocity ends the contact state; a face the body still presses on takes it back at
  // once, through its own contact.
  b.supports = 0;
  b.acc = b.field_acc;
  ++b.version;
  w.reschedule(i);
  if (w.on_motion_change) w.on_motion_change(i, w.now);
}

template <class T> T World<T>::kinetic_energy() const {
  T e{};
  for (BodyIndex i : impl_->moving) {
    const auto& b = impl_->bodies[i];
    const Vec2<T> v = impl_->kinematics(b, impl_->now).v;
    e += b.mass * dot(v, v) / T(2);
    if (b.rotates) e += impl_->spin_of(b).inertia * impl_->spin_of(b).omega * impl_->spin_of(b).omega / T(2);
  }
  return e;
}

template <class T> T World<T>::potential_energy() const {
  T e{};
  for (BodyIndex i : impl_->moving) {
    const auto& b = impl_->bodies[i];
    e -= b.mass * dot(b.field_acc, impl_->kinematics(b, impl_->now).p);
  }
  return e;
}

template <class T> Vec2<T> World<T>::momentum() const {
  Vec2<T> m;
  for (BodyIndex i : impl_->moving) {
    const auto& b = impl_->bodies[i];
    m += impl_->kinematics(b, impl_->now).v * b.mass;
  }
  return m;
}

template <class T> typename World<T>::Overlap World<T>::largest_overlap() const {
  const Impl& w = *impl_;
  Overlap worst;
  for (BodyIndex i = 0; i < w.bodies.size(); ++i) {
    for (BodyIndex j = i + 1; j < w.bodies.size(); ++j) {
      const auto& a = w.bodies[i];
      const auto& b = w.bodies[j];
      if (a.fixed && b.fixed) continue;
      const Kinematics<T> ka = w.kinematics(a, w.now), kb = w.kinematics(b, w.now);
      const bool turning = a.rotates || b.rotates;
      const Separation<T> sep = w.separation_at(a, b, w.now);
      const Overlap o = Impl::measure_overlap(-sep.gap, sep.contact_distance,
                                              turning ? w.rotating_rounding_scale(a, b, w.now)
                                                      : Impl::rounding_scale(a.shape, ka, b.shape, kb, w.now),
                                              i, j);
      if (o.ulps > worst.ulps) worst = o;
    }
  }
  return worst;
}

template <class T> typename World<T>::Overlap World<T>::largest_contact_overlap() const { return impl_->worst_contact; }

template <class T> std::uint64_t World<T>::state_hash() const {
  StateHasher h;
  h.add(impl_->now);
  for (BodyIndex i = 0; i < impl_->bodies.size(); ++i) {
    const Kinematics<T> k = impl_->kinematics(impl_->bodies[i], impl_->now);
    h.add(k.p.x);
    h.add(k.p.y);
    h.add(k.v.x);
    h.add(k.v.y);
    if (impl_->bodies[i].rotates) {
      h.add(impl_->angle_at(impl_->bodies[i], impl_->now));
      h.add(impl_->spin_of(impl_->bodies[i]).omega);
    }
  }
  return h.value();
}

}  // namespace pge
