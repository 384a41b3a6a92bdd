// Rotating bodies' mechanics and contact functions (issue 25, items 4 and 5): the mass properties
// of polygons and rods (pge/detail/rigid.hpp), the collision impulse with lever arms, the contact
// functions of turning features (pge/detail/contact_rotating.hpp), and contact times found from
// them by the rotating root finder (pge/detail/roots_rotating.hpp).
//
// Expected values are independent of the code under test: closed forms from mechanics textbooks
// (the inertia of a rectangle, a right triangle, a regular hexagon, a rod; the impulse of a box
// corner on a wall), a 50-digit reference that decomposes a polygon into triangles (each
// triangle's inertia from its side lengths, (a^2 + b^2 + c^2) / 36 per unit mass, moved to the
// polygon's centroid by the parallel-axis theorem), conservation laws evaluated in 50 digits,
// the contact geometry evaluated directly in 50 digits (rotation matrices applied to the
// features, no waves), and contact times from asin or from bisection of a point-in-polygon
// predicate in 50 digits.
#include "pge/detail/contact_rotating.hpp"
#include "pge/detail/predict_rotating.hpp"
#include "pge/detail/predict_rotating_fast.hpp"
#include "pge/detail/rigid.hpp"

#include <gtest/gtest.h>

#include <boost/math/constants/constants.hpp>
#include <boost/multiprecision/cpp_bin_float.hpp>

#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <random>
#include <type_traits>
#include <vector>

namespace {

using pge::RootStatus;
using pge::StartRule;
using pge::Vec2;
using pge::detail::Interval;
using High = boost::multiprecision::cpp_bin_float_50;
using V = Vec2<double>;
using VH = Vec2<High>;

constexpr double kEps = std::numeric_limits<double>::epsilon();

VH high(const V& v) { return {High(v.x), High(v.y)}; }
High norm(const VH& v) { return boost::multiprecision::sqrt(dot(v, v)); }
double rel(const High& got, const High& want) {
  return static_cast<double>(boost::multiprecision::abs(got - want) / boost::multiprecision::abs(want));
}

// --- mass properties ----------------------------------------------------------------------------

TEST(RigidMass, TextbookShapes) {
  using pge::detail::polygon_mass_properties;
  // A square of side 2 about its centre: (w^2 + h^2) / 12 = 8 / 12 per unit mass.
  const auto sq = polygon_mass_properties<double>({{-1, -1}, {1, -1}, {1, 1}, {-1, 1}});
  EXPECT_EQ(sq.area, 4.0);
  EXPECT_EQ(sq.centroid.x, 0.0);
  EXPECT_EQ(sq.centroid.y, 0.0);
  EXPECT_NEAR(sq.inertia_per_mass, 2.0 / 3.0, 2 * kEps);

  // A 3 x 0.5 rectangle a million units from the origin keeps its (w^2 + h^2) / 12: the
  // vertices are shifted to the centroid before the second moment is summed.
  const double X = 1.0e6, Y = -2.0e6;
  const auto far = polygon_mass_properties<double>({{X, Y}, {X + 3, Y}, {X + 3, Y + 0.5}, {X, Y + 0.5}});
  EXPECT_NEAR(far.area, 1.5, 1.5 * 4 * kEps);
  EXPECT_NEAR(far.centroid.x, X + 1.5, 4 * X * kEps);
  EXPECT_NEAR(far.centroid.y, Y + 0.25, 4 * -Y * kEps);
  const double want_far = (9.0 + 0.25) / 12.0;
  // The centroid is off by up to an ulp of 2e6 (2e-10): the second moment about a point that
  // close to the centroid differs from J_G by area times its square, 1e-20; the shifted vertices
  // are exact differences. The parallel-axis form would lose about 12 of 16 digits here.
  EXPECT_LE(std::abs(far.inertia_per_mass - want_far) / want_far, 8 * kEps);

  // A right triangle with legs a, b along the axes: centroid (a/3, b/3), (a^2 + b^2) / 18.
  const double a = 3, b = 4;
  const auto tri = polygon_mass_properties<double>({{0, 0}, {a, 0}, {0, b}});
  EXPECT_EQ(tri.area, 6.0);
  EXPECT_NEAR(tri.centroid.x, a / 3, 2 * kEps);
  EXPECT_NEAR(tri.centroid.y, b / 3, 2 * kEps);
  EXPECT_NEAR(tri.inertia_per_mass, (a * a + b * b) / 18, 25.0 / 18 * 8 * kEps);

  // A regular hexagon of side s: 5 s^2 / 12 (six equilateral triangles of side s, each s^2 / 12
  // about its centroid, moved out by s / sqrt 3).
  const double s = 1.5;
  std::vector<V> hex;
  for (int k = 0; k < 6; ++k) hex.push_back({s * std::cos(k * M_PI / 3), s * std::sin(k * M_PI / 3)});
  const auto hx = polygon_mass_properties(hex);
  EXPECT_NEAR(hx.inertia_per_mass, 5 * s * s / 12, 16 * kEps);
  EXPECT_NEAR(hx.area, 1.5 * std::sqrt(3.0) * s * s, 16 * kEps);

  // Clockwise vertices: the area is negative, the inertia (a ratio of two signed sums) is not.
  const auto cw = polygon_mass_properties<double>({{-1, 1}, {1, 1}, {1, -1}, {-1, -1}});
  EXPECT_EQ(cw.area, -4.0);
  EXPECT_NEAR(cw.inertia_per_mass, 2.0 / 3.0, 2 * kEps);

  // A rod of length L about its midpoint: L^2 / 12.
  EXPECT_NEAR(pge::detail::rod_inertia_per_mass<double>({1, 1}, {4, 5}), 25.0 / 12, 2 * kEps);

  // Degenerate outlines give zero, not a division by zero.
  const auto line = polygon_mass_properties<double>({{0, 0}, {1, 1}, {2, 2}});
  EXPECT_EQ(line.area, 0.0);
  EXPECT_EQ(line.inertia_per_mass, 0.0);
}

// Convex polygons on ellipses at random angles, centred up to 1e3 from the origin.
std::vector<V> random_convex(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0, 1);
  const int n = std::uniform_int_distribution<int>(3, 12)(rng);
  std::vector<double> angle;
  for (int k = 0; k < n; ++k) angle.push_back(2 * M_PI * u(rng));
  std::sort(angle.begin(), angle.end());
  const double rx = std::pow(10.0, 2 * u(rng) - 1), ry = rx * (0.2 + u(rng));
  const double tilt = M_PI * u(rng), cx = 2e3 * u(rng) - 1e3, cy = 2e3 * u(rng) - 1e3;
  std::vector<V> p;
  for (const double t : angle) {
    const double x = rx * std::cos(t), y = ry * std::sin(t);
    p.push_back({cx + x * std::cos(tilt) - y * std::sin(tilt), cy + x * std::sin(tilt) + y * std::cos(tilt)});
  }
  return p;
}

TEST(RigidMass, RandomConvexPolygonsAgreeWithATriangleDecompositionIn50Digits) {
  std::mt19937_64 rng(5);
  double worst_area = 0, worst_centroid = 0, worst_inertia = 0;
  int tested = 0;
  for (int i = 0; i < 3000; ++i) {
    const std::vector<V> p = random_convex(rng);
    // The reference: the fan of triangles (p0, p_k, p_k+1), each with its own area, centroid and
    // inertia (a^2 + b^2 + c^2) / 36 per unit mass about that centroid; then the parallel-axis
    // theorem about the total centroid, all in 50 digits.
    High area = 0;
    VH moment{0, 0};
    std::vector<High> areas, own;
    std::vector<VH> centres;
    for (std::size_t k = 1; k + 1 < p.size(); ++k) {
      const VH A = high(p[0]), Bv = high(p[k]), C = high(p[k + 1]);
      const High ak = cross(Bv - A, C - A) / 2;
      const VH gk = (A + Bv + C) * (High(1) / 3);
      const VH ab = Bv - A, bc = C - Bv, ca = A - C;
      areas.push_back(ak);
      centres.push_back(gk);
      own.push_back((dot(ab, ab) + dot(bc, bc) + dot(ca, ca)) / 36);
      area += ak;
      moment = moment + gk * ak;
    }
    // Nearly degenerate draws (three points almost on a line) test cancellation, not inertia.
    const VH extent = high(p[0]) - centres[0];
    if (area < High(1e-3) * dot(extent, extent)) continue;
    ++tested;
    const VH g = moment * (High(1) / area);
    High inertia = 0;
    for (std::size_t k = 0; k < areas.size(); ++k) {
      const VH off = centres[k] - g;
      inertia += areas[k] * (own[k] + dot(off, off));
    }
    inertia /= area;

    const auto got = pge::detail::polygon_mass_properties(p);
    worst_area = std::max(worst_area, rel(High(got.area), area));
    // The centroid against the polygon's size (its coordinates near 1e3 carry their own ulps).
    const High size = boost::multiprecision::sqrt(inertia);
    worst_centroid = std::max(worst_centroid, static_cast<double>(norm(high(got.centroid) - g) / size));
    worst_inertia = std::max(worst_inertia, rel(High(got.inertia_per_mass), inertia));
  }
  EXPECT_GT(tested, 2500);
  // The vertices are exact; the errors are those of the sums: the edge vectors relative to
  // vertex 0 (or the centroid) are exact or within an ulp of the coordinates, ~1e3, against a
  // size from 0.02 to 10, so up to ~5e4 ulps of the size in the worst draws; the products and
  // sums add a few more. The bounds say "within 1e-10 relative", which a formula error (a wrong
  // constant, a missing term, a sign) misses by many orders of magnitude.
  RecordProperty("worst_area_rel", std::to_string(worst_area));
  RecordProperty("worst_centroid_rel", std::to_string(worst_centroid));
  RecordProperty("worst_inertia_rel", std::to_string(worst_inertia));
  std::printf("worst relative error: area %.3g, centroid %.3g, inertia %.3g\n", worst_area, worst_centroid,
              worst_inertia);
  EXPECT_LE(worst_area, 1e-10);
  EXPECT_LE(worst_centroid, 1e-10);
  EXPECT_LE(worst_inertia, 1e-10);
}

