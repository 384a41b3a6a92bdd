#include "fuzz_check.hpp"

#include "pge/invariants.hpp"
#include "pge/scene_io.hpp"
#include "pge/validate.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <exception>

namespace pge::fuzz {

void fail_with_scene(std::string_view target, const std::string& what, const Scene& scene) {
  std::string json;
  try {
    json = write_scene(scene);
  } catch (const std::exception& e) {
    json = std::string("(the scene cannot be written: ") + e.what() + ")";
  }
  std::fprintf(stderr, "\n%.*s: FAILURE: %s\nscene:\n%s\n", static_cast<int>(target.size()), target.data(),
               what.c_str(), json.c_str());
  std::fflush(stderr);
  std::abort();
}

bool check_scene(const Scene& scene, std::string_view target) {
  if (validate_scene(scene)) return false;
  if (scene.bodies.size() > kFuzzMaxBodies) return false;
  Scene run = scene;
  run.run.until = std::min(run.run.until, kFuzzUntil);
  run.run.max_events = std::min(run.run.max_events, kFuzzMaxEvents);
  run.run.frames_per_second = 0;  // frames change nothing; they would only cost time
  InvariantOptions options;
  options.solver = run.run.solver;
  options.storms_fail = false;
  // Half the inputs (an odd event budget) run with the broad-phase grid forced on: fuzz scenes
  // are small, and BroadPhase::Auto would predict all pairs for every one of them.
  options.broad_phase = scene.run.max_events % 2 == 1 ? BroadPhase::Grid : BroadPhase::Auto;
  const InvariantReport report = check_invariants(run, options);
  if (report.failure) {
    const Failure& f = *report.failure;
    fail_with_scene(target,
                    std::string(failure_kind_name(f.kind)) + " at t = " + std::to_string(f.time) + ": " + f.detail,
                    run);
  }
  return true;
}

}  // namespace pge::fuzz
