// Static geometry of convex outlines, shared by scene validation (doubles, from the scene) and
// the engine (its scalar, from its state): separations and sizes, no motion.
//
// An outline is a convex polygon given counter-clockwise, or a segment a, b seen as the
// degenerate polygon [a, b]: its two edges a->b and b->a are the segment's two sides. Edge k
// runs from vertex k to vertex k + 1 (mod n) and faces the outward normal (e.y, -e.x); a point q
// is in front of it by cross(q - start, e) / |e|. Vertices come from an accessor `v(k)`, so that
// callers need not build arrays.
#pragma once

#include "pge/vec2.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>

namespace pge {

// The outward normal of a counter-clockwise polygon's edge vector (right-hand perpendicular).
template <class T> Vec2<T> outward_normal(const Vec2<T>& e) { return {e.y, -e.x}; }

template <class T> T max_abs(const Vec2<T>& p) {
  using std::abs;
  return std::max(abs(p.x), abs(p.y));
}

// Separating-axis test over the edge normals of both outlines: the largest, over the axes, of
// the smallest signed distance of the other outline's vertices in front of the edge. Positive:
// the outlines are apart (by at least that much); zero: touching; negative: minus the depth of
// the least penetration (for convex outlines the edge normals are the only candidate axes).
template <class T, class VP, class VQ>
T outline_separation(const VP& vp, std::size_t np, const VQ& vq, std::size_t nq) {
  using std::sqrt;
  T best = -std::numeric_limits<T>::infinity();
  auto scan = [&best](const auto& owner, std::size_t n_owner, const auto& other, std::size_t n_other) {
    for (std::size_t j = 0; j < n_owner; ++j) {
      const Vec2<T> a = owner(j);
      const Vec2<T> e = owner((j + 1) % n_owner) - a;
      const T len = sqrt(dot(e, e));
      T nearest = std::numeric_limits<T>::infinity();
      for (std::size_t k = 0; k < n_other; ++k) nearest = std::min(nearest, cross(other(k) - a, e) / len);
      best = std::max(best, nearest);
    }
  };
  scan(vp, np, vq, nq);
  scan(vq, nq, vp, np);
  return best;
}

// Signed distance from point c to an outline: the distance to its nearest edge when c is
// outside (or on it), minus the distance to the nearest edge line when c is strictly inside.
// A segment has no inside: c is in front of one of its two sides or on its line.
template <class T, class V> T point_outline_distance(const Vec2<T>& c, const V& v, std::size_t n) {
  using std::sqrt;
  bool inside = true;
  T nearest = std::numeric_limits<T>::infinity();
  T depth = std::numeric_limits<T>::infinity();
  for (std::size_t k = 0; k < n; ++k) {
    const Vec2<T> a = v(k);
    const Vec2<T> e = v((k + 1) % n) - a;
    const Vec2<T> q = c - a;
    const T ee = dot(e, e);
    const T front = cross(q, e);
    if (!(front < T(0))) inside = false;
    const T lambda = std::clamp(dot(q, e) / ee, T(0), T(1));
    const Vec2<T> off = q - e * lambda;
    nearest = std::min(nearest, sqrt(dot(off, off)));
    depth = std::min(depth, -front / sqrt(ee));
  }
  return inside ? -depth : nearest;
}

// The larger side of the outline's bounding box: its size, independent of where its reference
// point is.
template <class T, class V> T outline_size(const V& v, std::size_t n) {
  Vec2<T> lo = v(0), hi = v(0);
  for (std::size_t k = 1; k < n; ++k) {
    const Vec2<T> p = v(k);
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
  }
  return std::max(hi.x - lo.x, hi.y - lo.y);
}

}  // namespace pge