// --- the impulse --------------------------------------------------------------------------------

using Rigid = pge::detail::RigidState<double>;

TEST(RigidImpulse, BoxCornerOnAWallSpinsTheBox) {
  // A unit-mass square of side 2 (I = 2/3) moving left at 1 hits a fixed wall with its corner
  // (-1, -1) relative to the centre; the wall is body a, the normal (1, 0) from the wall to the
  // box. k = 1 + (r x n)^2 / I = 1 + 1 / (2/3) = 5/2, j = 2 / k = 4/5; the box leaves at
  // v = -1 + 0.8 = -0.2 and w = j (r x n) / I = 0.8 * 1 / (2/3) = 1.2 (counter-clockwise: the
  // corner below the centre is pushed right).
  Rigid wall{{0, 0}, 0, 0, 0};
  Rigid box{{-1, 0}, 0, 1, 1.5};
  const V P{0, 0}, cb{1, 1};
  const auto r = pge::detail::apply_rigid_impulse(wall, {-5, 0}, box, cb, P, {1, 0}, 1.0);
  ASSERT_TRUE(r.applied);
  EXPECT_NEAR(r.j, 0.8, 2 * kEps);
  EXPECT_NEAR(box.v.x, -0.2, 2 * kEps);
  EXPECT_EQ(box.v.y, 0.0);
  EXPECT_NEAR(box.w, 1.2, 4 * kEps);
  EXPECT_EQ(wall.v.x, 0.0);
  EXPECT_EQ(wall.w, 0.0);
  // Energy: 1/2 before; after 0.2^2 / 2 + (2/3) 1.2^2 / 2 = 0.02 + 0.48 = 0.5.
  EXPECT_NEAR(0.5 * box.v.x * box.v.x + 0.5 * (2.0 / 3.0) * box.w * box.w, 0.5, 8 * kEps);
}

TEST(RigidImpulse, BallOnTheEndOfAFreeRod) {
  // A unit ball falling at 1 onto the end of a free unit rod of length 2 (I = 1/3): the ball is
  // a, the rod b, contact at the rod's end r_b = (1, 0), normal (0, -1) from the ball down to
  // the rod. k = 1 + 1 + (r_b x n)^2 / I = 2 + 1 / (1/3) = 5, v_n = -1, j = 2 / 5: the ball
  // leaves at -0.6, the rod's centre at -0.4, and w = j (r_b x n) / I = 0.4 (-1) 3 = -1.2.
  Rigid ball{{0, -1}, 0, 1, 0};
  Rigid rod{{0, 0}, 0, 1, 3};
  const auto r = pge::detail::apply_rigid_impulse(ball, {1, 0.5}, rod, {0, 0}, {1, 0}, {0, -1}, 1.0);
  ASSERT_TRUE(r.applied);
  EXPECT_NEAR(r.j, 0.4, 2 * kEps);
  EXPECT_NEAR(ball.v.y, -0.6, 2 * kEps);
  EXPECT_NEAR(rod.v.y, -0.4, 2 * kEps);
  EXPECT_NEAR(rod.w, -1.2, 4 * kEps);
  // Momentum -1 before and after; energy 1/2 = 0.18 + 0.08 + (1/3) 1.44 / 2 = 0.18 + 0.08 + 0.24.
  EXPECT_NEAR(ball.v.y + rod.v.y, -1.0, 2 * kEps);
}

TEST(RigidImpulse, SeparatingOrImmovablePairsGetNoImpulse) {
  Rigid a{{0, 0}, 0, 1, 1}, b{{1, 0}, 0, 1, 1};  // b moves away along n = (1, 0)
  EXPECT_FALSE(pge::detail::apply_rigid_impulse(a, {0, 0}, b, {2, 0}, {1, 0}, {1, 0}, 1.0).applied);
  EXPECT_EQ(b.v.x, 1.0);
  Rigid f{{0, 0}, 0, 0, 0}, g{{-1, 0}, 0, 0, 0};  // both fixed: k = 0
  EXPECT_FALSE(pge::detail::apply_rigid_impulse(f, {0, 0}, g, {2, 0}, {1, 0}, {1, 0}, 1.0).applied);
  EXPECT_EQ(g.v.x, -1.0);
}

// Random pairs, in 50 digits from the doubles before and after: linear momentum, angular
// momentum about the origin and about another point, Newton's law of restitution at the contact
// point, and (e = 1) kinetic energy with the rotational part.
TEST(RigidImpulse, RandomPairsConserveMomentumAngularMomentumAndEnergy) {
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> u(-1, 1);
  double worst_p = 0, worst_l = 0, worst_e = 0, worst_law = 0;
  int applied = 0;
  for (int i = 0; i < 20000; ++i) {
    const double mag = std::pow(10.0, 3 * u(rng));
    const V ca{mag * u(rng), mag * u(rng)}, cb{mag * u(rng), mag * u(rng)};
    const V P = (ca + cb) * 0.5 + V{u(rng), u(rng)} * mag;
    const V n{u(rng), u(rng)};
    const double e = i % 2 == 0 ? 1.0 : 0.5 * (1 + u(rng));
    auto body = [&](bool may_be_fixed) {
      Rigid b;
      b.v = {10 * u(rng), 10 * u(rng)};
      b.w = 5 * u(rng);
      b.inv_mass = may_be_fixed && i % 5 == 0 ? 0.0 : std::pow(10.0, u(rng));
      b.inv_inertia = b.inv_mass == 0 ? 0.0 : (i % 7 == 0 ? 0.0 : std::pow(10.0, 2 * u(rng)) / (mag * mag));
      if (b.inv_inertia == 0) b.w = 0;  // no inertia to spin with (fixed, or does not rotate)
      if (b.inv_mass == 0) b.v = {0, 0};  // fixed: a moving fixed body would do work
      return b;
    };
    Rigid a = body(true), b = body(false);
    const Rigid a0 = a, b0 = b;
    if (!pge::detail::apply_rigid_impulse(a, ca, b, cb, P, n, e).applied) continue;
    ++applied;
    // Momenta of the movable bodies (a fixed body absorbs momentum by design).
    const VH O{0, 0}, Q{High(ca.x) + 7, High(cb.y) - 3};
    struct Sums {
      VH p{0, 0};
      High l_origin = 0, l_q = 0, energy = 0, scale_p = 0, scale_l = 0;
    };
    auto sums = [&](const Rigid& x, const V& c, Sums& s) {
      if (x.inv_mass == 0) return;
      const High m = High(1) / High(x.inv_mass);
      const VH v = high(x.v);
      s.p = s.p + v * m;
      s.scale_p += m * norm(v);
      const High spin = x.inv_inertia == 0 ? High(0) : High(x.w) / High(x.inv_inertia);
      s.l_origin += spin + m * cross(high(c) - O, v);
      s.l_q += spin + m * cross(high(c) - Q, v);
      s.scale_l += boost::multiprecision::abs(spin) + m * (norm(high(c) - O) + norm(high(c) - Q)) * norm(v);
      s.energy += m * dot(v, v) / 2 + (x.inv_inertia == 0 ? High(0) : High(x.w) * spin / 2);
    };
    Sums before, after;
    sums(a0, ca, before);
    sums(b0, cb, before);
    sums(a, ca, after);
    sums(b, cb, after);
    // Momentum is conserved between two movable bodies, angular momentum when both also turn (a
    // body that does not rotate has infinite inertia: it takes up torque without turning).
    if (a0.inv_mass != 0) {
      worst_p = std::max(worst_p, static_cast<double>(norm(after.p - before.p) / (before.scale_p + after.scale_p) / kEps));
    }
    if (a0.inv_inertia != 0 && b0.inv_inertia != 0) {
      worst_l = std::max(worst_l, static_cast<double>(boost::multiprecision::abs(after.l_origin - before.l_origin) /
                                                      (before.scale_l + after.scale_l) / kEps));
      worst_l = std::max(
          worst_l, static_cast<double>(boost::multiprecision::abs(after.l_q - before.l_q) / (before.scale_l + after.scale_l) / kEps));
    }
    // Restitution at the contact point: (u_b - u_a) . n after = -e times before.
    auto contact_vn = [&](const Rigid& x, const V& c, const Rigid& y, const V& d) {
      const VH rx = high(P) - high(c), ry = high(P) - high(d);
      const VH ux = high(x.v) + VH{-rx.y, rx.x} * High(x.w), uy = high(y.v) + VH{-ry.y, ry.x} * High(y.w);
      return dot(uy - ux, high(n));
    };
    const High vn0 = contact_vn(a0, ca, b0, cb), vn1 = contact_vn(a, ca, b, cb);
    // The contact velocity's scale: the speeds and the spin times the lever arms.
    auto speed = [&](const Rigid& x, const V& c) { return norm(high(x.v)) + abs(High(x.w)) * norm(high(P) - high(c)); };
    const High scale_v = (speed(a0, ca) + speed(b0, cb) + speed(a, ca) + speed(b, cb)) * norm(high(n));
    worst_law = std::max(worst_law, static_cast<double>(abs(vn1 + High(e) * vn0) / scale_v / kEps));
    if (e == 1.0)
      worst_e = std::max(worst_e, static_cast<double>(abs(after.energy - before.energy) / before.energy / kEps));
  }
  EXPECT_GT(applied, 5000);
  std::printf("worst in eps of the scale: momentum %.3g, angular momentum %.3g, restitution %.3g, energy %.3g\n",
              worst_p, worst_l, worst_law, worst_e);
  // The exact impulse conserves all of these exactly; the doubles differ from it by the rounding
  // of j (a few operations, relative to j) and of each updated velocity (half an ulp each), so
  // every error is a small multiple of eps of the quantities involved. Where the lever-arm terms
  // dominate k (large (r x n)^2 / I), j itself carries the cancellation of u = v + w x r. Each
  // bound is a fixed count of eps, not a loosened tolerance: a wrong lever arm or sign gives
  // errors of order 1 (1e16 eps).
  // Measured with seed 9: 0.76, 0.41, 1.96 and 10.4 (energy squares the velocities and sums
  // terms that may cancel the change).
  EXPECT_LE(worst_p, 4);
  EXPECT_LE(worst_l, 4);
  EXPECT_LE(worst_law, 8);
  EXPECT_LE(worst_e, 32);
}

