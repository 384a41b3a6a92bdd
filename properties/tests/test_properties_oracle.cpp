// Property 3 (earliest time), judged by the exact oracle: for every event of a short run on a
// generated scene the engine's pair is the exact earliest contact (never a miss or a phantom),
// for the robust and the certified solver, and its time is the exact time correctly rounded
// (certified's promise; robust keeps it too, since both re-derive event times exactly). Kept
// apart from test_properties because it links the oracle (CGAL, GMP).
// Reproduce a failure with the RC_PARAMS string rapidcheck prints; run longer with
//   RC_PARAMS="seed=1 max_success=100000" build/properties/tests/test_properties_oracle
#include "pge/generators.hpp"
#include "pge/oracle.hpp"
#include "pge/scene_io.hpp"
#include "pge/world.hpp"

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <filesystem>
#include <vector>
#include <string>

namespace pge {
namespace {

// A short run: enough events for hand-overs, simultaneous impacts and re-predictions after
// them, few enough that an exact judgement of every event stays cheap.
constexpr std::uint64_t kShortRunEvents = 100;

struct Tally {
  std::uint64_t events = 0;
  std::uint64_t misorders = 0;  // near-simultaneous pairs taken in the other order (not failures)
  std::uint64_t ties = 0;
  std::string problem;          // the first violation of property 3, empty if none
};

// Runs the scene with `solver`, judging every event against property 3.
Tally judge_every_event(const Scene& scene, SolverKind solver) {
  WorldOptions wo;
  wo.solver = solver;
  wo.max_events = kShortRunEvents;
  World<double> world(scene, wo);
  oracle::Referee referee(oracle::exact_state(world));
  Tally tally;
  oracle::follow(world, referee, [&](const CollisionInfo<double>& info, const oracle::ExactEvent&,
                                     const oracle::Judgement& j) {
    ++tally.events;
    if (!tally.problem.empty()) return;
    const std::string where = std::string(solver_name(solver)) + " event " + std::to_string(tally.events - 1) +
                              " at t = " + std::to_string(info.time) + ", bodies " + scene.bodies[info.a].id +
                              " and " + scene.bodies[info.b].id + ": " +
                              std::string(oracle::verdict_name(j.verdict));
    if (oracle::is_failure(j.verdict)) {
      tally.problem = where;  // never a miss or a phantom
    } else if (!j.pair_time || j.ulps != 0) {
      // The time is the exact time of the engine's pair correctly rounded: robust and certified
      // both re-derive every event time from the exact paths (World::refine_near_top), so a
      // time error (more than kAgreeUlps) cannot pass either. (Two pairs whose exact times
      // round to the same double may still be taken in the other order: a misorder, below
      // the time's resolution, counted.)
      tally.problem = where + ", off by " + std::to_string(j.ulps) + " ulps";
    }
    if (j.verdict == oracle::Verdict::Tie) ++tally.ties;
    if (j.verdict == oracle::Verdict::Misorder) ++tally.misorders;
  });
  world.run();
  if (tally.problem.empty() && referee.stats().misses_between_events > 0)
    tally.problem = std::string(solver_name(solver)) + ": a contact before a body slid off a face was never processed";
  if (tally.problem.empty() && world.stop_reason() == StopReason::ReachedUntil && referee.judge_end().miss)
    tally.problem = std::string(solver_name(solver)) + ": a contact before the horizon was never processed";
  return tally;
}

GenOptions short_runs() {
  GenOptions o;
  o.max_events = kShortRunEvents;
  return o;
}

// 3. Every event is the exact earliest contact, for robust and for certified, at the exact time
// correctly rounded. Circles, segments and polygons.
RC_GTEST_PROP(OracleProperties, EveryEventIsTheExactEarliestContact, ()) {
  const GeneratedScene g = *gen_scene(short_runs());
  const bool polygons = std::any_of(g.scene.bodies.begin(), g.scene.bodies.end(),
                                    [](const BodyDesc& b) { return b.shape == ShapeKind::Polygon; });
  RC_CLASSIFY(polygons, "polygons");
  RC_CLASSIFY(g.gravity, "gravity");
  const Tally robust = judge_every_event(g.scene, SolverKind::Robust);
  if (!robust.problem.empty()) RC_FAIL(robust.problem);
  const Tally certified = judge_every_event(g.scene, SolverKind::Certified);
  if (!certified.problem.empty()) RC_FAIL(certified.problem);
  RC_CLASSIFY(robust.events > 0, "has events");
  RC_CLASSIFY(robust.misorders + certified.misorders > 0, "misorders");
  RC_CLASSIFY(robust.ties + certified.ties > 0, "ties");
}

// The scenes property 3 found failing, each fixed in the engine (fixtures/regressions/oracle/,
// the note in each says what failed): the property must hold on every one.
TEST(OracleRegressions, Property3HoldsOnEveryFixedScene) {
  std::vector<std::string> files;
  for (const auto& e : std::filesystem::directory_iterator(PGE_ORACLE_REGRESSIONS_DIR))
    if (e.path().extension() == ".json") files.push_back(e.path().string());
  std::sort(files.begin(), files.end());
  ASSERT_GE(files.size(), 4u);
  for (const std::string& f : files)
    for (SolverKind solver : {SolverKind::Robust, SolverKind::Certified}) {
      const LoadedScene loaded = read_scene_file(f);
      const Tally t = judge_every_event(loaded.scene, solver);
      EXPECT_TRUE(t.problem.empty()) << f << ": " << t.problem;
    }
}

}  // namespace
}  // namespace pge
