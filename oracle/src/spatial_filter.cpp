#include "spatial_filter.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace pge::oracle::detail {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

Interval enclose_time(const Dyadic& t) { return Interval::enclose(t); }

double norm_up(double x, double y) { return sqrt_up((square(Interval(x)) + square(Interval(y))).hi()); }

double mid(const Interval& v) { return 0.5 * v.lo() + 0.5 * v.hi(); }

std::uint64_t pair_key(BodyIndex i, BodyIndex j) {
  const BodyIndex a = std::min(i, j), b = std::max(i, j);
  return (static_cast<std::uint64_t>(a) << 32) | static_cast<std::uint64_t>(b);
}

BodyPair pair_of(std::uint64_t key) {
  return {static_cast<BodyIndex>(key >> 32), static_cast<BodyIndex>(key & 0xffffffffu)};
}

// What the filter knows of a body's shape from `now` on: a disc about a point on a quadratic
// path (moving bodies and fixed circles), or a fixed convex outline.
struct Hull {
  bool outline = false;
  const PointPath<Interval>* centre = nullptr;
  Interval reach;                               // the disc's radius, an upper bound
  const std::vector<V2<Interval>>* vertices = nullptr;  // the outline's world vertices
};

// max over the hull of n.x at tau, as a polynomial in tau with interval coefficients.
Poly<Interval> support(const Hull& h, double nx, double ny) {
  if (h.outline) {
    double lo = -kInf, hi = -kInf;
    for (const V2<Interval>& v : *h.vertices) {
      const Interval s = v.x * Interval(nx) + v.y * Interval(ny);
      lo = std::max(lo, s.lo());
      hi = std::max(hi, s.hi());
    }
    return Poly<Interval>::constant(Interval(lo, hi));
  }
  Poly<Interval> p = h.centre->x * Interval(nx) + h.centre->y * Interval(ny);
  p.c[0] = p.c[0] + h.reach * Interval(norm_up(nx, ny));
  return p;
}

// A gap g(tau) (an enclosure of it for each tau >= 0, degree <= 2) stays positive at least as
// long as this (tau, a lower bound): g >= G - beta tau + gamma tau^2 with G = lo(g0) > 0, beta =
// max(-lo(g1), 0) and gamma = lo(g2) of either sign, positive before its first root
// 2G / (beta + sqrt(beta^2 - 4 gamma G)), rounded towards zero here, and for ever when nothing
// closes it (beta = 0 and gamma >= 0) or when it has no root (beta^2 < 4 gamma G, certainly).
double positive_for(const Poly<Interval>& g) {
  const double G = g.c[0].lo();
  if (!(G > 0)) return 0;
  const double beta = std::max(g.deg >= 1 ? -g.c[1].lo() : 0.0, 0.0);
  const double gamma = g.deg >= 2 ? g.c[2].lo() : 0.0;
  if (beta == 0 && gamma >= 0) return kInf;
  const double disc = (square(Interval(beta)) - Interval(4.0) * Interval(gamma) * Interval(G)).hi();
  if (disc < 0) return kInf;
  const double den = (Interval(beta) + Interval(sqrt_up(disc))).hi();
  if (!(den > 0) || std::isnan(den)) return 0;
  const double q = next_down(G / den);  // below G / den: the quotient rounds by half an ulp at most
  if (!(q > 0)) return 0;
  return std::min(2 * q, std::numeric_limits<double>::max());  // doubling is exact (or saturates)
}

// How long (tau from now, a lower bound) b stays strictly on the +n side of a: the gap
// g(tau) = min_b n.x - max_a n.x.
double separated_for(const Hull& a, const Hull& b, double nx, double ny) {
  if (nx == 0 && ny == 0) return 0;
  return positive_for(-support(b, -nx, -ny) - support(a, nx, ny));
}

// The same for two discs, along n: g(tau) = n.(cb(tau) - ca(tau)) - (ra + rb) |n|, with the
// centres' difference taken first (half the products of two supports; the same enclosure's
// meaning, an interval bound of the same gap).
double discs_separated_for(const Hull& a, const Hull& b, double nx, double ny) {
  if (nx == 0 && ny == 0) return 0;
  Poly<Interval> g;
  g.deg = std::max({a.centre->x.deg, a.centre->y.deg, b.centre->x.deg, b.centre->y.deg});
  const Interval n_x(nx), n_y(ny);
  for (int k = 0; k <= g.deg; ++k)
    g.c[k] = (b.centre->x.c[k] - a.centre->x.c[k]) * n_x + (b.centre->y.c[k] - a.centre->y.c[k]) * n_y;
  g.c[0] = g.c[0] - (a.reach + b.reach) * Interval(norm_up(nx, ny));
  return positive_for(g);
}

