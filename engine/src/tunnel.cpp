#include "pge/tunnel.hpp"

#include "tunnel_watch.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace pge {
namespace {

// A fixed circle is tested along chords of the arc, each within a quarter of the circle's
// radius of the arc (a parabola leaves its chord by |acc| h^2 / 8 over a step h): a chord that
// comes closer to the centre than the radius less that deviation proves the arc entered the
// circle. At most this many chords per arc (then the deviation is larger, and a shallow pass
// through the rim may go unseen: the test never alarms on a correct run, it may miss a graze of
// a deep tunnel). Pegs are tested only when the arc's box meets theirs.
constexpr int kMaxChordsPerArc = 256;
constexpr double kChordDeviationOfRadius = 0.25;
// Bisection steps for where an arc crosses a side's line: more than double's 53 bits of any
// bracket, so the crossing point is as exact as the arc's own evaluation.
constexpr int kCrossingBisections = 80;
// The grid of fixed bodies (FixedBodies): from this many fixed bodies on (fewer are tested one by
// one, as cheap as a cell lookup), at most this many cells a side (about one fixed body per
// cell). A fixed body whose box spans more cells than this (a box's long walls) is tested for
// every path; a path whose box spans more cells than this tests every fixed body. Only the cost
// depends on these: every body near a path is tested either way.
constexpr std::size_t kGridMinFixed = 32;
constexpr double kGridMaxSide = 1024;
constexpr std::uint64_t kMaxCellsPerFixedBody = 16;
constexpr std::uint64_t kMaxCellsPerPath = 64;

Vec2d at(const PositionPath& p, Vec2d offset, double s) { return p.p0 + offset + p.v * s + p.acc * (s * s / 2); }

// The range of one coordinate of the path over [s0, s1]: the ends and the extremum between.
void coordinate_range(double x0, double v, double a, double s0, double s1, double& lo, double& hi) {
  const auto x = [&](double s) { return x0 + v * s + a * (s * s / 2); };
  lo = std::min(x(s0), x(s1));
  hi = std::max(x(s0), x(s1));
  if (a != 0) {
    const double s = -v / a;
    if (s > s0 && s < s1) lo = std::min(lo, x(s)), hi = std::max(hi, x(s));
  }
}

double segment_distance(Vec2d p, Vec2d a, Vec2d b) {
  const Vec2d ab = b - a;
  const double len2 = dot(ab, ab);
  const double u = len2 > 0 ? std::clamp(dot(p - a, ab) / len2, 0.0, 1.0) : 0.0;
  const Vec2d d = p - (a + ab * u);
  return std::hypot(d.x, d.y);
}

// Whether the point's path meets the closed segment [a, b]: on each piece of the path over
// which its signed distance to the line (a quadratic in s) is monotone, a change of sign is
// located by bisection and the crossing point projected onto the segment.
bool meets_side(const PositionPath& p, Vec2d offset, Vec2d a, Vec2d b) {
  const Vec2d e = b - a;
  const double len2 = dot(e, e);
  const auto side = [&](double s) { return cross(e, at(p, offset, s) - a); };
  double cuts[3] = {p.s0, p.s1, p.s1};
  const double curvature = cross(e, p.acc);
  if (curvature != 0) {
    const double turn = -cross(e, p.v) / curvature;  // where the signed distance is extreme
    if (turn > p.s0 && turn < p.s1) cuts[1] = turn;
  }
  for (int k = 0; k < 2; ++k) {
    double lo = cuts[k], hi = cuts[k + 1];
    double f_lo = side(lo), f_hi = side(hi);
    if ((f_lo > 0 && f_hi > 0) || (f_lo < 0 && f_hi < 0)) continue;
    for (int n = 0; n < kCrossingBisections && f_lo != 0; ++n) {
      const double mid = lo + (hi - lo) / 2;
      if (mid <= lo || mid >= hi) break;
      const double f_mid = side(mid);
      if ((f_mid > 0) == (f_lo > 0) && f_mid != 0) lo = mid, f_lo = f_mid;
      else hi = mid, f_hi = f_mid;
    }
    const double u = dot(at(p, offset, f_lo == 0 ? lo : hi) - a, e) / len2;
    if (u >= 0 && u <= 1) return true;
  }
  return false;
}

// Whether the point's path provably enters the open disc of `radius` about `centre`.
bool enters_circle(const PositionPath& p, Vec2d offset, Vec2d centre, double radius) {
  const double span = p.s1 - p.s0;
  const double acc = std::hypot(p.acc.x, p.acc.y);
  int chords = 1;
  if (acc > 0) {
    const double step = std::sqrt(8 * kChordDeviationOfRadius * radius / acc);
    chords = static_cast<int>(std::clamp(std::ceil(span / step), 1.0, static_cast<double>(kMaxChordsPerArc)));
  }
  const double h = span / chords;
  const double deviation = acc * h * h / 8;
  Vec2d from = at(p, offset, p.s0);
  for (int k = 1; k <= chords; ++k) {
    const Vec2d to = at(p, offset, k == chords ? p.s1 : p.s0 + h * k);
    if (segment_distance(centre, from, to) + deviation < radius) return true;
    from = to;
  }
  return false;
}

}  // namespace

