// The pieces both scene generators build with (generators.cpp, rotating_generators.cpp): exact
// dyadic parameters drawn by rapidcheck, the bodies they are made into, and the exact scaling and
// shifting that places a motif. Private to the generators.
#pragma once

#include "pge/scene.hpp"
#include "pge/scene_io.hpp"

#include <rapidcheck.h>

#include <cmath>
#include <ostream>
#include <string>
#include <vector>

namespace pge::scene_parts {

// Unit-scale motif coordinates are multiples of 2^-kQuantumBits: sums of them and of dyadic
// offsets stay exact, which is what keeps a degenerate placement degenerate in doubles.
inline constexpr int kQuantumBits = 20;

inline double quantize(double x, int bits = kQuantumBits) {
  return std::ldexp(std::nearbyint(std::ldexp(x, bits)), -bits);
}

// rapidcheck scales integer ranges with its size parameter (small early cases); choices and
// parameters here use the whole range at every size, so that every kind is generated from the
// start. The number of motifs still grows with the size.
inline constexpr int kFullSize = 100;
template <class T> rc::Gen<T> uniform_in(T lo, T hi) { return rc::gen::resize(kFullSize, rc::gen::inRange<T>(lo, hi)); }

// One of `choices`, uniformly at every size; shrinks towards the first.
template <class T> rc::Gen<T> one_of(std::vector<T> choices) {
  return rc::gen::map(uniform_in<std::size_t>(0, choices.size()), [choices](std::size_t k) { return choices[k]; });
}

// A parameter in [-1, 1] with `bits` bits after the point; shrinks towards 0.
inline rc::Gen<double> gen_signed(int bits) {
  const int n = 1 << bits;
  return rc::gen::map(uniform_in(0, 2 * n + 1), [bits](int k) {
    const int v = (k % 2 == 1) ? -(k + 1) / 2 : k / 2;  // 0, -1, 1, -2, 2, ...
    return std::ldexp(static_cast<double>(v), -bits);
  });
}
// The same in [0, 1].
inline rc::Gen<double> gen_unit(int bits) {
  return rc::gen::map(uniform_in(0, (1 << bits) + 1), [bits](int k) { return std::ldexp(double(k), -bits); });
}

inline BodyDesc circle_body(double r, Vec2d p, Vec2d v, double mass) {
  BodyDesc b;
  b.shape = ShapeKind::Circle;
  b.radius = r;
  b.position = p;
  b.velocity = v;
  b.mass = mass;
  return b;
}

inline BodyDesc polygon_body(std::vector<Vec2d> vertices, Vec2d p, Vec2d v, double mass) {
  BodyDesc b;
  b.shape = ShapeKind::Polygon;
  b.vertices = std::move(vertices);
  b.position = p;
  b.velocity = v;
  b.mass = mass;
  return b;
}

inline BodyDesc box_body(double hx, double hy, Vec2d p, Vec2d v, double mass) {
  return polygon_body({{-hx, -hy}, {hx, -hy}, {hx, hy}, {-hx, hy}}, p, v, mass);
}

inline BodyDesc triangle_body(double h, Vec2d p, Vec2d v, double mass) {
  return polygon_body({{-h, -h}, {h, -h}, {0, h}}, p, v, mass);
}

inline BodyDesc fixed_segment(Vec2d a, Vec2d b) {
  BodyDesc s;
  s.shape = ShapeKind::Segment;
  s.a = a;
  s.b = b;
  s.fixed = true;
  return s;
}

inline void make_fixed(BodyDesc& b) {
  b.fixed = true;
  b.velocity = {};
  b.acceleration = {};
}

// Scales a body by 2^k (exact) and moves it by dx along x (exact for quantised coordinates).
// Angles and angular velocities do not change with scale.
inline void place(BodyDesc& b, int k, double dx) {
  auto s = [k](Vec2d v) { return Vec2d{std::ldexp(v.x, k), std::ldexp(v.y, k)}; };
  b.radius = std::ldexp(b.radius, k);
  b.a = s(b.a);
  b.b = s(b.b);
  for (Vec2d& v : b.vertices) v = s(v);
  b.position = s(b.position);
  b.position.x += dx;
  b.velocity = s(b.velocity);
  b.acceleration = s(b.acceleration);
}

// Appends motif `index`'s bodies to `s`: scaled by 2^k and moved along x beside the motifs before
// it (`x` is the right end of the last one; the first is centred at 0), `gap` apart at its scale,
// each body named "m<index>-<body>". The motif fits in [-extent, extent]^2 at unit scale. Returns
// its half-width at its scale.
inline double append_motif(Scene& s, std::vector<BodyDesc> bodies, std::size_t index, int k, double extent, double gap,
                           double& x) {
  const double half = std::ldexp(extent, k);
  if (index > 0) x += half + std::ldexp(gap, k);
  for (std::size_t j = 0; j < bodies.size(); ++j) {
    bodies[j].id = "m" + std::to_string(index) + "-" + std::to_string(j);
    place(bodies[j], k, x);
  }
  s.bodies.insert(s.bodies.end(), bodies.begin(), bodies.end());
  x += half;
  return half;
}

// What rapidcheck shows for a generated scene: its motifs by name, then the scene as JSON.
template <class Motif, class Name>
void print_motifs_and_scene(std::ostream& os, const std::vector<Motif>& motifs, Name name, const Scene& scene) {
  os << "motifs:";
  for (Motif m : motifs) os << ' ' << name(m);
  os << "\nscene JSON:\n" << write_scene(scene);
}

}  // namespace pge::scene_parts