TEST(RigidImpulse, NonRotatingBodiesGetTheTranslatingImpulseBitForBit) {
  // With both inverse inertias zero, every angular term is an exact zero: the result must be the
  // translating engine's j = -(1 + e) v_n / (n.n (1/m_a + 1/m_b)) with the same roundings.
  std::mt19937_64 rng(13);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int i = 0; i < 10000; ++i) {
    Rigid a{{10 * u(rng), 10 * u(rng)}, 0, std::pow(10.0, u(rng)), 0};
    Rigid b{{10 * u(rng), 10 * u(rng)}, 0, i % 3 == 0 ? 0.0 : std::pow(10.0, u(rng)), 0};
    const V n{u(rng), u(rng)}, ca{u(rng), u(rng)}, cb{u(rng), u(rng)}, P{u(rng), u(rng)};
    const double e = 0.5 * (1 + u(rng));
    V va = a.v, vb = b.v;
    const double vn = dot(vb - va, n), nn = dot(n, n);
    const bool approach = vn < 0;
    if (approach) {
      const double j = -(1 + e) * vn / (nn * (a.inv_mass + b.inv_mass));
      va -= n * (j * a.inv_mass);
      vb += n * (j * b.inv_mass);
    }
    const auto r = pge::detail::apply_rigid_impulse(a, ca, b, cb, P, n, e);
    ASSERT_EQ(r.applied, approach);
    ASSERT_EQ(a.v.x, va.x);
    ASSERT_EQ(a.v.y, va.y);
    ASSERT_EQ(b.v.x, vb.x);
    ASSERT_EQ(b.v.y, vb.y);
    ASSERT_EQ(a.w, 0.0);
    ASSERT_EQ(b.w, 0.0);
  }
}

// --- contact functions --------------------------------------------------------------------------

using Path = pge::detail::StoredPath<double>;

// The exact position of body point r (body frame) at time t, in 50 digits.
struct HighPath {
  Path p;
  VH centre(const High& t) const {
    const High s = t - High(p.t0);
    return high(p.p0) + high(p.v0) * s + high(p.a) * (s * s / 2);
  }
  High angle(const High& t) const { return High(p.theta0) + High(p.omega) * (t - High(p.t0)); }
  VH turn(const V& r, const High& t) const {
    const High th = angle(t), c = cos(th), s = sin(th);
    return {c * High(r.x) - s * High(r.y), s * High(r.x) + c * High(r.y)};
  }
  VH point(const V& r, const High& t) const { return centre(t) + turn(r, t); }
};

Path random_path(std::mt19937_64& rng, int kind) {
  std::uniform_real_distribution<double> u(-1, 1);
  Path p;
  p.t0 = 5 * u(rng);
  p.p0 = {10 * u(rng), 10 * u(rng)};
  p.v0 = {5 * u(rng), 5 * u(rng)};
  p.a = kind % 3 == 0 ? V{0, 0} : V{0, -9.81 * (1 + u(rng))};
  // kind 1: does not turn (angle and rate exactly zero); kind 2: turned but not turning.
  p.theta0 = kind == 1 ? 0.0 : 3 * u(rng);
  p.omega = kind == 1 || kind == 2 ? 0.0 : 10 * u(rng);
  return p;
}

bool encloses(const Interval<double>& iv, const High& x) { return High(iv.lo()) <= x && x <= High(iv.hi()); }

TEST(RotationContacts, FunctionEnclosuresHoldTheDirectGeometry) {
  using namespace pge::detail;
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> u(-1, 1);
  double worst_width = 0;
  int folded = 0;
  for (int i = 0; i < 4000; ++i) {
    const Path P = random_path(rng, i % 4), Q = random_path(rng, (i / 4) % 4);
    const HighPath hp{P}, hq{Q};
    const double origin = 5 * u(rng);
    const PathAt<double> ap = path_at(P, origin), aq = path_at(Q, origin);
    const V r = i % 5 == 0 ? V{0, 0} : V{2 * u(rng), 2 * u(rng)};
    const double rho = r.x == 0 && r.y == 0 ? 0.1 + std::abs(u(rng)) : 0.0;
    const V q{2 * u(rng), 2 * u(rng)}, q_end{3 * u(rng), 3 * u(rng)};
    const FeatureFunctions<double> pe = point_edge_functions(ap, r, rho, aq, q, q_end);
    const WaveSum<double> cv = circle_vertex_function(ap, rho, aq, q);
    // Which bodies turn decides how many waves there are: none, one or two.
    const int turning = (P.theta0 != 0 || P.omega != 0 ? 1 : 0) + (Q.theta0 != 0 || Q.omega != 0 ? 1 : 0);
    if (Q.theta0 == 0 && Q.omega == 0) {
      EXPECT_EQ(cv.wave_count, 0);
      ++folded;
    }
    EXPECT_LE(pe.gap.wave_count, turning) << i;
    for (int k = 0; k < 8; ++k) {
      const double t = origin + 2 * std::abs(u(rng));
      const High T(t);
      const VH V_ = hp.point(r, T), A = hq.point(q, T), E = hq.point(q_end, T) - A;
      const High gap = cross(V_ - A, E) - High(rho) * norm(E), along = dot(V_ - A, E);
      const VH C = hp.centre(T) - A;
      const High cv_want = dot(C, C) - High(rho) * High(rho);
      const Interval<double> g = pe.gap(Interval<double>(t)), al = pe.along(Interval<double>(t)),
                             c = cv(Interval<double>(t));
      ASSERT_TRUE(encloses(g, gap)) << i << " " << k;
      ASSERT_TRUE(encloses(al, along)) << i << " " << k;
      ASSERT_TRUE(encloses(c, cv_want)) << i << " " << k;
      // Tight as well as right, against the size of the terms: positions up to ~10 + 5 |s0| +
      // 10 s0^2 (s0 = t - t0 up to 12), times an edge up to ~4.
      const High sc = (1 + norm(hp.centre(T)) + norm(hq.centre(T)) + 4) * (norm(high(q_end) - high(q)) + 1);
      worst_width = std::max(worst_width, static_cast<double>(High(g.width()) / sc / kEps));
    }
  }
  EXPECT_GT(folded, 500);
  std::printf("worst gap enclosure width: %.3g eps of the terms' size\n", worst_width);
  // The enclosures widen by the interval roundings of a few dozen operations (the path's terms
  // at t0 != origin, the products with e, the sin/cos of up to 70 rad): a bound of 256 eps of
  // the terms' size, about 13 bits, is what a root finder needs to place roots within a few
  // ulps of the scale; an enclosure that lost its tightness (an interval dependency blowing up)
  // would be orders of magnitude wider. Measured with seed 17: 191.
  EXPECT_LE(worst_width, 256);
}

// The rate at which a contact's gap closes (detail::gap_rate_sign: what an impulse must leave
// not approaching, E7 in docs/rotation.md), decided from the exact paths where double cannot.
// Expected: the derivative of cross(p - q, e) - rho |e| in 50 digits by the product rule, from
// the material points' velocities (the centre's plus omega perp(R r)) and the edge's turn
// (e' = omega_Q perp(e), so |e| is constant): independent of the code's wave sums. Each case's
// velocity is first set so that the rate vanishes up to the rounding of the stored velocity,
// where double's enclosure cannot tell the sign and the wider types must.
TEST(RotationContacts, TheGapsRateIsDecidedFromTheExactPathsWhereDoubleCannotTellIt) {
  using namespace pge::detail;
  std::mt19937_64 rng(29);
  std::uniform_real_distribution<double> u(-1, 1);
  const auto perp_h = [](const VH& v) { return VH{-v.y, v.x}; };
  int decided = 0, past_double = 0, zero = 0;
  for (int i = 0; i < 3000; ++i) {
    Path P = random_path(rng, i % 4);
    const Path Q = random_path(rng, (i / 4) % 4);
    const double t = P.t0 + 2 * std::abs(u(rng));
    const bool circle = i % 5 == 0;
    const V r = circle ? V{0, 0} : V{2 * u(rng), 2 * u(rng)};
    const double rho = circle ? 0.1 + std::abs(u(rng)) : 0.0;
    const V q{2 * u(rng), 2 * u(rng)}, q_end{3 * u(rng), 3 * u(rng)};
    const auto rate = [&](const Path& p_path) {
      const HighPath hp{p_path}, hq{Q};
      const High T(t);
      const High sp = T - High(p_path.t0), sq = T - High(Q.t0);
      const VH vp = high(p_path.v0) + high(p_path.a) * sp, vq = high(Q.v0) + high(Q.a) * sq;
      const VH arm_p = hp.turn(r, T), arm_q = hq.turn(q, T), e = hq.turn(q_end, T) - arm_q;
      const VH up = vp + perp_h(arm_p) * High(p_path.omega), uq = vq + perp_h(arm_q) * High(Q.omega);
      const VH d = hp.point(r, T) - hq.point(q, T);
      return std::pair{cross(up - uq, e) + cross(d, perp_h(e) * High(Q.omega)), e};
    };
    // The velocity that makes the rate vanish, rounded to doubles.
    const auto [g0, e] = rate(P);
    const VH fix = VH{e.y, -e.x} * (-g0 / dot(e, e));
    P.v0 = V{static_cast<double>(High(P.v0.x) + fix.x), static_cast<double>(High(P.v0.y) + fix.y)};
    const High g = rate(P).first;
    pge::detail::RotatingShape<double> sp, sq;
    sp.path = P;
    sq.path = Q;
    sp.radius = rho;
    const std::vector<V> p_vertices{r}, q_vertices{q, q_end};
    if (!circle) sp.vertices = p_vertices;
    sq.vertices = q_vertices;
    pge::detail::RotatingContact<double> c;
    c.feature = circle ? RotatingFeature::CircleEdge : RotatingFeature::VertexEdge;
    c.point_on_a = true;
    c.point = 0;
    c.edge = 0;
    const int want = g > 0 ? 1 : (g < 0 ? -1 : 0);
    const int got = gap_rate_sign(sp, sq, c, t);
    // A sign is never wrong; one that quad cannot tell is 0 (the rate is then within quad's
    // rounding of zero: exactly zero, in these cases).
    if (got != 0) {
      ASSERT_EQ(got, want) << i;
      ++decided;
    } else {
      ASSERT_EQ(want, 0) << i << " " << static_cast<double>(g);
      ++zero;
    }
    past_double += gap_rate_sign_in<double>(sp, sq, c, t) == 0 && got != 0;
  }
  std::printf("rates decided %d (%d past double), exactly zero %d\n", decided, past_double, zero);
  EXPECT_GT(decided, 2500);
  EXPECT_GT(past_double, 2000);  // most need the wider types: the test reaches them
}

