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
#include "pge/detail/rigid.hpp"

#include <gtest/gtest.h>

#include <boost/math/constants/constants.hpp>
#include <boost/multiprecision/cpp_bin_float.hpp>

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
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
    const V q{2 * u(rng), 2 * u(rng)}, e{3 * u(rng), 3 * u(rng)};
    const FeatureFunctions<double> pe = point_edge_functions(ap, r, rho, aq, q, e);
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
      const VH V_ = hp.point(r, T), A = hq.point(q, T), E = hq.turn(e, T);
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
      const High sc = (1 + norm(hp.centre(T)) + norm(hq.centre(T)) + 4) * (norm(high(e)) + 1);
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
      const auto f = point_edge_functions(path_at(ball, 0.0), V{0, 0}, rho, path_at(rod, 0.0), V{L, 0}, V{-2 * L, 0});
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

// Two squares turning in opposite senses while their centres close: the first contact over all
// vertex-edge pairs, each root kept only where the vertex is on the edge (along in [0, e.e]),
// against the first time a vertex of either square is inside the other, found by sampling and
// bisecting the point-in-polygon predicate in 50 digits.
struct SpinningSquare {
  Path path;
  double h;
  std::vector<V> corners() const { return {{-h, -h}, {h, -h}, {h, h}, {-h, h}}; }
};

// The first contact of a vertex of P with an edge of Q in [lo, hi] (t = hi if none): its time,
// the gap enclosure's width there, and the features.
struct FirstContact {
  double t, width = 0;
  V r, q, e;
};
int rejected_crossings = 0;  // crossings of edges' lines beyond the edges, searched past
FirstContact first_vertex_edge(const SpinningSquare& P, const SpinningSquare& Q, double lo, double hi) {
  using namespace pge::detail;
  const PathAt<double> ap = path_at(P.path, lo), aq = path_at(Q.path, lo);
  const std::vector<V> pc = P.corners(), qc = Q.corners();
  FirstContact best{hi, 0, {}, {}, {}};
  for (const V& r : pc)
    for (std::size_t k = 0; k < qc.size(); ++k) {
      const V q = qc[k], e = qc[(k + 1) % qc.size()] - q;
      const auto f = point_edge_functions(ap, r, 0.0, aq, q, e);
      double from = lo;
      int tries = 0;
      for (; tries < 64 && from < best.t; ++tries) {
        const auto root = earliest_wave_root(f.gap, from, best.t, StartRule::CrossingsOnly, 1000000);
        EXPECT_NE(root.status, RootStatus::Undecided);
        if (root.status != RootStatus::Root) break;
        const auto along = f.along(Interval<double>(root.t));
        if (along.hi() >= 0 && along.lo() <= dot(e, e)) {
          best = {root.t, f.gap(Interval<double>(root.t)).width(), r, q, e};
          break;
        }
        from = past_crossing(f.gap, root.t, best.t);  // on the edge's line, off the edge: search on
      }
      EXPECT_LT(tries, 64);
      rejected_crossings += tries;
    }
  return best;
}

// A vertex of P inside Q (strictly) at t, in T: each body's rotation computed once.
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
template <class T> bool vertex_inside(const SpinningSquare& P, const SpinningSquare& Q, const T& t) {
  const Placed<T> pp = place(P.path, t), pq = place(Q.path, t);
  const std::vector<V> qc = Q.corners();
  for (const V& r : P.corners()) {
    const Vec2<T> x = pp.at(r);
    bool inside = true;
    for (std::size_t k = 0; k < qc.size() && inside; ++k) {
      const Vec2<T> a = pq.at(qc[k]), b = pq.at(qc[(k + 1) % qc.size()]);
      inside = cross(x - a, b - a) < T(0);
    }
    if (inside) return true;
  }
  return false;
}

