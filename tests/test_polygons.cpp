// Polygons and segments (issue 3): every contact category between circles, polygons and walls,
// with hand-derived expectations. Every expected value is derived in the comment above it from
// the equations of motion and the impulse formula of DESIGN.md,
//   j = -(1 + e) (v_rel . n) / (n . n (1/m1 + 1/m2)),
// never taken from a run of the engine. Conventions: polygon edge k runs from vertex k to
// vertex k + 1 and faces outward along (e.y, -e.x); the collision normal points from body a
// (the lower index) to body b.
#include "pge/constants.hpp"
#include "pge/validate.hpp"
#include "pge/world.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

namespace pge {
namespace {

// Scene building: one body at a time, moving unless made fixed.
struct Body {
  BodyDesc d;
  Body& at(Vec2d p) { d.position = p; return *this; }
  Body& moving(Vec2d v, double mass = 1) { d.velocity = v; d.mass = mass; return *this; }
  Body& fixed() { d.fixed = true; return *this; }
  operator BodyDesc() const { return d; }  // NOLINT: a builder reads best converted in place
};

Body ball(const std::string& id, double r) {
  Body b;
  b.d.id = id;
  b.d.shape = ShapeKind::Circle;
  b.d.radius = r;
  return b;
}

Body polygon(const std::string& id, std::vector<Vec2d> vertices) {
  Body b;
  b.d.id = id;
  b.d.shape = ShapeKind::Polygon;
  b.d.vertices = std::move(vertices);
  return b;
}

// An axis-aligned box centred on its position, vertices counter-clockwise from the lower left:
// edge 0 bottom, 1 right, 2 top, 3 left.
Body box(const std::string& id, double half_w, double half_h) {
  return polygon(id, {{-half_w, -half_h}, {half_w, -half_h}, {half_w, half_h}, {-half_w, half_h}});
}

Body segment(const std::string& id, Vec2d a, Vec2d b) {
  Body s;
  s.d.id = id;
  s.d.shape = ShapeKind::Segment;
  s.d.a = a;
  s.d.b = b;
  return s;
}

Scene scene_of(std::vector<BodyDesc> bodies, double until, Vec2d gravity = {}) {
  Scene s;
  s.name = "polygons";
  s.world.gravity = gravity;
  s.bodies = std::move(bodies);
  s.run.until = until;
  return s;
}

template <class T> std::vector<CollisionInfo<T>> collisions_of(World<T>& w) {
  std::vector<CollisionInfo<T>> out;
  w.on_collision([&](const CollisionInfo<T>& c) { out.push_back(c); });
  w.run();
  return out;
}

// Which contact a collision is: the pair, the kind and the features (-1: not checked).
struct ContactSpec {
  BodyIndex a, b;
  ContactKind kind;
  int feature_a, feature_b;
};

template <class T> void expect_contact(const CollisionInfo<T>& e, const ContactSpec& spec) {
  EXPECT_EQ(e.a, spec.a);
  EXPECT_EQ(e.b, spec.b);
  EXPECT_EQ(e.contact, spec.kind);
  if (spec.feature_a >= 0) {
    EXPECT_EQ(e.feature_a, spec.feature_a);
  }
  if (spec.feature_b >= 0) {
    EXPECT_EQ(e.feature_b, spec.feature_b);
  }
}

template <class T> class PolygonsAllScalars : public ::testing::Test {};
using ScalarTypes = ::testing::Types<float, double, long double, Quad>;
TYPED_TEST_SUITE(PolygonsAllScalars, ScalarTypes);

// ---------------------------------------------------------------------------------------------
// Circle against polygon

// A fixed 4 x 2 box centred at the origin (top edge 2 from (2, 1) to (-2, 1), outward normal
// (0, 4)) and a ball of radius 1 at (0.5, 5) falling at 1: the centre reaches y = 1 + 1 = 2 at
// t = 3, projecting at x = 0.5, inside the edge: a circle/edge-interior contact, box edge 2
// against ball feature 0. The fixed box reflects the normal velocity: (0, -1) -> (0, 1), and at
// t = 4 the ball is back at (0.5, 3). Small integers and halves: exact in every type.
TYPED_TEST(PolygonsAllScalars, CircleHitsFixedPolygonEdge) {
  using T = TypeParam;
  World<T> w(scene_of({box("box", 2, 1).fixed(), ball("ball", 1).at({0.5, 5}).moving({0, -1})}, 4));
  const auto events = collisions_of(w);
  ASSERT_EQ(events.size(), 1u);
  expect_contact(events[0], {0, 1, ContactKind::CircleEdge, 2, 0});
  EXPECT_EQ(events[0].time, T(3));
  EXPECT_EQ(events[0].normal, (Vec2<T>{T(0), T(1)}));
  EXPECT_EQ(w.snapshot(1).velocity, (Vec2<T>{T(0), T(1)}));
  EXPECT_EQ(w.snapshot(1).position, (Vec2<T>{T(0.5), T(3)}));
}

// The same box and a ball of radius 1 coming down the diagonal from (5, 4) at (-1, -1) towards
// the corner (2, 1) (vertex 2). Its centre is (2, 1) + (3 - t)(1, 1), at distance
// sqrt(2) (3 - t) from the corner, which is 1 at t = 3 - 1/sqrt(2). It never reaches an edge's
// interior first: the top edge's offset line y = 2 is crossed at t = 2 where x = 3 > 2, the right
// edge's x = 3 at t = 2 where y = 2 > 1. A circle/vertex contact, normal from the vertex to the
// centre, (1, 1)/sqrt(2); the velocity is along the normal, so the fixed corner reverses it to
// (1, 1). Tolerances: the contact function 2 t^2 - 12 t + 17 has exact (integer) coefficients,
// so the root is within a couple of ulps of t ~ 2.3 (ulp 4.4e-16): 1e-15. The normal comes from
// the centre at that time, rounded to ~1e-15 in all, and v' = v - 2 (v . n) n moves by about
// 2 |v| (1e-15) ~ 3e-15: 4e-15.
TEST(Polygons, CircleHitsPolygonCornerExactly) {
  World<double> w(scene_of({box("box", 2, 1).fixed(), ball("ball", 1).at({5, 4}).moving({-1, -1})}, 3));
  const auto events = collisions_of(w);
  ASSERT_EQ(events.size(), 1u);
  expect_contact(events[0], {0, 1, ContactKind::CircleVertex, 2, -1});
  EXPECT_NEAR(events[0].time, 3 - 1 / std::sqrt(2.0), 1e-15);
  EXPECT_NEAR(events[0].normal.x, std::sqrt(0.5), 1e-15);  // from the box (a) to the ball (b)
  EXPECT_NEAR(events[0].normal.y, std::sqrt(0.5), 1e-15);
  EXPECT_NEAR(w.snapshot(1).velocity.x, 1, 4e-15);
  EXPECT_NEAR(w.snapshot(1).velocity.y, 1, 4e-15);
}

// A ball of radius 1 falling straight down at x = 2, exactly over the box's corner (2, 1): at
// t = 3 (centre at (2, 2)) it touches the top edge at its very end (projection 0 on edge 2,
// which starts at (2, 1)) and the vertex, at the same time and with the same normal (0, 1).
// One contact, reported as the edge (CircleEdge comes before CircleVertex in the fixed order),
// and one impulse: the velocity (0, -1) becomes (0, 1), after which the vertex function is
// increasing and no second collision follows. Exact in every type.
TYPED_TEST(PolygonsAllScalars, CircleOnTheCornerOfAnEdgeIsOneCollision) {
  using T = TypeParam;
  World<T> w(scene_of({box("box", 2, 1).fixed(), ball("ball", 1).at({2, 5}).moving({0, -1})}, 5));
  const auto events = collisions_of(w);
  ASSERT_EQ(events.size(), 1u);
  expect_contact(events[0], {0, 1, ContactKind::CircleEdge, 2, -1});
  EXPECT_EQ(events[0].time, T(3));
  EXPECT_EQ(w.snapshot(1).velocity, (Vec2<T>{T(0), T(1)}));
}

// A ball (mass 1, radius 1) at (-5, 0) moving at 2 towards a moving 2 x 2 box (mass 3) at (5, 0)
// moving at -2. The ball's right side -4 + 2t meets the box's left edge (edge 3) 4 - 2t at
// t = 2. Head-on along x, so the one-dimensional elastic formulas apply:
// v1' = ((m1 - m2) u1 + 2 m2 u2) / (m1 + m2) = (-2 * 2 + 6 * (-2)) / 4 = -4 and
// v2' = ((m2 - m1) u2 + 2 m1 u1) / (m1 + m2) = (2 * (-2) + 2 * 2) / 4 = 0; momentum
// 1 * 2 + 3 * (-2) = -4 before and after. Tolerance: 1/3 is rounded (1e-16 relative).
TEST(Polygons, CircleHitsMovingPolygonAndMomentumIsConserved) {
  World<double> w(scene_of({ball("ball", 1).at({-5, 0}).moving({2, 0}, 1), box("box", 1, 1).at({5, 0}).moving({-2, 0}, 3)}, 3));
  const auto events = collisions_of(w);
  ASSERT_EQ(events.size(), 1u);
  expect_contact(events[0], {0, 1, ContactKind::CircleEdge, -1, 3});
  EXPECT_EQ(events[0].time, 2.0);
  EXPECT_NEAR(events[0].va_after.x, -4, 1e-14);
  EXPECT_NEAR(events[0].vb_after.x, 0, 1e-14);
  EXPECT_NEAR(w.momentum().x, -4, 1e-14);
}

// ---------------------------------------------------------------------------------------------
// Polygon against polygon

// Two 2 x 2 boxes of equal height face to face: a (mass 1) at x = 0 moving at 1, b (mass 3) at
// x = 5 moving at -1. a's right edge x = 1 + t meets b's left edge x = 4 - t at t = 1.5; the
// edges are parallel and their ends meet exactly (a's corners on b's corners), so every
// vertex/edge pair of the contact is at an edge's end: a corner contact whose overlap cone is
// the half-plane x > 0 (the faces are collinear), hence the normal is the faces' normal (1, 0).
// One collision; 1D elastic: va = ((1 - 3) 1 + 6 (-1)) / 4 = -2, vb = ((3 - 1)(-1) + 2) / 4 = 0.
TEST(Polygons, BoxSlidesIntoBoxEdgeToEdge) {
  World<double> w(scene_of({box("a", 1, 1).moving({1, 0}, 1), box("b", 1, 1).at({5, 0}).moving({-1, 0}, 3)}, 3));
  const auto events = collisions_of(w);
  ASSERT_EQ(events.size(), 1u);
  expect_contact(events[0], {0, 1, ContactKind::VertexEdge, -1, -1});
  EXPECT_EQ(events[0].time, 1.5);
  EXPECT_TRUE(events[0].corner);
  EXPECT_EQ(events[0].normal, (Vec2d{1, 0}));
  EXPECT_NEAR(w.snapshot(0).velocity.x, -2, 1e-15);
  EXPECT_NEAR(w.snapshot(1).velocity.x, 0, 1e-15);
  EXPECT_EQ(w.snapshot(0).velocity.y, 0.0);
}

// The same boxes with b raised by 1/2: a's upper right vertex (vertex 2, (1 + t, 1)) meets b's
// left edge (edge 3, x = 4 - t, y in [-1/2, 3/2]) in its interior at t = 1.5, and at the same
// instant b's lower left vertex (vertex 0) meets a's right edge (edge 1). The fixed order takes
// a's vertex first (VertexEdge before EdgeVertex); the impulse along (1, 0) leaves b's vertex
// receding, so there is one collision with the same velocities as above.
TEST(Polygons, OffsetBoxesMeetFaceToFaceInTheEdgeInterior) {
  World<double> w(scene_of({box("a", 1, 1).moving({1, 0}, 1), box("b", 1, 1).at({5, 0.5}).moving({-1, 0}, 3)}, 3));
  const auto events = collisions_of(w);
  ASSERT_EQ(events.size(), 1u);
  expect_contact(events[0], {0, 1, ContactKind::VertexEdge, 2, 3});
  EXPECT_EQ(events[0].time, 1.5);
  EXPECT_FALSE(events[0].corner);
  EXPECT_NEAR(w.snapshot(0).velocity.x, -2, 1e-15);
  EXPECT_NEAR(w.snapshot(1).velocity.x, 0, 1e-15);
}

// A unit box whose bottom is exactly level with the top of a fixed box (y = 0) slides at 1
// along x from the left onto it. Its lower right vertex crosses the line of the fixed box's left
// edge at that edge's end (the corner (0, 0)), but the bodies only ever touch along y = 0: the
// overlap cone at the corner is the quadrant x > 0, y < 0 and the motion runs along its boundary.
// No collision.
TYPED_TEST(PolygonsAllScalars, BoxSlidingLevelOverACornerDoesNotCollide) {
  using T = TypeParam;
  World<T> w(scene_of({polygon("block", {{0, -2}, {2, -2}, {2, 0}, {0, 0}}).fixed(),
                       polygon("slider", {{-1, 0}, {0, 0}, {0, 1}, {-1, 1}}).at({-1, 0}).moving({1, 0})},
                      4));
  EXPECT_TRUE(collisions_of(w).empty());
  EXPECT_EQ(w.snapshot(1).position.x, T(3));
}

// Triangle corner on box corner. The fixed box [0, 2] x [-2, 0] has its corner (0, 0) at
// vertex 3. The triangle (0, 0), (-1, 4), (-4, 1) (counter-clockwise) has its apex, vertex 0,
// at its position (-1, 2), and moves at (1, -2): the apex reaches (0, 0) at t = 1, coming from
// outside (up and left). The box's interior directions at its corner are (1, 0) and (0, -1);
// the reverses of the triangle's at its apex, (4, -1) and (1, -4), lie between them, so the
// overlap cone is the quadrant x > 0, y < 0, and (1, -2) points into it: one corner collision.
// Its normal bisects the cone's outward normals (-1, 0) and (0, 1): n = (-1, 1)/sqrt(2), from
// the box (a) to the triangle (b). The fixed box reflects: v . n = (-1 - 2)/sqrt(2), so
// v' = (1, -2) - 2 (v . n) n = (1, -2) + 3 (-1, 1) = (-2, 1). Four vertex/edge pairs meet at
// that instant, but a vertex meets an edge only where no neighbour of it lies nearer the edge's
// front than it (the oracle's feature pairs, contact_polygon.hpp's extreme_towards): the box's
// corner has (0, -2) nearer triangle edge 0 (outward normal (4, 1): dot 0 at the corner, -2 at
// (0, -2)) and (2, 0) nearer edge 2 (normal (-1, -4)), so the pairs are the apex against box
// edges 2 and 3 (edge-vertex, box edge first). Exact in every type.
TYPED_TEST(PolygonsAllScalars, TriangleCornerHitsBoxCorner) {
  using T = TypeParam;
  World<T> w(scene_of({polygon("box", {{0, -2}, {2, -2}, {2, 0}, {0, 0}}).fixed(),
                       polygon("tri", {{0, 0}, {-1, 4}, {-4, 1}}).at({-1, 2}).moving({1, -2})},
                      2));
  const auto events = collisions_of(w);
  ASSERT_EQ(events.size(), 1u);
  expect_contact(events[0], {0, 1, ContactKind::EdgeVertex, -1, 0});
  EXPECT_TRUE(events[0].feature_a == 2 || events[0].feature_a == 3) << events[0].feature_a;
  EXPECT_EQ(events[0].time, T(1));
  EXPECT_TRUE(events[0].corner);
  EXPECT_EQ(events[0].normal.x, -events[0].normal.y);
  EXPECT_LT(events[0].normal.x, T(0));
  EXPECT_EQ(w.snapshot(1).velocity, (Vec2<T>{T(-2), T(1)}));
  // At t = 2 the apex is back at (0, 0) + (-2, 1) = (-2, 1), the position at (-2, 1) too.
  EXPECT_EQ(w.snapshot(1).position, (Vec2<T>{T(-2), T(1)}));
}

// The same corner hit with the box free (mass 3, at rest): along n = (-1, 1), v_rel . n =
// ((1, -2) - 0) . (-1, 1) = -3, n . n = 2, so j = -2 (-3) / (2 (1/3 + 1)) = 9/4; the triangle
// gets (1, -2) + (9/4)(-1, 1) = (-5/4, 1/4), the box -(9/4)(1/3)(-1, 1) = (3/4, -3/4).
// Momentum (1, -2) before and (-5/4 + 9/4, 1/4 - 9/4) = (1, -2) after; energy 5/2 before and
// (25/16 + 1/16)/2 + 3 (9/16 + 9/16)/2 = 13/16 + 27/16 = 5/2 after. Tolerance: 1/3 is rounded.
TEST(Polygons, TriangleCornerHitsFreeBoxCornerConservingMomentum) {
  World<double> w(scene_of({polygon("box", {{0, -2}, {2, -2}, {2, 0}, {0, 0}}).moving({0, 0}, 3),
                            polygon("tri", {{0, 0}, {-1, 4}, {-4, 1}}).at({-1, 2}).moving({1, -2}, 1)},
                           2));
  const double e0 = w.kinetic_energy();
  const auto events = collisions_of(w);
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].a, 0u);
  EXPECT_EQ(events[0].b, 1u);
  EXPECT_EQ(events[0].time, 1.0);
  EXPECT_TRUE(events[0].corner);
  EXPECT_NEAR(events[0].vb_after.x, -1.25, 1e-15);
  EXPECT_NEAR(events[0].vb_after.y, 0.25, 1e-15);
  EXPECT_NEAR(events[0].va_after.x, 0.75, 1e-15);
  EXPECT_NEAR(events[0].va_after.y, -0.75, 1e-15);
  EXPECT_NEAR(w.momentum().x, 1, 1e-15);
  EXPECT_NEAR(w.momentum().y, -2, 1e-15);
  EXPECT_NEAR(w.kinetic_energy(), e0, 1e-15);
}