double ulps_off(double t, const High& exact) {
  const double ulp = std::nextafter(t, INFINITY) - t;
  return static_cast<double>(abs(High(t) - exact) / High(ulp));
}

// Where a crossing can be placed. The root finder reports the first double at which the gap's
// enclosure is not certainly positive; the enclosure holds the exact gap and is `width` wide
// there, so the report lies between the exact time minus width / |slope| (the uncertainty zone,
// where a positive exact gap is still within the enclosure's width of zero) and the exact time
// plus an ulp. The width is the coefficients' own rounding, not the finder's; the tests bound it
// separately, in ulps of the time.
struct Timing {
  double ulps;       // |t - exact| in ulps of t
  double zone_ulps;  // width / |slope| in ulps of t
  bool within_zone;
};
Timing timing(double t, const High& exact, double width, const High& slope) {
  const High ulp = High(std::nextafter(t, INFINITY) - t);
  const High zone = High(width) / abs(slope);
  const High off = High(t) - exact;
  return {ulps_off(t, exact), static_cast<double>(zone / ulp), off <= 2 * ulp && -off <= zone + 2 * ulp};
}

TEST(RotationContacts, SpinningRodReachesAFixedBallAtTheAsinTime) {
  // A rod of half-length L centred at c, angle -1 at t = 0 turning at w > 0, against a fixed
  // ball of radius rho centred at c + (D, 0) (sqrt(D^2 - rho^2) <= L: the rod's edge reaches it,
  // not its end). The edge from (L, 0) to (-L, 0) (body frame) has gap
  //   cross(C - A, E) - rho |E| = -2 L D sin(theta) - 2 L rho,
  // zero first at sin(theta) = -rho / D: t = (1 - asin(rho / D)) / w.
  using namespace pge::detail;
  std::mt19937_64 rng(19);
  std::uniform_real_distribution<double> u(0, 1);
  double worst = 0, worst_zone = 0, worst_width = 0;
  for (int i = 0; i < 400; ++i) {
    const double L = 0.5 + 2 * u(rng), D = L * (0.3 + 0.6 * u(rng)), rho = D * (0.05 + 0.6 * u(rng));
    const double w = std::pow(10.0, 3 * u(rng) - 1);
    for (const double cx : {0.0, 1.0e6}) {
      Path rod{0, {cx, 0}, {0, 0}, {0, 0}, -1, w};
      // The ball's centre is the double nearest cx + D; the closed form uses it as stored.
      Path ball{0, {cx + D, 0}, {0, 0}, {0, 0}, 0, 0};
      const High Dx = High(cx + D) - High(cx);
      const High want = (1 - asin(High(rho) / Dx)) / High(w);
      const auto f = point_edge_functions(path_at(ball, 0.0), V{0, 0}, rho, path_at(rod, 0.0), V{L, 0}, V{-L, 0});
      const auto root = earliest_wave_root(f.gap, 0.0, 4.0 / w, StartRule::CrossingsOnly, 100000);
      ASSERT_EQ(root.status, RootStatus::Root) << i;
      EXPECT_FALSE(root.tangent);
      // On the edge at the contact: along in [0, e.e].
      const auto along = f.along(Interval<double>(root.t));
      EXPECT_TRUE(along.lo() >= 0 && along.hi() <= 4 * L * L) << i;
      // The slope of the exact gap at the contact: -2 L D cos(theta) w.
      const High slope = -2 * High(L) * Dx * cos(asin(High(rho) / Dx)) * High(w);
      const Timing tm = timing(root.t, want, f.gap(Interval<double>(root.t)).width(), slope);
      EXPECT_TRUE(tm.within_zone) << i << ": " << tm.ulps << " ulps, zone " << tm.zone_ulps;
      worst = std::max(worst, tm.ulps);
      worst_zone = std::max(worst_zone, tm.zone_ulps);
      // The enclosure's width at the contact in eps of the gap's scale, 2 L D.
      worst_width = std::max(worst_width, static_cast<double>(High(f.gap(Interval<double>(root.t)).width()) /
                                                              (2 * High(L) * Dx) / kEps));
    }
  }
  std::printf("rod-ball contact time: worst %.3g ulps off; uncertainty zone up to %.3g ulps, enclosure width up "
              "to %.3g eps of 2 L D\n",
              worst, worst_zone, worst_width);
  // The width is the coefficients' roundings (D (-2 L) and rho |e|, one each, the argument w s,
  // and sin's enclosure): a few eps of the scale. The zone is that over the slope, magnified by
  // asin's slope near the contact and by the contact angle being a difference (1 - asin(rho / D)).
  EXPECT_LE(worst_width, 8);
}

// --- pair prediction ----------------------------------------------------------------------------
//
// Pairs of convex shapes (outlines of 2 to 7 vertices, circles) whose centres close while one or
// both turn: the predictor's first contact (pge/detail/predict_rotating.hpp) against the first
// time the closed shapes intersect, found by sampling an intersection predicate in double and
// bisecting it in 50 digits. The predicate is the textbook one for convex shapes, independent of
// the contact functions: a vertex strictly inside the other outline or two edges crossing
// properly; for a circle, its centre inside the outline or an edge closer than the radius.

using Shape = pge::detail::RotatingShape<double>;

struct Body {
  Path path;
  double radius = 0;
  std::vector<V> vertices;  // body frame, counter-clockwise
  Shape shape() const {
    Shape s;
    s.path = path;
    s.radius = radius;
    s.vertices = vertices;
    s.reach = radius;
    for (const V& v : vertices) s.reach = std::max(s.reach, std::sqrt(dot(v, v)));
    s.reach *= 1 + 4 * kEps;  // sqrt and the squares round: a bound must not be below the truth
    return s;
  }
};

template <class T> Vec2<T> lift(const V& v) { return {T(v.x), T(v.y)}; }
template <class T> struct Placed {
  Vec2<T> c;
  T cs, sn;
  Vec2<T> at(const V& r) const { return c + Vec2<T>{cs * T(r.x) - sn * T(r.y), sn * T(r.x) + cs * T(r.y)}; }
};
template <class T> Placed<T> place(const Path& p, const T& t) {
  using std::cos;
  using std::sin;
  const T s = t - T(p.t0), th = T(p.theta0) + T(p.omega) * s;
  return {lift<T>(p.p0) + lift<T>(p.v0) * s + lift<T>(p.a) * (s * s / 2), cos(th), sin(th)};
}

template <class T> std::vector<Vec2<T>> world(const Body& b, const T& t) {
  const Placed<T> p = place(b.path, t);
  std::vector<Vec2<T>> out;
  for (const V& v : b.vertices) out.push_back(p.at(v));
  return out;
}
template <class T> int side(const Vec2<T>& a, const Vec2<T>& b, const Vec2<T>& x) {
  const T c = cross(b - a, x - a);
  return c > T(0) ? 1 : (c < T(0) ? -1 : 0);
}
template <class T> bool strictly_inside(const Vec2<T>& x, const std::vector<Vec2<T>>& poly) {
  if (poly.size() < 3) return false;
  for (std::size_t k = 0; k < poly.size(); ++k)
    if (side(poly[k], poly[(k + 1) % poly.size()], x) <= 0) return false;
  return true;
}
template <class T> T distance_to_segment_squared(const Vec2<T>& x, const Vec2<T>& a, const Vec2<T>& b) {
  const Vec2<T> e = b - a, d = x - a;
  T s = dot(d, e) / dot(e, e);
  s = s < T(0) ? T(0) : (s > T(1) ? T(1) : s);
  const Vec2<T> off = d - e * s;
  return dot(off, off);
}

template <class T> bool intersect(const Body& A, const Body& B, const T& t) {
  if (A.vertices.empty() != B.vertices.empty()) {
    const Body& round = A.vertices.empty() ? A : B;
    const Body& outline = A.vertices.empty() ? B : A;
    const Vec2<T> c = place(round.path, t).c;
    const std::vector<Vec2<T>> p = world(outline, t);
    if (strictly_inside(c, p)) return true;
    const T rr = T(round.radius) * T(round.radius);
    for (std::size_t k = 0; k < p.size(); ++k)
      if (distance_to_segment_squared(c, p[k], p[(k + 1) % p.size()]) < rr) return true;
    return false;
  }
  const std::vector<Vec2<T>> a = world(A, t), b = world(B, t);
  for (const auto& x : a)
    if (strictly_inside(x, b)) return true;
  for (const auto& x : b)
    if (strictly_inside(x, a)) return true;
  for (std::size_t i = 0; i < a.size(); ++i)
    for (std::size_t k = 0; k < b.size(); ++k) {
      const Vec2<T> &p = a[i], &q = a[(i + 1) % a.size()], &r = b[k], &s = b[(k + 1) % b.size()];
      if (side(p, q, r) * side(p, q, s) < 0 && side(r, s, p) * side(r, s, q) < 0) return true;
    }
  return false;
}

