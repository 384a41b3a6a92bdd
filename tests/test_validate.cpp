// validate_scene at scale and at the edges of the supported range (issue 10). Expected answers
// come from the geometry of the scenes built here, not from running the code.
#include "pge/constants.hpp"
#include "pge/validate.hpp"
#include "pge/world.hpp"

#include "scene_bodies.hpp"

#include <gtest/gtest.h>

#include <cstddef>
#include <stdexcept>
#include <string>

namespace pge {
namespace {

// A side x side lattice of discs of radius 0.4 at unit spacing, body k at (k % side, k / side):
// neighbours are 1 apart, 0.2 more than the radius sum, so nothing overlaps.
constexpr std::size_t kSide = 1000;
constexpr double kRadius = 0.4;

Scene lattice(std::size_t side) {
  Scene s;
  s.bodies.reserve(side * side + 1);
  for (std::size_t k = 0; k < side * side; ++k) {
    BodyDesc b;
    b.id = "c" + std::to_string(k);
    b.radius = kRadius;
    b.position = {static_cast<double>(k % side), static_cast<double>(k / side)};
    b.velocity = {1, 0};
    s.bodies.push_back(std::move(b));
  }
  return s;
}

using test_scene::wall;

// The box around the lattice: 1 from the outermost centres, 0.6 more than a radius.
void add_box(Scene& s, std::size_t side) {
  const double lo = -1, hi = static_cast<double>(side);
  s.bodies.push_back(wall("floor", {lo, lo}, {hi, lo}));
  s.bodies.push_back(wall("right", {hi, lo}, {hi, hi}));
  s.bodies.push_back(wall("ceiling", {hi, hi}, {lo, hi}));
  s.bodies.push_back(wall("left", {lo, hi}, {lo, lo}));
}

TEST(ValidateLarge, MillionDiscsInABoxAreValid) {
  Scene s = lattice(kSide);
  add_box(s, kSide);
  ASSERT_EQ(s.bodies.size(), 1000004u);
  const auto problem = validate_scene(s);
  EXPECT_FALSE(problem) << problem->field << ": " << problem->message;
}

TEST(ValidateLarge, ReportsTheFirstOverlappingPairInPairOrder) {
  Scene s = lattice(kSide);
  // Disc 500000 moved to (5.5, 0): 0.5 from discs 5 and 6, which overlap it by (0.8 - 0.5) / 0.8.
  // Disc 11 moved to (10.5, 0): 0.5 from disc 10. Checking every pair (i, j), i < j, in order
  // meets (5, 500000) first, although disc 11 comes before disc 500000.
  s.bodies[500000].position = {5.5, 0};
  s.bodies[11].position = {10.5, 0};
  const auto problem = validate_scene(s);
  ASSERT_TRUE(problem);
  EXPECT_EQ(problem->body, 500000);
  EXPECT_EQ(problem->field, "position");
  EXPECT_NE(problem->message.find("overlaps body \"c5\" at the start by 0.37"), std::string::npos) << problem->message;
}

TEST(ValidateLarge, FindsAWallThroughTheLattice) {
  Scene s = lattice(kSide);
  add_box(s, kSide);
  // A fixed wall along y = 500.2 crosses row 500 (centres at y = 500, 0.2 < 0.4 away); the first
  // disc of that row, 500000, is the first pair partner of the wall (the last body).
  s.bodies.push_back(wall("shelf", {-1, 500.2}, {1000, 500.2}));
  const auto problem = validate_scene(s);
  ASSERT_TRUE(problem);
  EXPECT_EQ(problem->body, static_cast<int>(s.bodies.size() - 1));
  EXPECT_NE(problem->message.find("overlaps body \"c500000\""), std::string::npos) << problem->message;
}

TEST(ValidateLarge, DuplicateIdNamesTheFirstHolder) {
  Scene s = lattice(300);
  s.bodies[89999].id = "c7";
  s.bodies[50000].id = "c7";
  const auto problem = validate_scene(s);
  ASSERT_TRUE(problem);
  EXPECT_EQ(problem->body, 50000);
  EXPECT_EQ(problem->field, "id");
  EXPECT_EQ(problem->message, "duplicates the id of bodies[7]");
}

TEST(ValidateLarge, FixedBodiesMayOverlapEachOther) {
  Scene s;
  s.bodies.push_back(wall("a", {0, 0}, {10, 0}));
  s.bodies.push_back(wall("b", {5, -5}, {5, 5}));
  EXPECT_FALSE(validate_scene(s));
}

// ---- supported range (constants.hpp) ---------------------------------------------------------

Scene one_disc() {
  Scene s;
  BodyDesc b;
  b.id = "ball";
  b.radius = 1;
  s.bodies.push_back(b);
  return s;
}

void expect_problem(const Scene& s, const std::string& field, const std::string& words) {
  const auto problem = validate_scene(s);
  ASSERT_TRUE(problem) << "no problem found; expected " << field;
  EXPECT_EQ(problem->field, field);
  EXPECT_NE(problem->message.find(words), std::string::npos) << problem->message;
}

TEST(ValidateRange, EdgesOfTheRangeAreAccepted) {
  Scene s = one_disc();
  s.bodies[0].position = {kMaxSceneMagnitude, -kMaxSceneMagnitude};
  s.bodies[0].velocity = {kMinSceneScale, -kMinSceneScale};
  s.bodies[0].acceleration = {0, -0.0};
  s.bodies[0].mass = kMaxSceneMagnitude;
  s.bodies[0].radius = kMinSceneScale;
  s.world.gravity = {0, -kMaxSceneMagnitude};
  s.run.until = kMaxSceneMagnitude;
  const auto problem = validate_scene(s);
  EXPECT_FALSE(problem) << problem->field << ": " << problem->message;
}

TEST(ValidateRange, HugeAndTinyValuesAreClearErrors) {
  const std::string words = "out of the supported range";
  Scene s = one_disc();
  s.bodies[0].position = {1e300, 0};
  expect_problem(s, "position", words);
  s = one_disc();
  s.bodies[0].velocity = {0, 1e300};
  expect_problem(s, "velocity", words);
  s = one_disc();
  s.bodies[0].velocity = {1, 5e-312};  // subnormal
  expect_problem(s, "velocity", words);
  s = one_disc();
  s.bodies[0].acceleration = {-1e31, 0};
  expect_problem(s, "acceleration", words);
  s = one_disc();
  s.bodies[0].mass = 1e-31;
  expect_problem(s, "mass", words);
  s = one_disc();
  s.bodies[0].radius = 1e31;
  expect_problem(s, "circle.radius", words);
  s = one_disc();
  s.world.gravity = {0, -1e289};
  expect_problem(s, "world.gravity", words);
  s = one_disc();
  s.run.until = 1e300;
  expect_problem(s, "run.until", words);
  s = one_disc();
  s.bodies[0].shape = ShapeKind::Polygon;
  s.bodies[0].vertices = {{0, 0}, {1e40, 0}, {0, 1}};
  expect_problem(s, "polygon.vertices[1]", words);
  s = one_disc();
  s.bodies[0].shape = ShapeKind::Segment;
  s.bodies[0].fixed = true;
  s.bodies[0].a = {0, 0};
  s.bodies[0].b = {0, 1e-40};
  expect_problem(s, "segment.b", words);
}

TEST(ValidateRange, FramesAreBounded) {
  Scene s = one_disc();
  s.run.until = 10;
  s.run.frames_per_second = kMaxFramesPerRun / 10;  // exactly the limit: fine
  EXPECT_FALSE(validate_scene(s));
  s.run.frames_per_second = 1e300;
  expect_problem(s, "run.frames_per_second", "frames over run.until");
}

TEST(ValidateRange, WorldChecksItsOverrides) {
  const Scene s = one_disc();
  WorldOptions o;
  o.until = 1e31;
  EXPECT_THROW(World<double>(s, o), std::invalid_argument);
  o.until = 10;
  o.frames_per_second = 1e9;  // 1e10 frames over 10 s
  EXPECT_THROW(World<double>(s, o), std::invalid_argument);
  o.frames_per_second = 1;
  EXPECT_NO_THROW(World<double>(s, o));
}

}  // namespace
}  // namespace pge
