// pge_peers (issue 11): the measures on hand-made cases, and the peers against an exact answer.
#include "pge/peers.hpp"

#include "pge/scene_io.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using pge::BodyDesc;
using pge::ShapeKind;
using pge::Vec2d;
namespace peers = pge::peers;

BodyDesc circle(double r) {
  BodyDesc b;
  b.shape = ShapeKind::Circle;
  b.radius = r;
  return b;
}
BodyDesc square(double half) {  // counter-clockwise, centred on the reference point
  BodyDesc b;
  b.shape = ShapeKind::Polygon;
  b.vertices = {{-half, -half}, {half, -half}, {half, half}, {-half, half}};
  return b;
}
BodyDesc segment(Vec2d a, Vec2d b) {
  BodyDesc s;
  s.shape = ShapeKind::Segment;
  s.a = a;
  s.b = b;
  s.fixed = true;
  return s;
}

// Two equal discs (radius 1, mass 1) 10 apart at speeds 1 and -1, e = 1: they touch at t = 4 and
// swap velocities; at t = 5 they are at x = 3 and x = 7. Every value is a small dyadic number.
const char* kHeadOn = R"({"format": "pge-scene/1", "name": "head-on",
  "bodies": [
    {"id": "left", "circle": {"radius": 1}, "position": [0, 0], "velocity": [1, 0], "mass": 1},
    {"id": "right", "circle": {"radius": 1}, "position": [10, 0], "velocity": [-1, 0], "mass": 1}],
  "run": {"until": 5}})";

TEST(PeersMeasures, OverlapDepthOfCircles) {
  EXPECT_DOUBLE_EQ(peers::overlap_depth(circle(1), {0, 0}, circle(1), {1.5, 0}), 0.5);
  EXPECT_EQ(peers::overlap_depth(circle(1), {0, 0}, circle(1), {2.5, 0}), 0.0);
  // 3-4-5: centres 5 apart, radii 3 and 2.5: overlap 0.5.
  EXPECT_DOUBLE_EQ(peers::overlap_depth(circle(3), {0, 0}, circle(2.5), {3, 4}), 0.5);
}

TEST(PeersMeasures, OverlapDepthAgainstSegmentAndPolygon) {
  const BodyDesc floor = segment({-10, 0}, {10, 0});
  EXPECT_DOUBLE_EQ(peers::overlap_depth(circle(1), {0, 0.75}, floor, {0, 0}), 0.25);
  EXPECT_EQ(peers::overlap_depth(circle(1), {0, 1.5}, floor, {0, 0}), 0.0);
  // Past the segment's end the distance is to the end point: (10.6, 0.8) is 1 from (10, 0):
  // touching, no overlap.
  EXPECT_NEAR(peers::overlap_depth(circle(1), {10.6, 0.8}, floor, {0, 0}), 0.0, 1e-15);
  // A circle whose centre is inside a square (side 2) by 0.25 from the right side: depth 1.25.
  EXPECT_DOUBLE_EQ(peers::overlap_depth(circle(1), {0.75, 0}, square(1), {0, 0}), 1.25);
  // Two squares of side 2, centres 1.5 apart along x: separating-axis depth 0.5.
  EXPECT_DOUBLE_EQ(peers::overlap_depth(square(1), {0, 0}, square(1), {1.5, 0.25}), 0.5);
  EXPECT_EQ(peers::overlap_depth(square(1), {0, 0}, square(1), {2.5, 0}), 0.0);
}

// Tunnelling is tested once, for PGE and the peers alike, in tests/test_tunnel.cpp.
TEST(PeersMeasures, Sizes) {
  EXPECT_EQ(peers::body_size(circle(0.25)), 0.25);
  EXPECT_EQ(peers::body_size(square(1)), 1.0);  // inradius of a square of side 2
  EXPECT_TRUE(std::isinf(peers::body_size(segment({0, 0}, {1, 0}))));
}

