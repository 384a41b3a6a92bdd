// pge_peers (issue 11): the measures on hand-made cases, and the peers against an exact answer.
#include "pge/peers.hpp"

#include "pge/scene_io.hpp"
#include "pge/trace_io.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
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
  EXPECT_EQ(peers::default_settings("box2d3").size(), 6u);
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
  for (const char* engine : {"box2d", "chipmunk", "box2d3"}) {
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
  for (const char* engine : {"box2d", "chipmunk", "box2d3"}) {
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

// --- rotation (issue 25: the peers turn what PGE turns) ---------------------------------------

// The pivot and inertia the peers are given: a uniform rectangle w x h of mass m has m (w^2 +
// h^2) / 12 about its centroid (the textbook closed form), wherever its reference point is; a
// thin rod m L^2 / 12 about its midpoint; the scene's own inertia wins. Inputs are dyadic, so the
// closed forms are exact; the engine's polygon formula (a triangle fan, about a dozen roundings
// of numbers below 8) is allowed 8 eps relative.
TEST(PeersRotation, InertiaIsTheClosedForm) {
  const double eps = std::numeric_limits<double>::epsilon();
  BodyDesc box = square(0.75);  // 1.5 x 1.5
  box.vertices = {{-0.75, -0.25}, {0.75, -0.25}, {0.75, 0.25}, {-0.75, 0.25}};  // w = 1.5, h = 0.5
  box.mass = 3;
  box.rotates = true;
  const double closed = 3 * (1.5 * 1.5 + 0.5 * 0.5) / 12;  // 0.625
  peers::RigidFrame f = peers::rigid_frame(box);
  EXPECT_TRUE(f.rotates);
  EXPECT_NEAR(f.inertia, closed, 8 * eps * closed);
  EXPECT_EQ(f.pivot.x, 0.0);
  EXPECT_EQ(f.pivot.y, 0.0);
  // The same rectangle with its reference point at a corner: the pivot is the centre (0.75, 0.25).
  box.vertices = {{0, 0}, {1.5, 0}, {1.5, 0.5}, {0, 0.5}};
  f = peers::rigid_frame(box);
  EXPECT_NEAR(f.inertia, closed, 8 * eps * closed);
  EXPECT_NEAR(f.pivot.x, 0.75, 8 * eps);
  EXPECT_NEAR(f.pivot.y, 0.25, 8 * eps);
  box.inertia = 2.5;  // the scene's inertia
  EXPECT_EQ(peers::rigid_frame(box).inertia, 2.5);
  BodyDesc rod = segment({1, 0}, {1, 2});
  rod.fixed = false;
  rod.mass = 3;
  rod.rotates = true;
  f = peers::rigid_frame(rod);
  EXPECT_NEAR(f.inertia, 3 * 4 / 12.0, 8 * eps);
  EXPECT_EQ(f.pivot.x, 1.0);
  EXPECT_EQ(f.pivot.y, 1.0);
  // A fixed body turns about its position with no inertia (infinite); one that does not turn: 0.
  rod.fixed = true;
  f = peers::rigid_frame(rod);
  EXPECT_TRUE(f.rotates);
  EXPECT_EQ(f.inertia, 0.0);
  EXPECT_EQ(f.pivot.x, 0.0);
  box.rotates = false;
  f = peers::rigid_frame(box);
  EXPECT_FALSE(f.rotates);
  EXPECT_EQ(f.inertia, 0.0);
}

// Overlap with angles: two squares of side 2, centres 2.25 apart along x, apart at angle 0. The
// second turned by pi/4 reaches sqrt(2) from its centre along x, to 2.25 - sqrt(2) < 1: on the
// unturned square's normal (1, 0) the projections [-1, 1] and [2.25 - sqrt(2), 2.25 + sqrt(2)]
// overlap by sqrt(2) - 1.25 = 0.164; on the turned square's normals (1, 1)/sqrt(2) by
// sqrt(2) - (2.25/sqrt(2) - 1) = 0.823, on (0, 1) by 2: the depth is the smallest, sqrt(2) - 1.25.
TEST(PeersRotation, OverlapDepthTurnsTheShapes) {
  const double pi = std::acos(-1.0);
  EXPECT_EQ(peers::overlap_depth(square(1), {0, 0}, square(1), {2.25, 0}), 0.0);
  EXPECT_EQ(peers::overlap_depth(square(1), {0, 0}, 0.0, square(1), {2.25, 0}, 0.0), 0.0);
  EXPECT_NEAR(peers::overlap_depth(square(1), {0, 0}, 0.0, square(1), {2.25, 0}, pi / 4), std::sqrt(2.0) - 1.25, 1e-15);
}

// One box spinning freely, no contacts, no field: its reference point is at a corner, so the
// scene's position turns about the centroid c = (0.5, 0.25) (the classic place to go wrong).
// Closed form: pivot(t) = p0 + R(a0) c + v t, angle(t) = a0 + w t, position(t) = pivot(t) -
// R(angle(t)) c, velocity v and spin w for ever. Tolerances from the peer's arithmetic: each step
// adds dt w to the angle and dt v to the pivot, each rounded by at most half an ulp of the result
// (eps/2 relative) and dt itself rounded once, so after N steps the error is at most (N + 2) eps
// times the largest magnitude (float eps 2^-23 for Box2D, double 2^-52 for Chipmunk); a position
// adds |c| times the angle's error.
const char* kFreeSpin = R"({"format": "pge-scene/2", "name": "free-spin",
  "bodies": [
    {"id": "box", "polygon": {"vertices": [[0, 0], [1, 0], [1, 0.5], [0, 0.5]]}, "position": [3, 2],
     "velocity": [0.5, -0.25], "mass": 2, "angle": 0.25, "angular_velocity": 2}],
  "run": {"until": 1}})";

