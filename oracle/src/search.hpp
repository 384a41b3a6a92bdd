// Searching a frame for contacts: one pair exactly, and the certified filter that picks the
// pairs worth solving.
#pragma once

#include "contact.hpp"
#include "spatial_filter.hpp"

#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

namespace pge::oracle::detail {

struct SearchCounters {
  std::uint64_t pairs_examined = 0;
  std::uint64_t pairs_filtered = 0;
  std::uint64_t pairs_exact = 0;
  std::uint64_t features_exact = 0;
};

// The earliest contact of a pair and every feature pair touching then.
struct PairResult {
  RootHandle tau;
  bool overlap_rule = false;
  std::vector<FeaturePair> features;
};

// The pair's earliest contact in tau in [0, tau_hi] (exact). With `filter`, feature pairs that
// the interval test rules out over `window` (an enclosure of [0, tau_hi]) are not solved.
std::optional<PairResult> pair_contact(Frame& frame, FeatureCache& features, BodyIndex a, BodyIndex b,
                                       const Dyadic& tau_hi, const Interval& window, bool filter, SearchCounters& n);

// The number of body pairs that are not both fixed.
std::uint64_t pair_count(const Frame& frame);

// Every pair (a < b, not both fixed, not `skip`, not resting) that may touch in tau in
// [0, tau_hi], ascending. With `filter`: pairs all of whose feature pairs fail the interval test
// over the window are left out, and with `spatial` only the pairs the spatial filter cannot vouch
// for are tested; without `filter` every pair is returned. `total` is pair_count(frame), counted
// in n.pairs_examined.
std::vector<BodyPair> candidate_pairs(Frame& frame, FeatureCache& features, const Dyadic& tau_hi, bool filter,
                                      SpatialFilter* spatial, std::uint64_t total, BodyPair skip, SearchCounters& n);

}  // namespace pge::oracle::detail