// The triangle's apex passing exactly through the box's corner without entering: starting at
// (-1, -1) (left of the box) and moving at (1, 1), the apex crosses the line x = 0 of the box's
// left edge exactly at its end (0, 0), then runs above the box; the triangle stays above the
// line y = x, the box below it. (1, 1) is outside the overlap cone (the quadrant x > 0, y < 0):
// the corner is passed, not entered. No collision.
TYPED_TEST(PolygonsAllScalars, VertexPassingThroughACornerIsNotACollision) {
  using T = TypeParam;
  World<T> w(scene_of({polygon("box", {{0, -2}, {2, -2}, {2, 0}, {0, 0}}).fixed(),
                       polygon("tri", {{0, 0}, {-1, 4}, {-4, 1}}).at({-1, -1}).moving({1, 1})},
                      3));
  EXPECT_TRUE(collisions_of(w).empty());
}

// A 2 x 2 box falling under gravity g = 2 from rest, its bottom (vertices 0 and 1) at y = 1,
// onto a fixed 8 x 1 block whose top edge (edge 2) is y = 0: the bottom is at 1 - t^2, which
// reaches 0 at t = 1 at speed 2 t = 2. The block reflects the velocity to (0, 2); the box rises
// and falls back in 2 t = 2 seconds, hitting again at t = 3, again at speed 2. The contact is the
// box's vertex against the block's edge interior (x = -1 and 1 lie inside [-4, 4]): EdgeVertex
// with block edge 2 and box vertex 0 (vertex 1 touches at the same instant and is ordered after
// it). Exact in every type: the contact function (vertex 0 in front of edge 2, times its length
// 8) is 8 - 8 t^2, then 16 s - 8 s^2, and the edge normal (0, 8) gives j = 2 * 16 / 64 = 1/2.
TYPED_TEST(PolygonsAllScalars, PolygonFallsUnderGravityOntoFixedPolygon) {
  using T = TypeParam;
  World<T> w(scene_of({polygon("block", {{-4, -1}, {4, -1}, {4, 0}, {-4, 0}}).fixed(),
                       box("box", 1, 1).at({0, 2}).moving({0, 0})},
                      3.5, {0, -2}));
  const auto events = collisions_of(w);
  ASSERT_EQ(events.size(), 2u);
  EXPECT_EQ(events[0].time, T(1));
  EXPECT_EQ(events[1].time, T(3));
  for (const auto& e : events) {
    EXPECT_EQ(e.a, 0u);
    EXPECT_EQ(e.b, 1u);
    EXPECT_EQ(e.contact, ContactKind::EdgeVertex);
    EXPECT_EQ(e.feature_a, 2);
    EXPECT_EQ(e.feature_b, 0);
    EXPECT_EQ(e.vb_before, (Vec2<T>{T(0), T(-2)}));
    EXPECT_EQ(e.vb_after, (Vec2<T>{T(0), T(2)}));
  }
}

