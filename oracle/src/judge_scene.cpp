#include "judge_scene.hpp"

#include "turn.hpp"

#include "pge/world.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace pge::oracle::detail {

SceneModel scene_model(const Scene& scene) {
  WorldOptions options;
  options.broad_phase = BroadPhase::AllPairs;  // only the state is read: no grid to build
  options.frames_per_second = 0;
  const World<double> world(scene, options);
  SceneModel m;
  m.state = exact_state(world);
  for (BodyIndex i = 0; i < scene.bodies.size(); ++i) {
    m.index.emplace(scene.bodies[i].id, i);
    m.ids.push_back(scene.bodies[i].id);
    m.pivot.push_back(world.rotates(i) ? std::optional(ExactVec::from(world.pivot(i))) : std::nullopt);
    m.reference.push_back(scene.bodies[i].position);
  }
  return m;
}

ExactVec pivot_of(const SceneModel& m, BodyIndex i, const Vec2d& reference, double angle) {
  const ExactVec r = ExactVec::from(reference);
  if (!m.pivot[i]) return r;
  const ExactVec d = turned({*m.pivot[i]}, Dyadic::from(angle))[0];
  return {Dyadic::from((r.x + d.x).to_double()), Dyadic::from((r.y + d.y).to_double())};
}

Vec2d reference_of(const SceneModel& m, BodyIndex i, const ExactVec& pivot, const Dyadic& angle) {
  const ExactVec d = m.pivot[i] ? turned({*m.pivot[i]}, angle)[0] : ExactVec{};
  return {(pivot.x - d.x).to_double(), (pivot.y - d.y).to_double()};
}

Dyadic angle_at(const ExactMotion& m, const Dyadic& t) { return m.theta0 + m.omega * (t - m.t0); }

void TraceFailer::fail(int line, const std::string& element, const std::string& field, const std::string& reason) const {
  std::string where = field;
  if (line <= 0 && !element.empty()) where = field.empty() ? element : element + "." + field;
  throw TraceError(trace_.origin, line, where, reason);
}

BodyIndex TraceFailer::body(const SceneModel& m, int line, const std::string& element, const std::string& field,
                            const std::string& id) const {
  const auto it = m.index.find(id);
  if (it == m.index.end()) fail(line, element, field, fmt::format("no body \"{}\" in the scene", id.substr(0, 80)));
  return it->second;
}

void TraceFailer::finite(double x, int line, const std::string& element, const std::string& field) const {
  if (!std::isfinite(x)) fail(line, element, field, fmt::format("{} is not a finite number", x));
}

void TraceFailer::finite(const TraceState& s, int line, const std::string& element, const std::string& field) const {
  const double v[4] = {s.position.x, s.position.y, s.velocity.x, s.velocity.y};
  for (int k = 0; k < 4; ++k) finite(v[k], line, element, fmt::format("{}[{}]", field, k));
}

namespace {

ExactVec operator+(const ExactVec& a, const ExactVec& b) { return {a.x + b.x, a.y + b.y}; }
ExactVec operator-(const ExactVec& a, const ExactVec& b) { return {a.x - b.x, a.y - b.y}; }
Dyadic dot(const ExactVec& a, const ExactVec& b) { return a.x * b.x + a.y * b.y; }
Dyadic cross(const ExactVec& a, const ExactVec& b) { return a.x * b.y - a.y * b.x; }

struct Edge {
  ExactVec a, b;
};

// A polygon's edges (counter-clockwise), or a segment's one edge.
std::vector<Edge> edges_of(const Placed& p) {
  std::vector<Edge> out;
  const std::size_t n = p.vertices.size();
  if (p.shape == ShapeKind::Segment) return {{p.vertices[0], p.vertices[1]}};
  for (std::size_t k = 0; k < n; ++k) out.push_back({p.vertices[k], p.vertices[(k + 1) % n]});
  return out;
}

// The squared distance from q to the edge, exactly.
mpq_class distance2(const ExactVec& q, const Edge& e) {
  const ExactVec d = e.b - e.a, w = q - e.a;
  const Dyadic along = dot(w, d), length2 = dot(d, d);
  if (along.sign() <= 0) return dot(w, w).to_mpq();
  if (compare(along, length2) >= 0) return dot(q - e.b, q - e.b).to_mpq();
  const Dyadic c = cross(d, w);
  return (c * c).to_mpq() / length2.to_mpq();
}

Separation circle_circle(const Placed& a, const Placed& b) {
  const ExactVec d = b.centre - a.centre;
  const Dyadic d2 = dot(d, d), reach = a.radius + b.radius;
  const int s = compare(d2, reach * reach);
  if (s >= 0) return {s, 0};
  return {-1, std::max(0.0, reach.to_double() - std::sqrt(d2.to_double()))};
}

Separation circle_other(const Placed& c, const Placed& o) {
  const std::vector<Edge> edges = edges_of(o);
  const double r = c.radius.to_double();
  if (o.shape == ShapeKind::Polygon) {
    bool inside = true;
    double nearest = std::numeric_limits<double>::infinity();
    for (const Edge& e : edges) {
      const ExactVec d = e.b - e.a;
      const Dyadic side = cross(d, c.centre - e.a);  // > 0: inside of a counter-clockwise edge
      if (side.sign() <= 0) inside = false;
      nearest = std::min(nearest, side.to_double() / std::sqrt(dot(d, d).to_double()));
    }
    if (inside) return {-1, r + nearest};
  }
  mpq_class d2 = distance2(c.centre, edges[0]);
  for (const Edge& e : edges) d2 = std::min(d2, distance2(c.centre, e));
  const mpq_class r2 = (c.radius * c.radius).to_mpq();
  const int s = cmp(d2, r2) < 0 ? -1 : (cmp(d2, r2) > 0 ? 1 : 0);
  if (s >= 0) return {s, 0};
  return {-1, std::max(0.0, r - std::sqrt(d2.get_d()))};
}

// Separating axes: the normals of both bodies' edges; the gap along each, exactly in units of
// the normal's length.
Separation convex_convex(const Placed& a, const Placed& b) {
  int sign = -1;
  double depth = std::numeric_limits<double>::infinity();
  for (const Placed* owner : {&a, &b}) {
    for (const Edge& e : edges_of(*owner)) {
      const ExactVec d = e.b - e.a;
      const ExactVec n{d.y, -d.x};
      const auto extent = [&n](const Placed& p) {
        Dyadic lo = dot(n, p.vertices[0]), hi = lo;
        for (const ExactVec& v : p.vertices) {
          const Dyadic x = dot(n, v);
          if (x < lo) lo = x;
          if (x > hi) hi = x;
        }
        return std::pair(lo, hi);
      };
      const auto [alo, ahi] = extent(a);
      const auto [blo, bhi] = extent(b);
      const Dyadic gap = std::max(blo - ahi, alo - bhi);
      if (gap.sign() > 0) return {1, 0};
      if (gap.sign() == 0) sign = 0;
      depth = std::min(depth, -gap.to_double() / std::sqrt(dot(n, n).to_double()));
    }
  }
  return sign == 0 ? Separation{0, 0} : Separation{-1, std::max(0.0, depth)};
}

double size_of(const ExactBody& b) {
  double lo_x = 0, lo_y = 0, hi_x = 0, hi_y = 0;
  bool first = true;
  for (const ExactVec& v : b.local) {
    const double x = v.x.to_double(), y = v.y.to_double();
    lo_x = first ? x : std::min(lo_x, x);
    hi_x = first ? x : std::max(hi_x, x);
    lo_y = first ? y : std::min(lo_y, y);
    hi_y = first ? y : std::max(hi_y, y);
    first = false;
  }
  return std::max(hi_x - lo_x, hi_y - lo_y);
}

}  // namespace