TEST(PeersMeasures, RmsErrorAndExtent) {
  const pge::LoadedScene s = pge::parse_scene(kHeadOn, "head-on");
  // Bounding box of the two discs: x in [-1, 11], y in [-1, 1]: diagonal sqrt(144 + 4).
  EXPECT_DOUBLE_EQ(peers::scene_extent(s.scene), std::sqrt(148.0));
  // Errors 3 and 4 (a 3-4-5 triangle in the second): RMS sqrt((9 + 25) / 2) = sqrt(17).
  EXPECT_DOUBLE_EQ(peers::rms_error(s.scene, {{3, 0}, {10, 0}}, {{0, 0}, {7, 4}}, 1.0), std::sqrt(17.0));
  EXPECT_DOUBLE_EQ(peers::rms_error(s.scene, {{3, 0}, {10, 0}}, {{0, 0}, {7, 4}}, 2.0), std::sqrt(17.0) / 2);
}

TEST(PeersReference, HeadOnIsExact) {
  const pge::LoadedScene s = pge::parse_scene(kHeadOn, "head-on");
  const auto ref = peers::reference_positions(s.scene, 0);
  ASSERT_EQ(ref.size(), 2u);
  EXPECT_EQ(ref[0].x, 3.0);
  EXPECT_EQ(ref[1].x, 7.0);
  // Every scalar: the inputs are small dyadic numbers, so the touch at t = 4 and the positions at
  // t = 5 are exact in float as in quad (the drifts are computed in the run's own scalar).
  std::vector<peers::Setting> settings = peers::default_settings("pge");
  for (const char* solver : {"robust", "certified"})
    for (const char* scalar : {"float", "long-double", "quad"}) settings.push_back(peers::pge_setting(solver, scalar));
  for (const peers::Setting& st : settings) {
    const peers::Outcome o = peers::run_setting(s, st, 0);
    EXPECT_TRUE(o.error.empty()) << o.error;
    EXPECT_EQ(o.horizon, 5.0);
    EXPECT_EQ(o.energy_drift, 0.0) << st.label;
    EXPECT_EQ(o.momentum_drift, 0.0) << st.label;  // 0/0 -> 0: the total momentum is 0
    EXPECT_EQ(o.final_error, 0.0) << st.label;
    EXPECT_EQ(o.tunnelled, 0) << st.label;
  }
}

TEST(PeersSettings, SeveralRatesAndIterationCounts) {
  EXPECT_EQ(peers::default_settings("pge").size(), 2u);
  EXPECT_EQ(peers::default_settings("box2d").size(), 6u);
  EXPECT_EQ(peers::default_settings("chipmunk").size(), 6u);
  EXPECT_TRUE(peers::default_settings("bullet").empty());
  const peers::Setting q = peers::pge_setting("certified", "quad");
  EXPECT_EQ(q.label, "pge certified/quad");
  EXPECT_EQ(q.engine, "pge");
  // An unknown scalar is refused (run_setting reports it, it does not fall back to double).
  const pge::LoadedScene s = pge::parse_scene(kHeadOn, "head-on");
  EXPECT_THROW(peers::run_setting(s, peers::pge_setting("robust", "half"), 0), std::invalid_argument);
}

// The peers swap the velocities too: they end within a few steps' travel of x = 3 and 7 (the
// contact is resolved at a step end, up to a step late, and the overlap is pushed apart), with
// energy kept to float (Box2D) or double (Chipmunk) rounding. Without the package the outcome
// says it is not installed.
TEST(PeersHeadOn, PeersSwapVelocities) {
  const pge::LoadedScene s = pge::parse_scene(kHeadOn, "head-on");
  for (const char* engine : {"box2d", "chipmunk"}) {
    for (const peers::Setting& st : peers::default_settings(engine)) {
      const peers::Outcome o = peers::run_setting(s, st, 0);
      if (!peers::available(engine)) {
        EXPECT_NE(o.error.find("is not installed"), std::string::npos) << o.error;
        continue;
      }
      ASSERT_TRUE(o.error.empty()) << o.error;
      EXPECT_LT(std::abs(o.energy_drift), 1e-6) << st.label;
      EXPECT_EQ(o.tunnelled, 0) << st.label;
      EXPECT_LT(o.penetration, 0.05) << st.label;
      // The error of the final positions: at most 4 steps of travel at speed 1, over the extent
      // sqrt(148) (measured: 0.5 to 1 step's travel at 60 and 240 Hz, 0.5 to 2 at 1 kHz).
      EXPECT_LT(o.final_error, 4 / st.hz / std::sqrt(148.0)) << st.label;
    }
  }
}

