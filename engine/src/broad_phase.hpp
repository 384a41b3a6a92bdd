// The broad phase (DESIGN.md, "Scale"): a uniform cell grid that tells the world which bodies
// can touch a given moving body before one of them changes its motion or crosses a cell.
//
// Every moving body whose bounding circle (radius `reach` around its position) is at most the
// grid's body radius R sits in the cell of its position; two such bodies in cells that are not
// neighbours (a Chebyshev distance of 2 or more) are at least s - 2m apart, where s is the cell
// side and m the slack a registered position may drift outside its cell before a crossing event
// moves it (hysteresis: a crossing fires m/2 past the cell's side, so a body that stops on a
// side does not cross back and forth). s = 2R(1 + 2^-10) + 2m, so those two bodies cannot
// touch. A fixed body is registered in every cell its bounding box covers: a moving body can
// touch it only while the box meets the body's cell grown by R + m < s, that is, one of the 3x3
// cells around it.
//
// Bodies the grid cannot hold are global: every body is predicted against them and they
// against every body. These are moving bodies larger than R, moving bodies outside the grid's
// region or where double-precision cell arithmetic could be off by m/8 (far from the origin,
// or a clock too coarse for their speed), and fixed bodies that would cover too many cells.
// A moving body that leaves the region becomes global for good. With every body global the
// world predicts all pairs, as it does without a broad phase.
//
// The grid works in double whatever the world's scalar: cells are a coarse filter, and every
// bound above has room for far more than double rounding.
#pragma once

#include "pge/event.hpp"

#include "aligned.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

namespace pge {

class CellGrid {
 public:
  static constexpr std::uint32_t kGlobal = std::numeric_limits<std::uint32_t>::max();

  // A grid of nx x ny cells of side `cell` whose first cell starts at (x0, y0).
  void configure(double x0, double y0, double cell, double margin, std::uint32_t nx, std::uint32_t ny) {
    x0_ = x0;
    y0_ = y0;
    cell_ = cell;
    margin_ = margin;
    nx_ = nx;
    ny_ = ny;
    cells_.assign(static_cast<std::size_t>(nx) * ny, Cell{});
    spill_.clear();
    free_spill_.clear();
  }

  double cell_size() const { return cell_; }
  double margin() const { return margin_; }
  std::size_t cell_count() const { return cells_.size(); }

  // The cell holding (x, y), or kGlobal outside the grid.
  std::uint32_t cell_of(double x, double y) const {
    const double fx = std::floor((x - x0_) / cell_), fy = std::floor((y - y0_) / cell_);
    if (!(fx >= 0 && fy >= 0 && fx < nx_ && fy < ny_)) return kGlobal;  // NaN included
    return static_cast<std::uint32_t>(fy) * nx_ + static_cast<std::uint32_t>(fx);
  }

  // The cell range [ix0, ix1] x [iy0, iy1] a box covers, clipped to the grid; false if the box
  // misses the grid.
  bool cover(double lo_x, double lo_y, double hi_x, double hi_y, std::uint32_t& ix0, std::uint32_t& iy0,
             std::uint32_t& ix1, std::uint32_t& iy1) const {
    const double fx0 = std::floor((lo_x - x0_) / cell_), fy0 = std::floor((lo_y - y0_) / cell_);
    const double fx1 = std::floor((hi_x - x0_) / cell_), fy1 = std::floor((hi_y - y0_) / cell_);
    if (!(fx1 >= 0 && fy1 >= 0 && fx0 < nx_ && fy0 < ny_)) return false;
    ix0 = static_cast<std::uint32_t>(std::max(fx0, 0.0));
    iy0 = static_cast<std::uint32_t>(std::max(fy0, 0.0));
    ix1 = static_cast<std::uint32_t>(std::min(fx1, static_cast<double>(nx_ - 1)));
    iy1 = static_cast<std::uint32_t>(std::min(fy1, static_cast<double>(ny_ - 1)));
    return true;
  }

  // A body registered in several cells (a fixed body) is inserted as `shared`: visit_around
  // says so with each of its entries, so that a caller can report it once without looking the
  // body up (with 1e5 bodies, a cache miss per candidate). Only unshared bodies are removed.
  void insert(std::uint32_t cell, BodyIndex b, bool shared = false) {
    Cell& c = cells_[cell];
    if (shared) b |= kShared;
    if (c.n < kInline) {
      c.slot[c.n++] = b;
      return;
    }
    if (c.spill == 0) {
      if (free_spill_.empty()) {
        spill_.emplace_back();
        c.spill = static_cast<std::uint32_t>(spill_.size());
      } else {
        c.spill = free_spill_.back();
        free_spill_.pop_back();
      }
    }
    spill_[c.spill - 1].push_back(b);
    ++c.n;
  }
  // Removes b from the cell; the cell's last entry takes its place.
  void remove(std::uint32_t cell, BodyIndex b) {
    Cell& c = cells_[cell];
    BodyIndex* at = nullptr;
    for (std::uint32_t k = 0; k < std::min(c.n, kInline); ++k)
      if (c.slot[k] == b) at = &c.slot[k];
    if (c.n > kInline) {
      std::vector<BodyIndex>& more = spill_[c.spill - 1];
      if (!at) {
        const auto it = std::find(more.begin(), more.end(), b);
        if (it == more.end()) return;
        at = &*it;
      }
      *at = more.back();
      more.pop_back();
      if (more.empty()) {
        free_spill_.push_back(c.spill);
        c.spill = 0;
      }
    } else {
      if (!at) return;
      *at = c.slot[c.n - 1];
    }
    --c.n;
  }

