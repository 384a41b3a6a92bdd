#include "scene_bytes.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <numbers>
#include <string>

namespace pge::fuzz {
namespace {

// Header flag bits.
constexpr std::uint8_t kSolverMask = 0x03;       // 0 robust, 1 fast, 2 certified, 3 robust
constexpr std::uint8_t kHasGravity = 0x04;       // world.gravity follows
constexpr std::uint8_t kHasRestitution = 0x08;   // world.restitution follows (else 1)
// Body flag bits (the low two bits are the shape: 0 circle, 1 segment, 2 polygon, 3 circle).
constexpr std::uint8_t kShapeMask = 0x03;
constexpr std::uint8_t kFixed = 0x04;
constexpr std::uint8_t kNoGravity = 0x08;
constexpr std::uint8_t kOwnRestitution = 0x10;
constexpr std::uint8_t kHasAcceleration = 0x20;
constexpr std::uint8_t kHasVelocity = 0x40;
constexpr std::uint8_t kTurns = 0x80;  // a polygon or segment that rotates: angle and rate follow
// Polygon mode byte: even generates a convex polygon on an ellipse, odd lists the vertices.
constexpr std::uint8_t kExplicitVertices = 0x01;
// Number tags: below kTagShort a one-byte number on a grid of 1/8 in [-8, 8); from kTagShort to
// kTagRaw - 1 an int16 times a power of two; kTagRaw an IEEE-754 bit pattern (NaN, infinities
// and huge values included, which validation then rejects).
constexpr std::uint8_t kTagShort = 0x80;
constexpr std::uint8_t kTagRaw = 0xFF;
constexpr int kShortExponentBias = 40;  // int16 * 2^((tag & 0x3F) - 40): 2^-40 up to 2^23

class Reader {
 public:
  explicit Reader(std::span<const std::uint8_t> bytes) : bytes_(bytes) {}
  std::uint8_t byte() { return pos_ < bytes_.size() ? bytes_[pos_++] : 0; }
  std::uint64_t le(int n) {
    std::uint64_t v = 0;
    for (int i = 0; i < n; ++i) v |= std::uint64_t{byte()} << (8 * i);
    return v;
  }
  double number() {
    const std::uint8_t tag = byte();
    if (tag < kTagShort) return (static_cast<double>(tag) - 64) / 8;
    if (tag == kTagRaw) return std::bit_cast<double>(le(8));
    const auto k = static_cast<std::int16_t>(static_cast<std::uint16_t>(le(2)));
    return std::ldexp(static_cast<double>(k), (tag & 0x3F) - kShortExponentBias);
  }
  Vec2d vector() {
    const double x = number();
    return {x, number()};
  }

