// One scheduled contact and one cell crossing per moving body, in an indexed 4-ary min-heap:
// updating a body's events is O(log n) and leaves no stale copies behind.
#pragma once

#include "pge/event.hpp"

#include "aligned.hpp"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <type_traits>
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
  // face (support slot feature_a) at `time` (resting contact, world_rest.hpp).
  bool leave = false;
  // Not a contact: the rotating predictor's search for this pair ran out of its box budget
  // (world_rotation.hpp); nothing touches before `time`, where the owner is predicted again.
  bool resume = false;
  // Rotating: found at its search's start, so `time` is the contact's exact time
  // (detail::RotatingContact::at_start, the corner rule's).
  bool at_start = false;

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

// Each moving body owns two events: its earliest predicted contact (a Scheduled entry) and,
// with the grid on, its next cell crossing (a time). One heap orders the bodies by the earlier
// of the two, so that an event updates a body's node once (a collision reschedules both
// events of each of its bodies; a crossing, the body's contact and crossing): with 1e5 bodies
// every sift is a few cache misses, and two heaps took twice as many. At equal times a
// crossing comes first (it changes no motion, and the contacts it may add are predicted from
// the paths as they are).
// The heap array holds each node's time beside its owner, so that sifting compares times in
// contiguous memory and reads the full entry only to break a tie between contacts.
template <class T> class EventHeap {
 public:
  void reset(std::size_t body_count, const std::vector<BodyIndex>& members) {
    slots_.assign(body_count, Slot{});
    heap_.assign(kRoot, Node{});
    heap_.reserve(kRoot + members.size());
    for (BodyIndex i : members) {
      slots_[i].pos = static_cast<std::uint32_t>(heap_.size());
      heap_.push_back(node(i));
    }
  }
  bool empty() const { return heap_.size() == kRoot; }
  // Whether the earliest event is a cell crossing (then top_time() is its time); otherwise it
  // is top(), the earliest contact (invalid if nothing is scheduled at all).
  bool top_is_crossing() const { return heap_[kRoot].crossing_first(); }
  T top_time() const { return heap_[kRoot].time; }
  const Scheduled<T>& top() const { return slots_[heap_[kRoot].owner].entry; }
  BodyIndex top_index() const { return heap_[kRoot].owner; }
  const Scheduled<T>& at(BodyIndex i) const { return slots_[i].entry; }
  // Calls f(owner, partner) for the bodies whose events come right after the top's (the root's
  // children, one cache line of nodes), with each one's contact partner (kNoBody: none): what
  // the next steps will most likely read, known without reading their entries.
  template <class F> void visit_next(F f) const {
    for (std::size_t c = first_child(kRoot); c < first_child(kRoot) + kArity && c < heap_.size(); ++c)
      f(heap_[c].owner, heap_[c].partner());
  }
  // Whether sift_down requests the next level's lines ahead (worth it once the heap outgrows the
  // cache; World turns it on with its other prefetches).
  void set_prefetching(bool on) { prefetching_ = on; }
  // Prefetches body i's slot (its contact, crossing time and place in the heap: one line).
  void prefetch(BodyIndex i) const { prefetch_line(&slots_[i]); }

  // Owners of every valid contact whose time is <= bound (children are never earlier than
  // their parent, so the walk stops at the first later node on each branch).
  template <class F> void visit_up_to(const T& bound, F f) const {
    std::vector<std::size_t>& stack = stack_;
    stack.clear();
    if (!empty()) stack.push_back(kRoot);
    while (!stack.empty()) {
      const std::size_t k = stack.back();
      stack.pop_back();
      if (!(heap_[k].time <= bound)) continue;
      const Scheduled<T>& e = slots_[heap_[k].owner].entry;
      if (e.valid() && e.time <= bound) f(heap_[k].owner);
      for (std::size_t c = first_child(k); c < first_child(k) + kArity && c < heap_.size(); ++c) stack.push_back(c);
    }
  }

  std::size_t memory_bytes() const {
    return slots_.capacity() * sizeof(Slot) + heap_.capacity() * sizeof(Node) + stack_.capacity() * sizeof(std::size_t);
  }

  // Replaces body i's contact; its crossing stays.
  void set(BodyIndex i, const Scheduled<T>& s) {
    slots_[i].entry = s;
    update(i);
  }
  // Replaces body i's contact and its crossing time (never(): none).
  void set(BodyIndex i, const Scheduled<T>& s, const T& crossing) {
    slots_[i].entry = s;
    slots_[i].crossing = crossing;
    update(i);
  }
  void set_crossing(BodyIndex i, const T& crossing) {
    slots_[i].crossing = crossing;
    update(i);
  }

  static T never() { return std::numeric_limits<T>::infinity(); }

 private:
  static constexpr std::uint32_t kAbsent = std::numeric_limits<std::uint32_t>::max();
  // Children per node: four halve the levels a sift crosses (each a likely cache miss once the
  // heap outgrows the cache) for two more comparisons per level, in one cache line.
  static constexpr std::size_t kArity = 4;
  struct Node {
    static constexpr std::uint32_t kCrossingBit = 1u << 31, kNoPartner = kCrossingBit - 1;
    T time{};  // the earlier of the contact's and the crossing's times (infinity: neither)
    BodyIndex owner = kNoBody;
    // Bit 31: `time` is the crossing's. Bits 0-30: the contact's partner (kNoPartner: none);
    // body indices are below kMaxBodies < 2^31.
    std::uint32_t bits = kNoPartner;
    bool crossing_first() const { return (bits & kCrossingBit) != 0; }
    BodyIndex partner() const { return (bits & kNoPartner) == kNoPartner ? kNoBody : bits & kNoPartner; }
  };
  // The root sits at index kRoot (the slots before it are unused), so that a node's children
  // start on a multiple of kArity: with 16-byte nodes in a 64-byte aligned array (double) a
  // sift reads one cache line per level instead of two.
  static constexpr std::size_t kRoot = kArity - 1;
  static constexpr std::size_t first_child(std::size_t k) { return kArity * k - kArity * (kArity - 2); }
  static constexpr std::size_t parent(std::size_t k) { return (k + kArity * (kArity - 2)) / kArity; }
  static_assert(first_child(kRoot) == kRoot + 1 && first_child(kRoot) % kArity == 0 && parent(first_child(kRoot)) == kRoot);

  Node node(BodyIndex i) const {
    const Slot& s = slots_[i];
    const T& contact = s.entry.time;  // infinity when invalid
    const bool crossing_first = s.crossing <= contact && s.crossing != never();
    const std::uint32_t partner = s.entry.valid() ? s.entry.partner : Node::kNoPartner;
    return {crossing_first ? s.crossing : contact, i, partner | (crossing_first ? Node::kCrossingBit : 0u)};
  }
  // A later time only sinks and an earlier one only rises: the other direction's comparison
  // would read a parent's or children's line for nothing. At an equal time the old key cannot
  // be compared with the new one (the entry is already replaced), so both directions are tried.
  void update(BodyIndex i) {
    const std::uint32_t k = slots_[i].pos;
    if (k == kAbsent) return;
    const Node n = node(i);
    const Node old = heap_[k];
    heap_[k] = n;
    if (old.time < n.time) {
      sift_down(k);
    } else if (n.time < old.time) {
      sift_up(k);
    } else {
      sift_up(k);
      sift_down(slots_[i].pos);
    }
  }

  // Time; at equal times crossings before contacts, crossings by owner, contacts in the order of
  // Scheduled::key_less; equal keys (one contact held by both of its bodies) by owner.
  bool less(const Node& x, const Node& y) const {
    if (x.time < y.time) return true;
    if (y.time < x.time) return false;
    // Two infinite times: bodies with nothing scheduled (a gas in a grid has many contacts
    // missing: a body with no contact among its neighbours waits for its next cell crossing),
    // in owner order without reading the entries, each a cache miss with 1e5 bodies.
    if (x.time == never()) return x.owner < y.owner;
    if (x.crossing_first() != y.crossing_first()) return x.crossing_first();
    if (!x.crossing_first()) {
      const Scheduled<T>& a = slots_[x.owner].entry;
      const Scheduled<T>& b = slots_[y.owner].entry;
      if (a.key_less(b)) return true;
      if (b.key_less(a)) return false;
    }
    return x.owner < y.owner;
  }
  void place(std::size_t k, const Node& n) {
    heap_[k] = n;
    slots_[n.owner].pos = static_cast<std::uint32_t>(k);
  }
  void sift_up(std::size_t k) {
    const Node n = heap_[k];
    while (k > kRoot) {
      const std::size_t up = parent(k);
      if (!less(n, heap_[up])) break;
      place(k, heap_[up]);
      k = up;
    }
    place(k, n);
  }
  // The child of four at `first` that less() puts first. By time alone, without branches (the
  // comparisons of a sift are the queue's mispredictions), when the earliest time is one child's
  // only; at a tie, less() in order, as for fewer children.
  std::size_t earliest_of_four(std::size_t first) const {
    const T t0 = heap_[first].time, t1 = heap_[first + 1].time, t2 = heap_[first + 2].time, t3 = heap_[first + 3].time;
    const bool b01 = t1 < t0, b23 = t3 < t2;
    const T m01 = b01 ? t1 : t0, m23 = b23 ? t3 : t2;
    const bool right = m23 < m01;
    const T m = right ? m23 : m01;
    const int at_m = int(t0 == m) + int(t1 == m) + int(t2 == m) + int(t3 == m);
    if (at_m == 1) return first + (right ? 2 + std::size_t(b23) : std::size_t(b01));
    std::size_t child = first;
    for (std::size_t c = first + 1; c < first + kArity; ++c)
      if (less(heap_[c], heap_[child])) child = c;
    return child;
  }
  void sift_down(std::size_t k) {
    const Node n = heap_[k];
    const std::size_t size = heap_.size();
    for (;;) {
      const std::size_t first = first_child(k);
      if (first >= size) break;
      std::size_t child = first;
      const std::size_t end = std::min(first + kArity, size);
      // The next level's line is one of the children's child groups: all are requested before
      // the comparisons pick one, so that a deep sift waits for about one miss per two levels
      // rather than one per level.
      if (prefetching_)
        for (std::size_t c = first; c < end && first_child(c) < size; ++c) prefetch_line(&heap_[first_child(c)]);
      if (end - first == kArity) {
        child = earliest_of_four(first);
      } else {
        for (std::size_t c = first + 1; c < end; ++c)
          if (less(heap_[c], heap_[child])) child = c;
      }
      if (!less(heap_[child], n)) break;
      place(k, heap_[child]);
      k = child;
    }
    place(k, n);
  }

  // Everything the queue keeps per body, together: an event reads a body's contact and
  // crossing and finds its node through `pos` in one line (for double: 48 + 8 + 4 bytes,
  // aligned), where three arrays cost three misses per body with 1e5 bodies.
  struct alignas(64) Slot {
    Scheduled<T> entry;
    T crossing = never();  // never(): none
    std::uint32_t pos = kAbsent;  // the owner's index in heap_
  };
  static_assert(sizeof(Slot) == 64 || !std::is_same_v<T, double>, "a double slot fills one cache line");
  std::vector<Slot, CacheAligned<Slot>> slots_;
  std::vector<Node, CacheAligned<Node>> heap_ = std::vector<Node, CacheAligned<Node>>(kRoot);
  mutable std::vector<std::size_t> stack_;  // scratch of visit_up_to
  bool prefetching_ = false;
};

}  // namespace pge