bool straight(const PointPath<Interval>& p) {
  for (int k = 2; k <= std::max(p.x.deg, p.y.deg); ++k)
    if (!is_exact_zero(p.x.c[k]) || !is_exact_zero(p.y.c[k])) return false;
  return true;
}

// Two discs on straight paths: |D(tau)|^2 - (ra + rb)^2, with D = D0 + V tau the centres'
// difference, is positive exactly while they are disjoint, and it is the quadratic
// V.V tau^2 + 2 D0.V tau + D0.D0 - (ra + rb)^2. Its first root is the pair's contact (when
// they meet at all): no axis fixed now can vouch for longer, and a pair that passes by without
// meeting is vouched for until a motion changes.
double straight_discs_apart_for(const Hull& a, const Hull& b) {
  const Interval dx = b.centre->x.c[0] - a.centre->x.c[0], dy = b.centre->y.c[0] - a.centre->y.c[0];
  const Interval vx = b.centre->x.c[1] - a.centre->x.c[1], vy = b.centre->y.c[1] - a.centre->y.c[1];
  Poly<Interval> g;
  g.deg = 2;
  g.c[0] = square(dx) + square(dy) - square(a.reach + b.reach);
  g.c[1] = Interval(2.0) * (dx * vx + dy * vy);
  g.c[2] = square(vx) + square(vy);
  return positive_for(g);
}

}  // namespace

SpatialFilter::SpatialFilter(const std::vector<BodyModel<Interval>>& bodies, const Dyadic& now)
    : bodies_(bodies), reach_(bodies.size(), 0.0), paths_(bodies.size()), last_moved_(bodies.size(), -kInf),
      entries_(bodies.size()) {
  std::vector<double> moving;
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const BodyModel<Interval>& b = bodies[i];
    double r = b.radius.hi();
    if (b.shape != ShapeKind::Circle) {
      r = 0;
      for (const V2<Interval>& v : b.local)
        r = std::max(r, sqrt_up((square(v.x) + square(v.y)).hi()));
    }
    reach_[i] = r;
    if (!b.fixed) moving.push_back(r);
  }
  if (!moving.empty()) {
    std::nth_element(moving.begin(), moving.begin() + static_cast<long>(moving.size() / 2), moving.end());
    cell_ = kFilterCellReaches * moving[moving.size() / 2];
  }
  if (!(cell_ > 0) || !std::isfinite(cell_)) cell_ = 1;
  const Interval t = enclose_time(now);
  for (BodyIndex i = 0; i < bodies.size(); ++i) make_entry(i, t, -kInf);
}

void SpatialFilter::moved(std::span<const BodyIndex> bodies, const Dyadic& now) {
  const Interval t = enclose_time(now);
  // Every body is dropped before any is made again: a pair of them is bounded once, when the
  // second is made, from both new paths.
  for (const BodyIndex i : bodies) {
    // The mean time between changes of motion, an exponential running mean (only a speed matter).
    if (const double dt = t.lo() - last_moved_[i]; dt > 0 && std::isfinite(dt))
      free_time_ = free_time_ > 0 ? 0.98 * free_time_ + 0.02 * dt : dt;
    last_moved_[i] = t.lo();
    paths_[i].valid = false;
    drop_entry(i);
  }
  for (const BodyIndex i : bodies) make_entry(i, t, -kInf);
}

std::vector<BodyPair> SpatialFilter::pairs_within(const Dyadic& now, const Dyadic& tau_hi) {
  const Interval t = enclose_time(now);
  const double w = (t + enclose_time(tau_hi)).hi();  // the window's end, rounded up
  // Every box must hold its body up to the window's end.
  while (!expiry_.empty() && expiry_.top().first < w) {
    const auto [until, tag] = expiry_.top();
    expiry_.pop();
    const auto [version, i] = tag;
    if (entries_[i].version != version) continue;  // remade since
    drop_entry(i);
    make_entry(i, t, w);
  }
  // Pairs not vouched for up to w; a bound made before now is remade from now first. Every
  // entry up to w is taken off the heap and the live ones go back after the sweep.
  std::vector<BodyPair> out;
  std::vector<Live>& live = live_;  // scratch, kept between calls
  live.clear();
  while (!by_time_.empty() && by_time_.front().time <= w) {
    const Timed top = by_time_.front();
    std::pop_heap(by_time_.begin(), by_time_.end(), std::greater<>());
    by_time_.pop_back();
    const auto it = bounds_.find(top.key);
    if (it == bounds_.end() || it->second.stamp != top.stamp) continue;  // stale
    const BodyPair p = pair_of(top.key);
    Live l{top.key, top.time, it->second.made};
    if (l.made < t.lo()) l = {top.key, pair_bound(p.first, p.second, t), t.lo()};
    if (l.bound <= w) out.push_back(p);
    live.push_back(l);
  }
  for (const Live& l : live) push_bound(l.key, l.bound, l.made);
  std::sort(out.begin(), out.end());
  return out;
}

