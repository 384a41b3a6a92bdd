// A body's shape as the contact code sees it, built once when the world is made, and the
// motion of a body at one instant.
#pragma once

#include "geometry.hpp"

#include "pge/scene.hpp"
#include "pge/vec2.hpp"

#include <cmath>
#include <cstddef>
#include <vector>

namespace pge {

template <class T> struct Kinematics {
  Vec2<T> p, v, a;  // position, velocity, acceleration at one instant
};

template <class T> struct BodyShape {
  ShapeKind kind = ShapeKind::Circle;
  bool fixed = false;
  T radius{};            // circles
  // Next to the radius: every prediction of two circles reads both (pair_scale), and with 1e5
  // bodies each further cache line of a candidate is another miss (see World's Body).
  T span{};              // largest coordinate magnitude of `world` (fixed) or `local`
  T reach{};             // farthest point of the body from its position (circles: the radius)
  Vec2<T> seg_a, seg_b;  // fixed segments: world endpoints (world[0], world[1])
  // Polygons and segments (outlines, see geometry.hpp: a segment has the edges a->b and b->a).
  std::vector<Vec2<T>> local;     // vertices relative to the position, as in the scene
  std::vector<Vec2<T>> world;     // fixed bodies: position + local, rounded once
  std::vector<Vec2<T>> edges;     // vertex k+1 - vertex k, from `world` if fixed, else `local`
  std::vector<T> edge_length;     // |edges[k]|
  T size{};                       // larger side of the bounding box

  bool is_outline() const { return kind != ShapeKind::Circle; }
  std::size_t vertex_count() const { return local.size(); }

  // Vertex k of a body at position p, as base + offset: a moving body's vertex is exactly
  // p + local[k], a fixed body's is world[k]. Differences of two vertices subtract the bases
  // first, so that positions far from the origin cancel before the small offsets are added.
  Vec2<T> base(const Vec2<T>& p, std::size_t k) const { return fixed ? world[k] : p; }
  Vec2<T> offset(std::size_t k) const { return fixed ? Vec2<T>{} : local[k]; }
  Vec2<T> vertex(const Vec2<T>& p, std::size_t k) const { return fixed ? world[k] : p + local[k]; }

  // The largest coordinate magnitude of the body's points when it is at p: the scale at which
  // its coordinates are rounded.
  T coordinate_scale(const Vec2<T>& p) const {
    if (fixed && is_outline()) return span;
    return max_abs(p) + span;
  }
};

template <class T> BodyShape<T> make_body_shape(const BodyDesc& d) {
  using std::sqrt;
  BodyShape<T> s;
  s.kind = d.shape;
  s.fixed = d.fixed;
  s.radius = T(d.radius);
  s.reach = s.radius;
  if (d.shape == ShapeKind::Circle) return s;
  if (d.shape == ShapeKind::Segment) s.local = {vec_cast<T>(d.a), vec_cast<T>(d.b)};
  for (const Vec2d& v : d.vertices) s.local.push_back(vec_cast<T>(v));
  const Vec2<T> position = vec_cast<T>(d.position);
  if (d.fixed)
    for (const Vec2<T>& v : s.local) s.world.push_back(position + v);
  if (d.shape == ShapeKind::Segment && d.fixed) {
    s.seg_a = s.world[0];
    s.seg_b = s.world[1];
  }
  const std::vector<Vec2<T>>& pts = d.fixed ? s.world : s.local;
  const std::size_t n = pts.size();
  for (std::size_t k = 0; k < n; ++k) {
    s.edges.push_back(pts[(k + 1) % n] - pts[k]);
    s.edge_length.push_back(sqrt(dot(s.edges[k], s.edges[k])));
    s.span = std::max(s.span, max_abs(pts[k]));
    const Vec2<T> from_position = d.fixed ? s.world[k] - position : s.local[k];
    s.reach = std::max(s.reach, sqrt(dot(from_position, from_position)));
  }
  s.size = outline_size<T>([&](std::size_t k) { return s.local[k]; }, n);
  return s;
}

}  // namespace pge
