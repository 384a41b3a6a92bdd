// The referee for rotation (issue 26): certified contact times of turning bodies against closed
// forms, an exact tangency, a contact after a thousand near misses, and faked engine mistakes on
// turning bodies, each caught with the right verdict. Expected values come from closed forms
// evaluated with mpmath at 50 digits (each test says which), never from the code under test.
#include "oracle_states.hpp"
#include "pge/oracle.hpp"
#include "pge/scene_io.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <numbers>
#include <optional>
#include <random>

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


// The pair filter in front of the rotating search (rotating.cpp, apart_through): a separating
// axis proven over the whole search window, in double intervals. It may leave out only pairs
// that certainly do not touch, so every answer with the filters on equals the one with every
// pair solved. These cases put a contact at the window's very end, where a bound that rounds
// inwards, or that forgets the motion, the turning or a circle's radius over the window, would
// leave the pair out.
bool same_next(const NextEvent& x, const NextEvent& y) {
  if (x.time.has_value() != y.time.has_value() || x.pairs.size() != y.pairs.size()) return false;
  if (x.time && x.time->compare(*y.time) != 0) return false;
  for (std::size_t k = 0; k < x.pairs.size(); ++k)
    if (x.pairs[k].a != y.pairs[k].a || x.pairs[k].b != y.pairs[k].b || x.pairs[k].features != y.pairs[k].features ||
        x.pairs[k].overlap_rule != y.pairs[k].overlap_rule)
      return false;
  return true;
}

// A turning polygon as the oracle holds it: vertices about its pivot p, angle theta0 + omega t.
ExactBody turning(std::vector<Vec2d> local, Vec2d p, Vec2d v, double theta0, double omega) {
  ExactBody b = testing::moving_polygon(std::move(local), p, v);
  b.rotates = true;
  b.inertia = Dyadic::from(0.25);
  b.motion.theta0 = Dyadic::from(theta0);
  b.motion.omega = Dyadic::from(omega);
  return b;
}

NextEvent search_to(std::vector<ExactBody> bodies, double horizon, bool filter) {
  return next_event(testing::state_of(std::move(bodies), horizon), {filter, kAgreeUlps});
}

TEST(RotationRefereeFilter, KeepsAPairTouchingExactlyAtTheWindowsEnd) {
  // Turning bodies at a rate of 0 (the rotating search, exact sin and cos) whose faces meet at
  // t = 1 exactly, the search's horizon: the swept shapes touch at the window's end and nowhere
  // before, so the separating-axis bound is tight there.
  const std::vector<Vec2d> box = testing::square(0.5);
  const std::vector<std::vector<ExactBody>> scenes = {
      {turning(box, {0, 0}, {1, 0}, 0, 0), testing::fixed_segment({1.5, -5}, {1.5, 5})},
      {turning(box, {0, 0}, {1, 0}, 0, 0), turning(box, {3, 0.25}, {-1, 0}, 0, 0)},  // no corner on a corner
      {turning(box, {0, 0}, {0, 0}, 0, 0), testing::moving_circle(0.5, {2, 0}, {-1, 0})},
      {testing::moving_circle(0.25, {0, 0.75}, {0, 0}), turning(box, {0, -1}, {0, 1}, 0, 0)},
  };
  for (std::size_t k = 0; k < scenes.size(); ++k) {
    const NextEvent on = search_to(scenes[k], 1, true), off = search_to(scenes[k], 1, false);
    ASSERT_TRUE(on.time.has_value()) << "scene " << k;
    EXPECT_EQ(on.time->compare(Dyadic(1)), 0) << "scene " << k;
    EXPECT_TRUE(same_next(on, off)) << "scene " << k;
  }
}

TEST(RotationRefereeFilter, RandomTurningPairsAgreeWithTheUnfilteredSearchAtTheirContactsTime) {
  // A turning polygon driven into a wall, a turning polygon or a ball, at random rates, angles
  // and speeds; the search's horizon is put on the exact contact time (the doubles just below
  // and above it, and 2^-30 s either side), where the swept shapes are within rounding of
  // touching at the window's end. Filter on and off must agree on every one.
  std::mt19937_64 rng(2026120526);
  const auto uniform = [&](double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); };
  const std::vector<std::vector<Vec2d>> shapes = {
      testing::square(0.25), testing::diamond(0.3), {{-0.2, -0.15}, {0.25, -0.1}, {0, 0.3}}};
  int contacts = 0;
  for (int n = 0; n < 60; ++n) {
    const auto shape = [&] { return shapes[static_cast<std::size_t>(n) % shapes.size()]; };
    ExactBody mover = turning(shape(), {0, uniform(-0.2, 0.2)}, {uniform(0.5, 2), uniform(-0.3, 0.3)},
                              uniform(-3, 3), uniform(-20, 20));
    std::vector<ExactBody> bodies = {mover};
    switch (n % 3) {
      case 0: bodies.push_back(testing::fixed_segment({1, -5}, {1, 5})); break;
      case 1: bodies.push_back(turning(shape(), {1.2, uniform(-0.2, 0.2)}, {uniform(-1, 0), 0}, uniform(-3, 3), uniform(-20, 20))); break;
      default: bodies.push_back(testing::moving_circle(0.2, {1.1, uniform(-0.2, 0.2)}, {uniform(-1, 0), 0})); break;
    }
    const NextEvent far = search_to(bodies, 4, false);
    if (!far.time) continue;
    ++contacts;
    const double t = far.time->to_double();
    const double below = far.time->compare(Dyadic::from(t)) > 0 ? t : std::nextafter(t, 0.0);
    const double above = std::nextafter(below, 4.0);
    for (const double h : {below, above, below - 0x1p-30, above + 0x1p-30}) {
      const NextEvent on = search_to(bodies, h, true), off = search_to(bodies, h, false);
      EXPECT_TRUE(same_next(on, off)) << "case " << n << " horizon " << h;
      EXPECT_EQ(on.time.has_value(), h > below) << "case " << n << " horizon " << h;
    }
  }
  EXPECT_GT(contacts, 40);  // not vacuous: most cases meet before the horizon
}

TEST(RotationRefereeFilter, KeepsTheOverlapRuleForATurningCornerJustPastAWall) {
  // A diamond's corner 2^-30 m past a wall's line, the diamond moving on into it (and turning):
  // overlapping and approaching, a contact at tau = 0 by the overlap rule (oracle/README.md). No
  // other axis is shallower (the wall's ends lie far on both sides of the diamond's edge lines),
  // so neither the search's quick test for that nor the pair filter may drop it.
  const double x = 0.5 - 0x1p-30;
  for (const double omega : {0.0, 1.0}) {
    const std::vector<ExactBody> bodies = {turning(testing::diamond(0.5), {0, 0}, {1, 0}, 0, omega),
                                           testing::fixed_segment({x, -5}, {x, 5})};
    for (const bool filter : {true, false}) {
      const NextEvent next = search_to(bodies, 1, filter);
      ASSERT_TRUE(next.time.has_value()) << "omega " << omega << " filter " << filter;
      EXPECT_EQ(next.time->compare(Dyadic()), 0);
      ASSERT_EQ(next.pairs.size(), 1u);
      EXPECT_TRUE(next.pairs[0].overlap_rule);
      EXPECT_TRUE(testing::has_feature(next.pairs[0], ContactKind::VertexEdge, 1, 0));
    }
  }
}

}  // namespace
}  // namespace pge::oracle
