// Following a World's moving bodies along their paths, for tunnels (pge/tunnel.hpp). Private:
// the World runs it (WorldOptions::watch_tunnels, PGE_VALIDATE builds) and lists what it found
// (World::tunnels()).
#pragma once

#include "pge/scalar.hpp"
#include "pge/tunnel.hpp"

#include <vector>

namespace pge {

// The world tells the watch when a moving body leaves its path (a collision, a slide off a
// face's end, set_velocity: just before its motion changes) and, at the end of the run, that
// every path ends. A body's path is its motion since its reference time t0, which the world
// moves only when the motion changes, so the watch keeps nothing per body: it reads the path
// from the world's body record (in cache: the event is processing that body) and tests it,
// O(fixed bodies near the path) box tests per motion change.
template <class T> class TunnelWatch {
 public:
  explicit TunnelWatch(const Scene& scene);
  // Moving body i, whose interior point is `offset` from its position (interior_offset), leaves
  // the path p(t) = p0 + v0 (t - t0) + acc (t - t0)^2 / 2 at `now`: tests it from t0 to now.
  // True when this found the body's first tunnel.
  bool leave(BodyIndex i, Vec2d offset, const T& t0, const Vec2<T>& p0, const Vec2<T>& v0, const Vec2<T>& acc,
             const T& now);
  // The first tunnel of each body that had one, in the order found.
  const std::vector<Tunnel>& tunnels() const { return tunnels_; }

 private:
  FixedBodies fixed_;
  std::vector<Tunnel> tunnels_;
};

extern template class TunnelWatch<float>;
extern template class TunnelWatch<double>;
extern template class TunnelWatch<long double>;
extern template class TunnelWatch<Quad>;

}  // namespace pge
