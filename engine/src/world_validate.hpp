// World<T>::Impl, part of world_impl.hpp. Validation: the expensive checks of PGE_VALIDATE builds
// after every event, and the tunnel watch of every moving body's path.
#pragma once

#include "world_impl.hpp"

namespace pge {

#ifdef PGE_VALIDATE
template <class T> inline auto World<T>::Impl::validate(const World& self) -> void {
  using std::isfinite;
  if (now < last_validated_time) throw std::logic_error("PGE_VALIDATE: time went backwards");
  last_validated_time = now;
  for (BodyIndex i : moving) {
    const Kinematics<T> k = kinematics(bodies[i], now);
    if (!(isfinite(k.p.x) && isfinite(k.p.y) && isfinite(k.v.x) && isfinite(k.v.y)))
      throw std::logic_error("PGE_VALIDATE: body \"" + bodies[i].id + "\" has a non-finite state");
  }
  if (bodies.size() <= 200 || (bodies.size() <= kValidateScanMaxBodies && (++validations & 1023) == 0)) {
    const Overlap o = self.largest_overlap();
    if (overlap_past_bound(to_double(o.ulps), to_double(o.depth), to_double(start_overlap_depth)))
      throw std::logic_error("PGE_VALIDATE: bodies \"" + bodies[o.a].id + "\" and \"" + bodies[o.b].id +
                             "\" overlap past the bound");
  }
}
#endif

template <class T> inline auto World<T>::Impl::watch_path(BodyIndex i) -> void {
  if (!tunnel_watch) return;
  const Body& b = bodies[i];
  if (b.fixed || b.shape.kind == ShapeKind::Segment) return;
  // An interior point: a rotating polygon's path is its centroid's already.
  const Vec2d offset = b.shape.kind == ShapeKind::Polygon && !b.rotates ? vertex_centroid(b.shape.local) : Vec2d{};
  if (!tunnel_watch->leave(i, offset, b.t0, b.p0, b.v0, b.acc, now)) return;
  if (!kValidating || !promises_every_collision(solver)) return;
  const Tunnel& t = tunnel_watch->tunnels().back();
  throw TunnelError(t, "PGE_VALIDATE: " + tunnel_text(t, bodies[t.body].id, bodies[t.fixed].id));
}

template <class T> inline auto World<T>::Impl::watch_end() -> void {
  if (!tunnel_watch || tunnels_finished) return;
  tunnels_finished = true;
  for (BodyIndex i : moving) watch_path(i);
}

}  // namespace pge
