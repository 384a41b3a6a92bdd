// Searching a frame for contacts: one pair exactly, and the certified filter that picks the
// pairs worth solving.
#pragma once

#include "contact.hpp"

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

using BodyPair = std::pair<BodyIndex, BodyIndex>;

// Every pair (a < b, not both fixed, not `skip`) that may touch in tau in [0, window.hi()],
// ascending. With `filter`: pairs whose swept bounding boxes are disjoint, or all of whose
// feature pairs fail the interval test, are left out; without it every pair is returned.
std::vector<BodyPair> candidate_pairs(Frame& frame, FeatureCache& features, const Interval& window, bool filter,
                                      BodyPair skip, SearchCounters& n);

}  // namespace pge::oracle::detail