PositionPath straight_path(Vec2d from, Vec2d to) { return {from, to - from, {}, 0, 1}; }

std::string tunnel_text(const Tunnel& t, const std::string& body_id, const std::string& fixed_id) {
  std::ostringstream out;
  out.precision(17);
  out << "body \"" << body_id << "\" passed through fixed body \"" << fixed_id << "\" between t = " << t.from
      << " and t = " << t.to;
  return out.str();
}

std::optional<Vec2d> interior_offset(const BodyDesc& moving) {
  switch (moving.shape) {
    case ShapeKind::Circle: return Vec2d{};
    case ShapeKind::Segment: return std::nullopt;
    case ShapeKind::Polygon: return vertex_centroid(moving.vertices);
  }
  return std::nullopt;
}

FixedBodies::FixedBodies(const Scene& scene) {
  offsets_.reserve(scene.bodies.size());
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    const BodyDesc& b = scene.bodies[i];
    offsets_.push_back(b.fixed ? std::nullopt : interior_offset(b));
    // A spinning fixed body (a turnstile) has no fixed outline to pass through: not watched.
    if (!b.fixed || b.rotates) continue;
    Placed f;
    f.index = static_cast<BodyIndex>(i);
    if (b.shape == ShapeKind::Circle) {
      f.circle = true;
      f.centre = b.position;
      f.radius = b.radius;
      f.lo = b.position - Vec2d{b.radius, b.radius};
      f.hi = b.position + Vec2d{b.radius, b.radius};
    } else {
      if (b.shape == ShapeKind::Segment) f.edges = {b.position + b.a, b.position + b.b};
      else for (const Vec2d& v : b.vertices) f.edges.push_back(b.position + v);
      f.lo = f.hi = f.edges[0];
      for (const Vec2d& v : f.edges) {
        f.lo = {std::min(f.lo.x, v.x), std::min(f.lo.y, v.y)};
        f.hi = {std::max(f.hi.x, v.x), std::max(f.hi.y, v.y)};
      }
    }
    fixed_.push_back(std::move(f));
  }
  build_grid();
}

bool FixedBodies::hits(const Placed& f, const PositionPath& path, Vec2d offset, Vec2d lo, Vec2d hi) const {
  if (hi.x < f.lo.x || lo.x > f.hi.x || hi.y < f.lo.y || lo.y > f.hi.y) return false;
  if (f.circle) return enters_circle(path, offset, f.centre, f.radius);
  // A segment is its one side a -> b; a polygon each of its sides.
  const std::size_t sides = f.edges.size() == 2 ? 1 : f.edges.size();
  for (std::size_t k = 0; k < sides; ++k)
    if (meets_side(path, offset, f.edges[k], f.edges[(k + 1) % f.edges.size()])) return true;
  return false;
}

void FixedBodies::build_grid() {
  if (fixed_.size() < kGridMinFixed) return;
  Vec2d lo = fixed_[0].lo, hi = fixed_[0].hi;
  for (const Placed& f : fixed_) {
    lo = {std::min(lo.x, f.lo.x), std::min(lo.y, f.lo.y)};
    hi = {std::max(hi.x, f.hi.x), std::max(hi.y, f.hi.y)};
  }
  if (!(std::isfinite(lo.x) && std::isfinite(lo.y) && std::isfinite(hi.x) && std::isfinite(hi.y))) return;
  // About one fixed body per cell; a flat extent (every fixed body on one line) is one cell wide.
  const auto side = static_cast<std::uint32_t>(
      std::min<double>(kGridMaxSide, std::ceil(std::sqrt(static_cast<double>(fixed_.size())))));
  Grid& g = grid_;
  g.lo = lo;
  g.nx = hi.x > lo.x ? side : 1;
  g.ny = hi.y > lo.y ? side : 1;
  g.cell = {hi.x > lo.x ? (hi.x - lo.x) / g.nx : 1.0, hi.y > lo.y ? (hi.y - lo.y) / g.ny : 1.0};
  std::vector<std::vector<std::uint32_t>> cells(static_cast<std::size_t>(g.nx) * g.ny);
  for (std::uint32_t k = 0; k < fixed_.size(); ++k) {
    const auto [x0, x1, y0, y1] = cell_range(fixed_[k].lo, fixed_[k].hi);
    if (static_cast<std::uint64_t>(x1 - x0 + 1) * (y1 - y0 + 1) > kMaxCellsPerFixedBody) {
      g.everywhere.push_back(k);
      continue;
    }
    for (std::uint32_t y = y0; y <= y1; ++y)
      for (std::uint32_t x = x0; x <= x1; ++x) cells[static_cast<std::size_t>(y) * g.nx + x].push_back(k);
  }
  g.start.reserve(cells.size() + 1);
  for (const auto& c : cells) {
    g.start.push_back(static_cast<std::uint32_t>(g.items.size()));
    g.items.insert(g.items.end(), c.begin(), c.end());
  }
  g.start.push_back(static_cast<std::uint32_t>(g.items.size()));
}