// The reference contact time in [0, horizon]: the last time before the first of `samples`
// samples at which the shapes intersect (sampled in double, confirmed in 50 digits on both
// sides), refined by 170 bisections in 50 digits. Negative if no sample intersects.
High reference_contact(const Body& A, const Body& B, double horizon, int samples) {
  int first = 0;
  for (int k = 1; k <= samples && first == 0; ++k)
    if (intersect(A, B, horizon * k / samples)) first = k;
  if (first == 0) return High(-1);
  High lo = High(horizon) * (first - 1) / samples, hi = High(horizon) * first / samples;
  EXPECT_FALSE(intersect(A, B, lo));
  EXPECT_TRUE(intersect(A, B, hi));
  for (int k = 0; k < 170; ++k) {
    const High m = (lo + hi) / 2;
    (intersect(A, B, m) ? hi : lo) = m;
  }
  return lo;
}

// The reported feature's function (built as the predictor builds it, from origin 0), its width at
// t, and the exact function's slope at the reference time (central difference in 50 digits).
struct FeatureCheck {
  double width;
  High slope, scale;
};
FeatureCheck check_feature(const Body& A, const Body& B, const pge::detail::RotatingContact<double>& c, const High& at) {
  using namespace pge::detail;
  const Body& P = c.point_on_a ? A : B;
  const Body& Q = c.point_on_a ? B : A;
  const PathAt<double> pp = path_at(P.path, 0.0), pq = path_at(Q.path, 0.0);
  const HighPath hp{P.path}, hq{Q.path};
  const std::size_t n = Q.vertices.size();
  const V q = Q.vertices[c.edge], q_end = Q.vertices[(c.edge + 1) % n];
  const V r = c.feature == RotatingFeature::VertexEdge ? P.vertices[c.point] : V{0, 0};
  double width = 0;
  std::function<High(const High&)> exact;
  // The size of the relative path's terms from the search's origin, 0: the offset there and the
  // distances moved since (the contact's own distance may be a small difference of them).
  const High terms = norm(hp.centre(0) - hq.centre(0)) + norm(hp.centre(at) - hp.centre(0)) +
                     norm(hq.centre(at) - hq.centre(0));
  High scale;
  if (c.feature == RotatingFeature::CircleVertex) {
    width = circle_vertex_function(pp, P.radius, pq, q)(Interval<double>(c.t)).width();
    exact = [&](const High& s) {
      const VH d = hp.centre(s) - hq.point(q, s);
      return dot(d, d) - High(P.radius) * High(P.radius);
    };
    const High reach = terms + norm(high(q)) + High(P.radius);
    scale = reach * reach;
  } else {
    width = point_edge_functions(pp, r, P.radius, pq, q, q_end).gap(Interval<double>(c.t)).width();
    exact = [&](const High& s) {
      const VH start = hq.point(q, s), E = hq.point(q_end, s) - start;
      return cross(hp.point(r, s) - start, E) - High(P.radius) * norm(E);
    };
    scale = (terms + norm(high(r)) + norm(high(q)) + High(P.radius)) * norm(high(q_end) - high(q));
  }
  const High step("1e-20");
  return {width, (exact(at + step) - exact(at - step)) / (2 * step), scale};
}

// Random shapes about their centres: outlines on ellipses (2 vertices: a segment), or circles.
Body random_body(std::mt19937_64& rng, int shape) {
  std::uniform_real_distribution<double> u(0, 1);
  Body b;
  if (shape == 0) {
    b.radius = 0.2 + u(rng);
    return b;
  }
  const int n = shape == 1 ? 2 : std::uniform_int_distribution<int>(3, 7)(rng);
  const double rx = 0.3 + u(rng), ry = rx * (0.3 + 0.7 * u(rng)), base = 2 * M_PI * u(rng);
  std::vector<double> angle;
  for (int k = 0; k < n; ++k) angle.push_back(n == 2 ? base + k * M_PI : 2 * M_PI * u(rng));
  std::sort(angle.begin(), angle.end());
  for (const double t : angle) b.vertices.push_back({rx * std::cos(t), ry * std::sin(t)});
  return b;
}

struct PairScene {
  Body A, B;
  double horizon;
};

// A closes on B from the left, B on A from the right, a little off-centre (thin shapes may pass
// each other untouched); each turns (a circle
// never does; one outline in four does not turn either); paths anchored at t0 != 0.
PairScene random_pair(std::mt19937_64& rng, double slow = 1, double spin = 1) {
  std::uniform_real_distribution<double> u(0, 1);
  PairScene s;
  s.A = random_body(rng, std::uniform_int_distribution<int>(0, 2)(rng));
  s.B = random_body(rng, std::uniform_int_distribution<int>(0, 2)(rng));
  if (s.A.vertices.empty() && s.B.vertices.empty()) s.B = random_body(rng, 2);
  const double reach = s.A.shape().reach + s.B.shape().reach;
  const double c = reach / 2 + 0.25 + u(rng), speed = (0.5 + u(rng)) / slow, cy = 0.2 * reach * (u(rng) - 0.5);
  const double t0 = u(rng) - 0.5;
  auto path = [&](Body& b, double x, double y, double vx, bool turns) {
    const double w = turns && !b.vertices.empty() ? (u(rng) < 0.5 ? -1 : 1) * (0.5 + 5 * u(rng)) * spin : 0.0;
    const double theta = turns && !b.vertices.empty() ? 3 * u(rng) : 0.0;
    b.path = {t0, {x + vx * t0, y}, {vx, 0}, {0, 0}, theta + w * t0, w};
  };
  path(s.A, -c, cy, speed, true);
  path(s.B, c, -cy, -speed, u(rng) < 0.75);
  s.horizon = 2 * c / speed;  // passing through each other
  return s;
}

TEST(RotationPairs, FirstContactOfTurningConvexShapesMatchesTheIntersectionReference) {
  std::mt19937_64 rng(29);
  double worst = 0, worst_zone = 0, worst_width = 0;
  std::uint64_t boxes = 0;
  int features[3] = {0, 0, 0}, misses = 0;
  for (int i = 0; i < 150; ++i) {
    const PairScene s = random_pair(rng);
    const Shape a = s.A.shape(), b = s.B.shape();
    const auto got = pge::detail::predict_rotating_pair(a, b, 0.0, s.horizon, StartRule::OverlapCollides);
    boxes += got.boxes;
    const High want = reference_contact(s.A, s.B, s.horizon, 20000);
    if (want < 0) {  // they pass without touching (thin shapes off-centre)
      EXPECT_EQ(got.status, RootStatus::None) << i;
      ++misses;
      continue;
    }
    ASSERT_EQ(got.status, RootStatus::Root) << i;
    EXPECT_FALSE(got.at_start_overlap) << i;
    ++features[static_cast<int>(got.feature)];
    const FeatureCheck fc = check_feature(s.A, s.B, got, want);
    const Timing tm = timing(got.t, want, fc.width, fc.slope);
    EXPECT_TRUE(tm.within_zone) << i << ": " << tm.ulps << " ulps off, zone " << tm.zone_ulps;
    worst = std::max(worst, tm.ulps);
    worst_zone = std::max(worst_zone, tm.zone_ulps);
    worst_width = std::max(worst_width, static_cast<double>(High(fc.width) / fc.scale / kEps));
    // The bounding circles change where the search starts, not what it finds.
    pge::detail::RotatingOptions no_bound;
    no_bound.bounding_circles = false;
    const auto plain = pge::detail::predict_rotating_pair(a, b, 0.0, s.horizon, StartRule::OverlapCollides, no_bound);
    ASSERT_EQ(plain.status, RootStatus::Root) << i;
    EXPECT_TRUE(timing(plain.t, want, fc.width, fc.slope).within_zone) << i;
  }
  std::printf("turning pairs: worst %.3g ulps off; uncertainty zone up to %.3g ulps, enclosure width up to %.3g eps "
              "of the function's scale; %llu boxes for 150 pairs; first contacts vertex-edge %d, circle-edge %d, "
              "circle-vertex %d; %d pairs pass without touching\n",
              worst, worst_zone, worst_width, static_cast<unsigned long long>(boxes), features[0], features[1],
              features[2], misses);
  EXPECT_LE(misses, 15);
  // Every kind of first contact occurs.
  for (const int f : features) EXPECT_GT(f, 0);
  // The crossing found with the functions built in double is placed again with the feature's
  // function built in long double from the stored values (11 more bits of coefficient), so the
  // time is within about an ulp of the exact one, not merely inside the double zone: measured
  // 0.99 ulps with seed 29 (98 ulps without that step).
  EXPECT_LE(worst, 2);
  // The width: the roundings of building the coefficients from paths anchored at t0 != 0, two
  // waves and their sin/cos enclosures, in eps of the size of the function's terms: measured 7.3
  // with seed 29.
  EXPECT_LE(worst_width, 16);
}

