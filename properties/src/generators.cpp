// Scene generators. Each motif is built at unit scale from a few random parameters, scaled by
// an exact power of two, and placed along x at a dyadic offset. Coordinates are quantised to
// multiples of 2^-20 of the motif scale, so that the placement offsets add exactly and the
// degenerate relations (touching, grazing, mirrored symmetry) survive in binary floating point.
// The y coordinates are never shifted, which keeps a one-ulp near-graze intact.
#include "pge/generators.hpp"

#include "scene_parts.hpp"

#include "pge/validate.hpp"

#include <algorithm>
#include <cmath>
#include <ostream>
#include <string>

namespace pge {
namespace {

using namespace scene_parts;

constexpr double kExtent = 16;      // every motif fits in [-16, 16] x [-16, 16] at unit scale
constexpr double kGap = 4;          // space between motifs, at the larger motif's scale

struct MotifSpec {
  Motif kind = Motif::Free;
  int scale_exp = 0;
  bool polygon = false;
  bool fixed_target = false;
  bool diagonal = false;     // use the 3-4-5 direction instead of an axis
  int count = 1;             // cradle length
  int sign = 1;              // near-graze: +1 miss by an ulp, -1 hit by an ulp
  double a = 0, b = 0, c = 0, d = 0;  // shape and motion parameters in [-1, 1]
  int mass_exp = 0;          // masses 2^k
  double restitution = 1;
  double accel = 0;          // per-body acceleration magnitude parameter (0: none)
  bool own_acceleration = true;  // floor motifs: pressed by an acceleration of their own
  bool inelastic = true;         // floor motifs: restitution below 1 allowed
};

// The motifs on a floor (RestSlide, TileJoint, Stack): what games are made of. The floor's top
// is y = 0: one segment or fixed box, or (TileJoint) two of them meeting at a joint x = j; the
// movers lie exactly on it (or on each other), or (TileJoint, diagonal) drop onto the joint from
// a height, pressed down by their own acceleration g, with a restitution of their own (0, 0.5 or
// 1: resting contact takes the bounces that remain).
std::vector<BodyDesc> realize_on_floor(const MotifSpec& m) {
  std::vector<BodyDesc> out;
  const double mass = std::ldexp(1.0, m.mass_exp);
  const double r1 = quantize(0.5 + 0.25 * m.a, 8);
  const double r2 = quantize(0.5 + 0.25 * m.b, 8);
  // Without an acceleration of their own they are pressed by the world's gravity, if any.
  const double g = m.own_acceleration ? quantize(0.25 + 0.75 * std::abs(m.d), 8) : 0.0;
  const double restitution = !m.inelastic ? 1.0 : (m.b < -0.5 ? 0.0 : (m.b < 0 ? 0.5 : 1.0));
  const auto tile = [&](double x0, double x1) {
    BodyDesc t;
    if (m.fixed_target) {
      t = box_body((x1 - x0) / 2, 1, {(x0 + x1) / 2, -1}, {}, 1);
      make_fixed(t);
    } else {
      t = fixed_segment({x0, 0}, {x1, 0});
    }
    return t;
  };
  const double joint = quantize(0.5 * m.a, 8);
  if (m.kind == Motif::TileJoint) {
    out.push_back(tile(-8, joint));
    out.push_back(tile(joint, 8));
  } else {
    out.push_back(tile(-8, 8));
  }
  // A mover whose lowest point is at height `lift`, centred at x.
  const auto mover = [&](double x, double lift, double vx, int shape) {
    BodyDesc b;
    if (shape == 0) b = circle_body(r1, {x, r1 + lift}, {vx, 0}, mass);
    else if (shape == 1) b = box_body(r1, r2, {x, r2 + lift}, {vx, 0}, mass);
    else b = triangle_body(r1, {x, r1 + lift}, {vx, 0}, mass);
    b.acceleration = {0, -g};
    b.restitution = restitution < 1 ? restitution : -1;
    return b;
  };
  const int shape = !m.polygon ? 0 : (m.c < 0 ? 2 : 1);
  const double vx = quantize(m.c);
  if (m.kind == Motif::Stack) {
    out.push_back(mover(0, 0, vx, 1));
    BodyDesc top = box_body(r1 / 2, r2 / 2, {quantize(0.25 * m.d), 2 * r2 + r2 / 2}, {quantize(m.d), 0}, mass);
    top.acceleration = {0, -g};
    top.restitution = out.back().restitution;
    out.push_back(top);
  } else if (m.kind == Motif::TileJoint && m.diagonal) {
    out.push_back(mover(joint, quantize(0.25 + 0.5 * std::abs(m.d), 8), vx, shape));  // lands across the joint
  } else {
    const double x = m.kind == Motif::TileJoint ? joint - 2 : quantize(2 * m.d);
    out.push_back(mover(x, 0, m.kind == Motif::TileJoint ? std::abs(vx) + 0.25 : vx, shape));
  }
  return out;
}

// The bodies of a motif at unit scale, centred near the origin.
std::vector<BodyDesc> realize(const MotifSpec& m) {
  std::vector<BodyDesc> out;
  const double mass = std::ldexp(1.0, m.mass_exp);
  const double r1 = quantize(0.5 + 0.25 * m.a, 8);
  const double r2 = quantize(0.5 + 0.25 * m.b, 8);
  const double speed = quantize(0.25 + 0.75 * std::abs(m.c));
  switch (m.kind) {
    case Motif::Free:
    case Motif::Count: {
      const Vec2d v{quantize(m.c), quantize(m.d)};
      if (m.polygon)
        out.push_back(m.a < 0 ? triangle_body(r1, {0, 0}, v, mass) : box_body(r1, r2, {0, 0}, v, mass));
      else
        out.push_back(circle_body(r1, {0, 0}, v, mass));
      break;
    }
    case Motif::TouchingPair: {
      // Centres exactly r1 + r2 apart: along x, or along (3, 4) with r1 + r2 a multiple of 5.
      const double k = m.diagonal ? quantize((r1 + r2) / 5, 8) : 0;
      const double rb = m.diagonal ? 5 * k - r1 : r2;
      const Vec2d offset = m.diagonal ? Vec2d{3 * k, 4 * k} : Vec2d{r1 + rb, 0};
      out.push_back(circle_body(r1, {0, 0}, {quantize(m.c), quantize(m.d)}, mass));
      out.push_back(circle_body(rb, offset, {quantize(-m.d), quantize(m.c)}, 1));
      break;
    }
    case Motif::Graze:
    case Motif::NearGraze: {
      // The mover's path y = R passes the target at centre distance exactly R = r1 + r2: the
      // contact function (x(t)^2 + R^2) - R^2 = x(t)^2 has a double root. NearGraze moves the
      // path one ulp out (+1: a miss) or in (-1: a hit of depth one ulp).
      const double big_r = r1 + r2;
      double y = big_r;
      if (m.kind == Motif::NearGraze) y = std::nextafter(big_r, m.sign > 0 ? 1e300 : 0.0);
      BodyDesc target = circle_body(r1, {0, 0}, {}, 1);
      if (m.fixed_target) make_fixed(target);
      out.push_back(target);
      out.push_back(circle_body(r2, {-(2 + big_r + std::abs(m.d)), y}, {speed, 0}, mass));
      break;
    }
    case Motif::Simultaneous: {
      // Two equal circles mirrored in x about the middle one reach it at the same instant.
      const double big_r = r1 + r2;
      const double k = quantize((big_r + 1 + std::abs(m.d)) / 5, 8);
      const Vec2d p = m.diagonal ? Vec2d{3 * k, 4 * k} : Vec2d{5 * k, 0};
      const Vec2d v = m.diagonal ? Vec2d{-3 * speed / 8, -4 * speed / 8} : Vec2d{-speed, 0};
      BodyDesc middle = circle_body(r1, {0, 0}, {}, 1);
      if (m.fixed_target) make_fixed(middle);
      out.push_back(middle);
      out.push_back(circle_body(r2, p, v, mass));
      out.push_back(circle_body(r2, {-p.x, p.y}, {-v.x, v.y}, mass));
      break;
    }
    case Motif::Cradle: {
      const int n = std::clamp(m.count, 2, 5);
      for (int i = 0; i < n; ++i) out.push_back(circle_body(r1, {2 * r1 * i, 0}, {}, 1));
      out.push_back(circle_body(r1, {-2 * r1 - 1 - std::abs(m.d), 0}, {speed, 0}, mass));
      break;
    }
    case Motif::WallHit: {
      out.push_back(fixed_segment({-2, 0}, {2, 0}));
      if (m.diagonal) {
        // Aimed exactly at endpoint b = (2, 0) along (-3, -4): head-on with the vertex.
        const double k = quantize(r1 / 5 + 0.25 + 0.25 * std::abs(m.d), 8);
        out.push_back(circle_body(r1, {2 + 3 * k + 3 * r1 / 5, 4 * k + 4 * r1 / 5}, {-3 * speed / 8, -4 * speed / 8}, mass));
      } else {
        out.push_back(circle_body(r1, {quantize(1.5 * m.a), r1 + 1 + std::abs(m.d)}, {quantize(m.b), -speed}, mass));
      }
      break;
    }
    case Motif::CornerHit: {
      // Box A's corner (h, h) and B's lower-left corner (h + g, h + g) meet when B has moved g
      // along (-1, -1): corner on corner, exactly.
      const double h = r1, h2 = r2, g = quantize(0.5 + 0.5 * std::abs(m.d), 8);
      BodyDesc a = m.a < 0 ? triangle_body(h, {0, 0}, {}, 1) : box_body(h, h, {0, 0}, {}, 1);
      if (m.fixed_target) make_fixed(a);
      out.push_back(a);
      out.push_back(box_body(h2, h2, {h + g + h2, h + g + h2}, {-speed, -speed}, mass));
      break;
    }
    case Motif::RestSlide:
    case Motif::TileJoint:
    case Motif::Stack:
      return realize_on_floor(m);
    case Motif::TouchSlide: {
      // A fixed ceiling (a segment, or a fixed box's bottom face) at y = 0 over x in [-12, 12] and
      // a body touching it from below, moving along it: zero normal speed, nothing pressing it in
      // (a graze at t = 0). The ceiling is long enough that no body reaches its ends by the
      // horizon at unit speed (a graze of a segment's end vertex is a harder case of its own).
      const Vec2d v{quantize(m.c), 0};
      if (m.fixed_target) {
        BodyDesc ceiling = box_body(12, 1, {0, 1}, {}, 1);
        make_fixed(ceiling);
        out.push_back(ceiling);
      } else {
        out.push_back(fixed_segment({-12, 0}, {12, 0}));
      }
      const double x = quantize(4 * m.d);
      if (m.polygon) out.push_back(box_body(r1, r2, {x, -r2}, v, mass));
      else out.push_back(circle_body(r1, {x, -r1}, v, mass));
      break;
    }
  }
  for (BodyDesc& b : out) {
    if (b.fixed) continue;
    b.restitution = m.restitution < 1 ? m.restitution : -1;
    if (m.accel != 0) b.acceleration = {quantize(m.accel * 0.5), quantize(-std::abs(m.accel))};
  }
  return out;
}

rc::Gen<Motif> gen_motif_kind(const GenOptions& o) {
  std::vector<Motif> allowed;
  for (int k = 0; k < static_cast<int>(Motif::Count); ++k) {
    const auto m = static_cast<Motif>(k);
    if ((o.motif_mask & motif_bit(m)) == 0) continue;
    if ((m == Motif::CornerHit || m == Motif::Stack) && !o.polygons) continue;
    allowed.push_back(m);
  }
  if (allowed.empty()) allowed.push_back(Motif::Free);
  return one_of(std::move(allowed));
}

rc::Gen<MotifSpec> gen_motif(const GenOptions& o, bool elastic_only, bool with_accel) {
  return rc::gen::exec([=]() {
    MotifSpec m;
    m.kind = *gen_motif_kind(o);
    m.scale_exp = *uniform_in(0, o.max_scale_exp - o.min_scale_exp + 1) + o.min_scale_exp;
    if (m.scale_exp != 0 && *uniform_in(0, 2) == 0) m.scale_exp = 0;  // half the motifs at unit scale
    m.polygon = o.polygons && *uniform_in(0, 3) == 0;
    m.fixed_target = *uniform_in(0, 2) == 1;
    const bool boxes_as_floor = m.kind == Motif::RestSlide || m.kind == Motif::TileJoint || m.kind == Motif::TouchSlide;
    if (boxes_as_floor && !o.polygons) m.fixed_target = false;  // their fixed target is a box
    m.diagonal = *uniform_in(0, 2) == 1;
    m.count = *uniform_in(2, 6);
    m.sign = *uniform_in(0, 2) == 0 ? 1 : -1;
    m.a = *gen_signed(10);
    m.b = *gen_signed(10);
    m.c = *gen_signed(10);
    m.d = *gen_signed(10);
    m.mass_exp = *uniform_in(0, 7) - 3;
    if (!elastic_only && *uniform_in(0, 4) == 0) m.restitution = *rc::gen::element(0.0, 0.5, 0.9);
    if (with_accel && *uniform_in(0, 3) == 0) m.accel = *gen_unit(6);
    m.own_acceleration = o.accelerations;
    m.inelastic = o.inelastic;
    return m;
  });
}

}  // namespace

std::string_view motif_name(Motif m) {
  switch (m) {
    case Motif::Free: return "free";
    case Motif::TouchingPair: return "touching-pair";
    case Motif::Graze: return "graze";
    case Motif::NearGraze: return "near-graze";
    case Motif::Simultaneous: return "simultaneous";
    case Motif::Cradle: return "cradle";
    case Motif::WallHit: return "wall-hit";
    case Motif::CornerHit: return "corner-hit";
    case Motif::RestSlide: return "rest-slide";
    case Motif::TileJoint: return "tile-joint";
    case Motif::Stack: return "stack";
    case Motif::TouchSlide: return "touch-slide";
    case Motif::Count: break;
  }
  return "?";
}

void print_generated(const GeneratedScene& g, std::ostream& os) { print_motifs_and_scene(os, g.motifs, motif_name, g.scene); }

rc::Gen<GeneratedScene> gen_scene(const GenOptions& o) {
  return rc::gen::exec([o]() {
    const bool gravity = o.gravity && *uniform_in(0, 3) == 0;
    // Restitution < 1 under gravity, or under per-body accelerations that press a body against
    // another, can come to rest: a contact state the engine reports as a storm (of zero-impulse
    // contacts) until resting contact exists. Scenes that may hold accelerations stay elastic.
    const bool accel = o.accelerations && !gravity && *uniform_in(0, 1) == 0;
    const bool elastic_only = gravity || accel || !o.inelastic;
    const auto specs = *rc::gen::resize(
        o.max_motifs * 10, rc::gen::nonEmpty(rc::gen::container<std::vector<MotifSpec>>(gen_motif(o, elastic_only, accel))));

    GeneratedScene g;
    g.gravity = gravity;
    Scene& s = g.scene;
    s.name = "generated";
    s.run.until = o.until;
    s.run.max_events = o.max_events;
    if (gravity) s.world.gravity = {0, -1};
    double x = 0;
    double lowest = 0;
    int min_exp = 1000, max_exp = -1000;
    const std::size_t n = std::min<std::size_t>(specs.size(), static_cast<std::size_t>(o.max_motifs));
    for (std::size_t i = 0; i < n; ++i) {
      const MotifSpec& m = specs[i];
      g.motifs.push_back(m.kind);
      min_exp = std::min(min_exp, m.scale_exp);
      max_exp = std::max(max_exp, m.scale_exp);
      const double half = append_motif(s, realize(m), i, m.scale_exp, kExtent, kGap, x);
      lowest = std::min(lowest, -half);
    }
    g.mixed_scale = max_exp != min_exp;
    if (gravity) {
      BodyDesc floor;
      floor.id = "floor";
      floor.shape = ShapeKind::Segment;
      floor.fixed = true;
      const double margin = std::ldexp(kExtent, max_exp);
      floor.a = {-2 * margin, 2 * lowest};
      floor.b = {x + 2 * margin, 2 * lowest};
      s.bodies.push_back(floor);
    }
    return g;
  });
}

}  // namespace pge