TEST(PeersRotation, FreeSpinKeepsItsSpinAndTurnsByOmegaT) {
  const pge::LoadedScene s = pge::parse_scene(kFreeSpin, "free-spin");
  const Vec2d c{0.5, 0.25}, v{0.5, -0.25};
  const double a0 = 0.25, w = 2;
  for (const char* engine : {"box2d", "chipmunk", "box2d3"}) {
    if (!peers::available(engine)) continue;
    const double eps = std::string(engine) != "chipmunk" ? std::ldexp(1.0, -23) : std::ldexp(1.0, -52);
    for (const peers::Setting& st : peers::default_settings(engine)) {
      const peers::Outcome o = peers::run_setting(s, st, 1, peers::reference_positions(s.scene, 1), peers::Record::StepTrace);
      ASSERT_TRUE(o.error.empty()) << o.error;
      ASSERT_TRUE(o.trace.has_value());
      const double n = static_cast<double>(o.trace->steps.size());
      for (const pge::TraceStep& step : o.trace->steps) {
        ASSERT_EQ(step.turns.size(), 1u) << st.label;
        const double angle = a0 + w * step.t;
        // Box2D v3 turns a body by normalising (c, s) + h w (-s, c) each sub-step of length h: an
        // angle of atan(h w) instead of h w, short by at most (h w)^3 / 3 (the Taylor series of atan).
        const double substeps = std::string(engine) == "box2d3" ? st.hz * st.velocity_iterations : 0;
        const double hw = substeps > 0 ? w / substeps : 0;
        const double integrator = std::round(step.t * substeps) * hw * hw * hw / 3;
        const double angle_tol = (n + 2) * eps * std::max(angle, w) + integrator;
        EXPECT_NEAR(step.turns[0].angle, angle, angle_tol) << st.label << " t = " << step.t;
        EXPECT_NEAR(step.turns[0].angular_velocity, w, 2 * eps * w) << st.label;
        const Vec2d pivot = Vec2d{3, 2} + pge::rotated(a0, c) + v * step.t;
        const Vec2d expected = pivot - pge::rotated(angle, c);
        const double pos_tol = (n + 2) * eps * 4 + std::hypot(c.x, c.y) * angle_tol;
        EXPECT_NEAR(step.bodies[0].position.x, expected.x, pos_tol) << st.label << " t = " << step.t;
        EXPECT_NEAR(step.bodies[0].position.y, expected.y, pos_tol) << st.label << " t = " << step.t;
        EXPECT_NEAR(step.bodies[0].velocity.x, v.x, 2 * eps) << st.label;
        EXPECT_NEAR(step.bodies[0].velocity.y, v.y, 2 * eps) << st.label;
      }
      // Energy (m v^2 / 2 + I w^2 / 2) is kept to the peer's rounding of v and w.
      EXPECT_LT(std::abs(o.energy_drift), 8 * eps) << st.label;
    }
  }
}

