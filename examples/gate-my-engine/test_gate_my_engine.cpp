// The naive engine (naive_engine.hpp) gated by PGE's exact referee, as a user's own test would
// gate their engine: run a scene, write what the engine did as a step trace (pge-trace/2), and
// hold it to the referee's verdicts (pge/judge.hpp). Only the installed package is used:
// find_package(pge), targets pge::oracle and pge::io.
//
// The scene (scenes/bullet.json): a bullet of radius 0.02 at x = -0.905 flies at 20 m/s towards
// a thin wall, the segment x = 0, |y| <= 1; no gravity. It touches the wall when its centre
// reaches x = -0.02, at t = 0.885 / 20 = 0.04425 s exactly (up to the rounding of the scene's
// decimals), and bounces straight back.
#include "naive_engine.hpp"

#include "pge/judge.hpp"
#include "pge/scene_io.hpp"
#include "pge/trace_io.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <fstream>
#include <iostream>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

namespace {

constexpr double kContactTime = 0.885 / 20;  // seconds, derived above

// Runs `scene` on the naive engine with steps of dt seconds until the scene's run.until,
// recording every step: its end time, every moving body's state, the contacts it reported.
pge::Trace run_naive(const pge::Scene& scene, double dt) {
  naive::Engine engine(scene);
  pge::Trace trace;
  trace.mode = pge::TraceMode::Steps;
  trace.engine = "naive Euler, dt = " + std::to_string(dt);
  trace.scene = scene.name;
  for (const naive::Body& b : engine.bodies()) {
    if (!b.wall) trace.bodies.push_back(b.id);
  }
  const auto steps = static_cast<long>(std::ceil(scene.run.until / dt));
  for (long k = 0; k < steps; ++k) {
    pge::TraceStep step;
    for (const naive::Contact& c : engine.step(dt)) {
      step.contacts.push_back({engine.bodies()[c.a].id, engine.bodies()[c.b].id});
    }
    step.t = engine.time();
    for (const naive::Body& b : engine.bodies()) {
      if (!b.wall) step.bodies.push_back({{b.position.x, b.position.y}, {b.velocity.x, b.velocity.y}});
    }
    trace.steps.push_back(std::move(step));
  }
  return trace;
}

// Writes the trace to a file and reads it back, as a test that keeps its traces would (the file
// is left in the build folder, for `pge judge` by hand).
pge::Trace through_file(const pge::Trace& trace, const std::string& name) {
  const std::string path = std::string(TRACE_DIR) + "/" + name;
  {
    std::ofstream out(path);
    pge::write_trace(out, trace);
  }
  return pge::read_trace_file(path);
}

// The gate: passes when the referee finds no missed and no phantom contact; otherwise fails
// with the referee's one line per failure.
testing::AssertionResult no_contact_missed(const pge::oracle::TraceJudgement& j) {
  if (!j.failed()) return testing::AssertionSuccess();
  return testing::AssertionFailure() << pge::oracle::failure_text(j);
}

// The bullet scene run at `hz` steps a second, its trace kept as `trace_file`, and judged.
pge::oracle::TraceJudgement judge_bullet(double hz, const std::string& trace_file) {
  const pge::Scene scene = pge::read_scene_file(BULLET_SCENE).scene;
  return pge::oracle::judge_trace(scene, through_file(run_naive(scene, 1 / hz), trace_file));
}

// The only exact contact of the run, in step `step` (from 0) at kContactTime.
const pge::oracle::StepContact& the_contact(const pge::oracle::TraceJudgement& j, std::size_t step) {
  if (j.steps.contacts.size() != 1) {
    throw std::runtime_error("expected one contact, the referee found " + std::to_string(j.steps.contacts.size()));
  }
  const pge::oracle::StepContact& c = j.steps.contacts[0];
  EXPECT_EQ(c.step, step);
  EXPECT_TRUE(c.exact_time.has_value());
  EXPECT_NEAR(c.exact_time.value_or(0), kContactTime, 1e-12);
  return c;
}

// At 2,000 steps a second the bullet moves 0.01 per step, half its radius: the step that ends at
// t = 0.0445 (step 88, from 0) finds it 0.005 deep in the wall, the one before 0.005 short of it,
// and the engine reports the contact in the step where it exactly happens.
TEST(GateMyEngine, FineStepsMissNoContact) {
  const pge::oracle::TraceJudgement j = judge_bullet(2000, "bullet-2000hz.jsonl");

  EXPECT_TRUE(no_contact_missed(j));
  EXPECT_EQ(j.steps.summary.steps, 200u);
  EXPECT_EQ(j.steps.summary.on_time, 1u);
  const pge::oracle::StepContact& c = the_contact(j, 88);
  EXPECT_EQ(c.verdict, pge::oracle::StepVerdict::OnTime);
  EXPECT_EQ(c.reported_step, std::optional<std::size_t>(88));
}

// At 60 steps a second the bullet moves 1/3 per step: the steps end at x = -0.238 and 0.095, and
// no step ends with the bullet touching the wall; it has passed through. The contact happens
// exactly in step 2 (t from 1/30 to 1/20), and the referee calls it missed: tunnelling. The
// gate fails with the message a user of a 60 Hz engine would see (README.md quotes it).
TEST(GateMyEngine, CoarseStepsTunnelAndTheGateSaysSo) {
  const pge::oracle::TraceJudgement j = judge_bullet(60, "bullet-60hz.jsonl");

  const testing::AssertionResult gate = no_contact_missed(j);
  EXPECT_FALSE(gate);
  EXPECT_EQ(j.steps.summary.steps, 6u);
  EXPECT_EQ(j.steps.summary.missed, 1u);
  EXPECT_EQ(j.steps.summary.tunnelled, 1u);
  const pge::oracle::StepContact& c = the_contact(j, 2);
  EXPECT_EQ(c.verdict, pge::oracle::StepVerdict::Missed);
  EXPECT_EQ(c.miss, pge::oracle::MissKind::PassThrough);
  EXPECT_FALSE(c.reported_step.has_value());
  // The message is one line, the missed contact's: the pair, the step, the exact time and why.
  const std::string message = gate.message();
  EXPECT_EQ(message, pge::oracle::contact_text(c));
  EXPECT_NE(message.find("\"wall\"-\"bullet\" in step 2"), std::string::npos) << message;
  EXPECT_NE(message.find("missed (pass-through: tunnelling"), std::string::npos) << message;
  std::cout << "the gate's message at 60 Hz:\n" << message << "\n";
}

}  // namespace
