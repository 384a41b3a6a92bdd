// The pieces of a judgement: the verdict rule, time errors, conservation and the gap.
#pragma once

#include "features.hpp"
#include "pge/oracle.hpp"

#include <optional>

namespace pge::oracle::detail {

// Engine time minus the exact time rounded to format f, in ulps of f (clamped to +-2^62), and
// the relative error |engine - exact| / exact.
long long ulps_from(const Dyadic& engine, const ExactTime& exact, const TimeFormat& f);
double relative_error(const Dyadic& engine, const ExactTime& exact);

// The verdict rule (see Verdict in oracle.hpp). `own`: the exact contact time of the engine's
// pair; `earliest`: the exact first contact of any pair, up to at least max(own, engine time
// + agree_ulps + 1 ulps); `own_ulps`: ulps_from(engine_time, *own, f) when already known.
Verdict decide(const std::optional<ExactTime>& own, std::optional<long long> own_ulps, const NextEvent& earliest,
               const Dyadic& engine_time, const TimeFormat& f, long agree_ulps);

Conservation measure_conservation(const ExactBody& a, const ExactBody& b, const ExactEvent& e,
                                  const ExactMotion& a_after, const ExactMotion& b_after);

struct GapMeasure {
  double gap = 0;
  double contact_distance = 0;
};
// The engine's features at tau (time since the frame's now), from the exact contact function.
GapMeasure measure_gap(Frame& frame, FeatureCache& features, BodyIndex a, BodyIndex b, const FeaturePair& id,
                       const Dyadic& tau);

}  // namespace pge::oracle::detail