double SpatialFilter::box_span(BodyIndex i) const {
  // Long enough for the body to move about one cell: the box then meets a few cells.
  const BodyModel<Interval>& b = bodies_[i];
  const double speed = norm_up(std::max(std::abs(b.v0.x.lo()), std::abs(b.v0.x.hi())),
                               std::max(std::abs(b.v0.y.lo()), std::abs(b.v0.y.hi())));
  const double acc = norm_up(std::max(std::abs(b.acc.x.lo()), std::abs(b.acc.x.hi())),
                             std::max(std::abs(b.acc.y.lo()), std::abs(b.acc.y.hi())));
  double span = kMaxFilterSpan;
  if (speed > 0) span = std::min(span, cell_ / speed);
  if (acc > 0) span = std::min(span, std::sqrt(2 * cell_ / acc));
  // At most the mean free time, but never below the time to move one bounding radius: a box
  // that short hardly shrinks, and would only be remade more often (a body at rest keeps a box
  // that lasts).
  double radius_time = kMaxFilterSpan;
  if (speed > 0) radius_time = std::min(radius_time, reach_[i] / speed);
  if (acc > 0) radius_time = std::min(radius_time, std::sqrt(2 * reach_[i] / acc));
  if (free_time_ > 0) span = std::min(span, std::max(kFilterFreeTimes * free_time_, radius_time));
  return span;
}

const PointPath<Interval>& SpatialFilter::path_at(BodyIndex i, const Interval& now) const {
  CachedPath& c = paths_[i];
  if (!c.valid || c.now_lo != now.lo() || c.now_hi != now.hi()) {
    c.path = reference_path(bodies_[i], now);
    c.now_lo = now.lo();
    c.now_hi = now.hi();
    c.valid = true;
  }
  return c.path;
}

std::int64_t SpatialFilter::cell_of(double x) const { return static_cast<std::int64_t>(std::floor(x / cell_)); }

void SpatialFilter::make_entry(BodyIndex i, const Interval& now, double until) {
  const BodyModel<Interval>& b = bodies_[i];
  Entry& e = entries_[i];
  e.made = now.lo();
  e.listed = true;
  ++e.version;
  Interval x, y;
  if (b.fixed) {
    e.until = kInf;
    if (b.shape == ShapeKind::Circle) {
      x = b.p0.x + Interval(-reach_[i], reach_[i]);
      y = b.p0.y + Interval(-reach_[i], reach_[i]);
    } else {
      x = b.world.front().x;
      y = b.world.front().y;
      for (const V2<Interval>& v : b.world) x = hull(x, v.x), y = hull(y, v.y);
    }
  } else {
    e.until = std::max((now + Interval(box_span(i))).lo(), until);
    // tau in [0, until - now]: the box holds the shape over [now, until].
    const Interval tau(0.0, (Interval(e.until) - now).hi());
    const PointPath<Interval>& ref = path_at(i, now);
    x = evaluate(ref.x, tau) + Interval(-reach_[i], reach_[i]);
    y = evaluate(ref.y, tau) + Interval(-reach_[i], reach_[i]);
    expiry_.push({e.until, {e.version, i}});
  }
  e.box = {x.lo(), y.lo(), x.hi(), y.hi()};
  const double limit = kMaxFilterCellIndex * cell_;
  const bool bounded = std::abs(e.box.x0) < limit && std::abs(e.box.x1) < limit && std::abs(e.box.y0) < limit &&
                       std::abs(e.box.y1) < limit;
  std::vector<BodyIndex>& near = near_;  // scratch, kept between calls
  near.clear();
  e.cells.clear();
  e.wide = !bounded;
  if (bounded) {
    const std::int64_t cx0 = cell_of(e.box.x0), cx1 = cell_of(e.box.x1);
    const std::int64_t cy0 = cell_of(e.box.y0), cy1 = cell_of(e.box.y1);
    e.wide = (cx1 - cx0 + 1) * (cy1 - cy0 + 1) > kMaxFilterCells;
    if (!e.wide)
      for (std::int64_t cx = cx0; cx <= cx1; ++cx)
        for (std::int64_t cy = cy0; cy <= cy1; ++cy) {
          const std::uint64_t key = (static_cast<std::uint64_t>(cx) << 32) ^ static_cast<std::uint64_t>(cy & 0xffffffff);
          std::vector<BodyIndex>& in = grid_[key];
          e.cells.push_back(&in);
          near.insert(near.end(), in.begin(), in.end());
          in.push_back(i);
        }
  }
  if (e.wide) {
    for (BodyIndex j = 0; j < entries_.size(); ++j)
      if (j != i && entries_[j].listed) near.push_back(j);
    wide_.push_back(i);
  } else {
    near.insert(near.end(), wide_.begin(), wide_.end());
  }
  std::sort(near.begin(), near.end());
  near.erase(std::unique(near.begin(), near.end()), near.end());
  for (BodyIndex j : near) {
    if (j == i || (b.fixed && bodies_[j].fixed)) continue;
    const Box& o = entries_[j].box;
    if (e.box.x0 <= o.x1 && o.x0 <= e.box.x1 && e.box.y0 <= o.y1 && o.y0 <= e.box.y1) add_pair(i, j, now);
  }
}

