// The oracle's certified spatial filter: which body pairs can touch before a time, in O(1) pair
// checks per event instead of a sweep over every body. Written for the oracle alone (it shares
// nothing with the engine's broad phase: a referee that shares the player's broad phase would
// share its misses).
//
// What it vouches for. For a pair (a, b) it keeps a time T such that the two bodies' shapes are
// disjoint at every t in [t_made, T], where t_made is the state's time when the bound was made,
// as long as neither body's motion changes. Every contact a search from now >= t_made reports at
// a time t in [now, W] has the shapes meeting at t (a touch or a crossing: the contact point is on
// the feature and f <= 0 there) or at now (the overlap rule and the turning rule need the pair
// overlapping at now: f(now) < 0 for a point pair, the separating-axis overlap for a vertex
// against an edge). So a pair with T > W has no contact in [now, W] and may be left out.
//
// How. Each body has a box that holds its shape over [t_made, until] (its exact path evaluated in
// interval arithmetic over the whole time span), registered in the cells of a uniform grid. Two
// bodies whose boxes are disjoint cannot meet before the earlier `until`; a search up to W first
// remakes every box that ends before W. Pairs of bodies with overlapping boxes keep a bound T.
// For two discs on straight paths it is the first root of q(tau) = |D0 + V tau|^2 - R^2 (D the
// centres' difference, R the reaches' sum), positive exactly while they are disjoint. For the
// others it comes from a separating axis n: the gap g(tau) = min over b of n.x - max over a of
// n.x is a quadratic in tau with interval coefficients (a disc's support is n.c(tau) + R |n|, a
// fixed polygon's the largest n.v over its vertices). Either quadratic, with interval
// coefficients, is at least G - beta tau + gamma tau^2 for tau >= 0, with G = lo(c0) > 0, beta =
// max(-lo(c1), 0), gamma = lo(c2), so the shapes are disjoint before its first root
// 2G / (beta + sqrt(beta^2 - 4 gamma G)), computed rounding towards zero, and for ever if it has
// none (beta = 0 <= gamma, or beta^2 < 4 gamma G certainly). A bound that the search's window
// passes is remade from the current time (the gap is smaller then, but so is the time left).
// Only the pairs of bodies whose motion changed, or whose box ends, are remade.
#pragma once

#include "model.hpp"

#include <cstdint>
#include <queue>
#include <span>
#include <unordered_map>
#include <utility>
#include <vector>

namespace pge::oracle::detail {

using BodyPair = std::pair<BodyIndex, BodyIndex>;

// The grid's cell side, in median bounding radii of the moving bodies: a box made for a body
// moving about one cell then meets a few cells and a few neighbours. Any value is correct; this
// one only sets the speed (smaller: more cells per box; larger: more pairs per cell).
inline constexpr double kFilterCellReaches = 4;
// A body's box is made to last until it may have moved one cell (or the search's window ends),
// and at most this long (seconds): a body at rest gets a box that lasts, not an infinite one.
inline constexpr double kMaxFilterSpan = 0x1p40;
// ... and at most this many times the bodies' mean time between changes of motion (a running
// mean over the run), though never less than the time to move one bounding radius: a body in a
// dense gas collides long before it crosses a cell, and a box made for the whole crossing meets
// partners it will never reach. A box that ends before its body's next collision is remade
// (expiry); a shorter one meets fewer partners.
inline constexpr double kFilterFreeTimes = 1;
// A box over more cells than this (a long wall, a fast body, a search up to a far horizon) is
// kept in a list of wide bodies, paired with every body, instead of in the grid.
inline constexpr std::int64_t kMaxFilterCells = 256;
// Cell indices stay below 2^30 in magnitude (the grid's keys hold 32 bits a coordinate); a box
// reaching farther is a wide one.
inline constexpr double kMaxFilterCellIndex = 0x1p30;

class SpatialFilter {
 public:
  // The models must outlive the filter; their motions are read when a body is (re)made.
  SpatialFilter(const std::vector<BodyModel<Interval>>& bodies, const Dyadic& now);

