// One scheduled contact per moving body, in an indexed 4-ary min-heap: updating a body's
// event is O(log n) and leaves no stale copies behind.
#pragma once

#include "pge/event.hpp"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <vector>

namespace pge {

template <class T> struct Scheduled {
  T time = std::numeric_limits<T>::infinity();
  BodyIndex lo = kNoBody;  // the pair, lower index first
  BodyIndex hi = kNoBody;
  ContactKind contact = ContactKind::CircleCircle;
  std::uint16_t feature_a = 0;
  std::uint16_t feature_b = 0;
  bool at_start_overlap = false;
  bool corner = false;                  // a vertex against an edge's end (contact_polygon.hpp)
  BodyIndex partner = kNoBody;          // the other body of the pair, seen from the owner
  std::uint64_t partner_version = 0;    // the partner's version when this was predicted
  bool refined = false;                 // certified: time re-derived from the exact paths (refine.hpp)
  // Not a contact: the owner, resting on the fixed body `partner`, slides off the end of that
  // face (support slot feature_a) at `time` (resting contact, world.cpp).
  bool leave = false;

  bool valid() const { return lo != kNoBody; }

  // The fixed order of simultaneous events: time, then (all collisions) the lower body, the
  // higher body, then the contact kind and features so that the order is total.
  bool key_less(const Scheduled& o) const {
    if (!valid()) return false;
    if (!o.valid()) return true;
    if (time != o.time) return time < o.time;
    if (lo != o.lo) return lo < o.lo;
    if (hi != o.hi) return hi < o.hi;
    if (contact != o.contact) return contact < o.contact;
    if (feature_a != o.feature_a) return feature_a < o.feature_a;
    return feature_b < o.feature_b;
  }
};

// The heap array holds each entry's time beside its owner, so that sifting compares times in
// contiguous memory and reads the full entry only to break a tie: with 1e5 bodies the entries
// no longer fit in cache, and an indirect read per comparison was the queue's main cost.
template <class T> class EventHeap {
 public:
  void reset(std::size_t body_count, const std::vector<BodyIndex>& members) {
    entries_.assign(body_count, Scheduled<T>{});
    pos_.assign(body_count, kAbsent);
    heap_.clear();
    heap_.reserve(members.size());
    for (BodyIndex i : members) {
      pos_[i] = static_cast<std::uint32_t>(heap_.size());
      heap_.push_back({entries_[i].time, i});
    }
  }
  bool empty() const { return heap_.empty(); }
  const Scheduled<T>& top() const { return entries_[heap_.front().owner]; }
  BodyIndex top_index() const { return heap_.front().owner; }
  const Scheduled<T>& at(BodyIndex i) const { return entries_[i]; }

  // Owners of every valid entry whose time is <= bound, in heap order (children are never
  // earlier than their parent, so the walk stops at the first later entry on each branch).
  template <class F> void visit_up_to(const T& bound, F f) const {
    std::vector<std::size_t> stack;
    if (!heap_.empty()) stack.push_back(0);
    while (!stack.empty()) {
      const std::size_t k = stack.back();
      stack.pop_back();
      const Scheduled<T>& e = entries_[heap_[k].owner];
      if (!e.valid() || !(e.time <= bound)) continue;
      f(heap_[k].owner);
      for (std::size_t c = kArity * k + 1; c <= kArity * k + kArity && c < heap_.size(); ++c) stack.push_back(c);
    }
  }

  std::size_t memory_bytes() const {
    return entries_.capacity() * sizeof(Scheduled<T>) + pos_.capacity() * sizeof(std::uint32_t) +
           heap_.capacity() * sizeof(Node);
  }

  void set(BodyIndex i, const Scheduled<T>& s) {
    entries_[i] = s;
    const std::uint32_t k = pos_[i];
    if (k == kAbsent) return;
    heap_[k].time = s.time;
    sift_up(k);
    sift_down(pos_[i]);
  }

 private:
  static constexpr std::uint32_t kAbsent = std::numeric_limits<std::uint32_t>::max();
  // Children per node: four halve the levels a sift crosses (each a likely cache miss once the
  // heap outgrows the cache) for two more comparisons per level, in one or two cache lines.
  static constexpr std::size_t kArity = 4;
  struct Node {
    T time;  // the entry's time (infinity when invalid)
    BodyIndex owner;
  };

  // The order of Scheduled::key_less; equal keys (one contact held by both of its bodies) are
  // ordered by owner index. Invalid entries have an infinite time and sort last.
  bool less(const Node& x, const Node& y) const {
    if (x.time < y.time) return true;
    if (y.time < x.time) return false;
    const Scheduled<T>& a = entries_[x.owner];
    const Scheduled<T>& b = entries_[y.owner];
    if (a.key_less(b)) return true;
    if (b.key_less(a)) return false;
    return x.owner < y.owner;
  }
  void place(std::size_t k, const Node& n) {
    heap_[k] = n;
    pos_[n.owner] = static_cast<std::uint32_t>(k);
  }
  void sift_up(std::size_t k) {
    const Node n = heap_[k];
    while (k > 0) {
      const std::size_t parent = (k - 1) / kArity;
      if (!less(n, heap_[parent])) break;
      place(k, heap_[parent]);
      k = parent;
    }
    place(k, n);
  }
  void sift_down(std::size_t k) {
    const Node n = heap_[k];
    const std::size_t size = heap_.size();
    for (;;) {
      const std::size_t first = kArity * k + 1;
      if (first >= size) break;
      std::size_t child = first;
      const std::size_t end = std::min(first + kArity, size);
      for (std::size_t c = first + 1; c < end; ++c)
        if (less(heap_[c], heap_[child])) child = c;
      if (!less(heap_[child], n)) break;
      place(k, heap_[child]);
      k = child;
    }
    place(k, n);
  }

  std::vector<Scheduled<T>> entries_;
  std::vector<std::uint32_t> pos_;  // each owner's index in heap_ (bodies are 32-bit indices)
  std::vector<Node> heap_;
};

}  // namespace pge
