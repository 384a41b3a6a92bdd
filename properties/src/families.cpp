#include "pge/families.hpp"

#include <cmath>
#include <numbers>
#include <string>

namespace pge {

std::uint64_t SplitMix64::next() {
  std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ull);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

double SplitMix64::uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }

namespace {

void add_wall(Scene& s, const char* id, Vec2d a, Vec2d b) {
  BodyDesc w;
  w.id = id;
  w.shape = ShapeKind::Segment;
  w.fixed = true;
  w.a = a;
  w.b = b;
  s.bodies.push_back(w);
}

void add_box(Scene& s, double side) {
  add_wall(s, "wall-bottom", {0, 0}, {side, 0});
  add_wall(s, "wall-right", {side, 0}, {side, side});
  add_wall(s, "wall-top", {side, side}, {0, side});
  add_wall(s, "wall-left", {0, side}, {0, 0});
}

Scene base_scene(const GasParams& p, const std::string& name) {
  Scene s;
  s.name = name + "-" + std::to_string(p.bodies);
  s.world.gravity = {0, p.gravity == 0 ? 0.0 : -p.gravity};  // no negative zero in the file
  s.run.until = p.until;
  s.run.max_events = p.max_events;
  return s;
}

// Moving bodies on a jittered grid of per_row columns of cells cw x ch from (x0, y0) up (rows as
// needed): each centre stays `reach` away from its grid cell's edges, so none overlap.
template <class Shape>
void add_movers(Scene& s, const GasParams& p, double x0, double y0, std::uint32_t per_row, double cw, double ch,
                double reach, Shape shape) {
  const double slack_x = cw / 2 - reach, slack_y = ch / 2 - reach;
  SplitMix64 rng(p.seed);
  for (std::uint32_t i = 0; i < p.bodies; ++i) {
    BodyDesc b;
    b.id = "b" + std::to_string(i);
    shape(b, i);
    b.mass = 1;
    const double cx = x0 + (i % per_row + 0.5) * cw, cy = y0 + (i / per_row + 0.5) * ch;
    const double jx = slack_x > 0 ? slack_x * 0.9 : 0, jy = slack_y > 0 ? slack_y * 0.9 : 0;
    b.position = {cx + rng.uniform(-jx, jx), cy + rng.uniform(-jy, jy)};
    b.velocity = {rng.uniform(-p.speed, p.speed), rng.uniform(-p.speed, p.speed)};
    s.bodies.push_back(b);
  }
}

}  // namespace

Scene make_gas(const GasParams& p) {
  Scene s = base_scene(p, "gas");
  // Box side from the area fraction: n pi r^2 = fraction * side^2.
  const double side = std::sqrt(p.bodies * std::numbers::pi * p.radius * p.radius / p.area_fraction);
  add_box(s, side);
  // One square grid cell per disc, as many columns as rows (the layout of earlier versions, kept
  // so that a seed gives the same scene as before).
  const auto per_row = static_cast<std::uint32_t>(std::ceil(std::sqrt(static_cast<double>(p.bodies))));
  const double cell = side / per_row;
  add_movers(s, p, 0, 0, per_row, cell, cell, p.radius, [&](BodyDesc& b, std::uint32_t) {
    b.shape = ShapeKind::Circle;
    b.radius = p.radius;
  });
  return s;
}

Scene make_pegs(const GasParams& p) {
  GasParams q = p;
  if (q.gravity == 0) q.gravity = 1;
  Scene s = base_scene(q, "pegs");
  // The discs fill the upper half at the area fraction.
  const double side = std::sqrt(2 * p.bodies * std::numbers::pi * p.radius * p.radius / p.area_fraction);
  add_box(s, side);
  const double gap = 8 * p.radius;
  std::uint32_t pegs = 0;
  for (std::uint32_t row = 0;; ++row) {
    const double y = gap + row * gap;
    if (y > side / 2 - gap) break;
    const double shift = row % 2 == 0 ? 0 : gap / 2;
    for (double x = gap + shift; x < side - gap / 2; x += gap) {
      BodyDesc peg;
      peg.id = "peg" + std::to_string(pegs++);
      peg.shape = ShapeKind::Circle;
      peg.radius = p.radius;
      peg.fixed = true;
      peg.position = {x, y};
      s.bodies.push_back(peg);
    }
  }
  const auto columns = static_cast<std::uint32_t>(std::ceil(std::sqrt(2.0 * p.bodies)));
  const double cw = side / columns;
  const double ch = (side / 2) / ((p.bodies + columns - 1) / columns);
  add_movers(s, q, 0, side / 2, columns, cw, ch, p.radius, [&](BodyDesc& b, std::uint32_t) {
    b.shape = ShapeKind::Circle;
    b.radius = p.radius;
  });
  return s;
}