TEST(RotationContacts, CounterSpinningSquaresMeetWhenAVertexFirstEntersTheOther) {
  std::mt19937_64 rng(23);
  std::uniform_real_distribution<double> u(0, 1);
  double worst = 0, worst_zone = 0, worst_width = 0;
  for (int i = 0; i < 60; ++i) {
    const double h = 0.5 + u(rng), gap = 0.5 + 2 * u(rng), speed = 0.5 + u(rng), w = 1 + 4 * u(rng);
    const double c = h * std::sqrt(2.0) + gap / 2;  // at t = 0 the corner circles are `gap` apart
    const double cy = 0.4 * h * (u(rng) - 0.5);     // a little off-centre
    const double t0 = u(rng) - 0.5;                 // stored paths not anchored at the search's start
    const double ta = 3 * u(rng), tb = 3 * u(rng);  // the angles at t = 0
    const SpinningSquare A{{t0, {-c + speed * t0, cy}, {speed, 0}, {0, 0}, ta + w * t0, w}, h};
    const SpinningSquare B{{t0, {c - speed * t0, -cy}, {-speed, 0}, {0, 0}, tb - w * t0, -w}, h};
    const double horizon = c / speed;  // the centres meet
    const FirstContact ab = first_vertex_edge(A, B, 0.0, horizon), ba = first_vertex_edge(B, A, 0.0, horizon);
    const bool a_vertex = ab.t <= ba.t;
    const FirstContact& hit = a_vertex ? ab : ba;
    const double t = hit.t;
    ASSERT_LT(t, horizon) << i;
    // The reference: the first of 20,000 samples with a vertex inside (sampled in double, then
    // confirmed in 50 digits on both sides), then bisection in 50 digits to 170 bits.
    auto inside = [&](const auto& s) { return vertex_inside(A, B, s) || vertex_inside(B, A, s); };
    const int n = 20000;
    int first = 0;
    for (int k = 1; k <= n && first == 0; ++k)
      if (inside(horizon * k / n)) first = k;
    ASSERT_GT(first, 0) << i;
    High lo = High(horizon) * (first - 1) / n, hi = High(horizon) * first / n;
    ASSERT_FALSE(inside(lo)) << i;
    ASSERT_TRUE(inside(hi)) << i;
    for (int k = 0; k < 170; ++k) {
      const High m = (lo + hi) / 2;
      (inside(m) ? hi : lo) = m;
    }
    // The slope of the exact gap of the pair that touched, by a central difference in 50 digits.
    const HighPath hv{(a_vertex ? A : B).path}, he{(a_vertex ? B : A).path};
    auto exact_gap = [&](const High& s) {
      return cross(hv.point(hit.r, s) - he.point(hit.q, s), he.turn(hit.e, s));
    };
    const High step("1e-20");
    const High slope = (exact_gap(lo + step) - exact_gap(lo - step)) / (2 * step);
    const Timing tm = timing(t, lo, hit.width, slope);
    EXPECT_TRUE(tm.within_zone) << i << ": " << tm.ulps << " ulps, zone " << tm.zone_ulps;
    worst = std::max(worst, tm.ulps);
    worst_zone = std::max(worst_zone, tm.zone_ulps);
    // The enclosure's width in eps of the gap's scale: (|c_P - c_Q| + |r| + |q|) |e|.
    const High scale = (norm(hv.centre(lo) - he.centre(lo)) + norm(high(hit.r)) + norm(high(hit.q))) * norm(high(hit.e));
    worst_width = std::max(worst_width, static_cast<double>(High(hit.width) / scale / kEps));
  }
  std::printf("counter-spinning squares contact time: worst %.3g ulps off; uncertainty zone up to %.3g ulps, "
              "enclosure width up to %.3g eps of the gap's scale; %d edge-line crossings off the edges searched past\n",
              worst, worst_zone, worst_width, rejected_crossings);
  EXPECT_GT(rejected_crossings, 60);
  // The coefficients are built from stored paths anchored at t0 != 0 (s0 = -t0 enters c0, c1
  // and both phases) and two waves with their sin/cos enclosures add to the width: measured 17
  // eps of the scale with seed 23 (the rod's single wave from an exact anchor: 6.5).
  EXPECT_LE(worst_width, 32);
}

}  // namespace