// The step trace a peer records (issue 28). The bullet (fixtures/scenes/peers/
// peers-bullet-thin-wall.json): a ball of radius 0.5 at x = -2, 1e4 m/s towards a wall x in
// [0, 1e-4], to t = 1e-3: max(1, round(1e-3 hz)) = 1 step at every rate. Chipmunk moves the ball
// 10 m in it, to x = 8, past the wall; Box2D (scale 64, peer_sim.hpp) caps it at
// b2_maxTranslation = 2 units, 2 / 64 m, to x = -1.96875. Neither reports a contact.
const char* kBullet = R"({"format": "pge-scene/1", "name": "bullet",
  "bodies": [
    {"id": "wall", "polygon": {"vertices": [[0.0, -1.0], [0.0001, -1.0], [0.0001, 1.0], [0.0, 1.0]]}, "position": [0.0, 0.0], "fixed": true},
    {"id": "ball", "circle": {"radius": 0.5}, "position": [-2.0, 0.0], "velocity": [10000.0, 0.0], "mass": 1.0}],
  "run": {"until": 0.001}})";

TEST(PeersTrace, BulletRecordsOneStepWithoutContact) {
  const pge::LoadedScene s = pge::parse_scene(kBullet, "bullet");
  for (const char* engine : {"box2d", "chipmunk"}) {
    if (!peers::available(engine)) continue;
    for (const peers::Setting& st : peers::default_settings(engine)) {
      EXPECT_FALSE(peers::run_setting(s, st, 0).trace.has_value()) << st.label << ": a trace not asked for";
      const std::vector<Vec2d> reference = peers::reference_positions(s.scene, 0.001);
      const peers::Outcome o = peers::run_setting(s, st, 0.001, reference, peers::Record::StepTrace);
      ASSERT_TRUE(o.error.empty()) << o.error;
      ASSERT_TRUE(o.trace.has_value()) << st.label;
      const pge::Trace& t = *o.trace;
      EXPECT_EQ(t.mode, pge::TraceMode::Steps);
      EXPECT_EQ(t.engine, st.label);
      EXPECT_EQ(t.bodies, std::vector<std::string>{"ball"});
      ASSERT_EQ(t.steps.size(), 1u) << st.label;
      EXPECT_EQ(t.steps[0].t, 0.001);
      ASSERT_EQ(t.steps[0].bodies.size(), 1u);
      EXPECT_NEAR(t.steps[0].bodies[0].position.x, std::string(engine) == "box2d" ? -1.96875 : 8.0, 1e-6) << st.label;
      EXPECT_TRUE(t.steps[0].contacts.empty()) << st.label;
    }
  }
}

// Head-on (kHeadOn): the discs touch at t = 4; every peer reports the pair, first within two
// steps of t = 4 (it resolves an overlap at a step's end), and nothing before t = 4 - 2 dt.
TEST(PeersTrace, HeadOnReportsThePairNearTheContact) {
  const pge::LoadedScene s = pge::parse_scene(kHeadOn, "head-on");
  for (const char* engine : {"box2d", "chipmunk"}) {
    if (!peers::available(engine)) continue;
    for (const peers::Setting& st : peers::default_settings(engine)) {
      const peers::Outcome o = peers::run_setting(s, st, 5, peers::reference_positions(s.scene, 5), peers::Record::StepTrace);
      ASSERT_TRUE(o.trace.has_value()) << st.label;
      const double dt = 1 / st.hz;
      ASSERT_EQ(o.trace->steps.size(), static_cast<std::size_t>(std::lround(5 * st.hz)));
      double first = -1;
      for (const pge::TraceStep& step : o.trace->steps)
        if (!step.contacts.empty()) {
          first = step.t;
          EXPECT_EQ(step.contacts.size(), 1u);
          EXPECT_EQ(std::minmax(step.contacts[0].a, step.contacts[0].b), std::minmax(std::string("left"), std::string("right")));
          break;
        }
      EXPECT_GE(first, 4 - 2 * dt) << st.label;
      EXPECT_LE(first, 4 + 2 * dt) << st.label;
    }
  }
}

}  // namespace