  // Where a body registered in `cell` crosses out of it: the cell's sides pushed out by m/2.
  void exit_box(std::uint32_t cell, double& lo_x, double& lo_y, double& hi_x, double& hi_y) const {
    const double ix = cell % nx_, iy = cell / nx_;
    lo_x = x0_ + ix * cell_ - margin_ / 2;
    hi_x = x0_ + (ix + 1) * cell_ + margin_ / 2;
    lo_y = y0_ + iy * cell_ - margin_ / 2;
    hi_y = y0_ + (iy + 1) * cell_ + margin_ / 2;
  }

  // Calls f(body, shared) for every entry of the 3x3 cells around `cell`. When `except` is a cell, the
  // cells that are also around `except` are left out (the neighbours a crossing adds).
  template <class F> void visit_around(std::uint32_t cell, F f, std::uint32_t except = kGlobal) const {
    const std::int64_t cx = cell % nx_, cy = cell / nx_;
    const std::int64_t ex = except == kGlobal ? -1000 : except % nx_, ey = except == kGlobal ? -1000 : except / nx_;
    for (std::int64_t y = std::max<std::int64_t>(cy - 1, 0); y <= std::min<std::int64_t>(cy + 1, ny_ - 1); ++y) {
      for (std::int64_t x = std::max<std::int64_t>(cx - 1, 0); x <= std::min<std::int64_t>(cx + 1, nx_ - 1); ++x) {
        if (std::abs(x - ex) <= 1 && std::abs(y - ey) <= 1) continue;
        const Cell& c = cells_[static_cast<std::size_t>(y) * nx_ + static_cast<std::size_t>(x)];
        for (std::uint32_t k = 0; k < std::min(c.n, kInline); ++k) f(c.slot[k] & ~kShared, (c.slot[k] & kShared) != 0);
        if (c.n > kInline)
          for (BodyIndex b : spill_[c.spill - 1]) f(b & ~kShared, (b & kShared) != 0);
      }
    }
  }

  // Requests the cache lines of the 3x3 cells around `cell` (two per row at most), ahead of a
  // visit_around: an event knows its bodies' cells well before it visits them.
  void prefetch_around(std::uint32_t cell) const {
    const std::uint32_t cx = cell % nx_, cy = cell / nx_;
    const std::uint32_t x0 = cx > 0 ? cx - 1 : 0, x1 = std::min(cx + 1, nx_ - 1);
    for (std::uint32_t y = cy > 0 ? cy - 1 : 0; y <= std::min(cy + 1, ny_ - 1); ++y) {
      prefetch_line(&cells_[static_cast<std::size_t>(y) * nx_ + x0]);
      prefetch_line(&cells_[static_cast<std::size_t>(y) * nx_ + x1]);
    }
  }

  // Bytes held by the cells (capacity, for the memory figures).
  std::size_t memory_bytes() const {
    std::size_t bytes = cells_.capacity() * sizeof(Cell) + spill_.capacity() * sizeof(std::vector<BodyIndex>) +
                        free_spill_.capacity() * sizeof(std::uint32_t);
    for (const auto& more : spill_) bytes += more.capacity() * sizeof(BodyIndex);
    return bytes;
  }

 private:
  // A cell holds its first kInline bodies itself and the rest in a spill list: a visit reads
  // the 3x3 cells' records (three runs of contiguous memory) and, in the common case, nothing
  // else; a vector per cell would add a dependent load per cell, a cache miss each with 1e5
  // bodies. 32 bytes, two cells per cache line.
  static constexpr std::uint32_t kInline = 6;
  static constexpr BodyIndex kShared = BodyIndex{1} << 31;  // tag of a shared body's entries (kMaxBodies < 2^31)
  struct Cell {
    std::uint32_t n = 0;      // entries, inline and spilled
    std::uint32_t spill = 0;  // 1 + index into spill_ while n > kInline, else 0
    BodyIndex slot[kInline] = {};
  };
  double x0_ = 0, y0_ = 0, cell_ = 1, margin_ = 0;
  std::uint32_t nx_ = 0, ny_ = 0;
  std::vector<Cell, CacheAligned<Cell>> cells_;
  std::vector<std::vector<BodyIndex>> spill_;
  std::vector<std::uint32_t> free_spill_;  // spill_ entries no cell uses
};

// The earliest s in (0, limit] at which c0 + c1 s + c2 s^2 leaves [lo, hi], for c0 inside it;
// nothing if it stays inside up to limit. 0 if c0 is already outside.
inline std::optional<double> earliest_exit(double c0, double c1, double c2, double lo, double hi, double limit) {
  if (!(c0 >= lo && c0 <= hi)) return 0.0;
  if (c2 == 0) {  // a straight path (a gas without gravity): one side can be reached, the one ahead
    if (c1 == 0) return std::nullopt;
    const double r = ((c1 > 0 ? hi : lo) - c0) / c1;  // the general case's -(c0 - bound) / c1, exactly
    if (r > 0 && r <= limit) return r;
    return std::nullopt;
  }
  std::optional<double> best;
  // Smallest positive root of c2 s^2 + c1 s + d = 0, from the numerically stable pair.
  auto root = [&](double d) {
    double r = std::numeric_limits<double>::infinity();
    if (c2 == 0) {
      if (c1 != 0 && -d / c1 > 0) r = -d / c1;
    } else {
      const double disc = c1 * c1 - 4 * c2 * d;
      if (disc >= 0) {
        const double q = -0.5 * (c1 + std::copysign(std::sqrt(disc), c1));
        const double r1 = q / c2, r2 = q != 0 ? d / q : r1;
        if (r1 > 0) r = std::min(r, r1);
        if (r2 > 0) r = std::min(r, r2);
      }
    }
    if (r <= limit && (!best || r < *best)) best = r;
  };
  root(c0 - hi);
  root(c0 - lo);
  return best;
}

}  // namespace pge