 private:
  std::span<const std::uint8_t> bytes_;
  std::size_t pos_ = 0;
};

class Writer {
 public:
  void byte(std::uint8_t b) { out.push_back(b); }
  void number(double x) {  // always the raw form: exact for every double
    byte(kTagRaw);
    const auto bits = std::bit_cast<std::uint64_t>(x);
    for (int i = 0; i < 8; ++i) byte(static_cast<std::uint8_t>(bits >> (8 * i)));
  }
  void vector(const Vec2d& v) {
    number(v.x);
    number(v.y);
  }
  std::vector<std::uint8_t> out;
};

// Points on an ellipse in strictly increasing angle are in convex position and wind
// counter-clockwise; each vertex's angle is jittered by less than half its slot so the order
// holds. Rounding can still make three vertices collinear: validation rejects those.
std::vector<Vec2d> ellipse_polygon(Reader& in, std::size_t n) {
  const double rx = in.number();
  const double ry = in.number();
  std::vector<Vec2d> v(n);
  const double slot = 2 * std::numbers::pi / static_cast<double>(n);
  for (std::size_t k = 0; k < n; ++k) {
    const double jitter = (static_cast<double>(in.byte()) / 256 - 0.5) * 0.9 * slot;
    const double angle = slot * static_cast<double>(k) + jitter;
    v[k] = {rx * std::cos(angle), ry * std::sin(angle)};
  }
  return v;
}

}  // namespace

Scene decode_scene(std::span<const std::uint8_t> bytes) {
  Reader in(bytes);
  Scene s;
  const std::size_t n = in.byte() % (kMaxDecodedBodies + 1);
  const std::uint8_t flags = in.byte();
  switch (flags & kSolverMask) {
    case 1: s.run.solver = SolverKind::Fast; break;
    case 2: s.run.solver = SolverKind::Certified; break;
    default: s.run.solver = SolverKind::Robust; break;
  }
  if (flags & kHasGravity) s.world.gravity = in.vector();
  if (flags & kHasRestitution) s.world.restitution = in.number();
  s.run.until = in.number();
  for (std::size_t i = 0; i < n; ++i) {
    BodyDesc b;
    b.id = "b" + std::to_string(i);
    const std::uint8_t bf = in.byte();
    switch (bf & kShapeMask) {
      case 1:
        b.shape = ShapeKind::Segment;
        b.a = in.vector();
        b.b = in.vector();
        break;
      case 2: {
        b.shape = ShapeKind::Polygon;
        const std::size_t count = 3 + in.byte() % kPolygonVertexChoices;
        if (in.byte() & kExplicitVertices) {
          b.vertices.resize(count);
          for (auto& v : b.vertices) v = in.vector();
        } else {
          b.vertices = ellipse_polygon(in, count);
        }
        break;
      }
      default:
        b.shape = ShapeKind::Circle;
        b.radius = in.number();
        break;
    }
    b.position = in.vector();
    b.fixed = (bf & kFixed) != 0;
    b.gravity = (bf & kNoGravity) == 0;
    if (!b.fixed) {
      if (bf & kHasVelocity) b.velocity = in.vector();
      if (bf & kHasAcceleration) b.acceleration = in.vector();
      b.mass = in.number();
    }
    if (bf & kOwnRestitution) b.restitution = in.number();
    if ((bf & kTurns) && b.shape != ShapeKind::Circle) {
      b.rotates = true;
      b.angle = in.number();
      b.angular_velocity = in.number();
    }
    s.bodies.push_back(std::move(b));
  }
  return s;
}

bool encodable(const Scene& scene) {
  const std::size_t n = std::min(scene.bodies.size(), kMaxDecodedBodies);
  for (std::size_t i = 0; i < n; ++i) {
    const BodyDesc& b = scene.bodies[i];
    if (b.shape == ShapeKind::Polygon &&
        (b.vertices.size() < 3 || b.vertices.size() >= 3 + kPolygonVertexChoices))
      return false;
  }
  return true;
}

std::vector<std::uint8_t> encode_scene(const Scene& scene) {
  Writer out;
  const std::size_t n = std::min(scene.bodies.size(), kMaxDecodedBodies);
  out.byte(static_cast<std::uint8_t>(n));
  std::uint8_t flags = scene.run.solver == SolverKind::Fast ? 1 : scene.run.solver == SolverKind::Certified ? 2 : 0;
  flags |= kHasGravity | kHasRestitution;
  out.byte(flags);
  out.vector(scene.world.gravity);
  out.number(scene.world.restitution);
  out.number(scene.run.until);
  for (std::size_t i = 0; i < n; ++i) {
    const BodyDesc& b = scene.bodies[i];
    std::uint8_t bf = b.shape == ShapeKind::Segment ? 1 : b.shape == ShapeKind::Polygon ? 2 : 0;
    if (b.fixed) bf |= kFixed;
    if (!b.gravity) bf |= kNoGravity;
    if (!(b.restitution < 0)) bf |= kOwnRestitution;  // -0.0 is a restitution of its own
    if (!b.fixed) bf |= kHasVelocity | kHasAcceleration;
    if (b.rotates && b.shape != ShapeKind::Circle) bf |= kTurns;
    out.byte(bf);
    switch (b.shape) {
      case ShapeKind::Segment:
        out.vector(b.a);
        out.vector(b.b);
        break;
      case ShapeKind::Polygon:
        out.byte(static_cast<std::uint8_t>(b.vertices.size() - 3));
        out.byte(kExplicitVertices);
        for (const auto& v : b.vertices) out.vector(v);
        break;
      case ShapeKind::Circle: out.number(b.radius); break;
    }
    out.vector(b.position);
    if (!b.fixed) {
      out.vector(b.velocity);
      out.vector(b.acceleration);
      out.number(b.mass);
    }
    if (bf & kOwnRestitution) out.number(b.restitution);
    if (bf & kTurns) {
      out.number(b.angle);
      out.number(b.angular_velocity);
    }
  }
  return std::move(out.out);
}

}  // namespace pge::fuzz