  // These bodies' motions changed (every model already holds its new one); `now` is the
  // state's time from which the new motions hold.
  void moved(std::span<const BodyIndex> bodies, const Dyadic& now);

  // Every pair (a < b, not both fixed) whose shapes may meet in [now, now + tau_hi], ascending:
  // a pair left out certainly has no contact there.
  std::vector<BodyPair> pairs_within(const Dyadic& now, const Dyadic& tau_hi);

 private:
  struct Box {
    double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  };
  struct Entry {
    double made = 0;   // a lower bound of the state's time when the box was made
    double until = 0;  // the box holds the shape up to this time (an upper bound's lower bound)
    Box box;
    bool wide = false;  // too many cells (or unbounded): paired with every body instead
    bool listed = false;  // in the grid or the wide list (made, and not dropped since)
    // The grid's lists it is in (the map's elements never move, and are never erased).
    std::vector<std::vector<BodyIndex>*> cells;
    std::vector<BodyIndex> partners;  // bodies with a pair bound kept
    std::uint64_t version = 0;
  };
  struct PairBound {
    double time = 0;  // the shapes are disjoint up to this time
    double made = 0;  // the state's time (lower bound) the bound was made at
    std::uint64_t stamp = 0;  // the heap entry that stands for this bound
  };
  // The bounds by time, a binary heap with lazy deletion: an entry whose stamp is not its pair's
  // current one (the pair was dropped or remade) is stale and skipped.
  struct Timed {
    double time = 0;
    std::uint64_t key = 0;
    std::uint64_t stamp = 0;
    bool operator>(const Timed& o) const { return time > o.time || (time == o.time && stamp > o.stamp); }
  };

  void make_entry(BodyIndex i, const Interval& now, double until);
  void drop_entry(BodyIndex i);
  void add_pair(BodyIndex i, BodyIndex j, const Interval& now);
  void drop_pair(BodyIndex i, BodyIndex j);
  double pair_bound(BodyIndex i, BodyIndex j, const Interval& now) const;
  double box_span(BodyIndex i) const;
  // Body i's reference path from `now` (reference_path over the interval model), kept per body
  // until its motion or `now` changes: a body is paired with several partners at one time.
  const PointPath<Interval>& path_at(BodyIndex i, const Interval& now) const;
  std::int64_t cell_of(double x) const;

  const std::vector<BodyModel<Interval>>& bodies_;
  std::vector<double> reach_;  // bounding radius about the reference point (upper bound)
  struct CachedPath {
    bool valid = false;
    double now_lo = 0, now_hi = 0;
    PointPath<Interval> path;
  };
  mutable std::vector<CachedPath> paths_;  // path_at's, invalidated by moved()
  std::vector<double> last_moved_;          // when each body's motion last changed (-inf: never)
  double free_time_ = 0;                    // the running mean time between changes (0: none yet)
  double cell_ = 1;
  std::vector<Entry> entries_;
  std::unordered_map<std::uint64_t, std::vector<BodyIndex>> grid_;
  std::vector<BodyIndex> wide_;
  std::vector<BodyIndex> near_;  // make_entry's candidates (scratch)
  struct Live {  // a bound pairs_within took off the heap, to go back on it
    std::uint64_t key;
    double bound, made;
  };
  std::vector<Live> live_;  // pairs_within's (scratch)
  std::unordered_map<std::uint64_t, PairBound> bounds_;
  std::vector<Timed> by_time_;  // a min-heap (std::push_heap with std::greater)
  std::uint64_t next_stamp_ = 0;
  void push_bound(std::uint64_t key, double time, double made);
  using Expiry = std::pair<double, std::pair<std::uint64_t, BodyIndex>>;  // until, version, body
  std::priority_queue<Expiry, std::vector<Expiry>, std::greater<>> expiry_;
};

}  // namespace pge::oracle::detail