// A step trace with turns is written and read back, and a turn of the wrong form is refused.
TEST(PeersRotation, StepTraceCarriesTurns) {
  const pge::LoadedScene s = pge::parse_scene(kFreeSpin, "free-spin");
  for (const char* engine : {"box2d", "chipmunk", "box2d3"}) {
    if (!peers::available(engine)) continue;
    const peers::Setting st = peers::default_settings(engine).front();
    const peers::Outcome o = peers::run_setting(s, st, 0.1, peers::reference_positions(s.scene, 0.1), peers::Record::StepTrace);
    ASSERT_TRUE(o.trace.has_value());
    std::stringstream io;
    pge::write_trace(io, *o.trace);
    const pge::Trace back = pge::read_trace(io, "memory");
    ASSERT_EQ(back.steps.size(), o.trace->steps.size());
    ASSERT_EQ(back.steps.back().turns.size(), 1u);
    EXPECT_EQ(back.steps.back().turns[0].angle, o.trace->steps.back().turns[0].angle);
    EXPECT_EQ(back.steps.back().turns[0].angular_velocity, o.trace->steps.back().turns[0].angular_velocity);
  }
  std::istringstream bad(R"({"format":"pge-trace/2","mode":"steps","bodies":["box"]})"
                         "\n"
                         R"({"event":"step","t":0.5,"bodies":[[3,2,0.5,-0.25]],"turns":[[1.25]]})");
  try {
    pge::read_trace(bad, "t.jsonl");
    FAIL() << "no error";
  } catch (const pge::TraceError& e) {
    EXPECT_STREQ(e.what(), "t.jsonl:2: field \"turns[0]\": must be a turn [angle, angular velocity] of 2 numbers, got [1.25]");
  }
}

