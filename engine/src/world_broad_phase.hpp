// World<T>::Impl, part of world_impl.hpp. Broad phase and scheduling: which bodies a body is
// predicted against (every body, or the grid cells around it), its next cell crossing, and its one
// scheduled event in the heap.
#pragma once

#include "world_impl.hpp"

namespace pge {

template <class T> template <class F> inline auto World<T>::Impl::for_candidates(BodyIndex i, F f) -> void {
  if (!grid_on || bodies[i].cell == kGlobal) {
    for (BodyIndex j = 0; j < bodies.size(); ++j)
      if (j != i) f(j);
    return;
  }
  visit_cells(i, bodies[i].cell, kGlobal, f);
  for (BodyIndex j : globals) f(j);
}

template <class T> template <class F>
inline auto World<T>::Impl::visit_cells(BodyIndex i, std::uint32_t c, std::uint32_t except, F& f) -> void {
  std::vector<BodyIndex> list;
  list.swap(candidates);  // reentrant: a nested call would find an empty scratch list
  list.clear();
  next_scan();
  const auto keep = [&](BodyIndex j) { list.push_back(j); };
  grid.visit_around(c, [&](BodyIndex j, bool shared) { visit_once(i, j, shared, keep); }, except);
  if (prefetching)
    for (BodyIndex j : list) prefetch_hot(bodies[j]);
  for (BodyIndex j : list) f(j);
  candidates.swap(list);
}

template <class T> inline auto World<T>::Impl::prefetch_cells(BodyIndex i) const -> void {
  if (bodies[i].cell < grid.cell_count()) grid.prefetch_around(bodies[i].cell);
}

template <class T> inline auto World<T>::Impl::prefetch_candidates(BodyIndex i) const -> void {
  if (bodies[i].cell < grid.cell_count())
    grid.visit_around(bodies[i].cell, [&](BodyIndex j, bool) { prefetch_hot(bodies[j]); });
}

template <class T> inline auto World<T>::Impl::prefetch_hot(const Body& b) -> void {
  prefetch_line(&b);
  prefetch_line(reinterpret_cast<const char*>(&b) + 64);
}

template <class T> inline auto World<T>::Impl::next_scan() -> void {
  if (++scan == 0) {  // wrapped: forget every mark
    std::fill(seen.begin(), seen.end(), 0u);
    scan = 1;
  }
}

template <class T> template <class F>
inline auto World<T>::Impl::visit_once(BodyIndex i, BodyIndex j, bool shared, F& f) -> void {
  if (j == i) return;
  if (shared) {
    if (seen[j] == scan) return;
    seen[j] = scan;
  }
  f(j);
}

template <class T> inline auto World<T>::Impl::reschedule(BodyIndex i) -> void {
  const T crossing = grid_on ? crossing_time(i, now) : EventHeap<T>::never();
  Scheduled<T> best;
  for_candidates(i, [&](BodyIndex j) { offer(i, j, best); });
  const Body& b = bodies[i];
  for (int k = 0; k < b.supports; ++k) {
    const std::optional<T> t = leave_time(b, b.support[static_cast<std::size_t>(k)]);
    if (!t || !(*t < best.time || !best.valid())) continue;
    const BodyIndex f = b.support[static_cast<std::size_t>(k)].body;
    Scheduled<T> s;
    s.time = *t;
    s.lo = std::min(i, f);
    s.hi = std::max(i, f);
    s.feature_a = static_cast<std::uint16_t>(k);
    s.partner = f;
    s.refined = true;  // not a contact: nothing to re-derive
    s.leave = true;
    best = s;
  }
  heap.set(i, best, crossing);
}

template <class T> inline auto World<T>::Impl::setup_grid(BroadPhase mode) -> void {
  for (Body& b : bodies) b.cell = kGlobal;
  grid_on = mode == BroadPhase::Grid || (mode == BroadPhase::Auto && moving.size() >= kGridMinMovingBodies);
  if (!grid_on || moving.empty()) {
    grid_on = false;
    return;
  }
  std::vector<double> reach;
  reach.reserve(moving.size());
  for (BodyIndex i : moving) reach.push_back(to_double(bodies[i].shape.reach));
  std::vector<double> sorted = reach;
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2), sorted.end());
  const double median = sorted[sorted.size() / 2];
  double radius = 0;
  for (double r : reach)
    if (r <= 4 * median) radius = std::max(radius, r);
  const double margin = radius / 8;
  double side = 2 * radius * (1 + 0x1p-10) + 2 * margin;
  // The region: moving positions, then fixed boxes no larger than 64 times their extent.
  double lo_x = std::numeric_limits<double>::infinity(), lo_y = lo_x, hi_x = -lo_x, hi_y = -lo_x;
  for (BodyIndex i : moving) {
    const double x = to_double(bodies[i].p0.x), y = to_double(bodies[i].p0.y);
    lo_x = std::min(lo_x, x); hi_x = std::max(hi_x, x);
    lo_y = std::min(lo_y, y); hi_y = std::max(hi_y, y);
  }
  const double extent = std::max(hi_x - lo_x, hi_y - lo_y) + side;
  std::vector<std::array<double, 4>> boxes(bodies.size());
  for (BodyIndex j = 0; j < bodies.size(); ++j) {
    if (!bodies[j].fixed) continue;
    boxes[j] = fixed_box(bodies[j]);
    const auto& b = boxes[j];
    if (std::max(b[2] - b[0], b[3] - b[1]) > 64 * extent) continue;
    lo_x = std::min(lo_x, b[0]); lo_y = std::min(lo_y, b[1]);
    hi_x = std::max(hi_x, b[2]); hi_y = std::max(hi_y, b[3]);
  }
  const double cap = 16.0 * static_cast<double>(moving.size()) + 4096;
  const double w = hi_x - lo_x, h = hi_y - lo_y;
  side = std::max(side, std::sqrt((w + 4 * side) * (h + 4 * side) / cap));
  for (int k = 0; k < 64 && (w / side + 5) * (h / side + 5) > cap; ++k) side *= 1.25;
  if (!(std::isfinite(side) && side > 0 && std::isfinite(w) && std::isfinite(h))) {
    grid_on = false;
    return;
  }
  const auto nx = static_cast<std::uint32_t>(std::ceil(w / side) + 4), ny = static_cast<std::uint32_t>(std::ceil(h / side) + 4);
  grid.configure(lo_x - 2 * side, lo_y - 2 * side, side, margin, nx, ny);
  seen.assign(bodies.size(), 0u);
  for (std::size_t k = 0; k < moving.size(); ++k) {
    const BodyIndex i = moving[k];
    if (reach[k] > radius) {
      make_global(i);
      continue;
    }
    const std::uint32_t c = grid.cell_of(to_double(bodies[i].p0.x), to_double(bodies[i].p0.y));
    if (c == kGlobal) {
      make_global(i);
      continue;
    }
    bodies[i].cell = c;
    grid.insert(c, i);
  }
  // A fixed body in every cell its box grown by R + m covers (a moving body in a cell may be
  // m outside it and reach R further): a moving body finds it in its own cell, and so among
  // the 3x3 around it. More cells than the cap: global.
  const double fixed_cap = std::max(4096.0, 8.0 * static_cast<double>(moving.size()));
  for (BodyIndex j = 0; j < bodies.size(); ++j) {
    if (!bodies[j].fixed) continue;
    const auto& b = boxes[j];
    const double grow = radius + margin;
    std::uint32_t x0, y0, x1, y1;
    if (!grid.cover(b[0] - grow, b[1] - grow, b[2] + grow, b[3] + grow, x0, y0, x1, y1)) {
      bodies[j].cell = kOutside;
      continue;
    }
    if ((static_cast<double>(x1 - x0) + 1) * (static_cast<double>(y1 - y0) + 1) > fixed_cap) {
      make_global(j);
      continue;
    }
    bodies[j].cell = kInCells;
    for (std::uint32_t y = y0; y <= y1; ++y)
      for (std::uint32_t x = x0; x <= x1; ++x) grid.insert(y * nx + x, j, /*shared=*/true);
  }
}