// A row of three 2 x 2 boxes touching face to face at x = 0, 2, 4 and a striker box at x = -5
// moving at 1: the striker's right face -4 + t reaches the first box's left face -1 at t = 3.
// Each equal-mass elastic collision hands the whole velocity on, and each next pair is touching
// (contact function exactly 0) and approaching at that instant: three collisions at t = 3 in the
// fixed order (0, 1), (1, 2), (2, 3), each a corner contact of collinear faces. At t = 10 the
// last box is at 4 + 7 = 11, the others at rest at -2, 0, 2. Exact in every type.
TYPED_TEST(PolygonsAllScalars, BoxCradleHandsMomentumToTheLastBox) {
  using T = TypeParam;
  World<T> w(scene_of({box("striker", 1, 1).at({-5, 0}).moving({1, 0}), box("b1", 1, 1).at({0, 0}).moving({0, 0}),
                       box("b2", 1, 1).at({2, 0}).moving({0, 0}), box("b3", 1, 1).at({4, 0}).moving({0, 0})},
                      10));
  const auto events = collisions_of(w);
  ASSERT_EQ(events.size(), 3u);
  for (BodyIndex k = 0; k < 3; ++k) {
    EXPECT_EQ(events[k].time, T(3));
    EXPECT_EQ(events[k].a, k);
    EXPECT_EQ(events[k].b, k + 1);
  }
  const T expected_x[] = {-2, 0, 2, 11};
  for (BodyIndex i = 0; i < 4; ++i) EXPECT_EQ(w.snapshot(i).position.x, expected_x[i]) << "body " << i;
  EXPECT_EQ(w.snapshot(3).velocity.x, T(1));
}