// A unit square (mass 1, I = 1/6, the closed form above) turned by pi/6, not spinning, moving
// at u = 1 towards a fixed wall x = 2: its corner R(pi/6) (1/2, -1/2) strikes first. The impulse
// with lever arms (issue 25, derived by hand): with r that corner's arm, n = (1, 0), e = 1,
// j = 2 u / (1/m + r.y^2 / I), v' = u - j / m, w' = r.y j / I (clockwise: the corner is below the
// centre). The peer solves the contact at a step's end, but the box does not turn before it, so
// the corner's arm is the exact one, and a contact point moved along n changes no r x n.
// Beside it, far away, a square with "rotates": false strikes a fixed ball 0.3 off its centre
// line: a body free to turn would turn; this one keeps fixed rotation (angle and spin exactly 0
// in the peer) and comes straight back, v' = -u.
// Tolerances: Box2D is float (2^-24 per rounding, a few dozen roundings of numbers near 1: 1e-5);
// Chipmunk is double (1e-9: an iterative solver whose one contact converges in one iteration).
// Box2D at 60 Hz is held only to the sense of the spin: the box (scale 2, peer_sim.hpp) moves
// 1/30 a step, more than Box2D's contact skin (2 b2_polygonRadius = 0.02), so the strike is
// found by its time-of-impact sub-step, which resolves it from a state it has moved to a safe
// separation first, not from the touching one (measured: v' and w' 1.3% and 1.1% off); at 240
// and 1000 Hz a step moves less than the skin and the contact is found touching.
const char* kCornerStrike = R"({"format": "pge-scene/2", "name": "corner-strike",
  "bodies": [
    {"id": "spinner", "polygon": {"vertices": [[-0.5, -0.5], [0.5, -0.5], [0.5, 0.5], [-0.5, 0.5]]}, "position": [0, 0],
     "velocity": [1, 0], "mass": 1, "angle": 0.52359877559829882},
    {"id": "wall", "segment": {"a": [2, -2], "b": [2, 2]}, "fixed": true},
    {"id": "slider", "polygon": {"vertices": [[-0.5, -0.5], [0.5, -0.5], [0.5, 0.5], [-0.5, 0.5]]}, "position": [0, 10],
     "velocity": [1, 0], "mass": 1, "rotates": false},
    {"id": "ball", "circle": {"radius": 0.25}, "position": [2.25, 10.3], "fixed": true}],
  "run": {"until": 2}})";

TEST(PeersRotation, CornerStrikeSetsTheBoxSpinningAndFixedRotationStays) {
  const double pi = std::acos(-1.0), a = pi / 6, u = 1, m = 1, inertia = 1.0 / 6;
  const double ry = 0.5 * std::sin(a) - 0.5 * std::cos(a);  // the corner's arm: R(a) (1/2, -1/2)
  const double j = 2 * u / (1 / m + ry * ry / inertia);
  const double v_after = u - j / m, w_after = ry * j / inertia;  // -0.6653, -1.8286
  const pge::LoadedScene s = pge::parse_scene(kCornerStrike, "corner-strike");
  for (const char* engine : {"box2d", "chipmunk", "box2d3"}) {
    if (!peers::available(engine)) continue;
    const double tol = std::string(engine) != "chipmunk" ? 1e-5 : 1e-9;
    for (const peers::Setting& st : peers::default_settings(engine)) {
      const peers::Outcome o = peers::run_setting(s, st, 2, peers::reference_positions(s.scene, 2), peers::Record::StepTrace);
      ASSERT_TRUE(o.error.empty()) << o.error;
      ASSERT_EQ(o.trace->bodies, (std::vector<std::string>{"spinner", "slider"}));
      const pge::TraceStep& end = o.trace->steps.back();
      ASSERT_EQ(end.turns.size(), 2u);
      EXPECT_LT(end.turns[0].angular_velocity, -1.0) << st.label;  // clockwise, at least half the closed form
      if (std::string(engine) != "box2d" || st.hz != 60) {
        EXPECT_NEAR(end.bodies[0].velocity.x, v_after, tol * std::abs(v_after)) << st.label;
        EXPECT_NEAR(end.bodies[0].velocity.y, 0.0, tol) << st.label;
        EXPECT_NEAR(end.turns[0].angular_velocity, w_after, tol * std::abs(w_after)) << st.label;
      }
      EXPECT_NEAR(end.bodies[1].velocity.x, -u, tol) << st.label;
      EXPECT_NEAR(end.bodies[1].velocity.y, 0.0, tol) << st.label;
      for (const pge::TraceStep& step : o.trace->steps) {
        EXPECT_EQ(step.turns[1].angle, 0.0) << st.label << " t = " << step.t;
        EXPECT_EQ(step.turns[1].angular_velocity, 0.0) << st.label << " t = " << step.t;
      }
      EXPECT_LT(std::abs(o.energy_drift), 10 * tol) << st.label;
      EXPECT_EQ(o.tunnelled, 0) << st.label;
    }
  }
}
}  // namespace