void SpatialFilter::drop_entry(BodyIndex i) {
  Entry& e = entries_[i];
  for (BodyIndex j : e.partners) {
    const std::uint64_t key = pair_key(i, j);
    bounds_.erase(key);  // its heap entry is stale from now on
    std::vector<BodyIndex>& back = entries_[j].partners;
    back.erase(std::find(back.begin(), back.end(), i));
  }
  e.partners.clear();
  for (std::vector<BodyIndex>* in : e.cells) in->erase(std::find(in->begin(), in->end(), i));
  e.cells.clear();
  if (e.wide) wide_.erase(std::find(wide_.begin(), wide_.end(), i));
  e.wide = false;
  e.listed = false;
}

void SpatialFilter::add_pair(BodyIndex i, BodyIndex j, const Interval& now) {
  const std::uint64_t key = pair_key(i, j);
  const double bound = pair_bound(i, j, now);
  push_bound(key, bound, now.lo());
  entries_[i].partners.push_back(j);
  entries_[j].partners.push_back(i);
}

void SpatialFilter::push_bound(std::uint64_t key, double time, double made) {
  const std::uint64_t stamp = ++next_stamp_;
  bounds_[key] = {time, made, stamp};
  by_time_.push_back({time, key, stamp});
  std::push_heap(by_time_.begin(), by_time_.end(), std::greater<>());
  // Stale entries are dropped when they reach the top; a heap mostly stale is rebuilt.
  if (by_time_.size() > 2 * bounds_.size() + 1024) {
    by_time_.clear();
    for (const auto& [k, b] : bounds_) by_time_.push_back({b.time, k, b.stamp});
    std::make_heap(by_time_.begin(), by_time_.end(), std::greater<>());
  }
}

double SpatialFilter::pair_bound(BodyIndex i, BodyIndex j, const Interval& now) const {
  const auto hull_of = [&](BodyIndex k) {
    const BodyModel<Interval>& b = bodies_[k];
    Hull h;
    if (b.fixed && b.shape != ShapeKind::Circle) {
      h.outline = true;
      h.vertices = &b.world;
    } else {
      h.centre = &path_at(k, now);
      h.reach = Interval(reach_[k]);
    }
    return h;
  };
  const Hull a = hull_of(i), b = hull_of(j);
  double tau = 0;
  if (!a.outline && !b.outline) {
    // Two discs: their distance when both paths are straight, else the axis through their
    // centres now.
    if (straight(*a.centre) && straight(*b.centre)) tau = straight_discs_apart_for(a, b);
    else tau = discs_separated_for(a, b, mid(b.centre->x.c[0] - a.centre->x.c[0]), mid(b.centre->y.c[0] - a.centre->y.c[0]));
  } else {
    // A disc and a fixed outline: the outline's edge normals and the coordinate axes, both ways.
    const std::vector<V2<Interval>>& v = a.outline ? *a.vertices : *b.vertices;
    std::vector<std::pair<double, double>> axes = {{1, 0}, {0, 1}};
    for (std::size_t k = 0; k < v.size(); ++k) {
      const V2<Interval>& p = v[k];
      const V2<Interval>& q = v[(k + 1) % v.size()];
      axes.push_back({mid(q.y - p.y), -mid(q.x - p.x)});
    }
    for (const auto& [nx, ny] : axes) tau = std::max({tau, separated_for(a, b, nx, ny), separated_for(a, b, -nx, -ny)});
  }
  if (!(tau > 0)) return -kInf;  // nothing vouched for beyond now
  return (now + Interval(tau)).lo();
}

}  // namespace pge::oracle::detail
