// The referee for rotation (issue 26): certified contact times of turning bodies against closed
// forms, an exact tangency, a contact after a thousand near misses, and faked engine mistakes on
// turning bodies, each caught with the right verdict. Expected values come from closed forms
// evaluated with mpmath at 50 digits (each test says which), never from the code under test.
#include "pge/oracle.hpp"
#include "pge/scene_io.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <numbers>
#include <optional>

namespace pge::oracle {
namespace {

BodyDesc square(const std::string& id, double omega) {
  BodyDesc b;
  b.id = id;
  b.shape = ShapeKind::Polygon;
  b.vertices = {{-0.5, -0.5}, {0.5, -0.5}, {0.5, 0.5}, {-0.5, 0.5}};
  b.mass = 1;
  b.gravity = false;
  b.rotates = true;
  b.angular_velocity = omega;
  return b;
}

BodyDesc wall_segment(const std::string& id, double x) {
  BodyDesc b;
  b.id = id;
  b.shape = ShapeKind::Segment;
  b.a = {x, -5};
  b.b = {x, 5};
  b.fixed = true;
  return b;
}

// fixtures/scenes/rotation/square-spins-into-a-wall.json: a unit square spinning at 1 rad/s about the
// origin, a wall at x = 0.6 (the double nearest). Vertex 1 (0.5, -0.5) reaches it at
// t1 = pi/4 - acos(0.6 sqrt 2), 0.22779933669791162214542998907517844077688156267106
// (mpmath, 50 digits, X the double 0.59999999999999997779...).
Scene square_and_wall(double until) {
  Scene s;
  s.name = "square-and-wall";
  s.bodies = {square("box", 1.0), wall_segment("wall", 0.6)};
  s.run.until = until;
  return s;
}

TEST(RotationReferee, SquareSpinningIntoAWallMatchesTheAcosFormTo30Digits) {
  const World<double> world(square_and_wall(2));
  const NextEvent next = next_event(exact_state(world));
  ASSERT_TRUE(next.time);
  EXPECT_EQ(next.time->decimal(30), "0.227799336697911622145429989075");
  ASSERT_EQ(next.pairs.size(), 1u);
  EXPECT_EQ(next.pairs[0].features[0], (FeaturePair{ContactKind::VertexEdge, 1, 0}));
}

// fixtures/scenes/rotation/corner-grazes-a-wall.json: a diamond turned -0.5 rad spins at 1 rad/s; its
// vertex 0 is at x = cos(angle), which touches the wall's line x = 1 exactly at t = 0.5 (angle
// exactly 0) and turns back: a tangency, no contact (DESIGN.md). The referee proves it a graze
// (the function and its derivative exactly zero there) and finds nothing before the horizon; the
// engine's event there (its impulse is rounding) is undecided, never agreement.
TEST(RotationReferee, AnExactTangencyIsAGrazeAndTheEngineEventThereUndecided) {
  const LoadedScene loaded = read_scene_file(PGE_SCENES_DIR "/rotation/corner-grazes-a-wall.json");
  World<double> world(loaded.scene);
  EXPECT_FALSE(next_event(exact_state(world)).time.has_value());
  Referee referee(exact_state(world));
  std::vector<Verdict> verdicts;
  follow(world, referee, [&](const CollisionInfo<double>&, const ExactEvent&, const Judgement& j) {
    verdicts.push_back(j.verdict);
    EXPECT_NE(j.undecided_reason.find("graze"), std::string::npos) << j.undecided_reason;
  });
  world.run();
  ASSERT_EQ(verdicts.size(), 1u);
  EXPECT_EQ(verdicts[0], Verdict::Undecided);
  EXPECT_FALSE(referee.judge_end().miss);
}

// fixtures/scenes/rotation/corner-near-misses-a-wall-for-1000-turns.json: a corner passes within 1e-12
// of a wall on each of 1,000 turns before the diamond strikes a ball; the strike's time from the
// stored paths is 65.015207399248453 s (derive.py, 50 digits, rounded to double; the fixture's
// tolerance 1.14e-13, 8 ulps). No near miss may be taken for a contact, none skipped, and the
// work stays bounded (seconds, not a step per turn of fixed size).
TEST(RotationReferee, TheContactAfterAThousandNearMissesIsFound) {
  const LoadedScene loaded =
      read_scene_file(PGE_SCENES_DIR "/rotation/corner-near-misses-a-wall-for-1000-turns.json");
  const World<double> world(loaded.scene);
  const NextEvent next = next_event(exact_state(world));
  ASSERT_TRUE(next.time);
  EXPECT_NEAR(next.time->to_double(), 65.015207399248453, 1.14e-13);
  ASSERT_EQ(next.pairs.size(), 1u);
  EXPECT_EQ(loaded.scene.bodies[next.pairs[0].a].id + "-" + loaded.scene.bodies[next.pairs[0].b].id, "diamond-ball");
}

// The first real event of a run, with the motions after it.
struct Recorded {
  CollisionInfo<double> info;
  ExactMotion a_after, b_after;
};

Recorded first_event(const Scene& scene) {
  World<double> world(scene);
  std::optional<Recorded> r;
  world.on_collision([&](const CollisionInfo<double>& c) {
    if (!r) r = Recorded{c, exact_motion(world.motion(c.a)), exact_motion(world.motion(c.b))};
  });
  world.run();
  if (!r) throw std::logic_error("no event");
  return *r;
}

// A square spinning into a wall, and a ball falling onto a floor far away: from rest, its lowest
// point 4.905 m above the floor under g = 9.81, it lands at t = sqrt(2 h / g) = 1 s.
Scene square_wall_and_ball() {
  Scene s = square_and_wall(2);
  BodyDesc ball;
  ball.id = "ball";
  ball.shape = ShapeKind::Circle;
  ball.radius = 0.5;
  ball.position = {20, 0.5 + 4.905};
  ball.mass = 1;
  BodyDesc floor = wall_segment("floor", 0);
  floor.a = {15, 0};
  floor.b = {25, 0};
  s.world.gravity = {0, -9.81};
  s.bodies.push_back(ball);
  s.bodies.push_back(floor);
  return s;
}

TEST(RotationReferee, CatchesASkippedCornerContactAsAMiss) {
  // The engine "skips" the box's corner (t1 = 0.2278 s) and reports the ball's landing first, at
  // t = 1: an earlier approaching contact was passed over.
  const World<double> world(square_wall_and_ball());
  Referee referee(exact_state(world));
  ExactEvent e;
  e.time = Dyadic::from(1.0);
  e.a = 2;
  e.b = 3;
  e.contact = ContactKind::CircleEdge;
  e.va_before = {Dyadic::from(0.0), Dyadic::from(-9.81)};
  e.va_after = {Dyadic::from(0.0), Dyadic::from(9.81)};
  e.impulse = true;
  const ExactMotion after = exact_motion(world.motion(2));
  const Judgement j = referee.judge(e, after, exact_motion(world.motion(3)));
  EXPECT_EQ(j.verdict, Verdict::Miss);
  ASSERT_TRUE(j.earliest_time);
  EXPECT_EQ(j.earliest_time->decimal(20), "0.22779933669791162214");
}

TEST(RotationReferee, CatchesAContactOneRevolutionLateAsATimeError) {
  // The engine reports the box's corner one turn (2 pi s at 1 rad/s) after the true contact.
  const Recorded real = first_event(square_and_wall(10));
  const World<double> world(square_and_wall(10));
  Referee referee(exact_state(world));
  ExactEvent e = exact_event(real.info);
  e.time = Dyadic::from(real.info.time + 2 * std::numbers::pi);
  const Judgement j = referee.judge(e, real.a_after, real.b_after);
  EXPECT_EQ(j.verdict, Verdict::TimeError);
  ASSERT_TRUE(j.pair_time);
  EXPECT_EQ(j.pair_time->decimal(20), "0.22779933669791162214");
  // And the real event agrees: the referee itself is not the mistake.
  Referee fair(exact_state(world));
  EXPECT_EQ(fair.judge(exact_event(real.info), real.a_after, real.b_after).verdict, Verdict::Agree);
}

TEST(RotationReferee, CatchesAnImpulseWithoutLeverArmsInTheEnergy) {
  // The box's corner strikes the wall with the contact point r from the pivot and normal n; the
  // impulse j = -(1 + e) v_n / (1/m + (r x n)^2 / I) (issue 25, item 5) conserves energy with
  // e = 1. The mistake drops (r x n)^2 / I from the denominator and applies the larger impulse
  // with its lever arm: the kinetic energy (with I w^2 / 2) changes by a large fraction, which
  // the exact measure shows; the real event's change is rounding.
  const Recorded real = first_event(square_and_wall(2));
  const World<double> world(square_and_wall(2));
  const double m = 1, inertia = world.inertia(0);
  const CollisionInfo<double>& c = real.info;
  const double rx = c.point.x - world.motion(0).p0.x, ry = c.point.y - world.motion(0).p0.y;
  const double rxn = rx * c.normal.y - ry * c.normal.x;
  // Box is body a, the normal points from a to b: the contact point's normal speed, before.
  const double vn = (c.va_before.x - c.wa_before * ry) * c.normal.x + (c.va_before.y + c.wa_before * rx) * c.normal.y;
  const double wrong = -2 * vn / (1 / m);  // without (r x n)^2 / I
  ExactEvent e = exact_event(c);
  const Vec2d va{c.va_before.x + wrong * c.normal.x / m, c.va_before.y + wrong * c.normal.y / m};
  const double wa = c.wa_before + rxn * wrong / inertia;
  e.va_after = ExactVec::from(va);
  e.wa_after = Dyadic::from(wa);
  ExactMotion a_after = real.a_after;
  a_after.v0 = ExactVec::from(va);
  a_after.omega = Dyadic::from(wa);
  Referee referee(exact_state(world));
  const Judgement wrong_j = referee.judge(e, a_after, real.b_after);
  const double relative = std::abs(wrong_j.conservation.energy_change.to_double()) / wrong_j.conservation.kinetic_before;
  EXPECT_GT(relative, 0.1);
  Referee fair(exact_state(world));
  const Judgement right = fair.judge(exact_event(c), real.a_after, real.b_after);
  EXPECT_LT(std::abs(right.conservation.energy_change.to_double()) / right.conservation.kinetic_before, 1e-14);
}

TEST(RotationReferee, MeasuresASegmentsGapFromTheSideTheBodyIsOn) {
  // The wall is a segment: two-sided. An engine event faked at t = 0.1, before the box's corner
  // (0.5, -0.5), turned 0.1 rad, reaches it: the corner is at x = 0.5 (cos 0.1 + sin 0.1) =
  // 0.54738, 0.05262 short of the wall at 0.6 (the double nearest), on the box's side: a gap of
  // +0.05262, which measured from the wall's other side would be -0.05262.
  const Recorded real = first_event(square_and_wall(2));
  const World<double> world(square_and_wall(2));
  Referee referee(exact_state(world));
  ExactEvent e = exact_event(real.info);
  e.time = Dyadic::from(0.1);
  const Judgement j = referee.judge(e, real.a_after, real.b_after);
  EXPECT_NEAR(j.gap, 0.6 - 0.5 * (std::cos(0.1) + std::sin(0.1)), 1e-15);
}

}  // namespace
}  // namespace pge::oracle
