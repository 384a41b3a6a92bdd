// Every feature pair of DESIGN.md on hand-made states, with event.hpp's feature conventions.
// Contact times are derived in the comments from the straight-line (or parabolic) motion.
#include "oracle_states.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace pge::oracle {
namespace {

using namespace testing;

// The exact next event, which must exist and involve exactly the pair (a, b).
PairContact only_pair(const NextEvent& next, BodyIndex a, BodyIndex b) {
  EXPECT_TRUE(next.time);
  EXPECT_EQ(next.pairs.size(), 1u);
  if (next.pairs.empty()) return {};
  EXPECT_EQ(next.pairs[0].a, a);
  EXPECT_EQ(next.pairs[0].b, b);
  return next.pairs[0];
}

const Vec2d kLeft{-5, 0}, kRight{5, 0};  // a floor segment along y = 0

TEST(OracleFeatures, CircleAgainstSegmentEdgeFromEitherSide) {
  // Radius 1, centre 3 above (below) the line, speed 1 towards it: distance 1 at t = 2.
  for (double side : {1.0, -1.0}) {
    const NextEvent next = next_event(state_of({fixed_segment(kLeft, kRight), moving_circle(1, {0, 3 * side}, {0, -side})}));
    const PairContact p = only_pair(next, 0, 1);
    EXPECT_EQ(next.time->compare(Dyadic(2)), 0);
    EXPECT_TRUE(has_feature(p, ContactKind::CircleEdge, 0, 0));
    EXPECT_EQ(p.features.size(), 1u);
  }
}

TEST(OracleFeatures, CircleAgainstSegmentEndpoint) {
  // Centre moving along the segment's own line from x = 8 at speed 1: it is 1 from the
  // endpoint (5, 0) at t = 2; the edge interior is not reached (projection beyond the end).
  const NextEvent next = next_event(state_of({fixed_segment(kLeft, kRight), moving_circle(1, {8, 0}, {-1, 0})}));
  const PairContact p = only_pair(next, 0, 1);
  EXPECT_EQ(next.time->compare(Dyadic(2)), 0);
  EXPECT_TRUE(has_feature(p, ContactKind::CircleVertex, 1, 0));  // the segment (a) gives vertex 1
  EXPECT_EQ(p.features.size(), 1u);
}

TEST(OracleFeatures, ContactExactlyAtTheEdgeEndTouchesBothFeatures) {
  // Centre falling at x = 5 (over the endpoint): at t = 2 it is 1 above the line, projecting
  // exactly onto the end (projection = e.e), and 1 from the endpoint: both features at once.
  const NextEvent next = next_event(state_of({fixed_segment(kLeft, kRight), moving_circle(1, {5, 3}, {0, -1})}));
  const PairContact p = only_pair(next, 0, 1);
  EXPECT_EQ(next.time->compare(Dyadic(2)), 0);
  EXPECT_TRUE(has_feature(p, ContactKind::CircleEdge, 0, 0));
  EXPECT_TRUE(has_feature(p, ContactKind::CircleVertex, 1, 0));
}

TEST(OracleFeatures, CircleAgainstPolygonEdgeAndVertex) {
  // Fixed square [-1, 1]^2; edge 2 runs from (1, 1) to (-1, 1) (the top). A ball of radius 1/2
  // falling from (0, 3) at speed 1 is 1/2 above the top at t = 3/2.
  const NextEvent top = next_event(state_of({fixed_polygon(square(1)), moving_circle(0.5, {0, 3}, {0, -1})}));
  const PairContact p = only_pair(top, 0, 1);
  EXPECT_EQ(top.time->compare(Dyadic(mpz_class(3), -1)), 0);
  EXPECT_TRUE(has_feature(p, ContactKind::CircleEdge, 2, 0));
  // Along the diagonal from (3, 3) at velocity (-1, -1): the distance to the corner (1, 1),
  // vertex 2, is sqrt2 (2 - t), equal to 1/2 at t = 2 - sqrt2 / 4. The edges' lines are reached
  // earlier (t = 3/2) but beyond the edges' ends.
  const NextEvent corner = next_event(state_of({fixed_polygon(square(1)), moving_circle(0.5, {3, 3}, {-1, -1})}));
  const PairContact c = only_pair(corner, 0, 1);
  EXPECT_TRUE(has_feature(c, ContactKind::CircleVertex, 2, 0));
  EXPECT_EQ(c.features.size(), 1u);
  EXPECT_NEAR(corner.time->to_double(), 2 - std::sqrt(2.0) / 4, 4e-16);
}

TEST(OracleFeatures, PolygonEdgesAreOneSidedSegmentsTwoSided) {
  // A small ball inside the square moving up crosses the top edge's line from behind: no contact
  // with a polygon edge (touched from outside only), and the corners stay > 1 away.
  EXPECT_FALSE(next_event(state_of({fixed_polygon(square(1)), moving_circle(0.1, {0, 0}, {0, 1})})).time);
  // The same motion against a segment along the top: 0.1 from the line at t = 0.9.
  const NextEvent seg = next_event(state_of({fixed_segment({1, 1}, {-1, 1}), moving_circle(0.1, {0, 0}, {0, 1})}));
  ASSERT_TRUE(seg.time);
  EXPECT_EQ(seg.time->to_double(), 0.9);
}

TEST(OracleFeatures, PolygonVertexAgainstSegmentEdge) {
  // A square of half-size 1 falling from (0, 3) at speed 1: its bottom edge (vertices 0 and 1)
  // reaches y = 0 at t = 2, both vertices at once.
  const NextEvent flat = next_event(state_of({moving_polygon(square(1), {0, 3}, {0, -1}), fixed_segment(kLeft, kRight)}));
  const PairContact p = only_pair(flat, 0, 1);
  EXPECT_EQ(flat.time->compare(Dyadic(2)), 0);
  EXPECT_TRUE(has_feature(p, ContactKind::VertexEdge, 0, 0));
  EXPECT_TRUE(has_feature(p, ContactKind::VertexEdge, 1, 0));
  EXPECT_EQ(p.features.size(), 2u);
  // A diamond (vertex 0 at the bottom) touches with vertex 0 alone.
  const NextEvent tip = next_event(state_of({moving_polygon(diamond(1), {0, 3}, {0, -1}), fixed_segment(kLeft, kRight)}));
  const PairContact d = only_pair(tip, 0, 1);
  EXPECT_EQ(tip.time->compare(Dyadic(2)), 0);
  EXPECT_TRUE(has_feature(d, ContactKind::VertexEdge, 0, 0));
  EXPECT_EQ(d.features.size(), 1u);
}

TEST(OracleFeatures, SegmentVertexAgainstPolygonEdgeInBothOrders) {
  // A post from (0, 0) to (0, 1); a square of half-size 1 at (0.5, 4) falling at speed 1: its
  // bottom edge (edge 0, y = 3 - t) reaches the post's top (vertex 1) at t = 2.
  const NextEvent post_first = next_event(state_of({fixed_segment({0, 0}, {0, 1}), moving_polygon(square(1), {0.5, 4}, {0, -1})}));
  const PairContact p = only_pair(post_first, 0, 1);
  EXPECT_EQ(post_first.time->compare(Dyadic(2)), 0);
  EXPECT_TRUE(has_feature(p, ContactKind::VertexEdge, 1, 0));  // a's vertex 1, b's edge 0
  EXPECT_EQ(p.features.size(), 1u);
  const NextEvent box_first = next_event(state_of({moving_polygon(square(1), {0.5, 4}, {0, -1}), fixed_segment({0, 0}, {0, 1})}));
  const PairContact q = only_pair(box_first, 0, 1);
  EXPECT_TRUE(has_feature(q, ContactKind::EdgeVertex, 0, 1));  // a's edge 0, b's vertex 1
}

TEST(OracleFeatures, PolygonAgainstPolygon) {
  // Square A (half-size 1) at the origin moving right at speed 1; diamond B at (5, 0) at rest:
  // B's vertex 3 (local (-1, 0), at (4, 0)) meets A's right edge (edge 1, x = 1 + t) at t = 3.
  const NextEvent tip = next_event(state_of({moving_polygon(square(1), {0, 0}, {1, 0}), moving_polygon(diamond(1), {5, 0}, {0, 0})}));
  const PairContact p = only_pair(tip, 0, 1);
  EXPECT_EQ(tip.time->compare(Dyadic(3)), 0);
  EXPECT_TRUE(has_feature(p, ContactKind::EdgeVertex, 1, 3));
  EXPECT_EQ(p.features.size(), 1u);
  // Two squares, B at (5, 0.5): A's right edge meets B's left edge (edge 3, x = 4) at t = 3 over
  // y in [-0.5, 1]: A's vertex 2 (1, 1) lies on B's edge 3, and B's vertex 0 (4, -0.5) on A's
  // edge 1; A's vertex 1 and B's vertex 3 fall outside the other's edge.
  const NextEvent flat = next_event(state_of({moving_polygon(square(1), {0, 0}, {1, 0}), moving_polygon(square(1), {5, 0.5}, {0, 0})}));
  const PairContact q = only_pair(flat, 0, 1);
  EXPECT_EQ(flat.time->compare(Dyadic(3)), 0);
  EXPECT_TRUE(has_feature(q, ContactKind::VertexEdge, 2, 3));
  EXPECT_TRUE(has_feature(q, ContactKind::EdgeVertex, 1, 0));
  EXPECT_EQ(q.features.size(), 2u);
}

TEST(OracleFeatures, MovingSegmentAgainstParallelSegment) {
  // A vertical segment (half-length 1/2) at x = -3 moving right at speed 1 reaches the fixed
  // vertical segment x = 0, y in [-1, 1], at t = 3 with both its endpoints.
  const NextEvent next = next_event(state_of({fixed_segment({0, -1}, {0, 1}), moving_segment({0, -0.5}, {0, 0.5}, {-3, 0}, {1, 0})}));
  const PairContact p = only_pair(next, 0, 1);
  EXPECT_EQ(next.time->compare(Dyadic(3)), 0);
  EXPECT_TRUE(has_feature(p, ContactKind::EdgeVertex, 0, 0));
  EXPECT_TRUE(has_feature(p, ContactKind::EdgeVertex, 0, 1));
}

TEST(OracleFeatures, VertexEdgeUnderGravity) {
  // A square (half-size 1) released at rest at height 2 under gravity (0, -4): its bottom is at
  // 1 - 2 t^2, zero at t = sqrt(1/2); IEEE sqrt is correctly rounded.
  const NextEvent next = next_event(state_of({moving_polygon(square(1), {0, 2}, {0, 0}, 1, {0, -4}), fixed_segment(kLeft, kRight)}));
  ASSERT_TRUE(next.time);
  EXPECT_EQ(next.time->round_to(TimeFormat::of<double>()), Dyadic::from(std::sqrt(0.5)));
}

TEST(OracleCorners, CornerPassingExactlyByACornerIsNoCollision) {
  // Fixed square B = [-1, 1]^2 (corner (1, 1) is its vertex 2). Square A (half-size 1) at (1, 3)
  // moving (1, -1): its bottom-left corner travels (t, 2 - t), meets (1, 1) at t = 1 and passes
  // on to the right of B. A spans x in [t, 2 + t], y in [2 - t, 4 - t]: never overlapping B.
  EXPECT_FALSE(next_event(state_of({fixed_polygon(square(1)), moving_polygon(square(1), {1, 3}, {1, -1})})).time);
}

TEST(OracleCorners, CornerIntoCornerCollidesOnEveryFeatureThere) {
  // A from (4, 4) moving (-1, -1): its bottom-left corner (3 - t, 3 - t) meets B's corner (1, 1)
  // at t = 2 heading into B. All four feature pairs at the corner touch then: A's vertex 0 on
  // B's edges 1 and 2 (which meet at B's vertex 2), B's vertex 2 on A's edges 3 and 0.
  const NextEvent next = next_event(state_of({fixed_polygon(square(1)), moving_polygon(square(1), {4, 4}, {-1, -1})}));
  const PairContact p = only_pair(next, 0, 1);
  EXPECT_EQ(next.time->compare(Dyadic(2)), 0);
  EXPECT_TRUE(has_feature(p, ContactKind::EdgeVertex, 1, 0));
  EXPECT_TRUE(has_feature(p, ContactKind::EdgeVertex, 2, 0));
  EXPECT_TRUE(has_feature(p, ContactKind::VertexEdge, 2, 0));
  EXPECT_TRUE(has_feature(p, ContactKind::VertexEdge, 2, 3));
  EXPECT_EQ(p.features.size(), 4u);
}

TEST(OracleCorners, BoxSlidingLevelOntoAnotherIsNoCollision) {
  // A (half-size 1) at (-3, 2) moving right: its bottom, y = 1, is level with B's top. Its
  // bottom-right corner meets B's top-left corner at t = 1 and A slides on along B's top: the
  // two bodies only ever share a line, so nothing collides.
  EXPECT_FALSE(next_event(state_of({fixed_polygon(square(1)), moving_polygon(square(1), {-3, 2}, {1, 0})})).time);
}

TEST(OracleOverlapRule, OverlappingCirclesCollideNowOnlyWhenApproaching) {
  // Centres 2 - 2^-40 apart with radii 1: overlapping by 2^-40.
  const double x = 2 - std::ldexp(1.0, -40);
  const NextEvent in = next_event(state_of({moving_circle(1, {0, 0}, {1, 0}), moving_circle(1, {x, 0}, {0, 0})}));
  ASSERT_TRUE(in.time);
  EXPECT_EQ(in.time->compare(Dyadic()), 0);
  EXPECT_TRUE(in.pairs[0].overlap_rule);
  // Receding: the overlap is left alone and the pair never approaches again.
  EXPECT_FALSE(next_event(state_of({moving_circle(1, {0, 0}, {-1, 0}), moving_circle(1, {x, 0}, {0, 0})})).time);
}

TEST(OracleOverlapRule, PenetratingVertexCollidesNowOnTheAxisOfLeastPenetration) {
  // A square (half-size 1) whose bottom vertices are 2^-40 below the floor.
  const double y = 1 - std::ldexp(1.0, -40);
  const NextEvent down = next_event(state_of({moving_polygon(square(1), {0, y}, {0, -1}), fixed_segment(kLeft, kRight)}));
  const PairContact p = only_pair(down, 0, 1);
  EXPECT_EQ(down.time->compare(Dyadic()), 0);
  EXPECT_TRUE(p.overlap_rule);
  EXPECT_TRUE(has_feature(p, ContactKind::VertexEdge, 0, 0));
  EXPECT_TRUE(has_feature(p, ContactKind::VertexEdge, 1, 0));
  // Moving up it recedes from the floor. Its top vertices lie 2 beyond the floor's line seen
  // from the square's own side, and approach it further: by the one-sided distance alone that
  // would be an overlap, but the least penetration is 2^-40 along +y (bottom vertices), so no.
  EXPECT_FALSE(next_event(state_of({moving_polygon(square(1), {0, y}, {0, 1}), fixed_segment(kLeft, kRight)})).time);
}

TEST(OracleOverlapRule, VertexBehindAnotherEdgeIsNotAnOverlap) {
  // Fixed square B = [-1, 1]^2. Triangle A with vertices (0, 0), (0, 1), (-1, 1) placed at
  // (0.5, 1 - 2^-40): its bottom vertex 0 is 2^-40 deep in B's top face, and A slides right.
  // Vertex 0 is also 1.5 behind B's left edge line, projects onto that edge, is extreme towards
  // it (A lies left of it) and moves away from it, deeper, which the one-sided distance reads as
  // approaching. But the axis of least penetration is B's top face (2^-40), along which A only
  // slides: nothing collides now. (Later nothing touches either: A slides off to the right.)
  const std::vector<Vec2d> triangle{{0, 0}, {0, 1}, {-1, 1}};
  const double y = 1 - std::ldexp(1.0, -40);
  EXPECT_FALSE(next_event(state_of({fixed_polygon(square(1)), moving_polygon(triangle, {0.5, y}, {1, 0})})).time);
}

}  // namespace
}  // namespace pge::oracle
