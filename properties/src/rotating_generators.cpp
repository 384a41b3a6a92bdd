// Generators of small scenes with turning bodies (pge/rotating_generators.hpp). Each motif is
// built at unit scale from a few dyadic parameters, scaled by an exact power of two and shifted
// along x by a dyadic offset (scene_parts.hpp), so that its degenerate relation survives in
// doubles: a turning shape's centroid is its reference point (boxes, diamonds, rods, and
// triangles and kites whose centroids are the origin), so its pivot is its position; a placement
// at a dyadic time t1 turns the body to angle exactly 0 there (angle -omega t1, omega and t1 with
// few bits), where its corners sit at their unrotated places; a mirror image is the same shape at
// the negated angle and spin.
#include "pge/rotating_generators.hpp"

#include "pge/detail/rigid.hpp"

#include "scene_parts.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <ostream>
#include <string>

namespace pge {
namespace {

using namespace scene_parts;

constexpr double kExtent = 8;  // every motif fits in [-8, 8] x [-8, 8] at unit scale
constexpr double kGap = 4;     // space between motifs, at the larger motif's scale
constexpr int kMinScaleExp = -3;  // motif scales 2^k, k in [kMinScaleExp, kMaxScaleExp]
constexpr int kMaxScaleExp = 3;
// SlowSpin's rates are k 2^-kSlowSpinExp rad/s with k in [2^10, 2^11): 0.93e-9 to 1.9e-9.
constexpr int kSlowSpinExp = 40;
// FastSpin's rates: kFastSpinMin to kFastSpinMin + kFastSpinRange rad/s.
constexpr double kFastSpinMin = 50;
constexpr double kFastSpinRange = 150;

// The turning shapes, each with its centroid at the origin of its own coordinates.
enum class Outline : std::uint8_t { Box, Diamond, Triangle, Rod, Kite };

// The vertices of a shape of size s (half-width; a box's half-height is s * aspect, aspect in
// [1/2, 1]):
//   Box      [-s, s] x [-h, h]
//   Diamond  corners on the axes at distance s
//   Triangle (-s, -s), (s, -s), (0, 2s): centroid (0, 0), reach 2s
//   Kite     (s, 0), (-s/2, s/2), (-s/2, -s/2): centroid (0, 0), one corner at reach s, the
//            others at s / sqrt 2
//   Rod      a segment from (-s, 0) to (s, 0)
std::vector<Vec2d> outline_vertices(Outline o, double s, double aspect) {
  switch (o) {
    case Outline::Box: return {{-s, -s * aspect}, {s, -s * aspect}, {s, s * aspect}, {-s, s * aspect}};
    case Outline::Diamond: return {{s, 0}, {0, s}, {-s, 0}, {0, -s}};
    case Outline::Triangle: return {{-s, -s}, {s, -s}, {0, 2 * s}};
    case Outline::Kite: return {{s, 0}, {-s / 2, s / 2}, {-s / 2, -s / 2}};
    case Outline::Rod: break;
  }
  return {{-s, 0}, {s, 0}};
}

// The engine's centroid of a polygon is a sum of products scaled by 1 / (3 twice-area), rounded:
// the origin exactly for most sizes, an ulp off for some (a diamond of size 91/256). The size is
// moved up by steps of 2^-8 to the nearest one where the engine's pivot
// (detail::turning_mass, what World computes) is exactly the origin, so that the shape turns
// about its reference point and its corners at angle 0 are where they were placed. Scaling by a
// power of two keeps it exact.
double exact_pivot_size(Outline o, double s, double aspect) {
  constexpr double kStep = 0x1p-8;
  while (detail::turning_mass(outline_vertices(o, s, aspect), 1.0, 0.0).pivot != Vec2d{}) s += kStep;
  return s;
}

// A turning shape: its outline, size (exact_pivot_size) and aspect.
struct Shape {
  Outline outline = Outline::Box;
  double size = 1, aspect = 1;
};

Shape shape_of(Outline o, double size, double aspect = 1) { return {o, exact_pivot_size(o, size, aspect), aspect}; }

// The shape as a moving body turning at `omega` from `angle`.
BodyDesc turning_body(const Shape& sh, Vec2d p, Vec2d v, double mass, double angle, double omega) {
  const std::vector<Vec2d> vertices = outline_vertices(sh.outline, sh.size, sh.aspect);
  BodyDesc b = polygon_body(vertices, p, v, mass);
  if (sh.outline == Outline::Rod) {
    b.shape = ShapeKind::Segment;
    b.vertices.clear();
    b.a = vertices[0];
    b.b = vertices[1];
  }
  b.rotates = true;
  b.angle = angle;
  b.angular_velocity = omega;
  return b;
}

// An upper bound of the distance of a shape's points from its centroid: 2 s for every shape.
constexpr double kReachPerSize = 2;

BodyDesc fixed_box(double hx, double hy, Vec2d p) {
  BodyDesc b = box_body(hx, hy, p, {}, 1);
  make_fixed(b);
  return b;
}

struct SpinSpec {
  SpinMotif kind = SpinMotif::Spinner;
  int scale_exp = 0;
  int variant = 0;  // 0..3: the motif's target or placement
  int shape = 0;    // 0..3: the outline of its main body
  int sign = 1;     // the sense of a spin
  int tick = 1;     // 1..3: a placement's dyadic time, tick / 4 s
  int mass_exp = 0; // the main body's mass 2^k
  double until = 2;  // the run's horizon, s
  bool edge_end_landing = false;  // SpinGenOptions::edge_end_landing
  std::array<double, 6> p{};  // parameters in [-1, 1] with 10 bits after the point
};

double q8(double x) { return quantize(x, 8); }
double mag(double x) { return std::abs(x); }
Outline outline_of(int k) { return static_cast<Outline>(k % 4); }  // Box, Diamond, Triangle, Rod
double aspect_of(double x) { return 0.5 + 0.5 * q8(mag(x)); }
double angle_of(double x) { return quantize(3 * x, 10); }  // in [-3, 3] rad

// Generic: a turning body thrown at a wall, a fixed box, a ball, or another turning body.
std::vector<BodyDesc> spinner(const SpinSpec& m, double mass) {
  const auto& p = m.p;
  const Shape a = shape_of(outline_of(m.shape), q8(0.25 + 0.5 * mag(p[0])), aspect_of(p[1]));
  std::vector<BodyDesc> out;
  out.push_back(turning_body(a, {-3, q8(0.5 * p[2])}, {q8(1.5 + mag(p[3])), q8(0.25 * p[4])}, mass, angle_of(p[5]),
                             quantize(8 * p[1], 6)));
  switch (m.variant) {
    case 0: out.push_back(fixed_segment({0, -4}, {0, 4})); break;
    case 1: out.push_back(fixed_box(0.5, 1, {1, q8(0.5 * p[4])})); break;
    case 2: out.push_back(circle_body(q8(0.25 + 0.25 * mag(p[2])), {1, q8(0.5 * p[3])}, {q8(-0.5 * mag(p[5])), 0}, 1)); break;
    default: {
      const Shape b = shape_of(outline_of(m.shape + 1), q8(0.25 + 0.5 * mag(p[3])), aspect_of(p[0]));
      out.push_back(turning_body(b, {3, q8(-0.5 * p[2])}, {q8(-1 - mag(p[4])), q8(0.25 * p[0])}, 1, angle_of(p[3]),
                                 quantize(-8 * p[5], 6)));
    }
  }
  return out;
}

// Generic: a fixed body spinning at a constant rate about its position, struck from above by a
// ball or a turning box.
std::vector<BodyDesc> turnstile(const SpinSpec& m, double mass) {
  const auto& p = m.p;
  const Outline o = m.shape < 2 ? Outline::Rod : (m.shape == 2 ? Outline::Box : Outline::Triangle);
  const Shape sh = shape_of(o, q8(0.5 + 0.25 * mag(p[0])), aspect_of(p[1]));
  BodyDesc stile = turning_body(sh, {0, 0}, {}, 1, angle_of(p[2]), m.sign * quantize(0.5 + 3.5 * mag(p[1]), 6));
  make_fixed(stile);
  const Vec2d at{q8(0.75 * sh.size * p[4]), 3};
  const Vec2d v{0, q8(-1 - mag(p[5]))};
  BodyDesc striker = m.variant % 2 == 0
                         ? circle_body(q8(0.1 + 0.2 * mag(p[3])), at, v, mass)
                         : turning_body(shape_of(Outline::Box, 0.25), at, v, mass, angle_of(p[3]), quantize(4 * p[2], 6));
  return {stile, striker};
}

// (a) A corner exactly at a segment's end. Variant 0: a box at angle 0 whose corner (s, -h) is
// the end of a segment leaving it along the bottom edge's line, the right edge's line or the
// diagonal, at t = 0, the box turning and moving. Variants 1-3: a diamond falling and turning
// whose bottom corner is at t1 (angle exactly 0 then; its lowest point while |angle| < pi/4)
// exactly on the end (0, 0) of a floor segment to the right (1), to the left (2), or on the joint
// of both (3): at t1 = 0, or (SpinGenOptions::edge_end_landing) landing there at a dyadic t1 > 0.
std::vector<BodyDesc> edge_end(const SpinSpec& m, double mass) {
  const auto& p = m.p;
  const double omega = m.sign * quantize(0.125 + 0.875 * mag(p[2]), 6);  // |omega| t1 <= 3/4 < pi/4
  if (m.variant == 0) {
    const Shape box = shape_of(Outline::Box, q8(0.5 + 0.25 * p[0]), aspect_of(p[1]));
    const Vec2d corner{box.size, -box.size * box.aspect};
    const Vec2d away = m.shape % 3 == 0 ? Vec2d{2, 0} : (m.shape % 3 == 1 ? Vec2d{0, -2} : Vec2d{2, -2});
    return {turning_body(box, {0, 0}, {q8(p[3]), q8(p[4])}, mass, 0, 4 * omega),
            fixed_segment(corner, {corner.x + away.x, corner.y + away.y})};
  }
  const Shape diamond = shape_of(Outline::Diamond, q8(0.5 + 0.25 * p[0]));
  // Landing (on the scenes of odd `shape`, which variants 1-3 do not otherwise read) or at the start.
  const double r = diamond.size, t1 = m.edge_end_landing && m.shape % 2 == 1 ? 0.25 * m.tick : 0.0;
  const Vec2d v{q8(0.5 * p[3]), -q8(0.5 + 1.5 * mag(p[4]))};
  std::vector<BodyDesc> out;
  out.push_back(turning_body(diamond, {-v.x * t1, r - v.y * t1}, v, mass, 0.0 - omega * t1, omega));
  if (m.variant != 2) out.push_back(fixed_segment({0, 0}, {2, 0}));
  if (m.variant != 1) out.push_back(fixed_segment({-2, 0}, {0, 0}));
  return out;
}

// (b) A box with faces parallel to its target's at the start, turning at about 1e-9 rad/s: one
// corner leads the face by about 1e-9 of its size when they meet.
std::vector<BodyDesc> slow_spin(const SpinSpec& m, double mass) {
  const auto& p = m.p;
  const auto slow = [](double x) { return std::ldexp(1024 + std::floor(1023 * mag(x)), -kSlowSpinExp); };
  const Shape box = shape_of(Outline::Box, q8(0.5 + 0.25 * p[0]), aspect_of(p[1]));
  std::vector<BodyDesc> out;
  out.push_back(turning_body(box, {-2, q8(0.5 * p[2])}, {q8(0.5 + mag(p[3])), 0}, mass, 0, m.sign * slow(p[4])));
  switch (m.variant) {
    case 0: out.push_back(fixed_segment({0, -4}, {0, 4})); break;
    case 1: out.push_back(fixed_box(0.5, 1, {1, q8(0.5 * p[5])})); break;
    case 2: {
      const Shape other = shape_of(Outline::Box, q8(0.5 + 0.25 * p[1]), aspect_of(p[0]));
      out.push_back(turning_body(other, {2, q8(0.5 * p[5])}, {q8(-0.5 - mag(p[2])), 0}, 1, 0, -m.sign * slow(p[5])));
      break;
    }
    default: out.push_back(circle_body(0.5, {1, q8(0.5 * p[5])}, {}, 1));
  }
  return out;
}

// (c) A body turning at 50 to 200 rad/s starting apart from its target (a gap of at least 1/4
// beyond its reach) and closing at 1 to 2 m/s: tens of turns before the first contact.
std::vector<BodyDesc> fast_spin(const SpinSpec& m, double mass) {
  const auto& p = m.p;
  const Shape a = shape_of(outline_of(m.shape), q8(0.25 + 0.25 * mag(p[0])), aspect_of(p[1]));
  const double gap = q8(0.25 + 0.5 * mag(p[2]));
  const double x = kReachPerSize * a.size + gap;
  const auto rate = [&m](double k) { return m.sign * quantize(kFastSpinMin + kFastSpinRange * mag(k), 4); };
  std::vector<BodyDesc> out;
  out.push_back(turning_body(a, {-x, q8(0.5 * p[3])}, {q8(1 + mag(p[4])), 0}, mass, angle_of(p[5]), rate(p[1])));
  switch (m.variant) {
    case 0: out.push_back(fixed_segment({0, -4}, {0, 4})); break;
    case 1: {
      const double r = q8(0.25 + 0.25 * mag(p[5]));
      out.push_back(circle_body(r, {r, 0}, {}, 1));
      break;
    }
    case 2: out.push_back(fixed_box(0.5, 1, {0.5, 0})); break;
    default: {
      const Shape b = shape_of(outline_of(m.shape + 2), a.size, aspect_of(p[2]));
      out.push_back(turning_body(b, {kReachPerSize * b.size + gap, 0}, {q8(-1 - mag(p[0])), 0}, 1, angle_of(p[4]), -rate(p[5])));
    }
  }
  return out;
}

// (d) A turning body and its mirror image in x = 0 (the same shape, symmetric about its own
// vertical axis, at the negated angle and spin, the mirrored position and velocity, the same
// mass): what reaches x = 0 first is a corner of each, at the same point and instant.
std::vector<BodyDesc> corner_on_corner(const SpinSpec& m, double mass) {
  const auto& p = m.p;
  const Shape sh = shape_of(outline_of(m.shape), q8(0.25 + 0.5 * mag(p[0])), aspect_of(p[1]));
  const double x = kReachPerSize * sh.size + q8(0.125 + 0.25 * mag(p[1]));
  const double y = q8(0.5 * p[3]);
  const Vec2d v{q8(1 + mag(p[2])), q8(0.25 * p[3])};
  const double angle = angle_of(p[4]), omega = quantize(4 * p[5], 6);
  return {turning_body(sh, {-x, y}, v, mass, angle, omega), turning_body(sh, {x, y}, {-v.x, v.y}, mass, -angle, -omega)};
}

// (e) A corner whose circle of reach touches a line (or a ball) exactly: the shape turns about a
// pivot moving along y only, at angle 0 at t_g (angle -omega t_g), where its corner (s, 0) lies on
// the wall's line x = s (a segment, or a fixed box's face), or touches a resting ball centred at
// (s + R, 0), with zero normal speed, and turns away. A kite has that one corner at reach s; a
// diamond's next corner comes to the line a quarter turn later, a rod's other end half a turn
// later, at transcendental times, up to 2 rad/s: after the engine's impulse of rounding size at
// the exact tangency, that next one may be a near miss by about 1e-16, which the engine once
// took for a contact (docs/rotation.md, E3; the rates were kept low enough to put it after the
// horizon until it was fixed).
std::vector<BodyDesc> graze(const SpinSpec& m, double mass) {
  const auto& p = m.p;
  const Outline o = m.shape < 2 ? Outline::Kite : (m.shape == 2 ? Outline::Diamond : Outline::Rod);
  const Shape sh = shape_of(o, q8(0.5 + 0.25 * p[0]));
  const double s = sh.size, tg = 0.25 * m.tick;
  const double omega = m.sign * quantize(0.5 + 1.5 * mag(p[1]), 6);  // 0.5 to 2 rad/s
  const double vy = q8(0.5 * p[2]);
  std::vector<BodyDesc> out;
  out.push_back(turning_body(sh, {0, -vy * tg}, {0, vy}, mass, -omega * tg, omega));
  switch (m.variant) {
    case 0:
    case 1: out.push_back(fixed_segment({s, -4}, {s, 4})); break;
    case 2: out.push_back(fixed_box(0.5, 3, {s + 0.5, 0})); break;
    default: {
      const double r = q8(0.25 + 0.25 * mag(p[3]));
      out.push_back(circle_body(r, {s + r, 0}, {}, 1));
    }
  }
  return out;
}

std::vector<BodyDesc> realize(const SpinSpec& m) {
  const double mass = std::ldexp(1.0, m.mass_exp);
  switch (m.kind) {
    case SpinMotif::Spinner:
    case SpinMotif::Count: return spinner(m, mass);
    case SpinMotif::Turnstile: return turnstile(m, mass);
    case SpinMotif::EdgeEnd: return edge_end(m, mass);
    case SpinMotif::SlowSpin: return slow_spin(m, mass);
    case SpinMotif::FastSpin: return fast_spin(m, mass);
    case SpinMotif::CornerOnCorner: return corner_on_corner(m, mass);
    case SpinMotif::Graze: return graze(m, mass);
  }
  return {};
}

rc::Gen<SpinMotif> gen_spin_motif_kind(const SpinGenOptions& o) {
  std::vector<SpinMotif> allowed;
  for (int k = 0; k < static_cast<int>(SpinMotif::Count); ++k) {
    const auto m = static_cast<SpinMotif>(k);
    if ((o.motif_mask & spin_motif_bit(m)) != 0) allowed.push_back(m);
  }
  if (allowed.empty()) allowed.push_back(SpinMotif::Spinner);
  return one_of(std::move(allowed));
}

rc::Gen<SpinSpec> gen_spin_spec(const SpinGenOptions& o) {
  return rc::gen::exec([o]() {
    SpinSpec m;
    m.kind = *gen_spin_motif_kind(o);
    m.scale_exp = *uniform_in(kMinScaleExp, kMaxScaleExp + 1);
    if (m.scale_exp != 0 && *uniform_in(0, 2) == 0) m.scale_exp = 0;  // half the motifs at unit scale
    m.variant = *uniform_in(0, 4);
    m.shape = *uniform_in(0, 4);
    m.sign = *uniform_in(0, 2) == 0 ? 1 : -1;
    m.tick = *uniform_in(1, 4);
    m.mass_exp = *uniform_in(-2, 3);
    m.until = o.until;
    m.edge_end_landing = o.edge_end_landing;
    for (double& x : m.p) x = *gen_signed(10);
    return m;
  });
}

}  // namespace

std::string_view spin_motif_name(SpinMotif m) {
  switch (m) {
    case SpinMotif::Spinner: return "spinner";
    case SpinMotif::Turnstile: return "turnstile";
    case SpinMotif::EdgeEnd: return "corner-at-edge-end";
    case SpinMotif::SlowSpin: return "slow-spin";
    case SpinMotif::FastSpin: return "fast-spin";
    case SpinMotif::CornerOnCorner: return "corner-on-corner";
    case SpinMotif::Graze: return "tangent-graze";
    case SpinMotif::Count: break;
  }
  return "?";
}

bool is_degenerate(SpinMotif m) { return m != SpinMotif::Spinner && m != SpinMotif::Turnstile; }

bool SpinScene::degenerate() const { return std::any_of(motifs.begin(), motifs.end(), is_degenerate); }

void print_spin_scene(const SpinScene& s, std::ostream& os) { print_motifs_and_scene(os, s.motifs, spin_motif_name, s.scene); }

rc::Gen<SpinScene> gen_spin_scene(const SpinGenOptions& o) {
  return rc::gen::exec([o]() {
    const int count = *uniform_in(1, std::max(1, o.max_motifs) + 1);
    const bool elastic = !o.known_failures || *uniform_in(0, 4) != 0;
    SpinScene g;
    Scene& s = g.scene;
    s.name = "generated-rotating";
    s.run.until = o.until;
    s.run.max_events = o.max_events;
    double x = 0;
    for (int i = 0; i < count; ++i) {
      const SpinSpec m = *gen_spin_spec(o);
      g.motifs.push_back(m.kind);
      std::vector<BodyDesc> bodies = realize(m);
      for (BodyDesc& b : bodies)
        if (!elastic && !b.fixed) b.restitution = 0.5;
      append_motif(s, std::move(bodies), static_cast<std::size_t>(i), m.scale_exp, kExtent, kGap, x);
    }
    return g;
  });
}

}  // namespace pge
