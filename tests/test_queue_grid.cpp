// The event queue (engine/src/event_heap.hpp) and the grid's cells (broad_phase.hpp) against
// brute-force models, under random operations. The expected answers are computed here from the
// documented orders, by scanning every body: no heap, no cell records.
//   - EventHeap: after every update, the top is the minimum over all bodies of (earlier of the
//     contact's and the crossing's times; a crossing before a contact at equal times; contacts
//     by Scheduled::key_less; then owner); every 97 updates a copy emptied from the top yields
//     every scheduled body in that order, and visit_up_to reports exactly the valid contacts
//     at or before the bound, and visit_next reports the root's children with their contacts'
//     partners, the model's second body among them. Times are drawn from a few values so that
//     ties are common.
//   - CellGrid: after inserts and removes (cells fuller than their inline slots included),
//     visit_around reports the same bodies, each with whether it was inserted as shared (a
//     fixed body in several cells), as a list per cell would.
#include "broad_phase.hpp"
#include "event_heap.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <optional>
#include <random>
#include <tuple>
#include <utility>
#include <vector>

namespace pge {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// The order the heap documents, for one body (contact entry and crossing time).
struct Key {
  double time;
  int crossing_first;  // 0: crossing, 1: contact (crossings first)
  Scheduled<double> contact;
  BodyIndex owner;
};
Key key_of(const Scheduled<double>& c, double crossing, BodyIndex owner) {
  const bool cross = crossing != kInf && crossing <= c.time;
  return {cross ? crossing : c.time, cross ? 0 : 1, c, owner};
}
bool key_less(const Key& x, const Key& y) {
  if (x.time != y.time) return x.time < y.time;
  if (x.time == kInf) return x.owner < y.owner;
  if (x.crossing_first != y.crossing_first) return x.crossing_first < y.crossing_first;
  if (x.crossing_first == 1) {
    if (x.contact.key_less(y.contact)) return true;
    if (y.contact.key_less(x.contact)) return false;
  }
  return x.owner < y.owner;
}

TEST(EventHeap, TopAndVisitMatchAScanUnderRandomUpdates) {
  std::mt19937_64 g(20261122);
  const BodyIndex n = 300;
  std::vector<BodyIndex> members;
  for (BodyIndex i = 0; i < n; i += 1 + static_cast<BodyIndex>(g() % 2)) members.push_back(i);  // not every body
  EventHeap<double> heap;
  heap.reset(n, members);
  std::vector<Scheduled<double>> contact(n);
  std::vector<double> crossing(n, kInf);
  const double times[] = {0.5, 1.0, 1.0, 1.5, 2.0, kInf};
  for (int step = 0; step < 20000; ++step) {
    const BodyIndex i = members[g() % members.size()];
    const int what = static_cast<int>(g() % 3);
    if (what != 1) {  // a new contact (or none)
      Scheduled<double> s;
      const double t = times[g() % 6];
      if (t != kInf) {
        s.time = t;
        const BodyIndex other = static_cast<BodyIndex>(g() % 4);  // few partners: equal keys happen
        s.lo = std::min(i, other);
        s.hi = std::max(i, other);
        s.partner = other;
        s.feature_a = static_cast<std::uint16_t>(g() % 2);
      }
      contact[i] = s;
    }
    if (what != 0) crossing[i] = times[g() % 6];
    if (what == 0) heap.set(i, contact[i]);
    else if (what == 1) heap.set_crossing(i, crossing[i]);
    else heap.set(i, contact[i], crossing[i]);

    Key best = key_of(contact[members[0]], crossing[members[0]], members[0]);
    for (BodyIndex m : members) {
      const Key k = key_of(contact[m], crossing[m], m);
      if (key_less(k, best)) best = k;
    }
    ASSERT_EQ(heap.top_index(), best.owner) << "step " << step;
    ASSERT_EQ(heap.top_time(), best.time);
    ASSERT_EQ(heap.top_is_crossing(), best.crossing_first == 0 && best.time != kInf);
    // visit_next: the root's children, each with its contact's partner as the entry holds it
    // (none when invalid), and among them the body the model orders second.
    std::vector<std::pair<BodyIndex, BodyIndex>> next;
    heap.visit_next([&](BodyIndex owner, BodyIndex partner) { next.emplace_back(owner, partner); });
    ASSERT_EQ(next.size(), std::min<std::size_t>(4, members.size() - 1));
    for (const auto& [owner, partner] : next)
      ASSERT_EQ(partner, contact[owner].valid() ? contact[owner].partner : kNoBody) << "step " << step << ", body " << owner;
    std::optional<Key> second;
    for (BodyIndex m : members) {
      const Key k = key_of(contact[m], crossing[m], m);
      if (m != best.owner && (!second || key_less(k, *second))) second = k;
    }
    ASSERT_TRUE(std::any_of(next.begin(), next.end(), [&](const auto& e) { return e.first == second->owner; }))
        << "step " << step << ": the second event's body " << second->owner << " is not a child of the root";
    if (step % 97 == 0) {
      // The whole order, not only the top: a copy emptied from the top (each taken body's
      // events set to none) yields the bodies with something scheduled in the model's order.
      std::vector<Key> order;
      for (BodyIndex m : members)
        if (key_of(contact[m], crossing[m], m).time != kInf) order.push_back(key_of(contact[m], crossing[m], m));
      std::sort(order.begin(), order.end(), key_less);
      EventHeap<double> copy = heap;
      for (const Key& k : order) {
        ASSERT_EQ(copy.top_index(), k.owner) << "step " << step;
        copy.set(k.owner, Scheduled<double>{}, kInf);
      }
      ASSERT_EQ(copy.top_time(), kInf);
      const double bound = times[g() % 5];
      std::vector<BodyIndex> seen, want;
      heap.visit_up_to(bound, [&](BodyIndex b) { seen.push_back(b); });
      for (BodyIndex m : members)
        if (contact[m].valid() && contact[m].time <= bound) want.push_back(m);
      std::sort(seen.begin(), seen.end());
      ASSERT_EQ(seen, want) << "step " << step << ", bound " << bound;
    }
  }
}

TEST(CellGrid, VisitsWhatAListPerCellHolds) {
  std::mt19937_64 g(7);
  CellGrid grid;
  const std::uint32_t nx = 6, ny = 5;
  grid.configure(0, 0, 1, 0.1, nx, ny);
  using Entry = std::pair<BodyIndex, bool>;  // a body and whether it was inserted as shared
  std::vector<std::vector<Entry>> model(nx * ny);
  BodyIndex next = 0, next_shared = 999000;  // shared ones near kMaxBodies, never removed
  for (int step = 0; step < 5000; ++step) {
    // Cells 0 and 7 take many bodies (past the inline slots and back), the rest a few.
    const std::uint32_t c = g() % 3 == 0 ? (g() % 2 ? 0u : 7u) : static_cast<std::uint32_t>(g() % (nx * ny));
    if (g() % 10 == 0) {
      grid.insert(c, next_shared, /*shared=*/true);
      model[c].emplace_back(next_shared++, true);
    } else if (g() % 2 == 0 || model[c].empty()) {
      grid.insert(c, next);
      model[c].emplace_back(next++, false);
    } else {
      const std::size_t k = g() % model[c].size();
      if (!model[c][k].second) {
        grid.remove(c, model[c][k].first);
        model[c].erase(model[c].begin() + static_cast<std::ptrdiff_t>(k));
      }
    }
    grid.remove(c, next + 1000);  // a body the cell does not hold: nothing happens
    const std::uint32_t around = static_cast<std::uint32_t>(g() % (nx * ny));
    std::vector<Entry> seen, want;
    grid.visit_around(around, [&](BodyIndex b, bool shared) { seen.emplace_back(b, shared); });
    const int cx = static_cast<int>(around % nx), cy = static_cast<int>(around / nx);
    for (int y = cy - 1; y <= cy + 1; ++y)
      for (int x = cx - 1; x <= cx + 1; ++x)
        if (x >= 0 && y >= 0 && x < static_cast<int>(nx) && y < static_cast<int>(ny))
          for (const Entry& e : model[static_cast<std::size_t>(y) * nx + static_cast<std::size_t>(x)]) want.push_back(e);
    std::sort(seen.begin(), seen.end());
    std::sort(want.begin(), want.end());
    ASSERT_EQ(seen, want) << "step " << step << ", around cell " << around;
  }
  EXPECT_GT(model[0].size() + model[7].size(), 12u) << "the busy cells spilled past their inline slots";
  EXPECT_GT(next_shared, 999000u + 100u) << "shared bodies were inserted";
}

}  // namespace
}  // namespace pge