Placed place(const ExactBody& body, const ExactVec& position, const Dyadic& angle) {
  Placed p;
  p.shape = body.shape;
  p.radius = body.radius;
  p.centre = position;
  if (body.rotates) {
    for (const ExactVec& v : turned(body.local, angle)) p.vertices.push_back(position + v);
  } else if (body.fixed) {
    p.vertices = body.world;
  } else {
    for (const ExactVec& v : body.local) p.vertices.push_back(position + v);
  }
  return p;
}

Separation separation(const Placed& a, const Placed& b) {
  const bool ca = a.shape == ShapeKind::Circle, cb = b.shape == ShapeKind::Circle;
  if (ca && cb) return circle_circle(a, b);
  if (ca) return circle_other(a, b);
  if (cb) return circle_other(b, a);
  return convex_convex(a, b);
}

double contact_distance(const ExactBody& a, const ExactBody& b) {
  const bool ca = a.shape == ShapeKind::Circle, cb = b.shape == ShapeKind::Circle;
  if (ca && cb) return (a.radius + b.radius).to_double();
  if (ca) return a.radius.to_double();
  if (cb) return b.radius.to_double();
  return std::min(size_of(a), size_of(b));
}

Box bounding_box(const Placed& p) {
  // Each corner is a rounded sum or conversion: a relative 2^-40 outward covers it many times over.
  constexpr double kOutward = 0x1p-40;
  Box box;
  const auto add = [&box](double x, double y, bool first) {
    box.lo_x = first ? x : std::min(box.lo_x, x);
    box.hi_x = first ? x : std::max(box.hi_x, x);
    box.lo_y = first ? y : std::min(box.lo_y, y);
    box.hi_y = first ? y : std::max(box.hi_y, y);
  };
  if (p.shape == ShapeKind::Circle) {
    const double x = p.centre.x.to_double(), y = p.centre.y.to_double(), r = p.radius.to_double();
    add(x - r, y - r, true);
    add(x + r, y + r, false);
  } else {
    for (std::size_t k = 0; k < p.vertices.size(); ++k) add(p.vertices[k].x.to_double(), p.vertices[k].y.to_double(), k == 0);
  }
  const double m = kOutward * (1 + std::max({std::abs(box.lo_x), std::abs(box.hi_x), std::abs(box.lo_y), std::abs(box.hi_y)}));
  box.lo_x -= m;
  box.lo_y -= m;
  box.hi_x += m;
  box.hi_y += m;
  return box;
}

Box reach_box(const ExactBody& body, const ExactVec& position) {
  if (!body.rotates) return bounding_box(place(body, position));
  double reach = body.radius.to_double();
  for (const ExactVec& v : body.local) reach = std::max(reach, std::hypot(v.x.to_double(), v.y.to_double()));
  Placed disc;
  disc.centre = position;
  disc.radius = Dyadic::from(reach);
  return bounding_box(disc);  // outward by 2^-40 relative: more than the roundings of the reach
}

Dyadic body_energy(const ExactBody& body, const ExactVec& position, const ExactVec& velocity, const Dyadic& omega) {
  return body.mass * (dot(velocity, velocity).scaled(-1) - dot(body.field_acc, position)) +
         (body.inertia * omega * omega).scaled(-1);
}

}  // namespace pge::oracle::detail
