// Tunnelling (issue 22, pge/tunnel.hpp): hand-made paths through and past fixed bodies, and
// worlds that watch their bodies (WorldOptions::watch_tunnels): a ball bouncing off a thin wall,
// a ball that fast lets fall through a floor. Expected answers come from the geometry of the
// cases built here.
#include "pge/tunnel.hpp"

#include "pge/roots.hpp"
#include "pge/world.hpp"

#include "scene_bodies.hpp"

#include <gtest/gtest.h>

#include <string>

namespace pge {
namespace {

using test_scene::fixed_circle;
using test_scene::wall;

BodyDesc ball(Vec2d at, double radius = 0.5) { return test_scene::circle("ball", radius, at); }
// A fixed box [x0, x1] x [-1, 1].
BodyDesc fixed_box(const std::string& id, double x0, double x1) {
  BodyDesc s;
  s.id = id;
  s.shape = ShapeKind::Polygon;
  s.vertices = {{x0, -1}, {x1, -1}, {x1, 1}, {x0, 1}};
  s.fixed = true;
  return s;
}
// Body 0 moving, body 1 fixed.
Scene pair_scene(const BodyDesc& moving, const BodyDesc& fixed) {
  Scene s;
  s.bodies = {moving, fixed};
  return s;
}

BodyIndex through(const Scene& s, const PositionPath& p) { return FixedBodies(s).passed_through(0, p); }

TEST(Tunnel, StraightPathsThroughAndPastASegment) {
  const Scene s = pair_scene(ball({0, 0}), wall("wall", {1, -1}, {1, 1}));
  EXPECT_EQ(through(s, straight_path({0, 0}, {2, 0})), 1u);      // through the middle
  EXPECT_EQ(through(s, straight_path({0, 0.9}, {2, 0.9})), 1u);  // near an end, still within it
  EXPECT_EQ(through(s, straight_path({0, 2}, {2, 2})), kNoBody);  // past the end: the line, not the segment
  EXPECT_EQ(through(s, straight_path({0, 0}, {0.5, 0})), kNoBody);  // stops short (a bounce off the face)
  EXPECT_EQ(through(s, straight_path({0, 0}, {1, 0})), 1u);      // the centre on the face
}

TEST(Tunnel, ThinBoxPassedBetweenTwoLooks) {
  // Both ends outside the box: a test of the end points alone would see nothing.
  const Scene s = pair_scene(ball({-2, 0}), fixed_box("wall", 0, 1e-4));
  EXPECT_EQ(through(s, straight_path({-2, 0}, {2, 0})), 1u);
  EXPECT_EQ(through(s, straight_path({-2, 0}, {-0.5, 0})), kNoBody);
  EXPECT_EQ(through(s, straight_path({-2, 1.6}, {2, 1.6})), kNoBody);  // over the top
}

TEST(Tunnel, ArcsOverAndThroughAWall) {
  // A ball thrown from (0, 0) at (1, 4) under gravity (0, -2): y(s) = 4 s - s^2, over the wall
  // x = 2 (y in [0, 1]) at s = 2, where y = 4: clear, although the chord from s = 0 to s = 4
  // (landing at (4, 0)) runs along y = 0 through the foot of the wall.
  const Scene s = pair_scene(ball({0, 0}), wall("wall", {2, 0}, {2, 1}));
  EXPECT_EQ(through(s, {{0, 0}, {1, 4}, {0, -2}, 0, 4}), kNoBody);
  // Thrown at (1, 0.5) instead: y(s) = s / 2 - s^2, at the wall y(2) = -3, through a wall from
  // y = -4 to y = 1.
  const Scene tall = pair_scene(ball({0, 0}), wall("wall", {2, -4}, {2, 1}));
  EXPECT_EQ(through(tall, {{0, 0}, {1, 0.5}, {0, -2}, 0, 4}), 1u);
  // Only the part of the arc in [s0, s1] counts: it ends at s = 1.5, before the wall.
  EXPECT_EQ(through(tall, {{0, 0}, {1, 0.5}, {0, -2}, 0, 1.5}), kNoBody);
}

TEST(Tunnel, PegsAndPolygonsFollowAnInteriorPoint) {
  const Scene peg = pair_scene(ball({-2, 0}), fixed_circle("peg", 0.1, {0, 0}));
  EXPECT_EQ(through(peg, straight_path({-2, 0}, {2, 0})), 1u);
  EXPECT_EQ(through(peg, straight_path({-2, 0.2}, {2, 0.2})), kNoBody);
  // A falling arc x = s - 1, y = 0.05 - 0.05 s^2: at s = 1 it is at the peg's centre.
  EXPECT_EQ(through(peg, {{-1, 0.05}, {1, 0}, {0, -0.1}, 0, 2}), 1u);
  // A polygon whose position is a corner: its vertex centroid (0.5, 0.5) is what is followed.
  BodyDesc box = ball({0, 0});
  box.shape = ShapeKind::Polygon;
  box.vertices = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  const Scene s = pair_scene(box, wall("floor", {-5, 0.25}, {5, 0.25}));
  EXPECT_EQ(through(s, straight_path({0, 0}, {0, 1})), kNoBody);    // centroid 0.5 -> 1.5: above
  EXPECT_EQ(through(s, straight_path({0, 0}, {0, -1})), 1u);        // centroid 0.5 -> -0.5: through
  // A moving segment has no interior point: never reported.
  BodyDesc stick = wall("stick", {-0.5, 0}, {0.5, 0});
  stick.fixed = false;
  EXPECT_EQ(through(pair_scene(stick, wall("wall", {1, -1}, {1, 1})), straight_path({0, 0}, {2, 0})), kNoBody);
}

// 100 pegs of radius 0.1 at (x, y) for x, y in 0..9, body 1 + 10 y + x (body 0 the ball): enough
// for FixedBodies' grid; a path is answered by the first peg it enters in scene order, whether
// the grid lists the few near it or the path spans too much of the grid and every peg is tested.
TEST(Tunnel, ManyPegsFindTheOnePassedThrough) {
  Scene s;
  s.bodies.push_back(ball({-1, 0}));
  for (int y = 0; y < 10; ++y)
    for (int x = 0; x < 10; ++x) s.bodies.push_back(fixed_circle("peg", 0.1, {double(x), double(y)}));
  const FixedBodies pegs(s);
  EXPECT_EQ(pegs.passed_through(0, straight_path({-1, 3}, {10, 3})), 31u);          // row 3: peg (0, 3) first
  EXPECT_EQ(pegs.passed_through(0, straight_path({10, 3}, {-1, 3})), 31u);          // scene order, not path order
  EXPECT_EQ(pegs.passed_through(0, straight_path({-1, 3.5}, {10, 3.5})), kNoBody);  // between two rows
  EXPECT_EQ(pegs.passed_through(0, straight_path({4.5, -1}, {4.5, 10})), kNoBody);  // between two columns
  // From (2.9, 5) to (3.2, 5.05): at x = 3, y = 5 + 0.05 / 3, inside peg (3, 5).
  EXPECT_EQ(pegs.passed_through(0, straight_path({2.9, 5}, {3.2, 5.05})), 54u);
  EXPECT_EQ(pegs.passed_through(0, straight_path({-1, -1}, {10, 10})), 1u);  // the diagonal: (0, 0) first
  EXPECT_EQ(pegs.passed_through(0, straight_path({20, 20}, {30, 30})), kNoBody);  // far outside the pegs
}

// A ball that bounces off a thin wall: the world follows its two paths (to the bounce, and from
// it to the horizon) and finds no tunnel.
TEST(WorldTunnels, ABounceIsNoTunnel) {
  Scene s;
  BodyDesc b = ball({-2, 0});
  b.velocity = {1, 0};
  s.bodies = {b, fixed_box("wall", 0, 1e-4)};
  s.run.until = 10;
  WorldOptions wo;
  wo.watch_tunnels = true;
  for (const SolverKind solver : {SolverKind::Fast, SolverKind::Robust, SolverKind::Certified}) {
    wo.solver = solver;
    World<double> world(s, wo);
    world.run();
    EXPECT_EQ(world.counts().collisions, 1u) << solver_name(solver);  // bounced off the face at t = 1.5
    EXPECT_TRUE(world.tunnels().empty()) << solver_name(solver);
  }
}

// fixtures/scenes/rest/resting-on-floor.json: a ball of radius 0.5 lying on a floor under
// g = 9.81. Fast's closed form finds no contact (the contact function is 0 at t = 0, then
// negative), so the centre falls as y = 0.5 - 9.81 t^2 / 2 and crosses the floor at
// t = sqrt(1 / 9.81) = 0.32 s, x = 1.25 within the floor [-10, 10]: one tunnel, on the one path
// from t = 0 to the horizon 5. Fast promises nothing, so even a PGE_VALIDATE build lets the run
// end and lists it (what the report counts); robust rests the ball on the floor.
Scene ball_on_floor() {
  Scene s;
  s.world.gravity = {0, -9.81};
  BodyDesc b = ball({1.25, 0.5});
  s.bodies = {wall("floor", {-10, 0}, {10, 0}), b};
  s.run.until = 5;
  return s;
}

TEST(WorldTunnels, FastFallsThroughAFloorAndTheWorldSaysSo) {
  WorldOptions wo;
  wo.watch_tunnels = true;
  wo.solver = SolverKind::Fast;
  World<double> world(ball_on_floor(), wo);
  EXPECT_EQ(world.run(), StopReason::ReachedUntil);
  EXPECT_EQ(world.counts().collisions, 0u);
  ASSERT_EQ(world.tunnels().size(), 1u);
  const Tunnel& t = world.tunnels()[0];
  EXPECT_EQ(t.body, 1u);
  EXPECT_EQ(t.fixed, 0u);
  EXPECT_EQ(t.from, 0.0);
  EXPECT_EQ(t.to, 5.0);
  EXPECT_EQ(tunnel_text(t, "ball", "floor"), "body \"ball\" passed through fixed body \"floor\" between t = 0 and t = 5");
  EXPECT_LT(world.snapshot(1).position.y, -100.0);  // 0.5 - 9.81 * 25 / 2 = -122.1: well through
}

TEST(WorldTunnels, RobustAndCertifiedRestOnTheFloor) {
  for (const SolverKind solver : {SolverKind::Robust, SolverKind::Certified}) {
    WorldOptions wo;
    wo.watch_tunnels = true;
    wo.solver = solver;
    World<double> world(ball_on_floor(), wo);
    world.run();
    EXPECT_TRUE(world.tunnels().empty()) << solver_name(solver);
    EXPECT_EQ(world.snapshot(1).position.y, 0.5) << solver_name(solver);
  }
}

#ifndef PGE_VALIDATE
// Unwatched (and not a validation build), a world does no tunnel tests: they cost nothing.
TEST(WorldTunnels, UnwatchedWorldsListNothing) {
  WorldOptions wo;
  wo.solver = SolverKind::Fast;
  World<double> world(ball_on_floor(), wo);
  world.run();
  EXPECT_TRUE(world.tunnels().empty());
}
#endif

}  // namespace
}  // namespace pge