// The fast solver's rotating search (pge/detail/predict_rotating_fast.hpp: conservative
// advancement and Newton's method in plain double, no proof) on the same pairs and against the
// same 50-digit intersection reference: it finds the contacts there are, near the exact time,
// and says it found none where the shapes pass apart. Its promise is a game engine's, not
// robust's: the bounds below are what it measures with seed 29, with room, and they would catch
// a search that stops at the advancement's slop (about 1e-6 of the time to cross the shapes),
// skips a contact, or reports one where none is.
TEST(RotationPairs, FastSearchFindsTheContactsNearTheReferenceTime) {
  std::mt19937_64 rng(29);
  double worst = 0;
  int found = 0, apart = 0, wrong_status = 0;
  for (int i = 0; i < 150; ++i) {
    const PairScene s = random_pair(rng);
    // Past its step budget the search is Undecided at the time it reached; the engine predicts
    // again from there (a resume entry), and so does this loop.
    pge::detail::RotatingContact<double> got;
    got.t = 0;
    do got = pge::detail::predict_rotating_pair_fast(s.A.shape(), s.B.shape(), got.t, s.horizon);
    while (got.status == RootStatus::Undecided);
    const High want = reference_contact(s.A, s.B, s.horizon, 20000);
    if (want < 0) {
      ++apart;
      if (got.status != RootStatus::None) ++wrong_status;
      continue;
    }
    if (got.status != RootStatus::Root) {
      ++wrong_status;
      continue;
    }
    ++found;
    worst = std::max(worst, ulps_off(got.t, want));
  }
  std::printf("fast rotating search: %d contacts found, worst %.3g ulps off the reference; %d pairs apart; %d with "
              "the wrong status\n",
              found, worst, apart, wrong_status);
  EXPECT_EQ(wrong_status, 0);
  EXPECT_GE(found, 140);
  // Measured with seed 29: 146 contacts, worst 3.43 ulps (Newton's method from a slop short of
  // the contact converges to the crossing of the touching feature's gap, rounded in plain
  // double: no enclosure, so no bound on it is promised, only measured).
  EXPECT_LE(worst, 8);
}

// The feature pruning of two outlines (a feature searched only from when its point can reach its
// edge, and, while the shapes are proven apart, only where its vertex may be its outline's
// support point towards the edge: predict_rotating.hpp, supporting()) leaves out only features
// that cannot give the first contact: the same contact, to the bit, as searching every feature
// over the whole window, on random pairs of turning outlines (segments among them), slow and
// fast spins, and pairs started just after a first contact (touching, then apart a little later:
// the searches before that time take every feature).
TEST(RotationPairs, FeaturePruningFindsTheSameContactAsEveryFeature) {
  std::mt19937_64 rng(41);
  pge::detail::RotatingOptions every;
  every.prune_features = false;
  int roots = 0, restarts = 0, pairs = 0;
  std::uint64_t boxes_pruned = 0, boxes_full = 0;
  for (int i = 0; pairs < 300; ++i) {
    const double spin = i % 3 == 0 ? 0.05 : i % 3 == 1 ? 1.0 : 8.0;
    PairScene s = random_pair(rng, 1, spin);
    if (s.A.vertices.empty() || s.B.vertices.empty()) continue;  // outlines only
    ++pairs;
    const Shape a = s.A.shape(), b = s.B.shape();
    const auto pruned = pge::detail::predict_rotating_pair(a, b, 0.0, s.horizon, StartRule::OverlapCollides);
    const auto full = pge::detail::predict_rotating_pair(a, b, 0.0, s.horizon, StartRule::OverlapCollides, every);
    ASSERT_EQ(pruned.status, full.status) << i;
    ASSERT_EQ(pruned.t, full.t) << i;
    boxes_pruned += pruned.boxes;
    boxes_full += full.boxes;
    if (pruned.status != RootStatus::Root) continue;
    ++roots;
    EXPECT_EQ(pruned.tangent, full.tangent) << i;
    // From the contact on, touching, each body's velocity reversed there (leaving, as after a
    // bounce, so the shapes are apart a little later; still turning, so a corner may strike
    // again): the same again.
    const auto reversed = [&](const Body& x) {
      Body r = x;
      const double t = pruned.t;
      const V c = pge::detail::centre_at(x.path, t);
      r.path = {t, c, {-x.path.v0.x, -x.path.v0.y}, {0, 0}, pge::detail::angle_at(x.path, t), x.path.omega};
      return r;
    };
    const Body ra = reversed(s.A), rb = reversed(s.B);
    const Shape a2 = ra.shape(), b2 = rb.shape();
    const double end = pruned.t + s.horizon;
    const auto again = pge::detail::predict_rotating_pair(a2, b2, pruned.t, end, StartRule::OverlapCollides);
    const auto again_full = pge::detail::predict_rotating_pair(a2, b2, pruned.t, end, StartRule::OverlapCollides, every);
    ASSERT_EQ(again.status, again_full.status) << i;
    ASSERT_EQ(again.t, again_full.t) << i;
    boxes_pruned += again.boxes;
    boxes_full += again_full.boxes;
    restarts += again.status == RootStatus::Root;
  }
  std::printf("feature pruning: %d first contacts of 300 pairs of outlines, %d contacts again after reversing, "
              "all the same as searching every feature; %llu boxes against %llu\n", roots, restarts,
              static_cast<unsigned long long>(boxes_pruned), static_cast<unsigned long long>(boxes_full));
  EXPECT_GT(roots, 200);
  EXPECT_GT(restarts, 0);
  // It does leave features out.
  EXPECT_LT(boxes_pruned, boxes_full);
}

// The certified solver's promise on rotating pairs: the contact time is the double nearest the
// exact one. The spinning rod against a fixed ball (SpinningRodReachesAFixedBallAtTheAsinTime,
// the same cases, now through the whole pair predictor): t = (1 - asin(rho / D)) / w, evaluated
// in 50 digits with boost's asin and rounded to the nearest double by comparing neighbours in 50
// digits. Robust's times are counted beside it (within a few ulps, not promised nearest).
TEST(RotationPairs, CertifiedRotatingTimesAreTheNearestDoubles) {
  std::mt19937_64 rng(23);
  std::uniform_real_distribution<double> u(0, 1);
  pge::detail::RotatingOptions certified;
  certified.correctly_rounded = true;
  int nearest = 0, robust_nearest = 0, undecided = 0, cases = 0;
  double robust_worst = 0;
  for (int i = 0; i < 300; ++i) {
    const double L = 0.5 + 2 * u(rng), D = L * (0.3 + 0.6 * u(rng)), rho = D * (0.05 + 0.6 * u(rng));
    const double w = std::pow(10.0, 3 * u(rng) - 1);
    for (const double cx : {0.0, 1.0e6}) {
      const Body rod{{0, {cx, 0}, {0, 0}, {0, 0}, -1, w}, 0, {{L, 0}, {-L, 0}}};
      const Body ball{{0, {cx + D, 0}, {0, 0}, {0, 0}, 0, 0}, rho, {}};
      const High Dx = High(cx + D) - High(cx);
      const High want = (1 - asin(High(rho) / Dx)) / High(w);
      double best = static_cast<double>(want);
      for (const double x : {std::nextafter(best, -1.0), std::nextafter(best, 4.0 / w)})
        if (abs(High(x) - want) < abs(High(best) - want)) best = x;
      const auto c = pge::detail::predict_rotating_pair(ball.shape(), rod.shape(), 0.0, 4.0 / w,
                                                        StartRule::OverlapCollides, certified);
      const auto r = pge::detail::predict_rotating_pair(ball.shape(), rod.shape(), 0.0, 4.0 / w,
                                                        StartRule::OverlapCollides);
      ASSERT_EQ(c.status, RootStatus::Root) << i;
      ASSERT_EQ(r.status, RootStatus::Root) << i;
      ++cases;
      undecided += c.rounding_undecided;
      nearest += c.t == best;
      EXPECT_TRUE(c.rounding_undecided || c.t == best)
          << i << ": certified " << c.t << ", nearest " << best << " (" << (c.t - best) / (std::nextafter(best, 1e300) - best) << " ulps)";
      robust_nearest += r.t == best;
      robust_worst = std::max(robust_worst, std::abs(r.t - best) / (std::nextafter(best, 1e300) - best));
    }
  }
  std::printf("certified rotating times: %d of %d the nearest double, %d undecided; robust: %d nearest, worst %.0f ulps\n",
              nearest, cases, undecided, robust_nearest, robust_worst);
  EXPECT_EQ(undecided, 0);  // transversal crossings: 113 bits decide every rounding of a double
}

TEST(RotationPairs, BoundingCirclesThatNeverMeetCostOneQuadraticSearch) {
  // Two squares spinning fast side by side on parallel tracks 3 apart (reaches 0.71 each): they
  // never touch, and without the bounding circles every vertex-edge pair is searched over 50
  // turns.
  std::vector<V> square{{-0.5, -0.5}, {0.5, -0.5}, {0.5, 0.5}, {-0.5, 0.5}};
  Body A{{0, {0, 0}, {1, 0}, {0, 0}, 0, 30}, 0, square}, B{{0, {0, 3}, {1, 0}, {0, 0}, 0.3, -30}, 0, square};
  const auto with = pge::detail::predict_rotating_pair(A.shape(), B.shape(), 0.0, 10.0, StartRule::OverlapCollides);
  EXPECT_EQ(with.status, RootStatus::None);
  pge::detail::RotatingOptions no_bound;
  no_bound.bounding_circles = false;
  const auto without =
      pge::detail::predict_rotating_pair(A.shape(), B.shape(), 0.0, 10.0, StartRule::OverlapCollides, no_bound);
  EXPECT_EQ(without.status, RootStatus::None);
  std::printf("apart: %llu boxes with the bounding circles, %llu without\n", static_cast<unsigned long long>(with.boxes),
              static_cast<unsigned long long>(without.boxes));
  EXPECT_LE(with.boxes, 64u);
  EXPECT_GE(without.boxes, 1000u);
}