// Two 2 x 2 boxes overlapping by 2^-40 along x (as round-off could leave them): a at 0, b at
// 2 - 2^-40. The separating-axis depth is exactly 2^-40 (a's right vertices are 2^-40 behind b's
// left edge). Approaching (a at 1, b at -1), the overlap rule makes the least-penetration pair
// collide at t = 0 along x, exchanging the velocities; receding, the pair is left alone.
TEST(Polygons, OverlapRuleUsesTheLeastPenetrationAxis) {
  const double overlap = std::ldexp(1.0, -40);
  {
    World<double> w(scene_of({box("a", 1, 1).moving({1, 0}), box("b", 1, 1).at({2 - overlap, 0}).moving({-1, 0})}, 1));
    EXPECT_EQ(w.largest_overlap().depth, overlap);
    const auto events = collisions_of(w);
    ASSERT_EQ(events.size(), 1u);
    EXPECT_EQ(events[0].time, 0.0);
    EXPECT_TRUE(events[0].at_start_overlap);
    EXPECT_EQ(w.snapshot(0).velocity.x, -1.0);
    EXPECT_EQ(w.snapshot(1).velocity.x, 1.0);
  }
  World<double> w(scene_of({box("a", 1, 1).moving({-1, 0}), box("b", 1, 1).at({2 - overlap, 0}).moving({1, 0})}, 1));
  EXPECT_TRUE(collisions_of(w).empty());
}