std::array<std::uint32_t, 4> FixedBodies::cell_range(Vec2d lo, Vec2d hi) const {
  const Grid& g = grid_;
  const auto index = [](double x, double origin, double cell, std::uint32_t n) {
    const double k = std::floor((x - origin) / cell);
    return static_cast<std::uint32_t>(std::clamp(k, 0.0, static_cast<double>(n - 1)));
  };
  return {index(lo.x, g.lo.x, g.cell.x, g.nx), index(hi.x, g.lo.x, g.cell.x, g.nx), index(lo.y, g.lo.y, g.cell.y, g.ny),
          index(hi.y, g.lo.y, g.cell.y, g.ny)};
}

BodyIndex FixedBodies::passed_through(BodyIndex moving, const PositionPath& path) const {
  if (moving >= offsets_.size() || !offsets_[moving]) return kNoBody;
  return point_passed_through(*offsets_[moving], path);
}

BodyIndex FixedBodies::point_passed_through(Vec2d offset, const PositionPath& path) const {
  if (!(path.s1 >= path.s0)) return kNoBody;
  Vec2d lo, hi;
  coordinate_range(path.p0.x + offset.x, path.v.x, path.acc.x, path.s0, path.s1, lo.x, hi.x);
  coordinate_range(path.p0.y + offset.y, path.v.y, path.acc.y, path.s0, path.s1, lo.y, hi.y);
  const Grid& g = grid_;
  const bool finite = std::isfinite(lo.x) && std::isfinite(lo.y) && std::isfinite(hi.x) && std::isfinite(hi.y);
  std::array<std::uint32_t, 4> r{};
  if (finite && g.nx > 0) r = cell_range(lo, hi);
  const bool few_cells = finite && g.nx > 0 && static_cast<std::uint64_t>(r[1] - r[0] + 1) * (r[3] - r[2] + 1) <= kMaxCellsPerPath;
  if (!few_cells) {  // no grid, or a path across much of it: every fixed body, in scene order
    for (const Placed& f : fixed_)
      if (hits(f, path, offset, lo, hi)) return f.index;
    return kNoBody;
  }
  // The bodies listed in the path's cells (a path outside the grid's box is clamped into its
  // edge cells: the box test below rejects what is not near), tested in scene order.
  candidates_.assign(g.everywhere.begin(), g.everywhere.end());
  for (std::uint32_t y = r[2]; y <= r[3]; ++y)
    for (std::uint32_t x = r[0]; x <= r[1]; ++x) {
      const std::size_t c = static_cast<std::size_t>(y) * g.nx + x;
      candidates_.insert(candidates_.end(), g.items.begin() + g.start[c], g.items.begin() + g.start[c + 1]);
    }
  std::sort(candidates_.begin(), candidates_.end());
  candidates_.erase(std::unique(candidates_.begin(), candidates_.end()), candidates_.end());
  for (const std::uint32_t k : candidates_)
    if (hits(fixed_[k], path, offset, lo, hi)) return fixed_[k].index;
  return kNoBody;
}

template <class T> TunnelWatch<T>::TunnelWatch(const Scene& scene) : fixed_(scene) {}

template <class T>
bool TunnelWatch<T>::leave(BodyIndex i, Vec2d offset, const T& t0, const Vec2<T>& p0, const Vec2<T>& v0,
                           const Vec2<T>& acc, const T& now) {
  const PositionPath p{vec_cast<double>(p0), vec_cast<double>(v0), vec_cast<double>(acc), 0.0, to_double(T(now - t0))};
  const BodyIndex f = fixed_.point_passed_through(offset, p);
  if (f == kNoBody) return false;
  // Each body's first tunnel (a body through a floor may meet another below it).
  for (const Tunnel& t : tunnels_)
    if (t.body == i) return false;
  tunnels_.push_back({i, f, to_double(t0), to_double(now)});
  return true;
}

template class TunnelWatch<float>;
template class TunnelWatch<double>;
template class TunnelWatch<long double>;
template class TunnelWatch<Quad>;

}  // namespace pge