TEST(RotationPairs, BoundingCirclesMeetNoLaterThanTheClosedForm) {
  // World::Impl::predict_rotating answers "no contact" for a pair whose bounding circles cannot
  // meet before the time asked (bounding_circles_meet None): it must never say so, nor place the
  // meeting later, for circles that do meet. Centres on straight lines, reaches r_a + r_b = R:
  // |d + u t| = R first at t = (-(d.u) - sqrt((d.u)^2 - |u|^2 (|d|^2 - R^2))) / |u|^2, in 50
  // digits from the stored doubles. Pairs aimed past each other by more than R never meet.
  std::mt19937_64 rng(41);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<V> square{{-0.5, -0.5}, {0.5, -0.5}, {0.5, 0.5}, {-0.5, 0.5}};
  int met = 0, apart = 0;
  for (int i = 0; i < 2000; ++i) {
    const double scale = std::pow(10.0, 6 * u(rng) - 3);
    std::vector<V> a_shape, b_shape;
    for (const V& v : square) a_shape.push_back(v * scale);
    for (const V& v : square) b_shape.push_back(v * (scale * (0.2 + u(rng))));
    const double cx = u(rng) < 0.5 ? 0.0 : 1e6;
    const V pa{cx, cx}, pb{cx + scale * (3 + 10 * u(rng)), cx + scale * (20 * u(rng) - 10)};
    const double speed = std::pow(10.0, 4 * u(rng) - 2);
    const V va{speed * (u(rng) - 0.5), speed * (u(rng) - 0.5)}, vb{-speed * u(rng), speed * (u(rng) - 0.5)};
    Body A{{0, pa, va, {0, 0}, 0.3, 20 * u(rng) - 10}, 0, a_shape};
    Body B{{0, pb, vb, {0, 0}, -1.1, 20 * u(rng) - 10}, 0, b_shape};
    const Shape sa = A.shape(), sb = B.shape();
    const double hi = 100 * scale / speed;
    const auto meet = pge::detail::bounding_circles_meet(sa, sb, 0.0, hi, 100000);
    ASSERT_TRUE(meet.has_value()) << i;  // apart at the start
    const VH d = high(pb) - high(pa), w = high(vb) - high(va);
    const High R = High(sa.reach) + High(sb.reach);
    const High b = dot(d, w), a2 = dot(w, w), c = dot(d, d) - R * R;
    const High disc = b * b - a2 * c;
    const bool meets = disc >= 0 && b < 0 && (-b - boost::multiprecision::sqrt(disc)) / a2 <= High(hi);
    if (!meets) {
      ++apart;
      // Nothing to hold: a None here is right, and a Root is only a bound that is too early.
      continue;
    }
    ++met;
    const High want = (-b - boost::multiprecision::sqrt(disc)) / a2;
    ASSERT_EQ(meet->status, RootStatus::Root) << i << ": circles meeting at " << want << " ruled out";
    EXPECT_LE(High(meet->t), want) << i;
    EXPECT_LT(rel(High(meet->t), want), 1e-4) << i;  // a bound, not a slack one
  }
  std::printf("bounding circles: %d pairs meeting (none ruled out, none placed late), %d apart\n", met, apart);
  EXPECT_GT(met, 200);
  EXPECT_GT(apart, 200);
}

TEST(RotationPairs, ABoxBudgetGivesProgressAndTheSameContact) {
  // A slow approach with fast spins (up to ~500 turns before contact): with a budget of 20 boxes
  // per search the predictor returns Undecided with a time up to which nothing touches; predicting
  // again from there, call after call, reaches the contact an unbounded search finds.
  std::mt19937_64 rng(31);
  int calls_worst = 0;
  std::uint64_t boxes_worst = 0;
  for (int i = 0; i < 20; ++i) {
    const PairScene s = random_pair(rng, 20, 10);
    const Shape a = s.A.shape(), b = s.B.shape();
    const auto once = pge::detail::predict_rotating_pair(a, b, 0.0, s.horizon, StartRule::OverlapCollides);
    ASSERT_EQ(once.status, RootStatus::Root) << i;
    pge::detail::RotatingOptions small;
    small.max_boxes = 20;
    double lo = 0;
    int calls = 0;
    pge::detail::RotatingContact<double> step;
    do {
      step = pge::detail::predict_rotating_pair(a, b, lo, s.horizon, StartRule::OverlapCollides, small);
      ++calls;
      ASSERT_LE(calls, 100000) << i;
      if (step.status == RootStatus::Undecided) {
        // Progress: an Undecided call that ended where it began would loop for ever.
        ASSERT_GT(step.t, lo) << i;
        lo = step.t;
      }
    } while (step.status == RootStatus::Undecided);
    ASSERT_EQ(step.status, RootStatus::Root) << i;
    const High want = reference_contact(s.A, s.B, s.horizon, 200000);
    const FeatureCheck fc = check_feature(s.A, s.B, step, want);
    EXPECT_TRUE(timing(step.t, want, fc.width, fc.slope).within_zone) << i;
    EXPECT_TRUE(timing(once.t, want, check_feature(s.A, s.B, once, want).width, fc.slope).within_zone) << i;
    calls_worst = std::max(calls_worst, calls);
    boxes_worst = std::max(boxes_worst, once.boxes);
  }
  std::printf("budgeted prediction: up to %d calls of at most 20 boxes per search; unbounded: up to %llu boxes\n",
              calls_worst, static_cast<unsigned long long>(boxes_worst));
  EXPECT_GT(calls_worst, 1);  // the budget was reached
}

// The predictor in the other scalars: float (placed again in double), long double (no wider
// type: the first placement stands) and quad, on shapes converted from double draws.
template <class T> pge::detail::RotatingContact<T> predict_in(const PairScene& s, std::vector<Vec2<T>>& va,
                                                              std::vector<Vec2<T>>& vb) {
  auto convert = [](const Body& b, std::vector<Vec2<T>>& v) {
    pge::detail::RotatingShape<T> out;
    const Path& p = b.path;
    out.path = {T(p.t0), {T(p.p0.x), T(p.p0.y)}, {T(p.v0.x), T(p.v0.y)}, {T(p.a.x), T(p.a.y)}, T(p.theta0), T(p.omega)};
    for (const V& x : b.vertices) v.push_back({T(x.x), T(x.y)});
    out.vertices = v;
    out.radius = T(b.radius);
    out.reach = T(b.shape().reach * 1.001);  // float's rounding of the vertices stays inside
    return out;
  };
  const auto a = convert(s.A, va), b = convert(s.B, vb);
  return pge::detail::predict_rotating_pair(a, b, T(0), T(s.horizon), StartRule::OverlapCollides);
}

TEST(RotationPairs, OtherScalarsFindTheSameContacts) {
  std::mt19937_64 rng(37);
  int compared = 0;
  for (int i = 0; i < 20; ++i) {
    const PairScene s = random_pair(rng);
    const auto d = pge::detail::predict_rotating_pair(s.A.shape(), s.B.shape(), 0.0, s.horizon, StartRule::OverlapCollides);
    if (d.status != RootStatus::Root) continue;
    ++compared;
    std::vector<Vec2<float>> fa, fb;
    std::vector<Vec2<long double>> la, lb;
    std::vector<Vec2<pge::Quad>> qa, qb;
    const auto f = predict_in<float>(s, fa, fb);
    const auto l = predict_in<long double>(s, la, lb);
    const auto q = predict_in<pge::Quad>(s, qa, qb);
    ASSERT_EQ(f.status, RootStatus::Root) << i;
    ASSERT_EQ(l.status, RootStatus::Root) << i;
    ASSERT_EQ(q.status, RootStatus::Root) << i;
    // float's shapes are float roundings of the double ones: the contact moves by about their
    // relative size, 1e-7 of the shapes, over the approach speed (about 1).
    EXPECT_NEAR(static_cast<double>(f.t), d.t, 1e-5) << i;
    // long double and quad see the same shapes as double: the same contact within double's doubt.
    EXPECT_NEAR(static_cast<double>(l.t), d.t, 1e-13) << i;
    EXPECT_NEAR(static_cast<double>(q.t), d.t, 1e-13) << i;
  }
  EXPECT_GT(compared, 15);
}

// --- prediction and response together -----------------------------------------------------------
//
// A square of side 2 (unit mass, I = 2/3) falls at u onto a fixed floor (a segment along y = 0,
// its upper side the edge from (10, 0) to (-10, 0)) while it spins at w. The reference: the
// first time the lowest corner's height, H - u t + (R(theta(t)) r_k).y, reaches zero, by
// bisection in 50 digits; the corner's lever arm r there gives the impulse by hand with the
// normal n = (0, 1) from the floor to the box: v_n = -u + w r.x, j = -(1 + e) v_n / (1 + r.x^2 /
// I), v.y' = -u + j, w' = w + j r.x / I (r x n = r.x).

