// Every scene in fixtures/regressions/ reproduces a bug that was found and fixed. Each must run
// without breaking the engine's invariants: the overlap bound after every event, finite states,
// momentum across every collision and kinetic energy across every elastic one (the checks
// `pge fuzz` and the libFuzzer targets apply, properties/invariants), and no crash or hang (the
// run is bounded by the scene's until and max_events).
// Each scene's expect block (how the run ends, agreement with the oracle, ...) is enforced by
// `pge check`, in the CTest regression_expectations (tests/CMakeLists.txt), not here.
#include "pge/constants.hpp"
#include "pge/invariants.hpp"
#include "pge/scene_io.hpp"
#include "pge/world.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

namespace pge {
namespace {

std::vector<std::string> regression_scenes() {
  std::vector<std::string> out;
  for (const auto& e : std::filesystem::recursive_directory_iterator(PGE_REGRESSIONS_DIR))
    if (e.path().extension() == ".json") out.push_back(e.path().string());
  std::sort(out.begin(), out.end());
  return out;
}

class Regression : public ::testing::TestWithParam<std::string> {};

TEST_P(Regression, KeepsTheOverlapBoundAfterEveryEvent) {
  const LoadedScene loaded = read_scene_file(GetParam());
  World<double> w(loaded.scene);
  const double start_depth = w.largest_overlap().depth;  // allowed to stay (overlap_past_bound)
  std::uint64_t steps = 0;
  while (w.step()) {
    const auto o = w.largest_overlap();
    ASSERT_FALSE(overlap_past_bound(o.ulps, o.depth, start_depth)) << "after step " << steps << " at t = " << w.time() << ": bodies "
                                         << w.body_id(o.a) << " and " << w.body_id(o.b) << " overlap by " << o.depth;
    ++steps;
  }
  const auto o = w.largest_overlap();
  EXPECT_FALSE(overlap_past_bound(o.ulps, o.depth, start_depth)) << "at the end, t = " << w.time();
}

TEST_P(Regression, KeepsTheEngineInvariants) {
  const LoadedScene loaded = read_scene_file(GetParam());
  InvariantOptions options;
  options.solver = loaded.scene.run.solver;
  options.storms_fail = false;  // storms are reported, not failures (resting between moving bodies)
  const InvariantReport report = check_invariants(loaded.scene, options);
  EXPECT_FALSE(report.failure) << failure_kind_name(report.failure->kind) << " at t = " << report.failure->time << ": "
                               << report.failure->detail;
}

INSTANTIATE_TEST_SUITE_P(Fixtures, Regression, ::testing::ValuesIn(regression_scenes()),
                         [](const ::testing::TestParamInfo<std::string>& param_info) {
                           std::string name = std::filesystem::path(param_info.param).stem().string();
                           std::replace_if(name.begin(), name.end(), [](char c) { return !std::isalnum(c); }, '_');
                           return name;
                         });

}  // namespace
}  // namespace pge