// ---------------------------------------------------------------------------------------------
// Segments: fixed and moving, against circles, polygons and segments

// A ball of radius 1 at (2.6, 4.8), over a fixed segment from (0, 0) to (4, 0), moving at
// (1, -2) past its end b = (4, 0). The edge's offset line y = 1 is crossed at t = 1.9 where
// x = 4.5, beyond the end: the edge interior hands the contact over to the endpoint. Distance to
// (4, 0): (t - 1.4)^2 + (4.8 - 2 t)^2 = 1, i.e. 5 t^2 - 22 t + 24 = 5 (t - 2)(t - 2.4) = 0:
// contact at t = 2, centre (4.6, 0.8), normal (0.6, 0.8) from the endpoint to the centre.
// v . n = 0.6 - 1.6 = -1, so v' = (1, -2) + 2 (0.6, 0.8) = (2.2, -0.4).
// Tolerances: the function's terms reach 44 at t = 2 and are rounded there (inputs 2.6 and 4.8
// too), about 1e-14, against a slope |f'(2)| = 2: the root is within ~5e-15, so 1e-14. The centre
// then moves by |v| 5e-15 ~ 1.1e-14, turning the unit normal as much, and v' = v - 2 (v . n) n
// by ~ 2 |v| 1.1e-14 ~ 5e-14: 1e-13.
TEST(Polygons, CircleMovingPastASegmentEndHitsTheEndpoint) {
  World<double> w(scene_of({segment("wall", {0, 0}, {4, 0}).fixed(), ball("ball", 1).at({2.6, 4.8}).moving({1, -2})}, 2.2));
  const auto events = collisions_of(w);
  ASSERT_EQ(events.size(), 1u);
  expect_contact(events[0], {0, 1, ContactKind::CircleVertex, 1, -1});
  EXPECT_NEAR(events[0].time, 2, 1e-14);
  EXPECT_NEAR(events[0].vb_after.x, 2.2, 1e-13);
  EXPECT_NEAR(events[0].vb_after.y, -0.4, 1e-13);
}

// A ball of radius 1 touching the top of that segment (centre (1, 1)) and sliding along it at
// (1, 0): the edge's contact function is identically 0 (never crossing), and past the end the
// endpoint's, (x - 4)^2 with x = 1 + t, only touches zero at t = 3 (a graze). The interior hands
// over to the endpoint without a collision, and the ball goes on to (6, 1) at t = 5.
TYPED_TEST(PolygonsAllScalars, CircleSlidingAlongASegmentPastItsEndDoesNotCollide) {
  using T = TypeParam;
  World<T> w(scene_of({segment("wall", {0, 0}, {4, 0}).fixed(), ball("ball", 1).at({1, 1}).moving({1, 0})}, 5));
  EXPECT_TRUE(collisions_of(w).empty());
  EXPECT_EQ(w.snapshot(1).position, (Vec2<T>{T(6), T(1)}));
}

// A moving vertical segment ("bat", mass 1) from (0, -1) to (0, 1) at x = t hits a resting
// ball (mass 1, radius 1/2) at (3, 0) when t = 3 - 1/2 = 2.5, in the segment's interior (the
// centre projects at y = 0). Equal masses along the normal (1, 0): the bat stops and the ball
// leaves at (1, 0). Exact in every type.
TYPED_TEST(PolygonsAllScalars, MovingSegmentHitsBall) {
  using T = TypeParam;
  World<T> w(scene_of({segment("bat", {0, -1}, {0, 1}).moving({1, 0}), ball("ball", 0.5).at({3, 0}).moving({0, 0})}, 3));
  const auto events = collisions_of(w);
  ASSERT_EQ(events.size(), 1u);
  expect_contact(events[0], {0, 1, ContactKind::CircleEdge, -1, -1});
  EXPECT_EQ(events[0].time, T(2.5));
  EXPECT_EQ(events[0].normal, (Vec2<T>{T(1), T(0)}));
  EXPECT_EQ(events[0].va_after, (Vec2<T>{T(0), T(0)}));
  EXPECT_EQ(events[0].vb_after, (Vec2<T>{T(1), T(0)}));
}