struct FloorDrop {
  std::vector<V> floor{{-10, 0}, {10, 0}};
  std::vector<V> square{{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
  Shape floor_shape, box_shape;
  FloorDrop(double H, double u, double theta0, double w) {
    floor_shape.vertices = floor;
    floor_shape.reach = 10;
    box_shape.path = {0, {0, H}, {0, -u}, {0, 0}, theta0, w};
    box_shape.vertices = square;
    box_shape.reach = std::sqrt(2.0) * (1 + 4 * kEps);
  }
};

struct Bounce {
  double t, vx, vy, w;
  bool face_on_face;
};

Bounce drop_and_bounce(const FloorDrop& d, double e) {
  using namespace pge::detail;
  const auto c = predict_rotating_pair(d.floor_shape, d.box_shape, 0.0, 100.0, StartRule::OverlapCollides);
  EXPECT_EQ(c.status, RootStatus::Root);
  const RotatingGeometry<double> g = rotating_contact_geometry(d.floor_shape, d.box_shape, c);
  RigidState<double> floor{{0, 0}, 0, 0, 0}, box{d.box_shape.path.v0, d.box_shape.path.omega, 1, 1.5};
  const auto imp = apply_rigid_impulse(floor, V{0, 0}, box, centre_at(d.box_shape.path, c.t), g.point, g.normal, e);
  EXPECT_TRUE(imp.applied);
  return {c.t, box.v.x, box.v.y, box.w, g.face_on_face};
}

TEST(RotationResponse, SpinningSquareBouncesOffAFloorAsDerivedByHand) {
  std::mt19937_64 rng(41);
  std::uniform_real_distribution<double> u01(0, 1);
  double worst_t = 0, worst_v = 0;
  for (int i = 0; i < 40; ++i) {
    const double H = std::sqrt(2.0) + 0.1 + u01(rng), u = 0.5 + 2 * u01(rng), theta0 = 2 * M_PI * u01(rng);
    const double w = (u01(rng) < 0.5 ? -1 : 1) * (0.5 + 4 * u01(rng)), e = i % 2 == 0 ? 1.0 : u01(rng);
    const FloorDrop d(H, u, theta0, w);
    const Bounce got = drop_and_bounce(d, e);
    EXPECT_FALSE(got.face_on_face) << i;
    // The reference contact time and corner.
    auto lowest = [&](const auto& t, int* which) {
      using T = std::decay_t<decltype(t)>;
      using std::cos;
      using std::sin;
      const T th = T(theta0) + T(w) * t, cs = cos(th), sn = sin(th);
      T best = T(1e9);
      for (int k = 0; k < 4; ++k) {
        const T y = T(H) - T(u) * t + sn * T(d.square[k].x) + cs * T(d.square[k].y);
        if (y < best) {
          best = y;
          if (which) *which = k;
        }
      }
      return best;
    };
    // The lowest height is not monotone in t; the first zero is bracketed by sampling first (in
    // double, the bracket confirmed in 50 digits).
    const double end = got.t * 2;
    High lo = -1, hi = 0;
    const int n = 4001;
    for (int k = 1; k <= n; ++k)
      if (lowest(end * k / n, nullptr) <= 0) {
        lo = High(end) * (k - 1) / n;
        hi = High(end) * k / n;
        break;
      }
    ASSERT_GE(lo, 0) << i;
    // A sample where double says apart and 50 digits touching (the crossing within rounding of
    // it): the bracket moves back to a sample that is apart in 50 digits.
    int back = 0;
    for (; lowest(lo, nullptr) <= 0 && back < n; ++back) {
      hi = lo;
      lo -= High(end) / n;
    }
    ASSERT_GT(lowest(lo, nullptr), 0) << i;
    ASSERT_LE(lowest(hi, nullptr), 0) << i;
    for (int k = 0; k < 120; ++k) {  // 2^-120 of a sample: far below a double's ulp
      const High m = (lo + hi) / 2;
      (lowest(m, nullptr) > 0 ? lo : hi) = m;
    }
    int k = 0;
    lowest(hi, &k);  // the corner that touched
    const High th = High(theta0) + High(w) * lo;
    const High rx = cos(th) * High(d.square[k].x) - sin(th) * High(d.square[k].y);
    const High I = High(2) / 3;
    const High vn = -High(u) + High(w) * rx;
    const High j = -(1 + High(e)) * vn / (1 + rx * rx / I);
    const High want_vy = -High(u) + j, want_w = High(w) + j * rx / I;
    worst_t = std::max(worst_t, ulps_off(got.t, lo));
    const High scale = High(u) + abs(High(w)) * boost::multiprecision::sqrt(High(2));
    worst_v = std::max({worst_v, static_cast<double>(abs(High(got.vy) - want_vy) / scale / kEps),
                        static_cast<double>(abs(High(got.w) - want_w) / scale / kEps),
                        static_cast<double>(abs(High(got.vx)) / scale / kEps)});
  }
  std::printf("spinning square on a floor: time within %.3g ulps, v and w within %.3g eps of u + |w| sqrt 2\n",
              worst_t, worst_v);
  // The time within about an ulp (the pair predictor's wider placement); the velocities carry
  // the lever arm's rounding at that time (the corner moves by |w| sqrt 2 per unit of time) and
  // the impulse's few roundings.
  EXPECT_LE(worst_t, 2);
  EXPECT_LE(worst_v, 16);
}

TEST(RotationResponse, ASquareLandingFlatBouncesWithoutSpinning) {
  // No spin, flat: both lower corners reach the floor together. The contact is face on face, at
  // the middle of the stretch, so the lever arm is vertical and the box leaves as the translating
  // engine would send it: v.y' = e u exactly and no spin. Either corner as the point would give
  // w' = +-(1 + e) u / (1 + 1 / I) / I, about 1.2 (1 + e) u.
  for (const double e : {1.0, 0.5}) {
    const FloorDrop d(3.0, 2.0, 0.0, 0.0);
    const Bounce got = drop_and_bounce(d, e);
    EXPECT_TRUE(got.face_on_face);
    EXPECT_EQ(got.t, 1.0);  // the lower face at 3 - 1 = 2, falling at 2
    EXPECT_EQ(got.vy, 2.0 * e);
    EXPECT_EQ(got.vx, 0.0);
    EXPECT_EQ(got.w, 0.0);
  }
}

// A point leaving a corner's apex exactly along a bounding ray, when the ray turns with its body
// (pge/detail/corner.hpp, pge::enters_cone; docs/rotation.md, E6). By hand, for the quarter plane
// between cw = (1, 0) and ccw = (0, 1): a point moving at u = (1, 0) along cw stays on the x axis
// while the ray turns at w to angle w t, so it is inside (to the ray's left) exactly when the
// ray turns clockwise, w < 0; with an acceleration a = (0, 1) the point
// is at (t, t^2 / 2), at angle t / 2 to first order, inside iff w < 1/2. Along ccw (u = (0, 1))
// the point stays on the y axis, inside iff that ray turns counter-clockwise, w > 0. Without a
// turn (w = 0) the translating rule: a slide along the boundary with no acceleration enters not.
TEST(RotationResponse, ASlideAlongATurningRayEntersTheConeOnlyWhereTheRayTurnsAwayFromIt) {
  const pge::Cone<double> quarter{{1, 0}, {0, 1}};
  const V along_cw{1, 0}, along_ccw{0, 1}, none{0, 0}, up{0, 1};
  EXPECT_FALSE(pge::enters_cone(quarter, along_cw, none));
  EXPECT_TRUE(pge::enters_cone(quarter, along_cw, none, -1.0, 0.0));
  EXPECT_FALSE(pge::enters_cone(quarter, along_cw, none, 1.0, 0.0));
  EXPECT_TRUE(pge::enters_cone(quarter, along_cw, up));
  EXPECT_TRUE(pge::enters_cone(quarter, along_cw, up, 0.25, 0.0));
  EXPECT_FALSE(pge::enters_cone(quarter, along_cw, up, 0.75, 0.0));
  EXPECT_TRUE(pge::enters_cone(quarter, along_ccw, none, 0.0, 1.0));
  EXPECT_FALSE(pge::enters_cone(quarter, along_ccw, none, 0.0, -1.0));
  EXPECT_FALSE(pge::enters_cone(quarter, along_ccw, none));
}

TEST(RotationResponse, CornerOnCornerTakesTheConesBisectorAndEntersOnlyInsideIt) {
  // Two unit diamonds (vertices (1, 0), (0, 1), (-1, 0), (0, -1)), P about (-1, 0) and Q about
  // (1, 0), both at angle 0 at t = 0: P's vertex 0 is Q's vertex 2, at the origin, the end of
  // Q's edge 1 (from (1, 1) to (0, 0)). By hand: Q's interior directions there are (1, 1) and
  // (1, -1), P's reversed are the same two, so the overlap cone is the quarter turn about +x
  // between them, whose outward normals (-1, -1)/sqrt 2 and (-1, 1)/sqrt 2 bisect to (-sqrt 2, 0)
  // from Q towards P: the normal from a = P to b = Q is (sqrt 2, 0), y exactly 0. The relative
  // motion of the two tips enters the cone iff it lies strictly within 45 degrees of +x.
  using namespace pge::detail;
  const std::vector<V> diamond{{1, 0}, {0, 1}, {-1, 0}, {0, -1}};
  struct Case {
    V vp;
    double wp;
    bool enters;
  };
  // (2, 0): head on. (0, 2): sliding past. (1, 0) with spin 3: the tip moves at (1, 3), 71.6
  // degrees off +x. (1, 0) with spin 0.5: (1, 0.5), 26.6 degrees.
  for (const Case& k : {Case{{2, 0}, 0, true}, Case{{0, 2}, 0, false}, Case{{1, 0}, 3, false}, Case{{1, 0}, 0.5, true}}) {
    Shape p, q;
    p.path = {0, {-1, 0}, k.vp, {0, 0}, 0, k.wp};
    q.path = {0, {1, 0}, {0, 0}, {0, 0}, 0, 0};
    p.vertices = diamond;
    q.vertices = diamond;
    p.reach = q.reach = 1;
    RotatingContact<double> c;
    c.status = RootStatus::Root;
    c.t = 0;
    c.feature = RotatingFeature::VertexEdge;
    c.point_on_a = true;
    c.point = 0;
    c.edge = 1;
    const RotatingGeometry<double> g = rotating_contact_geometry(p, q, c);
    EXPECT_TRUE(g.corner);
    EXPECT_EQ(g.enters, k.enters) << k.vp.x << " " << k.vp.y << " " << k.wp;
    EXPECT_NEAR(g.normal.x, std::sqrt(2.0), 4 * kEps);
    EXPECT_EQ(g.normal.y, 0.0);
    // Without the corner rule (the fast solver's geometry): edge 1's outward normal (-1, 1),
    // from Q towards P, reversed to run from a = P to b = Q.
    const RotatingGeometry<double> edge = rotating_contact_geometry(p, q, c, false);
    EXPECT_FALSE(edge.corner);
    EXPECT_EQ(edge.normal.x, -edge.normal.y);
  }
}

}  // namespace