Scene make_polygons(const GasParams& p) {
  Scene s = base_scene(p, "polygons");
  const std::uint32_t obstacles = p.bodies / 16;
  const double r = p.radius;
  const double side = std::sqrt((p.bodies + obstacles) * std::numbers::pi * r * r / p.area_fraction);
  add_box(s, side);
  // The obstacles: regular pentagons of circumradius r on a coarse grid, the movers between.
  const auto per_row = static_cast<std::uint32_t>(std::ceil(std::sqrt(static_cast<double>(obstacles))));
  for (std::uint32_t k = 0; k < obstacles; ++k) {
    BodyDesc o;
    o.id = "obstacle" + std::to_string(k);
    o.shape = ShapeKind::Polygon;
    o.fixed = true;
    for (int v = 0; v < 5; ++v) {
      const double a = 2 * std::numbers::pi * v / 5 + std::numbers::pi / 2;
      o.vertices.push_back({r * std::cos(a), r * std::sin(a)});
    }
    const double cell = side / per_row;
    o.position = {(k % per_row + 0.5) * cell, (k / per_row + 0.5) * cell};
    s.bodies.push_back(o);
  }
  // Movers in the strips between obstacle rows would need a layout of their own; instead they
  // take the jittered grid and skip the cells whose disc meets an obstacle's.
  Scene movers = base_scene(p, "movers");
  GasParams more = p;
  more.bodies = p.bodies + 4 * obstacles + 16;
  const double h = 0.7 * r;  // squares of half side 0.7 r, triangles of circumradius r
  const auto columns = static_cast<std::uint32_t>(std::ceil(std::sqrt(static_cast<double>(more.bodies))));
  const double cell = side / columns;
  // Each mover turned by its own angle: edges of different bodies are then (almost) never
  // parallel, where a contact of two edges is a tie between two feature pairs.
  SplitMix64 turn(p.seed ^ 0x5eedull);
  add_movers(movers, more, 0, 0, columns, cell, cell, r, [&](BodyDesc& b, std::uint32_t i) {
    b.shape = ShapeKind::Polygon;
    const double angle = turn.uniform(0, 2 * std::numbers::pi);
    const int n = i % 2 == 0 ? 4 : 3;
    const double radius = n == 4 ? h * std::numbers::sqrt2 : r;  // a square of half side h
    for (int v = 0; v < n; ++v) {
      const double a = angle + 2 * std::numbers::pi * v / n;
      b.vertices.push_back({radius * std::cos(a), radius * std::sin(a)});
    }
  });
  std::uint32_t taken = 0;
  SplitMix64 spin(p.seed ^ 0x5b1eull);
  for (const BodyDesc& m : movers.bodies) {
    if (taken == p.bodies) break;
    if (m.fixed) continue;
    bool clear = true;
    for (std::uint32_t k = 0; k < obstacles && clear; ++k) {
      const Vec2d d = m.position - s.bodies[4 + k].position;
      clear = d.x * d.x + d.y * d.y > 4.5 * r * r;
    }
    if (!clear) continue;
    BodyDesc b = m;
    b.id = "b" + std::to_string(taken++);
    if (p.spin > 0) {
      b.rotates = true;
      b.angular_velocity = spin.uniform(-p.spin, p.spin);
    }
    s.bodies.push_back(b);
  }
  return s;
}

}  // namespace pge