// A 2 x 2 box at (0, 3) moving down at 1 onto a fixed segment floor from (-4, 0) to (4, 0): its
// bottom 2 - t reaches 0 at t = 2, its vertices 0 and 1 inside the segment. A segment is two-sided
// and this is its upper side (the engine's edge b->a, normal (0, 8)), reported as the segment's
// edge 0; the box is reflected to (0, 1). Exact in every type (normal lengths are powers of 2).
TYPED_TEST(PolygonsAllScalars, BoxLandsOnSegmentFromAbove) {
  using T = TypeParam;
  World<T> w(scene_of({segment("floor", {-4, 0}, {4, 0}).fixed(), box("box", 1, 1).at({0, 3}).moving({0, -1})}, 3));
  const auto events = collisions_of(w);
  ASSERT_EQ(events.size(), 1u);
  expect_contact(events[0], {0, 1, ContactKind::EdgeVertex, 0, 0});
  EXPECT_EQ(events[0].time, T(2));
  EXPECT_EQ(events[0].normal, (Vec2<T>{T(0), T(1)}));
  EXPECT_EQ(w.snapshot(1).velocity, (Vec2<T>{T(0), T(1)}));
}

// A 2 x 2 box at (7, 1/4) moving left at 1 towards the end b = (4, 0) of a fixed segment from
// (0, 0) to (4, 0): its left face x = 6 - t reaches the endpoint at t = 2, where the endpoint
// lies inside the face (y = 0 in [-3/4, 5/4]). The segment's vertex 1 against the box's edge 3,
// normal (1, 0) from the segment to the box; the box is reflected to (1, 0). Exact in every type.
TYPED_TEST(PolygonsAllScalars, SegmentEndpointHitsBoxFace) {
  using T = TypeParam;
  World<T> w(scene_of({segment("rail", {0, 0}, {4, 0}).fixed(), box("box", 1, 1).at({7, 0.25}).moving({-1, 0})}, 3));
  const auto events = collisions_of(w);
  ASSERT_EQ(events.size(), 1u);
  expect_contact(events[0], {0, 1, ContactKind::VertexEdge, 1, 3});
  EXPECT_EQ(events[0].time, T(2));
  EXPECT_EQ(events[0].normal, (Vec2<T>{T(1), T(0)}));
  EXPECT_EQ(w.snapshot(1).velocity, (Vec2<T>{T(1), T(0)}));
}

// A moving vertical stick (mass 2) from (0, 0) to (0, 2) relative to its position (1, 3), falling
// at 1 onto a fixed segment from (-4, 0) to (4, 0): its lower end reaches y = 0 at t = 3, inside
// the floor. The stick's vertex 0 against the floor's upper side (edge 0), normal (0, 8):
// j = 2 * 8 / (64 * 1/2) = 1/2, and the stick's velocity changes by (0, 8) * j / 2 = (0, 2),
// from (0, -1) to (0, 1). Exact in every type.
TYPED_TEST(PolygonsAllScalars, MovingSegmentLandsOnFixedSegment) {
  using T = TypeParam;
  World<T> w(scene_of({segment("floor", {-4, 0}, {4, 0}).fixed(), segment("stick", {0, 0}, {0, 2}).at({1, 3}).moving({0, -1}, 2)},
                      4));
  const auto events = collisions_of(w);
  ASSERT_EQ(events.size(), 1u);
  expect_contact(events[0], {0, 1, ContactKind::EdgeVertex, 0, 0});
  EXPECT_EQ(events[0].time, T(3));
  EXPECT_EQ(w.snapshot(1).velocity, (Vec2<T>{T(0), T(1)}));
}

// A moving horizontal stick (mass 1) from (-1, 0) to (1, 0) relative to its position (0, 3),
// falling at 1 onto the fixed 4 x 2 box (top edge 2 at y = 1, normal (0, 4)): both ends reach
// y = 1 at t = 2, inside the edge (x = -1 and 1 in [-2, 2]); the box's top corners (-2, 1) and
// (2, 1) lie beyond the stick's ends and never touch it. The box's edge 2 against the stick's
// vertex 0 (vertex 1 at the same instant is ordered after it); j = 2 * 4 / (16 * 1) = 1/2, so
// the stick's velocity changes by (0, 4) / 2 = (0, 2), from (0, -1) to (0, 1). Exact in every type.
TYPED_TEST(PolygonsAllScalars, MovingSegmentLandsOnFixedPolygon) {
  using T = TypeParam;
  World<T> w(scene_of({box("box", 2, 1).fixed(), segment("stick", {-1, 0}, {1, 0}).at({0, 3}).moving({0, -1})}, 3));
  const auto events = collisions_of(w);
  ASSERT_EQ(events.size(), 1u);
  expect_contact(events[0], {0, 1, ContactKind::EdgeVertex, 2, 0});
  EXPECT_EQ(events[0].time, T(2));
  EXPECT_EQ(events[0].vb_after, (Vec2<T>{T(0), T(1)}));
}

// ---------------------------------------------------------------------------------------------
// Far from the origin

// A scene with one contact of each kind: the triangle-corner hit above (t = 1, triangle to
// (-2, 1)); a ball of radius 1/2 from (5, 3) at (-1, -1) onto the box's corner (2, 0), touching
// when sqrt(2) (3 - t) = 1/2, at t = 3 - sqrt(2)/4, reversed to (1, 1); a ball of radius 1/2 from
// (6, -1) at (-1, 0) onto the box's right face x = 2 at t = 3.5, reversed to (1, 0); a 1 x 1 box
// from (-4.5, -1) at (1, 0) onto the box's left face x = 0 at t = 4, reversed to (-1, 0).
Scene four_contacts(Vec2d shift) {
  const auto at = [&](Vec2d p) { return Vec2d{p.x + shift.x, p.y + shift.y}; };
  return scene_of({polygon("box", {{0, -2}, {2, -2}, {2, 0}, {0, 0}}).at(at({0, 0})).fixed(),
                   polygon("tri", {{0, 0}, {-1, 4}, {-4, 1}}).at(at({-1, 2})).moving({1, -2}),
                   ball("corner-ball", 0.5).at(at({5, 3})).moving({-1, -1}),
                   ball("face-ball", 0.5).at(at({6, -1})).moving({-1, 0}),
                   box("cube", 0.5, 0.5).at(at({-4.5, -1})).moving({1, 0})},
                  6);
}

