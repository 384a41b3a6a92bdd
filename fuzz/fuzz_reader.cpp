// libFuzzer target: raw bytes -> pge::parse_scene. A SceneError is the reader doing its job;
// any other exception, a crash or a hang is a failure. A scene that parses must survive
// write_scene -> parse_scene bit for bit, and then runs like a fuzz_engine scene.
#include "fuzz_check.hpp"

#include "pge/scene_io.hpp"

#include <bit>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <string>
#include <string_view>

namespace {

using pge::BodyDesc;
using pge::Scene;
using pge::Vec2d;

// Bitwise: the round trip promises the same bits (-0.0 and 0.0 differ).
bool same(double a, double b) { return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b); }
bool same(const Vec2d& a, const Vec2d& b) { return same(a.x, b.x) && same(a.y, b.y); }

bool same_body(const BodyDesc& a, const BodyDesc& b) {
  if (a.vertices.size() != b.vertices.size()) return false;
  for (std::size_t k = 0; k < a.vertices.size(); ++k)
    if (!same(a.vertices[k], b.vertices[k])) return false;
  return a.id == b.id && a.shape == b.shape && same(a.radius, b.radius) && same(a.a, b.a) && same(a.b, b.b) &&
         same(a.position, b.position) && same(a.velocity, b.velocity) && same(a.acceleration, b.acceleration) &&
         a.fixed == b.fixed && same(a.mass, b.mass) && a.gravity == b.gravity && same(a.restitution, b.restitution) &&
         a.rotates == b.rotates && same(a.angle, b.angle) && same(a.angular_velocity, b.angular_velocity) &&
         same(a.inertia, b.inertia);
}

bool same_scene(const Scene& a, const Scene& b) {
  if (a.name != b.name || !same(a.world.gravity, b.world.gravity) || !same(a.world.restitution, b.world.restitution) ||
      !same(a.run.until, b.run.until) || a.run.max_events != b.run.max_events ||
      !same(a.run.frames_per_second, b.run.frames_per_second) || a.run.solver != b.run.solver ||
      a.bodies.size() != b.bodies.size())
    return false;
  for (std::size_t i = 0; i < a.bodies.size(); ++i)
    if (!same_body(a.bodies[i], b.bodies[i])) return false;
  return true;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  pge::LoadedScene loaded;
  try {
    loaded = pge::parse_scene(text, "fuzz.json");
  } catch (const pge::SceneError&) {
    return 0;  // rejected with a clear error: what the reader is for
  } catch (const std::exception& e) {
    pge::fuzz::fail_with_scene("fuzz_reader", std::string("parse_scene threw a non-SceneError: ") + e.what(), Scene{});
  }
  std::string written;
  try {
    written = pge::write_scene(loaded.scene, loaded.expect_json);
  } catch (const std::exception& e) {
    pge::fuzz::fail_with_scene("fuzz_reader", std::string("write_scene refused a scene the reader accepted: ") + e.what(),
                               loaded.scene);
  }
  try {
    const pge::LoadedScene back = pge::parse_scene(written, "fuzz-roundtrip.json");
    if (!same_scene(loaded.scene, back.scene) || back.expect_json != loaded.expect_json)
      pge::fuzz::fail_with_scene("fuzz_reader", "write_scene -> parse_scene changed the scene", loaded.scene);
  } catch (const std::exception& e) {
    pge::fuzz::fail_with_scene("fuzz_reader", std::string("parse_scene rejected what write_scene wrote: ") + e.what(),
                               loaded.scene);
  }
  pge::fuzz::check_scene(loaded.scene, "fuzz_reader");
  return 0;
}
