// The referee for other engines' traces (pge/judge.hpp, issue 28).
//
// (a) PGE's own runs written as traces, in events and in steps mode, judged as `pge check`
//     judges the same run (the oracle's Referee following the world), rotating scenes included
//     (issue 26);
// (b) hand-made step traces whose verdicts are worked out by hand in the comments, of a ball
//     and a wall and of a square spinning in place next to a wall;
// (c) bad traces: one error naming the line (or, in memory, the element) and the field.
#include "pge/judge.hpp"
#include "pge/oracle.hpp"
#include "pge/scene_io.hpp"
#include "pge/trace_io.hpp"
#include "pge/world.hpp"
#include "scene_bodies.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace pge {
namespace {

using oracle::StepVerdict;
using test_scene::circle;
using test_scene::wall;

// --- (a) PGE's own runs ----------------------------------------------------------------------

struct CheckedEvent {
  BodyIndex a, b;
  double t;
  oracle::Verdict verdict;
  long long ulps;
};

struct PgeRun {
  std::vector<CheckedEvent> checked;  // what pge check's referee says of each collision
  Trace events;                       // the same run as an events trace
  Trace steps;                        // and as a steps trace, a step per frame
};

// Runs `scene` as pge check does (oracle::follow's referee judging every collision) and writes
// the run as both kinds of trace: collisions with the pair's state before (its motion after the
// collision starts where it was) and velocities after; frames as steps, each with the pairs
// that collided since the frame before. A rotating body's state is written as `pge run
// --trace` writes it (cli/trace.hpp): its reference point (World::snapshot), and its angle and
// angular velocities; steps carry every listed body's turn in a scene with rotation.
PgeRun run_pge(const Scene& scene, SolverKind solver, double frames_per_second, std::uint64_t max_events) {
  WorldOptions wo;
  wo.solver = solver;
  wo.frames_per_second = frames_per_second;
  wo.max_events = max_events;
  World<double> world(scene, wo);
  PgeRun run;
  run.events.mode = TraceMode::Events;
  run.steps.mode = TraceMode::Steps;
  bool rotation = false;
  for (BodyIndex i = 0; i < world.body_count(); ++i) {
    if (!world.is_fixed(i)) run.steps.bodies.push_back(scene.bodies[i].id);
    rotation = rotation || world.rotates(i);
  }
  const auto at = [&world](BodyIndex i) { return world.rotates(i) ? world.snapshot(i).position : world.motion(i).p0; };
  oracle::Referee referee(oracle::exact_state(world));
  std::vector<TraceContact> since_frame;
  world.on_collision([&](const CollisionInfo<double>& c) {
    const oracle::Judgement j = referee.judge(oracle::exact_event(c), oracle::exact_motion(world.motion(c.a)),
                                              oracle::exact_motion(world.motion(c.b)));
    run.checked.push_back({c.a, c.b, c.time, j.verdict, j.ulps});
    TraceCollision t;
    t.t = c.time;
    t.a = scene.bodies[c.a].id;
    t.b = scene.bodies[c.b].id;
    t.before_a = {at(c.a), c.va_before};
    t.before_b = {at(c.b), c.vb_before};
    t.va_after = c.va_after;
    t.vb_after = c.vb_after;
    if (world.rotates(c.a) || world.rotates(c.b)) {
      // Named features, as pge run --trace writes them: an event at an exact graze is undecided
      // only where the gap of the engine's features says it is within rounding of the tangency.
      t.contact = contact_kind_name(c.contact);
      t.feature_a = c.feature_a;
      t.feature_b = c.feature_b;
      t.turning = true;
      t.turn_a = {world.snapshot(c.a).angle, c.wa_before};
      t.turn_b = {world.snapshot(c.b).angle, c.wb_before};
      t.wa_after = c.wa_after;
      t.wb_after = c.wb_after;
    }
    run.events.collisions.push_back(t);
    since_frame.push_back({t.a, t.b});
  });
  world.on_motion_change([&](BodyIndex i, double time) {
    ADD_FAILURE() << "the scenes of these tests have no resting contact; body " << i << " changed motion at " << time;
  });
  world.on_frame([&](const World<double>& w, double t) {
    TraceStep s;
    s.t = t;
    for (BodyIndex i = 0; i < w.body_count(); ++i) {
      if (w.is_fixed(i)) continue;
      const BodySnapshot<double> b = w.snapshot(i);
      s.bodies.push_back({b.position, b.velocity});
      if (rotation) s.turns.push_back({b.angle, b.angular_velocity});
    }
    s.contacts = std::move(since_frame);
    since_frame.clear();
    run.steps.steps.push_back(std::move(s));
  });
  while (world.step()) {
  }
  if (frames_per_second > 0) {
    EXPECT_TRUE(since_frame.empty()) << "the run ends on a frame (until a multiple of the frame period)";
  }
  run.events.end = TraceEnd{world.time(), world.stop_reason() == StopReason::ReachedUntil};
  return run;
}

Scene fixture(const std::string& name) { return read_scene_file(std::string(PGE_SCENES_DIR) + "/" + name).scene; }
Scene rotation_fixture(const std::string& name) {
  return read_scene_file(std::string(PGE_ROTATION_DIR) + "/" + name).scene;
}

// Events mode: every collision gets pge check's verdict and time error, to the ulp.
void expect_events_as_check(const Scene& scene, SolverKind solver, std::uint64_t max_events) {
  const PgeRun run = run_pge(scene, solver, 0, max_events);
  ASSERT_FALSE(run.checked.empty());
  const oracle::EventJudgement j = oracle::judge_events(scene, run.events);
  ASSERT_EQ(j.events.size(), run.checked.size());
  for (std::size_t k = 0; k < j.events.size(); ++k) {
    SCOPED_TRACE("collision " + std::to_string(k));
    EXPECT_EQ(j.events[k].judgement.verdict, run.checked[k].verdict);
    EXPECT_EQ(j.events[k].judgement.ulps, run.checked[k].ulps);
  }
}

TEST(JudgePgeRuns, EventsTraceGetsCheckVerdicts) {
  expect_events_as_check(fixture("basics/head-on.json"), SolverKind::Robust, 0);
  expect_events_as_check(fixture("basics/box-bounce.json"), SolverKind::Robust, 200);
  expect_events_as_check(fixture("games/snooker.json"), SolverKind::Robust, 200);
}

// Rotating scenes (issue 26): the trace's reference points and turns give the referee the paths
// pge check follows (each body's pivot is its reference point plus its turned pivot offset, the
// angle and spin the engine's), so the verdicts are pge check's, ulps included. peers-spinning-
// boxes has two boxes whose reference point is a corner, not the pivot.
TEST(JudgePgeRuns, EventsTraceOfRotatingScenesGetsCheckVerdicts) {
  expect_events_as_check(rotation_fixture("square-spins-into-a-wall.json"), SolverKind::Robust, 0);
  expect_events_as_check(rotation_fixture("square-spins-into-a-wall.json"), SolverKind::Certified, 0);
  expect_events_as_check(rotation_fixture("squares-spinning-in-opposite-senses-meet.json"), SolverKind::Robust, 0);
  expect_events_as_check(rotation_fixture("spinning-box-falls-onto-a-floor.json"), SolverKind::Certified, 0);
  expect_events_as_check(rotation_fixture("rod-spins-into-a-fixed-ball.json"), SolverKind::Robust, 0);
  expect_events_as_check(rotation_fixture("turnstile-struck-by-a-ball.json"), SolverKind::Robust, 0);
  expect_events_as_check(rotation_fixture("../peers/peers-spinning-boxes.json"), SolverKind::Certified, 0);
  expect_events_as_check(read_scene_file(std::string(PGE_CLI_TESTS_DIR) + "/rotating-box.json").scene, SolverKind::Robust, 50);
}

// The fast solver's rotating failures (docs/rotation.md, "The fast solver"), through the trace:
// an impulse at an exact tangency (pge check: undecided), a contact 4.8e-11 s early at 1e6 (time
// error), a corner striking on every turn a wall it misses by 1e-12 (phantoms). The same
// verdicts, event by event.
TEST(JudgePgeRuns, EventsTraceOfRotatingScenesGetsCheckFailures) {
  const auto count = [](const PgeRun& run, oracle::Verdict v) {
    return std::count_if(run.checked.begin(), run.checked.end(), [v](const CheckedEvent& e) { return e.verdict == v; });
  };
  const Scene graze = rotation_fixture("corner-grazes-a-wall.json");
  ASSERT_GT(count(run_pge(graze, SolverKind::Fast, 0, 40), oracle::Verdict::Undecided), 0);
  expect_events_as_check(graze, SolverKind::Fast, 40);
  const Scene far = rotation_fixture("square-spins-into-a-wall-far-from-the-origin.json");
  ASSERT_GT(count(run_pge(far, SolverKind::Fast, 0, 40), oracle::Verdict::TimeError), 0);
  expect_events_as_check(far, SolverKind::Fast, 40);
  const Scene near_miss = rotation_fixture("corner-near-misses-a-wall-for-1000-turns.json");
  const PgeRun run = run_pge(near_miss, SolverKind::Fast, 0, 40);
  ASSERT_GT(count(run, oracle::Verdict::Phantom), 0);
  expect_events_as_check(near_miss, SolverKind::Fast, 40);
  EXPECT_TRUE(oracle::judge_events(near_miss, run.events).failed());
}

// The fast solver's run of the pool break has misorders and phantoms by pge check's referee: the
// trace of it must get the very same ones, event by event.
TEST(JudgePgeRuns, EventsTraceGetsCheckFailures) {
  const Scene scene = fixture("simultaneous/pool-break.json");
  const PgeRun run = run_pge(scene, SolverKind::Fast, 0, 300);
  std::size_t failures = 0;
  for (const CheckedEvent& e : run.checked) failures += oracle::is_failure(e.verdict) ? 1 : 0;
  ASSERT_GT(failures, 0u) << "the scene no longer makes fast fail: choose another";
  expect_events_as_check(scene, SolverKind::Fast, 300);
  EXPECT_TRUE(oracle::judge_events(scene, run.events).failed());
}

// Steps mode: PGE agrees with the oracle on every collision (check: agree), so each collision
// is a contact on time, in the step whose (previous frame, frame] holds its time, and there is
// nothing else. The frame rate is high enough that no body collides twice in one step (the steps
// model follows a body up to its first contact in a step): checked first.
void expect_steps_as_check(Scene scene, double until, double frames_per_second) {
  scene.run.until = until;
  const PgeRun run = run_pge(scene, SolverKind::Robust, frames_per_second, 0);
  for (const CheckedEvent& e : run.checked) ASSERT_EQ(e.verdict, oracle::Verdict::Agree) << "t = " << e.t;
  std::map<std::pair<std::size_t, BodyIndex>, int> per_body;
  for (std::size_t k = 0; k < run.steps.steps.size(); ++k)
    for (const TraceContact& c : run.steps.steps[k].contacts)
      for (const std::string& id : {c.a, c.b})
        for (BodyIndex i = 0; i < scene.bodies.size(); ++i) {
          if (scene.bodies[i].id != id || scene.bodies[i].fixed) continue;
          ASSERT_LE(++per_body[std::make_pair(k, i)], 1) << "body " << id << " collides twice in step " << k << ": raise the frame rate";
        }
  const oracle::StepJudgement j = oracle::judge_steps(scene, run.steps);
  EXPECT_EQ(j.summary.contacts, run.checked.size());
  EXPECT_EQ(j.summary.on_time, run.checked.size());
  EXPECT_EQ(j.summary.late + j.summary.missed + j.summary.phantom, 0u) << oracle::failure_text({TraceMode::Steps, j, {}});
  EXPECT_EQ(j.summary.continuing_reports, 0u);
  ASSERT_EQ(j.contacts.size(), run.checked.size());
  for (std::size_t k = 0; k < j.contacts.size(); ++k) {
    const oracle::StepContact& c = j.contacts[k];
    const CheckedEvent& e = run.checked[k];
    EXPECT_EQ(c.a, scene.bodies[e.a].id);
    EXPECT_EQ(c.b, scene.bodies[e.b].id);
    EXPECT_LT(run.steps.steps[c.step - 1].t, e.t);  // step 0 is the frame at t = 0, the start
    EXPECT_LE(e.t, run.steps.steps[c.step].t);
    // The step starts from the frame's state, PGE's positions rounded to double, not from its
    // motion: the exact contact from there moves by that rounding over the closing speed, far
    // below a relative 1e-12 for these scenes (coordinates of order 1 to 100, speeds of order 1).
    ASSERT_TRUE(c.exact_time.has_value());
    EXPECT_NEAR(*c.exact_time, e.t, 1e-12 * e.t);
  }
}

TEST(JudgePgeRuns, StepsTraceGetsCheckVerdicts) {
  expect_steps_as_check(fixture("basics/head-on.json"), 5, 10);
  expect_steps_as_check(fixture("basics/box-bounce.json"), 20, 100);
  expect_steps_as_check(fixture("games/breakout.json"), 2, 1000);
  expect_steps_as_check(fixture("games/bagatelle.json"), 2, 1000);
  expect_steps_as_check(fixture("basics/gravity-box.json"), 2, 1000);
  // Rotating: the referee turns each body from the frame's angle at its angular velocity.
  expect_steps_as_check(rotation_fixture("square-spins-into-a-wall.json"), 2, 100);
  expect_steps_as_check(rotation_fixture("spinning-box-falls-onto-a-floor.json"), 1, 1000);
}

// --- (b) hand-made step traces ----------------------------------------------------------------
//
// The scene: a ball of radius 1/2 and mass 1 at the origin, moving right at 8, and a fixed wall,
// the segment x = 2 from y = -1 to 1; no gravity. Steps of 1/8 s. Every number is a dyadic
// rational, so each state below is exact in doubles. On the closed-form path from a state
// (x, v) the ball meets the wall when its centre reaches x = 2 - 1/2 = 3/2; from the start,
// at t = (3/2) / 8 = 3/16 = 0.1875, which lies in the second step (1/8, 1/4].

Scene wall_scene(double radius = 0.5, double speed = 8, double start_x = 0) {
  Scene s;
  s.name = "ball-and-wall";
  s.bodies.push_back(circle("ball", radius, {start_x, 0}, {speed, 0}));
  s.bodies.push_back(wall("wall", {2, -1}, {2, 1}));
  s.run.until = 1;
  return s;
}

Trace steps_trace(const std::vector<TraceStep>& steps) {
  Trace t;
  t.mode = TraceMode::Steps;
  t.engine = "hand-made";
  t.bodies = {"ball"};
  t.steps = steps;
  return t;
}

TraceStep step(double t, double x, double v, bool contact = false) {
  TraceStep s;
  s.t = t;
  s.bodies = {{{x, 0}, {v, 0}}};
  if (contact) s.contacts = {{"ball", "wall"}};
  return s;
}

// A correct trace: step 0 ends at x = 1; in step 1 the engine bounces the ball off the wall
// (reflected about x = 3/2: 2 - 1 = 1, velocity -8) and reports it; step 2 moves it to 0.
// Verdict: one contact, in step 1, at exact t = 3/16, on time. Overlap: none at any step's end
// (the nearest, x = 1, leaves a gap of 2 - 1 - 1/2 = 1/2). Energy 8^2 / 2 = 32 at every step:
// drift 0. Momentum goes from 8 to -8 (the wall takes 16): drift |-16| / 8 = 2.
TEST(JudgeSteps, CorrectTraceIsOnTime) {
  const oracle::StepJudgement j =
      oracle::judge_steps(wall_scene(), steps_trace({step(0.125, 1, 8), step(0.25, 1, -8, true), step(0.375, 0, -8)}));
  ASSERT_EQ(j.contacts.size(), 1u);
  const oracle::StepContact& c = j.contacts[0];
  EXPECT_EQ(c.a, "ball");
  EXPECT_EQ(c.b, "wall");
  EXPECT_EQ(c.step, 1u);
  EXPECT_EQ(c.verdict, StepVerdict::OnTime);
  ASSERT_TRUE(c.exact_time.has_value());
  EXPECT_EQ(*c.exact_time, 0.1875);
  EXPECT_EQ(c.reported_step, std::optional<std::size_t>(1));
  EXPECT_EQ(j.summary.on_time, 1u);
  EXPECT_EQ(j.summary.late + j.summary.missed + j.summary.phantom, 0u);
  EXPECT_FALSE(j.failed());
  EXPECT_EQ(j.summary.largest_depth, 0.0);
  EXPECT_EQ(j.summary.largest_energy_drift, 0.0);
  EXPECT_EQ(j.summary.energy_start, 32.0);
  EXPECT_EQ(j.summary.largest_momentum_drift, 2.0);
  EXPECT_EQ(j.depth, (std::vector<double>{0, 0, 0}));
}

// Reported one step late: in step 1 the engine lets the ball move on to x = 13/8 = 1.625 without
// a report (it overlaps the wall by 13/8 + 1/2 - 2 = 1/8, a quarter of its radius: below the
// bound of a half), and reports the pair in step 2, pushing it out to x = 11/8 with velocity -8.
// Verdict: the contact of step 1 (exact t = 3/16) is late by 1; step 2's report is that
// contact's, not another. Depth: 1/8 at the end of step 1 (relative 1/4), none after (x = 11/8
// leaves 2 - 11/8 - 1/2 = 1/8). Nothing fails: late is no miss.
TEST(JudgeSteps, ContactReportedOneStepLate) {
  const oracle::StepJudgement j = oracle::judge_steps(
      wall_scene(), steps_trace({step(0.125, 1, 8), step(0.25, 1.625, 8), step(0.375, 1.375, -8, true), step(0.5, 0.375, -8)}));
  ASSERT_EQ(j.contacts.size(), 1u);
  const oracle::StepContact& c = j.contacts[0];
  EXPECT_EQ(c.step, 1u);
  EXPECT_EQ(c.verdict, StepVerdict::Late);
  EXPECT_EQ(c.late_steps, 1u);
  EXPECT_EQ(c.reported_step, std::optional<std::size_t>(2));
  EXPECT_EQ(*c.exact_time, 0.1875);
  EXPECT_EQ(c.depth, 0.125);
  EXPECT_EQ(c.relative_depth, 0.25);
  EXPECT_EQ(j.summary.late, 1u);
  EXPECT_EQ(j.summary.largest_late_steps, 1u);
  EXPECT_EQ(j.summary.on_time + j.summary.missed + j.summary.phantom, 0u);
  EXPECT_EQ(j.depth, (std::vector<double>{0, 0.125, 0, 0}));
  EXPECT_FALSE(j.failed());
}

// Two steps late, the ball stuck in the wall: x = 13/8 at the end of steps 1 and 2 (velocity 0
// in step 2: the engine stopped it without a report), the report in step 3. Late by 2. The
// energy falls from 32 to 0 at the end of step 2: drift -1, largest |drift| 1.
TEST(JudgeSteps, ContactReportedTwoStepsLate) {
  const oracle::StepJudgement j = oracle::judge_steps(
      wall_scene(),
      steps_trace({step(0.125, 1, 8), step(0.25, 1.625, 8), step(0.375, 1.625, 0), step(0.5, 1.375, -8, true)}));
  ASSERT_EQ(j.contacts.size(), 1u);
  EXPECT_EQ(j.contacts[0].verdict, StepVerdict::Late);
  EXPECT_EQ(j.contacts[0].late_steps, 2u);
  EXPECT_EQ(j.energy_drift, (std::vector<double>{0, 0, -1, 0}));
  EXPECT_EQ(j.summary.largest_energy_drift, 1.0);
}

// Sunk past the bound: x = 15/8 at the end of step 1, unreported: the overlap is
// 15/8 + 1/2 - 2 = 3/8, three quarters of the radius, past the bound of a half: missed
// (overlap), whatever comes later; the report in step 2 is then of a pair already overlapping
// at the step's start (a continuing report, no verdict).
TEST(JudgeSteps, OverlapPastTheBoundIsMissed) {
  const oracle::StepJudgement j = oracle::judge_steps(
      wall_scene(), steps_trace({step(0.125, 1, 8), step(0.25, 1.875, 8), step(0.375, 1.375, -8, true)}));
  ASSERT_EQ(j.contacts.size(), 1u);
  EXPECT_EQ(j.contacts[0].verdict, StepVerdict::Missed);
  EXPECT_EQ(j.contacts[0].miss, oracle::MissKind::Overlap);
  EXPECT_EQ(j.contacts[0].relative_depth, 0.75);
  EXPECT_EQ(j.summary.continuing_reports, 1u);
  EXPECT_TRUE(j.failed());
}

// A bullet through a thin wall between two steps: radius 1/4 from x = 1/2 at speed 32, steps of
// 1/16 s (2 units each). On the path from the start it meets the wall when its centre reaches
// 2 - 1/4 = 7/4: at t = (7/4 - 1/2) / 32 = 5/128 = 0.0390625, inside step 0 (0, 1/16]. The
// engine ends step 0 at x = 5/2, half a unit past the wall (distance 1/2 > 1/4: apart), and never
// reports the pair. Verdict: missed, pass-through (tunnelling). Step 1 (to x = 9/2) moves away
// from the wall: no contact. The trace fails.
TEST(JudgeSteps, BulletThroughThinWallIsMissed) {
  const oracle::TraceJudgement j =
      oracle::judge_trace(wall_scene(0.25, 32, 0.5), steps_trace({step(0.0625, 2.5, 32), step(0.125, 4.5, 32)}));
  ASSERT_EQ(j.steps.contacts.size(), 1u);
  const oracle::StepContact& c = j.steps.contacts[0];
  EXPECT_EQ(c.step, 0u);
  EXPECT_EQ(*c.exact_time, 0.0390625);
  EXPECT_EQ(c.verdict, StepVerdict::Missed);
  EXPECT_EQ(c.miss, oracle::MissKind::PassThrough);
  EXPECT_FALSE(c.reported_step.has_value());
  EXPECT_EQ(j.steps.summary.missed, 1u);
  EXPECT_EQ(j.steps.summary.tunnelled, 1u);
  EXPECT_TRUE(j.failed());
  EXPECT_NE(oracle::failure_text(j).find("pass-through"), std::string::npos) << oracle::failure_text(j);
}

// A phantom: the engine reports the pair in step 0, which ends at x = 1. On the path from the
// start (x = 0, v = 8) the gap to the wall is 2 - x - 1/2 = 3/2 - 8t, from 3/2 down to 1/2 at
// t = 1/8: positive through the whole step, and the exact contact (t = 3/16) is in step 1.
// Verdicts: phantom in step 0; the bounce in step 1, reported there, on time.
TEST(JudgeSteps, ReportWithPositiveGapIsPhantom) {
  const oracle::StepJudgement j =
      oracle::judge_steps(wall_scene(), steps_trace({step(0.125, 1, 8, true), step(0.25, 1, -8, true)}));
  ASSERT_EQ(j.contacts.size(), 2u);
  EXPECT_EQ(j.contacts[0].step, 0u);
  EXPECT_EQ(j.contacts[0].verdict, StepVerdict::Phantom);
  EXPECT_FALSE(j.contacts[0].exact_time.has_value());
  EXPECT_EQ(j.contacts[1].step, 1u);
  EXPECT_EQ(j.contacts[1].verdict, StepVerdict::OnTime);
  EXPECT_EQ(j.summary.phantom, 1u);
  EXPECT_EQ(j.summary.on_time, 1u);
  EXPECT_TRUE(j.failed());
}

// Touching exactly at the step's start is a contact already, not a phantom (a phantom's gap is
// positive through the whole step): the ball rests against the wall, its centre at
// 2 - 1/2 = 3/2 (gap 0), still, and the engine reports the pair in every step (a cradle's
// touching balls, in Box2D's traces). No exact contact (the gap stays 0, no crossing), two
// continuing reports, no phantom. Before: two phantoms, and the trace failed.
TEST(JudgeSteps, TouchingAtTheStepStartIsNoPhantom) {
  const oracle::StepJudgement j =
      oracle::judge_steps(wall_scene(0.5, 0, 1.5), steps_trace({step(0.125, 1.5, 0, true), step(0.25, 1.5, 0, true)}));
  EXPECT_TRUE(j.contacts.empty());
  EXPECT_EQ(j.summary.continuing_reports, 2u);
  EXPECT_EQ(j.summary.phantom, 0u);
  EXPECT_FALSE(j.failed());
}

// A report of a pair whose body's path changed inside the step is not judged: the ball of
// CorrectTraceIsOnTime meets the wall at x = 2 at t = 3/16, inside step 1, and the engine reports
// that contact and also ball-"back" (a second wall at x = -1, behind the ball). On the path from
// step 1's start (x = 1, v = 8) the gap to "back" is 1 - 1/2 + 1 = 3/2 and grows, but that path
// ends at 3/16, where the bounce sends the ball back, and the referee does not follow the new
// path: the report is counted as unfollowed, neither contact nor phantom. The wall's contact is
// on time. Before: one phantom, and the trace failed.
TEST(JudgeSteps, ReportAfterAnotherContactInTheStepIsUnfollowed) {
  Scene scene = wall_scene();
  scene.bodies.push_back(wall("back", {-1, -1}, {-1, 1}));
  TraceStep bounce = step(0.25, 1, -8, true);
  bounce.contacts.push_back({"ball", "back"});
  const oracle::StepJudgement j = oracle::judge_steps(scene, steps_trace({step(0.125, 1, 8), bounce, step(0.375, 0, -8)}));
  ASSERT_EQ(j.contacts.size(), 1u);
  EXPECT_EQ(j.contacts[0].b, "wall");
  EXPECT_EQ(j.contacts[0].verdict, StepVerdict::OnTime);
  EXPECT_EQ(j.summary.unfollowed_reports, 1u);
  EXPECT_EQ(j.summary.phantom, 0u);
  EXPECT_FALSE(j.failed());
}

// The trace ends before the contact is reported: x = 13/8 at the end of step 1 (overlap 1/8,
// within the bound), no more steps. Missed, never reported.
TEST(JudgeSteps, UnreportedAtTheEndIsMissed) {
  const oracle::StepJudgement j = oracle::judge_steps(wall_scene(), steps_trace({step(0.125, 1, 8), step(0.25, 1.625, 8)}));
  ASSERT_EQ(j.contacts.size(), 1u);
  EXPECT_EQ(j.contacts[0].verdict, StepVerdict::Missed);
  EXPECT_EQ(j.contacts[0].miss, oracle::MissKind::Unreported);
}

// The closed-form path with gravity: a ball of radius 1/2 dropped from y = 1 onto the floor y = 0
// under gravity -8. From a state (y, v) the path is y + v tau - 4 tau^2; the engine's state at
// the end of step 0 (1/4 s) is on the exact path: y = 1 - 4/16 = 3/4, v = -2. From there the ball
// meets the floor when 3/4 - 2 tau - 4 tau^2 = 1/2, tau = (sqrt(2) - 1) / 4, so at
// t = 1/4 + tau = sqrt(2) / 4 (= sqrt(1/8), as from the start): inside step 1 (1/4, 1/2],
// reported there: on time, at the double nearest sqrt(2) / 4, which is sqrt(2.0) / 4 (a
// correctly rounded square root, divided by a power of two).
TEST(JudgeSteps, ClosedFormPathUnderGravity) {
  Scene s;
  s.world.gravity = {0, -8};
  s.bodies.push_back(circle("ball", 0.5, {0, 1}));
  s.bodies.push_back(wall("floor", {-1, 0}, {1, 0}));
  Trace t = steps_trace({});
  TraceStep s0;
  s0.t = 0.25;
  s0.bodies = {{{0, 0.75}, {0, -2}}};
  TraceStep s1;
  s1.t = 0.5;
  s1.bodies = {{{0, 0.75}, {0, 2}}};
  s1.contacts = {{"floor", "ball"}};
  t.steps = {s0, s1};
  const oracle::StepJudgement j = oracle::judge_steps(s, t);
  ASSERT_EQ(j.contacts.size(), 1u);
  EXPECT_EQ(j.contacts[0].a, "ball");  // scene order, whatever order the report names them in
  EXPECT_EQ(j.contacts[0].step, 1u);
  EXPECT_EQ(j.contacts[0].verdict, StepVerdict::OnTime);
  EXPECT_EQ(*j.contacts[0].exact_time, std::sqrt(2.0) / 4);
}

// The usage of pge/judge.hpp's comment, with a naive stepping engine: explicit Euler at 16 Hz,
// a contact reported (and the ball reflected) when it overlaps the wall at a step's end. On the
// bullet scene (radius 1/4 from x = 1/2 at 32; the wall x = 2) one step moves the ball 2 units,
// from 1/2 to 5/2, past the wall without ever overlapping it at a step's end: by hand, as in
// BulletThroughThinWallIsMissed, the exact contact at t = 5/128 is missed by passing through.
TEST(JudgeSteps, NaiveSteppingEngineTunnels) {
  const Scene scene = wall_scene(0.25, 32, 0.5);
  Trace trace;
  trace.mode = TraceMode::Steps;
  trace.engine = "naive Euler, 16 Hz";
  trace.bodies = {"ball"};
  Vec2d position = scene.bodies[0].position, velocity = scene.bodies[0].velocity;
  const double dt = 0.0625;
  for (int k = 1; k <= 2; ++k) {
    position = position + velocity * dt;
    std::vector<TraceContact> reported;
    if (std::abs(position.x - 2) < 0.25) {
      velocity.x = -velocity.x;
      reported.push_back({"ball", "wall"});
    }
    trace.steps.push_back({k * dt, {{position, velocity}}, reported});
  }
  const oracle::TraceJudgement j = oracle::judge_trace(scene, trace);
  EXPECT_TRUE(j.failed());
  EXPECT_EQ(j.steps.summary.missed, 1u);
  EXPECT_EQ(oracle::failure_text(j),
            "contact \"ball\"-\"wall\" in step 0 (exact t = 0.0390625): missed (pass-through: tunnelling, never reported)");
}

// --- (b') hand-made step traces of a rotating body -------------------------------------------
//
// The scene: a unit square (vertices (+-1/2, +-1/2), mass 1) at the origin, at rest, turning
// counter-clockwise at 1 rad/s from angle 0, and a fixed wall, the segment x = 5/8 from y = -1 to
// 1; no gravity. Every state below is exact in doubles: the centre stays at the origin, and with
// omega = 1 the angle at the end of a step of dyadic length is that dyadic time. Its corner
// (1/2, -1/2) is at distance R = sqrt(2) / 2 from the centre, at polar angle theta - pi/4, so its
// x is R cos(theta - pi/4): 1/2 at theta = 0, rising to R = 0.7071 > 5/8 at pi/4. It reaches the
// wall when cos(theta - pi/4) = (5/8) / R = (5/8) sqrt(2), i.e. first at
//   theta1 = pi/4 - acos((5/8) sqrt(2)) = 0.2987...,
// and, spinning on, leaves the wall's line at pi/4 + acos((5/8) sqrt(2)) = 1.2722. The other
// corners stay behind the line until the corner (-1/2, -1/2) (x = R cos(theta - 3 pi/4)) reaches
// it at 3 pi/4 - acos((5/8) sqrt(2)) = 1.8695. The corner meets the wall at
// y = -sqrt(R^2 - (5/8)^2) = -0.3307, inside the segment. Steps of 1/8 s: theta1 lies in the
// third step (1/4, 3/8] (index 2). From any state of these traces before the contact (the angle
// t at time t, omega 1) the referee's path is theta(t) = t, so the exact contact is at theta1 s.

// The scene is tests/cli/judge/square-spins-next-to-a-wall.json (tests/cli/judge.sh judges it too).
Scene spinning_square_scene() {
  return read_scene_file(std::string(PGE_CLI_TESTS_DIR) + "/judge/square-spins-next-to-a-wall.json").scene;
}

// The closed form above, in double: std::acos and std::sqrt are within an ulp or so each, and
// acos's slope at 0.88 is 2.1, so the double is within 1e-15 of theta1 (0.2987).
double spinning_square_contact_time() { return std::atan(1.0) - std::acos(0.625 * std::sqrt(2.0)); }
constexpr double kClosedFormError = 1e-15;

// The square at the end of a step: at the origin, at rest, at `angle`, turning at `omega`.
TraceStep spin_step(double t, double angle, double omega, bool contact = false) {
  TraceStep s;
  s.t = t;
  s.bodies = {{{0, 0}, {0, 0}}};
  s.turns = {{angle, omega}};
  if (contact) s.contacts = {{"box", "wall"}};
  return s;
}

Trace spin_trace(const std::vector<TraceStep>& steps) {
  Trace t = steps_trace(steps);
  t.bodies = {"box"};
  return t;
}

// Reported in its step: the engine turns the square to 1/8, 1/4, then in step 2 strikes the
// wall, reports it and sends the square back (angle 1/4, omega -1: the corner's x is then
// (cos 1/4 + sin 1/4) / 2 = 0.6081 < 5/8, apart, and turning away). Verdict: one contact, in step
// 2, at theta1, on time; no overlap at any step's end (the largest corner x at a step's end
// before the contact is 0.6081 at angle 1/4). Energy: I omega^2 / 2 with I = m (1 + 1) / 12 =
// 1/6 (a uniform square lamina about its centre), 1/12 at every step, whatever the sign of omega:
// drift 0.
TEST(JudgeRotatingSteps, ContactReportedInItsStepIsOnTime) {
  const oracle::StepJudgement j = oracle::judge_steps(
      spinning_square_scene(),
      spin_trace({spin_step(0.125, 0.125, 1), spin_step(0.25, 0.25, 1), spin_step(0.375, 0.25, -1, true), spin_step(0.5, 0.125, -1)}));
  ASSERT_EQ(j.contacts.size(), 1u) << oracle::failure_text({TraceMode::Steps, j, {}});
  const oracle::StepContact& c = j.contacts[0];
  EXPECT_EQ(c.step, 2u);
  EXPECT_EQ(c.verdict, StepVerdict::OnTime);
  ASSERT_TRUE(c.exact_time.has_value());
  EXPECT_NEAR(*c.exact_time, spinning_square_contact_time(), kClosedFormError);
  EXPECT_EQ(j.summary.on_time, 1u);
  EXPECT_EQ(j.summary.late + j.summary.missed + j.summary.phantom + j.summary.undecided, 0u);
  EXPECT_EQ(j.summary.largest_depth, 0.0);
  EXPECT_EQ(j.summary.energy_start, 1.0 / 12);
  EXPECT_EQ(j.summary.largest_energy_drift, 0.0);
  EXPECT_FALSE(j.failed());
}

// Reported one step late: in step 2 the engine turns the square on to 3/8 without a report: the
// corner's x is (cos 3/8 + sin 3/8) / 2 = 0.6484, past the wall by 0.0234 (the separating-axis
// depth: along x, the shallowest axis; the square's own normals see the long wall overlap it by
// 0.28 and 1), 0.0234 of the contact distance (1, the square's size, smaller than the wall's 2):
// below the bound of a half. The report comes in step 3, with the square sent back to 1/4. Verdict:
// the contact of step 2 (at theta1) late by 1.
TEST(JudgeRotatingSteps, ContactReportedOneStepLate) {
  const oracle::StepJudgement j = oracle::judge_steps(
      spinning_square_scene(), spin_trace({spin_step(0.125, 0.125, 1), spin_step(0.25, 0.25, 1), spin_step(0.375, 0.375, 1),
                                           spin_step(0.5, 0.25, -1, true), spin_step(0.625, 0.125, -1)}));
  ASSERT_EQ(j.contacts.size(), 1u) << oracle::failure_text({TraceMode::Steps, j, {}});
  const oracle::StepContact& c = j.contacts[0];
  EXPECT_EQ(c.step, 2u);
  EXPECT_EQ(c.verdict, StepVerdict::Late);
  EXPECT_EQ(c.late_steps, 1u);
  EXPECT_EQ(c.reported_step, std::optional<std::size_t>(3));
  EXPECT_NEAR(*c.exact_time, spinning_square_contact_time(), kClosedFormError);
  // The depth from the turned corner (rounded far below a double, turn.hpp) and rounded once.
  EXPECT_NEAR(c.depth, (std::cos(0.375) + std::sin(0.375)) / 2 - 0.625, 1e-16);
  EXPECT_FALSE(j.failed());
}

// The corner contact skipped: one long step from angle 1/4 to 3/2, unreported. On the path from
// the step's start the corner reaches the wall at theta1, inside the step, and at 3/2 every
// corner is behind the line again (the largest x, corner (1/2, -1/2)'s, R cos(3/2 - pi/4) =
// 0.534 < 5/8; (-1/2, -1/2) only arrives at 1.8695): apart at the next step's start without a
// report. Verdict: missed (pass-through), and the trace fails.
TEST(JudgeRotatingSteps, SkippedCornerContactIsMissed) {
  const oracle::StepJudgement j = oracle::judge_steps(
      spinning_square_scene(), spin_trace({spin_step(0.125, 0.125, 1), spin_step(0.25, 0.25, 1), spin_step(1.5, 1.5, 1)}));
  ASSERT_EQ(j.contacts.size(), 1u) << oracle::failure_text({TraceMode::Steps, j, {}});
  const oracle::StepContact& c = j.contacts[0];
  EXPECT_EQ(c.step, 2u);
  EXPECT_EQ(c.verdict, StepVerdict::Missed);
  EXPECT_EQ(c.miss, oracle::MissKind::PassThrough);
  EXPECT_NEAR(*c.exact_time, spinning_square_contact_time(), kClosedFormError);
  EXPECT_TRUE(j.failed());
}

// A phantom: the engine reports the pair in step 0, from angle 0 to 1/8, through which the
// corner's x rises from 1/2 to (cos 1/8 + sin 1/8) / 2 = 0.5584 < 5/8 (and the other corners stay
// further back): apart through the whole step. Then the real contact, reported in step 2, on time.
TEST(JudgeRotatingSteps, ReportWithTheCornerFarFromTheWallIsPhantom) {
  const oracle::StepJudgement j = oracle::judge_steps(
      spinning_square_scene(),
      spin_trace({spin_step(0.125, 0.125, 1, true), spin_step(0.25, 0.25, 1), spin_step(0.375, 0.25, -1, true)}));
  ASSERT_EQ(j.contacts.size(), 2u) << oracle::failure_text({TraceMode::Steps, j, {}});
  EXPECT_EQ(j.contacts[0].step, 0u);
  EXPECT_EQ(j.contacts[0].verdict, StepVerdict::Phantom);
  EXPECT_EQ(j.contacts[1].step, 2u);
  EXPECT_EQ(j.contacts[1].verdict, StepVerdict::OnTime);
  EXPECT_EQ(j.summary.phantom, 1u);
  EXPECT_TRUE(j.failed());
}

// The referee turns the square at the recorded angular velocity, not the scene's: a trace whose
// square spins at 2 rad/s from angle 1/4 at t = 1/4 (a peer's spin changed by something the trace
// does not show) meets the wall when 1/4 + 2 (t - 1/4) = theta1, at t = 1/8 + theta1 / 2 = 0.2744,
// in step 2 (1/4, 3/8]. Reported there: on time, at that time.
TEST(JudgeRotatingSteps, PathFollowsTheRecordedSpin) {
  const oracle::StepJudgement j = oracle::judge_steps(
      spinning_square_scene(), spin_trace({spin_step(0.125, 0.125, 1), spin_step(0.25, 0.25, 2), spin_step(0.375, 0.25, -1, true)}));
  ASSERT_EQ(j.contacts.size(), 1u) << oracle::failure_text({TraceMode::Steps, j, {}});
  EXPECT_EQ(j.contacts[0].verdict, StepVerdict::OnTime);
  EXPECT_NEAR(*j.contacts[0].exact_time, 0.125 + spinning_square_contact_time() / 2, kClosedFormError);
}

// A step of a rotating scene without the turns, and a turn off the scene's start, are refused.
TEST(JudgeRotatingSteps, MissingOrWrongTurnsAreRefused) {
  TraceStep bare = spin_step(0.125, 0.125, 1);
  bare.turns.clear();
  try {
    oracle::judge_steps(spinning_square_scene(), spin_trace({bare}));
    FAIL() << "no error";
  } catch (const TraceError& e) {
    EXPECT_EQ(e.field(), "steps[0].turns");
    EXPECT_NE(e.reason().find("body \"box\" rotates"), std::string::npos) << e.what();
  }
  try {
    oracle::judge_steps(spinning_square_scene(), spin_trace({spin_step(0, 0, 2)}));
    FAIL() << "no error";
  } catch (const TraceError& e) {
    EXPECT_STREQ(e.what(), "trace: field \"steps[0].turns[0][1]\": the state at t = 0 is the scene's: body \"box\" has "
                           "angular velocity 1 there, the trace 2");
  }
}

// A rotating pair's contact the referee cannot decide is undecided, counted apart, never agree
// or a failure. The square at angle 0, not turning (omega 0, but a rotating body: the rotating
// search judges it), slides right at 1 from the origin; a wall hangs from (1, -1/2) down to
// (1, -2). The square's corner (1/2, -1/2) meets exactly the wall's upper end at t = 1/2 (a
// contact at an edge's very end, which oracle/README.md's "Undecided" names), in step 1 (1/4,
// 1/2], where the engine reports it.
TEST(JudgeRotatingSteps, ContactAtAnEdgesEndIsUndecided) {
  Scene s = spinning_square_scene();
  s.bodies[0].angular_velocity = 0;
  s.bodies[0].velocity = {1, 0};
  s.bodies[1] = wall("wall", {1, -0.5}, {1, -2});
  TraceStep s0 = spin_step(0.25, 0, 0), s1 = spin_step(0.5, 0, 0, true);
  s0.bodies = {{{0.25, 0}, {1, 0}}};
  s1.bodies = {{{0.5, 0}, {-1, 0}}};
  const oracle::StepJudgement j = oracle::judge_steps(s, spin_trace({s0, s1}));
  ASSERT_EQ(j.contacts.size(), 1u) << oracle::failure_text({TraceMode::Steps, j, {}});
  EXPECT_EQ(j.contacts[0].verdict, StepVerdict::Undecided);
  EXPECT_EQ(j.contacts[0].reported_step, std::optional<std::size_t>(1));
  EXPECT_FALSE(j.contacts[0].undecided_reason.empty());
  EXPECT_EQ(j.summary.undecided, 1u);
  EXPECT_EQ(j.summary.contacts + j.summary.phantom, 0u);
  EXPECT_FALSE(j.failed());
}

// A trace written and read back is the same trace.
TEST(JudgeTraceIo, WriteThenReadGivesTheTraceBack) {
  Trace t = steps_trace({step(0.125, 1, 8), step(0.25, -0.0, -8, true)});
  std::stringstream io;
  write_trace(io, t);
  const Trace back = read_trace(io, "memory");
  EXPECT_EQ(back.mode, TraceMode::Steps);
  EXPECT_EQ(back.engine, "hand-made");
  EXPECT_EQ(back.bodies, t.bodies);
  ASSERT_EQ(back.steps.size(), 2u);
  EXPECT_EQ(back.steps[1].t, 0.25);
  EXPECT_TRUE(std::signbit(back.steps[1].bodies[0].position.x));
  EXPECT_EQ(back.steps[1].bodies[0].velocity.x, -8);
  ASSERT_EQ(back.steps[1].contacts.size(), 1u);
  EXPECT_EQ(back.steps[1].contacts[0].b, "wall");
  EXPECT_EQ(back.steps[1].line, 3);
}

// A turning pair's collision keeps its turns (angle and angular velocity before, angular
// velocities after) through a write and a read; a line with only some of them is refused.
TEST(JudgeTraceIo, CollisionTurnsRoundTrip) {
  Trace t;
  t.mode = TraceMode::Events;
  TraceCollision c;
  c.t = 0.5;
  c.a = "box";
  c.b = "wall";
  c.turning = true;
  c.turn_a = {0.25, -3};
  c.wa_after = 1.5;
  t.collisions = {c};
  std::stringstream io;
  write_trace(io, t);
  const Trace back = read_trace(io, "memory");
  ASSERT_EQ(back.collisions.size(), 1u);
  EXPECT_TRUE(back.collisions[0].turning);
  EXPECT_EQ(back.collisions[0].turn_a.angle, 0.25);
  EXPECT_EQ(back.collisions[0].turn_a.angular_velocity, -3);
  EXPECT_EQ(back.collisions[0].turn_b.angle, 0);
  EXPECT_EQ(back.collisions[0].wa_after, 1.5);
  std::istringstream partial(R"({"format":"pge-trace/2","mode":"events"})"
                             "\n"
                             R"({"event":"collision","t":0.5,"a":"box","b":"wall","before":[[0,0,0,0],[0,0,0,0]],"va":[0,0],"vb":[0,0],"turn":[[0,1],[0,0]]})");
  try {
    read_trace(partial, "t.jsonl");
    FAIL() << "no error";
  } catch (const TraceError& e) {
    EXPECT_STREQ(e.what(), "t.jsonl:2: field \"wa\": missing: a collision of a turning pair gives \"turn\", \"wa\" and \"wb\" together");
  }
}

// --- (c) bad traces ---------------------------------------------------------------------------

// The TraceError `text` raises when read, or when judged against the wall scene.
std::string error_of(const std::string& text) {
  try {
    std::istringstream in(text);
    oracle::judge_trace(wall_scene(), read_trace(in, "t.jsonl"));
  } catch (const TraceError& e) {
    return e.what();
  }
  return "no error";
}

const std::string kStepsHeader = R"({"format":"pge-trace/2","mode":"steps","bodies":["ball"]})"
                                 "\n";

TEST(JudgeBadTraces, OneLineNamingLineAndField) {
  EXPECT_EQ(error_of(kStepsHeader + R"({"event":"step","t":NaN,"bodies":[[0,0,8,0]]})"),
            "t.jsonl:2: field \"t\": NaN is not a JSON number; NaN and infinities are not allowed");
  EXPECT_EQ(error_of(kStepsHeader + R"({"event":"step","t":0.25,"bodies":[[0,0,8,0]]})"
                                    "\n"
                                    R"({"event":"step","t":0.125,"bodies":[[0,0,8,0]]})"),
            "t.jsonl:3: field \"t\": 0.125 is before the time of line 2 (0.25): times must increase from step to step");
  EXPECT_EQ(error_of(kStepsHeader + R"({"event":"step","t":0.25,"bodies":[[0,0,8,0]],"contacts":[["ball","wal"]]})"),
            "t.jsonl:2: field \"contacts[0][1]\": no body \"wal\" in the scene");
  EXPECT_EQ(error_of(kStepsHeader + R"({"event":"step","t":0.25,"bodies":[[0,0,1e400,0]]})"),
            "t.jsonl:2: field \"bodies[0][2]\": number 1e400 is out of range for a double (it would overflow to infinity)");
  EXPECT_EQ(error_of(kStepsHeader + R"({"event":"step","t":0.25,"bodies":[[0,0,8]]})"),
            "t.jsonl:2: field \"bodies[0]\": must be a state [x, y, vx, vy] of 4 numbers, got [0,0,8]");
  EXPECT_EQ(error_of(kStepsHeader + R"({"event":"step","t":0.25,"bodies":[[0,0,8,0]],"colour":1})"),
            "t.jsonl:2: field \"colour\": unknown key");
  EXPECT_EQ(error_of(R"({"format":"pge-trace/2","mode":"steps","bodies":["ball","wall"]})"),
            "t.jsonl:1: field \"bodies[1]\": body \"wall\" is fixed: a steps trace gives the states of moving bodies only");
  EXPECT_EQ(error_of(R"({"format":"pge-trace/2","mode":"steps","bodies":[]})"),
            "t.jsonl:1: field \"bodies\": moving body \"ball\" of the scene is missing: a steps trace gives every moving "
            "body's state");
  EXPECT_EQ(error_of(R"({"format":"pge-trace/2","mode":"frames","bodies":[]})"),
            "t.jsonl:1: field \"mode\": must be \"events\" or \"steps\", got \"frames\"");
  // The state at t = 0 is the scene's start (the ball is at the origin, moving at 8).
  EXPECT_EQ(error_of(kStepsHeader + R"({"event":"step","t":0,"bodies":[[0,0,7,0]]})"),
            "t.jsonl:2: field \"bodies[0][2]\": the state at t = 0 is the scene's: body \"ball\" has velocity 8 there, the "
            "trace 7");
  // Events: the ball cannot be at x = 1 at t = 1/8, when its path from the start puts it at 1.
  EXPECT_EQ(error_of(R"({"format":"pge-trace/2","mode":"events"})"
                     "\n"
                     R"({"event":"collision","t":0.125,"a":"ball","b":"wall","before":[[1.5,0,8,0],[0,0,0,0]],"va":[-8,0],"vb":[0,0]})"),
            "t.jsonl:2: field \"before[0][0]\": body \"ball\" is not where the scene and the trace's earlier collisions "
            "put it: 1 on its path, 1.5 in the trace");
  EXPECT_EQ(error_of(R"({"format":"pge-trace/2","mode":"events"})"
                     "\n"
                     R"({"event":"collision","t":0.1875,"a":"ball","b":"wall","before":[[1.5,0,8,0],[0,0,0,0]],"va":[-8,0],"vb":[1,0]})"),
            "t.jsonl:2: field \"vb\": body \"wall\" is fixed: it stays at rest");
  EXPECT_EQ(error_of(R"({"format":"pge-trace/2","mode":"events"})"
                     "\n"
                     R"({"event":"collision","t":0.1875,"a":"ball","b":"ball","before":[[1.5,0,8,0],[1.5,0,8,0]],"va":[-8,0],"vb":[1,0]})"),
            "t.jsonl:2: field \"b\": a body cannot collide with itself");
  EXPECT_EQ(error_of(R"({"format":"pge-trace/2","mode":"events","bodies":["wall","ball"]})"),
            "t.jsonl:1: field \"bodies[0]\": an events trace lists every body of the scene in scene order (2 bodies: \"ball\" "
            "first), or none");
  EXPECT_NE(error_of(R"({"format":"pge-trace/1","scene":"x"})").find("pge-trace/1 (before issue 28)"), std::string::npos);
}

// A trace made in memory has no lines: errors name the element.
TEST(JudgeBadTraces, InMemoryErrorsNameTheElement) {
  Trace t = steps_trace({step(0.125, 1, 8), step(0.125, 1, 8)});
  try {
    oracle::judge_steps(wall_scene(), t);
    FAIL() << "no error";
  } catch (const TraceError& e) {
    EXPECT_STREQ(e.what(), "trace: field \"steps[1].t\": 0.125 is not after the previous step's end 0.125: step times increase");
  }
  t = steps_trace({step(0.125, std::nan(""), 8)});
  try {
    oracle::judge_steps(wall_scene(), t);
    FAIL() << "no error";
  } catch (const TraceError& e) {
    EXPECT_STREQ(e.what(), "trace: field \"steps[0].bodies[0][0]\": nan is not a finite number");
  }
}

}  // namespace
}  // namespace pge
