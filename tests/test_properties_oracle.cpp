// Property 3 (earliest time), judged by the exact oracle: for every event of a short run on a
// generated scene the engine's pair is the exact earliest contact (never a miss or a phantom)
// and certified's times are the exact times correctly rounded. Robust: never a phantom; its
// order swaps of near-simultaneous contacts (oracle misses) are counted, not yet asserted. Kept apart from test_properties because it links the oracle (CGAL, GMP).
// Reproduce a failure with the RC_PARAMS string rapidcheck prints; run longer with
//   RC_PARAMS="seed=1 max_success=100000" build/tests/test_properties_oracle
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
  std::uint64_t not_agree = 0;  // time errors and misorders (robust only; never a failure)
  std::uint64_t ties = 0;
  std::uint64_t robust_misses = 0;  // robust taking the later of two near-simultaneous contacts
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
  const bool certified = solver == SolverKind::Certified;
  oracle::follow(world, referee, [&](const CollisionInfo<double>& info, const oracle::ExactEvent&,
                                     const oracle::Judgement& j) {
    ++tally.events;
    if (!tally.problem.empty()) return;
    const std::string where = std::string(solver_name(solver)) + " event " + std::to_string(tally.events - 1) +
                              " at t = " + std::to_string(info.time) + ", bodies " + scene.bodies[info.a].id +
                              " and " + scene.bodies[info.b].id + ": " +
                              std::string(oracle::verdict_name(j.verdict));
    if (j.verdict == oracle::Verdict::Miss && !certified) {
      // Robust solves the polynomial of the rounded state: its times can be off by more than
      // the oracle's agree window (kAgreeUlps), and of two contacts within that error of each
      // other it may take the later first, which the oracle calls a miss
      // (fixtures/regressions/oracle/known/robust-simultaneous-order-swap.json). Counted, not
      // asserted: closing this needs certified's exact re-derivation of times.
      ++tally.robust_misses;
    } else if (oracle::is_failure(j.verdict)) {
      tally.problem = where;  // never a miss or a phantom
    }
    // Certified is correctly rounded: the engine's time is the exact time of its pair rounded
    // to nearest. (Two pairs whose exact times round to the same double may still be taken in
    // the other order: a misorder, below the time's resolution.)
    else if (certified && (!j.pair_time || j.ulps != 0))
      tally.problem = where + ", off by " + std::to_string(j.ulps) + " ulps";
    if (j.verdict == oracle::Verdict::Tie) ++tally.ties;
    if (j.verdict == oracle::Verdict::TimeError || j.verdict == oracle::Verdict::Misorder) ++tally.not_agree;
  });
  world.run();
  if (tally.problem.empty() && world.stop_reason() == StopReason::ReachedUntil && referee.judge_end().miss)
    tally.problem = std::string(solver_name(solver)) + ": a contact before the horizon was never processed";
  return tally;
}

GenOptions short_runs() {
  GenOptions o;
  o.max_events = kShortRunEvents;
  return o;
}

// 3. Every event is the exact earliest contact, for robust and for certified; certified's times
// are correctly rounded. Circles, segments and polygons.
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
  RC_CLASSIFY(robust.not_agree > 0, "robust time error or misorder");
  RC_CLASSIFY(certified.not_agree > 0, "certified misorder");
  RC_CLASSIFY(robust.ties + certified.ties > 0, "ties");
  RC_CLASSIFY(robust.robust_misses > 0, "robust order swap (miss)");
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
      EXPECT_EQ(t.robust_misses, 0u) << f;
      EXPECT_GT(t.events, 0u) << f;
    }
}

}  // namespace
}  // namespace pge