// The same scene at the origin and shifted by (1e6 + 1/3, 1e6 - 2/7) (so that every shifted
// coordinate is rounded, at ulp(1e6) = 2^-33 ~ 1.2e-10) gives the same events: same pairs,
// kinds and corner flags, times and velocities to within 1e-8 relative. That bound: each
// contact function's coefficients carry a few ulps of 1e6 of position error, which at speeds of
// order 1 moves a root by ~1e-10 and a normal by ~1e-10 / radius; two orders of magnitude
// are left for the accumulation over the run. Both runs also match the hand-derived values.
TEST(Polygons, SameEventsFarFromTheOrigin) {
  constexpr double kRelative = 1e-8;
  const double root2 = std::sqrt(2.0);
  const double times[] = {1, 3 - root2 / 4, 3.5, 4};
  const BodyIndex partners[] = {1, 2, 3, 4};
  const Vec2d after[] = {{-2, 1}, {1, 1}, {1, 0}, {-1, 0}};
  std::vector<std::vector<CollisionInfo<double>>> runs;
  for (const Vec2d shift : {Vec2d{0, 0}, Vec2d{1e6 + 1.0 / 3, 1e6 - 2.0 / 7}}) {
    World<double> w(four_contacts(shift));
    runs.push_back(collisions_of(w));
    ASSERT_EQ(runs.back().size(), 4u);
    for (std::size_t k = 0; k < 4; ++k) {
      const auto& e = runs.back()[k];
      EXPECT_NEAR(e.time, times[k], kRelative * times[k]) << "event " << k;
      EXPECT_EQ(e.a, 0u);
      EXPECT_EQ(e.b, partners[k]);
      EXPECT_NEAR(e.vb_after.x, after[k].x, kRelative) << "event " << k;
      EXPECT_NEAR(e.vb_after.y, after[k].y, kRelative) << "event " << k;
    }
  }
  for (std::size_t k = 0; k < 4; ++k) {
    EXPECT_EQ(runs[0][k].contact, runs[1][k].contact) << "event " << k;
    EXPECT_EQ(runs[0][k].corner, runs[1][k].corner) << "event " << k;
    EXPECT_NEAR(runs[0][k].time, runs[1][k].time, kRelative * runs[0][k].time) << "event " << k;
  }
  EXPECT_TRUE(runs[0][0].corner);
  EXPECT_EQ(runs[0][1].contact, ContactKind::CircleVertex);
  EXPECT_EQ(runs[0][2].contact, ContactKind::CircleEdge);
  EXPECT_EQ(runs[0][3].contact, ContactKind::EdgeVertex);
}

// ---------------------------------------------------------------------------------------------
// Validation and measurement

std::string problem_of(const Scene& s) {
  const auto p = validate_scene(s);
  return p ? s.bodies[p->body].id + ": " + p->field + ": " + p->message : "";
}

// Overlaps at the start are rejected for every pair that can interact, naming the later body;
// two fixed bodies never interact and may overlap (walls crossing a cushion).
TEST(Polygons, StartOverlapIsRejectedForEveryPairType) {
  // Two 2 x 2 boxes 1.5 apart overlap by 1/2 of their size 2: 0.25.
  EXPECT_EQ(problem_of(scene_of({box("a", 1, 1), box("b", 1, 1).at({1.5, 0})}, 1)),
            "b: position: overlaps body \"a\" at the start by 0.25 of the contact distance (tolerance 1e-09)");
  // A ball of radius 1 centred 1/2 above the box's top face: 1/2 of the radius inside.
  EXPECT_EQ(problem_of(scene_of({box("a", 1, 1).fixed(), ball("b", 1).at({0, 1.5})}, 1)),
            "b: position: overlaps body \"a\" at the start by 0.5 of the contact distance (tolerance 1e-09)");
  // A fixed segment through the middle of a box: depth 1 (to either face) of the box's size 2.
  EXPECT_EQ(problem_of(scene_of({segment("a", {-5, 0}, {5, 0}).fixed(), box("b", 1, 1)}, 1)),
            "b: position: overlaps body \"a\" at the start by 0.5 of the contact distance (tolerance 1e-09)");
  // A moving segment crossing a fixed one at its middle: depth 1 of the smaller size 2.
  EXPECT_EQ(problem_of(scene_of({segment("a", {-5, 0}, {5, 0}).fixed(), segment("b", {0, -1}, {0, 1})}, 1)),
            "b: position: overlaps body \"a\" at the start by 0.5 of the contact distance (tolerance 1e-09)");
  EXPECT_EQ(problem_of(scene_of({box("a", 1, 1).fixed(), box("b", 1, 1).at({1, 0}).fixed()}, 1)), "");
  // Touching exactly is not overlapping.
  EXPECT_EQ(problem_of(scene_of({box("a", 1, 1), box("b", 1, 1).at({2, 0}), ball("c", 1).at({0, 2})}, 1)), "");
}