template <class T> inline auto World<T>::Impl::fixed_box(const Body& b) -> std::array<double, 4> {
  if (!b.shape.is_outline() || b.rotates) {  // a spinning body sweeps its bounding circle
    const double x = to_double(b.p0.x), y = to_double(b.p0.y);
    const double r = to_double(b.rotates ? b.shape.reach : b.shape.radius) * (1 + 0x1p-20);
    return {x - r, y - r, x + r, y + r};
  }
  std::array<double, 4> box{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
                            -std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
  for (const Vec2<T>& v : b.shape.world) {
    const double x = to_double(v.x), y = to_double(v.y);
    box[0] = std::min(box[0], x); box[1] = std::min(box[1], y);
    box[2] = std::max(box[2], x); box[3] = std::max(box[3], y);
  }
  return box;
}

template <class T> inline auto World<T>::Impl::make_global(BodyIndex i) -> void {
  if (!bodies[i].fixed && bodies[i].cell < kOutside) grid.remove(bodies[i].cell, i);
  bodies[i].cell = kGlobal;
  globals.push_back(i);
  ++counts.global_bodies;
  if (!bodies[i].fixed) heap.set_crossing(i, EventHeap<T>::never());
}

template <class T> inline auto World<T>::Impl::crossing_time(BodyIndex i, const T& from) -> T {
  if (bodies[i].cell == kGlobal) return EventHeap<T>::never();
  const Body& b = bodies[i];
  const Kinematics<T> k = kinematics(b, from);
  double lo_x, lo_y, hi_x, hi_y;
  grid.exit_box(bodies[i].cell, lo_x, lo_y, hi_x, hi_y);
  const double px = to_double(k.p.x), py = to_double(k.p.y), vx = to_double(k.v.x), vy = to_double(k.v.y);
  const double ax = to_double(k.a.x), ay = to_double(k.a.y);
  const double limit = to_double(horizon - from);
  std::optional<double> s = earliest_exit(px, vx, ax / 2, lo_x, hi_x, limit);
  const std::optional<double> sy = earliest_exit(py, vy, ay / 2, lo_y, hi_y, limit);
  if (sy && (!s || *sy < *s)) s = sy;
  using std::abs;
  const double until = s ? *s : std::max(limit, 0.0);
  const double tau = to_double(from - b.t0) + until;
  const double eps = std::max(static_cast<double>(std::numeric_limits<T>::epsilon()), 0x1p-52);
  const double speed = std::abs(vx) + std::abs(vy) + (std::abs(ax) + std::abs(ay)) * until;
  const double scale = std::max(std::abs(lo_x), std::abs(hi_x)) + std::max(std::abs(lo_y), std::abs(hi_y)) +
                       to_double(abs(b.p0.x) + abs(b.p0.y)) +
                       to_double(abs(b.v0.x) + abs(b.v0.y)) * tau +
                       to_double(abs(b.acc.x) + abs(b.acc.y)) * tau * tau / 2 +
                       speed * (to_double(abs(from)) + until);
  if (!(8 * eps * scale <= grid.margin() / 8)) {
    make_global(i);
    return EventHeap<T>::never();
  }
  return s ? from + T(*s) : EventHeap<T>::never();
}

template <class T> inline auto World<T>::Impl::cross(BodyIndex i, const T& at) -> void {
  ++counts.crossings;
  const std::uint32_t old = bodies[i].cell;
  const Kinematics<T> k = kinematics(bodies[i], at);
  const std::uint32_t c = grid.cell_of(to_double(k.p.x), to_double(k.p.y));
  if (c == kGlobal || c == old) {  // out of the grid, or not past the exit box: global
    make_global(i);
    reschedule(i);
    return;
  }
  // The old cell, the new one and the new neighbours, requested at once.
  if (prefetching) grid.prefetch_around(c);
  grid.remove(old, i);
  grid.insert(c, i);
  bodies[i].cell = c;
  Scheduled<T> best = heap.at(i);
  auto f = [&](BodyIndex j) { offer(i, j, best); };
  visit_cells(i, c, old, f);
  const T next = crossing_time(i, at);
  heap.set(i, best, next);
  if (bodies[i].cell == kGlobal) reschedule(i);
}

template <class T> inline auto World<T>::Impl::schedule_all() -> void {
  if (grid_on) {
    for (BodyIndex i : moving) reschedule(i);
    return;
  }
  std::vector<Scheduled<T>> best(bodies.size());
  for (BodyIndex i = 0; i < bodies.size(); ++i) {
    for (BodyIndex j = i + 1; j < bodies.size(); ++j) {
      // Offered to both bodies: of use up to the later of their best events so far.
      const auto until = [&](BodyIndex k) { return best[k].valid() && !bodies[k].fixed ? best[k].time : horizon; };
      auto c = predict(i, j, std::max(until(i), until(j)));
      if (!c) continue;
      Scheduled<T> s = scheduled(*c, i, j, j);
      if (!bodies[i].fixed && s.key_less(best[i])) best[i] = s;
      s.partner = i;
      s.partner_version = bodies[i].version;
      if (!bodies[j].fixed && s.key_less(best[j])) best[j] = s;
    }
  }
  for (BodyIndex i : moving) heap.set(i, best[i]);
}

}  // namespace pge
