// `pge fuzz`: generate scenes, check every invariant and the exact oracle's verdicts, shrink
// failures into regression fixtures.
#pragma once

#include "pge/roots.hpp"

#include <cstdint>
#include <string>

namespace pge::cli {

struct FuzzOptions {
  double time_limit = 0;          // seconds of wall time; 0: no limit (then --cases bounds it)
  std::uint64_t cases = 0;        // cases to run in this shard; 0: no limit (then --time bounds it)
  std::uint64_t seed = 1;
  std::uint64_t first = 0;        // first campaign case to run (reproduce case K: --first K --cases 1)
  std::uint32_t shard = 0;        // this shard's index in [0, shards)
  std::uint32_t shards = 1;
  SolverKind solver = SolverKind::Robust;
  std::string out = "fixtures/regressions";  // where shrunk failures are written
  std::uint32_t max_failures = 10;  // stop after this many distinct failures
  bool storms_fail = false;
  bool oracle = true;             // judge every event with the exact oracle (miss, phantom, rounding)
  bool polygons = true;
  // > 0: every moving polygon and segment turns, at a rate in [-spin, spin] rad/s drawn from its
  // id and the campaign seed (so a shrunk scene keeps its bodies' rates); judged by the referee
  // for rotation.
  double spin = 0;
  bool progress = false;
  bool quiet = false;
};

int fuzz_command(const FuzzOptions& options);

}  // namespace pge::cli