TEST(Polygons, PolygonShapeErrorsNameTheVertex) {
  auto shape_problem = [](std::vector<Vec2d> v) { return problem_of(scene_of({polygon("p", std::move(v))}, 1)); };
  EXPECT_EQ(shape_problem({{0, 0}, {0, 1}, {1, 1}, {1, 0}}),
            "p: polygon.vertices[1]: turns clockwise: vertices must be convex and counter-clockwise");
  EXPECT_EQ(shape_problem({{0, 0}, {1, 0}, {2, 0}, {1, 1}}), "p: polygon.vertices[1]: is collinear with its neighbours");
  EXPECT_EQ(shape_problem({{0, 0}, {1, 0}, {1, 1}, {1, 1}, {0, 1}}), "p: polygon.vertices[3]: repeats the previous vertex");
  EXPECT_EQ(shape_problem({{0, 0}, {1, 0}}), "p: polygon.vertices: needs at least 3 vertices, got 2");
}

// A regular n-gon of circumradius 1 centred on its position whose last edge, n - 1 (from vertex
// n - 1 round to vertex 0), is its bottom: vertex k at angle -pi/2 + pi (2k + 1) / n, so vertices
// n - 1 and 0 sit at (-+sin(pi/n), -cos(pi/n)) and edge n - 1 faces down, along (0, -1).
Body regular_polygon(const std::string& id, std::size_t n) {
  std::vector<Vec2d> v(n);
  for (std::size_t k = 0; k < n; ++k) {
    const double angle = -M_PI / 2 + M_PI * double(2 * k + 1) / double(n);
    v[k] = {std::cos(angle), std::sin(angle)};
  }
  return polygon(id, std::move(v));
}

// Polygons are limited to kMaxPolygonVertices vertices (feature indices are 16-bit, and a
// prediction tests every vertex against every edge); one more is refused, naming the field.
TEST(Polygons, PolygonPastTheVertexLimitIsRefused) {
  EXPECT_EQ(problem_of(scene_of({regular_polygon("p", kMaxPolygonVertices)}, 1)), "");
  EXPECT_EQ(problem_of(scene_of({regular_polygon("p", kMaxPolygonVertices + 1)}, 1)),
            "p: polygon.vertices: has " + std::to_string(kMaxPolygonVertices + 1) + " vertices: at most " +
                std::to_string(kMaxPolygonVertices) + " (constants.hpp, kMaxPolygonVertices)");
  EXPECT_THROW(World<double>(scene_of({regular_polygon("p", kMaxPolygonVertices + 1)}, 1)), std::invalid_argument);
}

// A fixed regular polygon at the vertex limit, n = 1024, its bottom edge 1023 (the highest
// index, wrapping round to vertex 0) at y = -cos(pi/1024) = -0.99999529..., and a ball of radius
// 0.5 at (0, -3) rising at 1. At x = 0 the bottom edge is the polygon's lowest point (its
// vertices are at x = -+sin(pi/1024) = -+0.0031, so the ball meets the edge's interior, not a
// vertex, and every other edge is higher there): its top -3 + t + 0.5 reaches -cos(pi/1024) at
// t = 2.5 - cos(pi/1024) = 1.50000470619... A circle/edge contact, polygon (body 0) edge 1023
// against the ball's feature 0, normal (0, -1) from the polygon to the ball; the fixed polygon
// reverses the ball: velocity (0, -1). Before the limit, a 70,000-gon reported its edge 68,055
// as 2,519 (16-bit wrap). Tolerances: the two vertices' y are cos and sin of rounded angles,
// within ~2e-16 of -cos(pi/1024), so the edge's height at x = 0 and the time (with its own
// rounding, ulp(1.5) = 2.2e-16) are within 1e-15: 1e-14. The edge's slope is at most
// 4e-16 / 0.0061 = 7e-14, which tilts the normal and the rebound by as much: 1e-12.
TEST(Polygons, CircleHitsTheLastEdgeOfAPolygonAtTheVertexLimit) {
  static_assert(kMaxPolygonVertices == 1024, "the expected values below are derived for n = 1024");
  World<double> w(scene_of({regular_polygon("round", kMaxPolygonVertices).fixed(), ball("ball", 0.5).at({0, -3}).moving({0, 1})}, 2));
  const auto events = collisions_of(w);
  ASSERT_EQ(events.size(), 1u);
  expect_contact(events[0], {0, 1, ContactKind::CircleEdge, 1023, 0});
  EXPECT_NEAR(events[0].time, 2.5 - std::cos(M_PI / 1024), 1e-14);
  EXPECT_NEAR(events[0].time, 1.50000470619, 1e-11);  // the same from a series: 1.5 + x^2/2 - x^4/24, x = pi/1024
  EXPECT_NEAR(events[0].normal.x, 0, 1e-12);
  EXPECT_NEAR(events[0].normal.y, -1, 1e-12);
  EXPECT_NEAR(w.snapshot(1).velocity.x, 0, 1e-12);
  EXPECT_NEAR(w.snapshot(1).velocity.y, -1, 1e-12);
}

// A ball of radius 1 centred 1 - 2^-40 above the top face of a fixed box overlaps it by 2^-40,
// measured against its radius; at the largest coordinate 2 (the box's corner) plus the radius 1,
// that is 2^-40 / (3 * 2^-52) = 2^12 / 3 ulps of double.
TEST(Polygons, LargestOverlapMeasuresCirclePolygonDepth) {
  const double depth = std::ldexp(1.0, -40);
  World<double> w(scene_of({box("box", 2, 1).fixed(), ball("ball", 1).at({0, 2 - depth}).moving({0, 1})}, 1));
  const auto o = w.largest_overlap();
  EXPECT_NEAR(o.depth, depth, std::ldexp(1.0, -52));
  EXPECT_NEAR(o.ulps, std::ldexp(1.0, 12) / 3, 1e-3);
}

}  // namespace
}  // namespace pge
