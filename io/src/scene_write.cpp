// Writing scene files: one body per line, doubles in shortest round-trip form; "pge-scene/1"
// unless a body has rotation, then "pge-scene/2".
#include "pge/scene_io.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <bit>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <fstream>

namespace pge {
namespace {

// Keeps keys in the order written, so files read top-down: id, shape, position, ...
using Json = nlohmann::ordered_json;

constexpr std::string_view kWhitespace = " \t\r\n";

// Defaults are left out only when bitwise equal: -0.0 == 0.0, but must still round-trip.
bool same_bits(double x, double y) {
  return std::bit_cast<std::uint64_t>(x) == std::bit_cast<std::uint64_t>(y);
}
bool same_bits(const Vec2d& u, const Vec2d& v) {
  return same_bits(u.x, v.x) && same_bits(u.y, v.y);
}

Json vec2(const Vec2d& v) { return Json::array({v.x, v.y}); }

Json shape_json(const BodyDesc& body) {
  switch (body.shape) {
    case ShapeKind::Circle:
      return Json::object({{"radius", body.radius}});
    case ShapeKind::Segment:
      return Json::object({{"a", vec2(body.a)}, {"b", vec2(body.b)}});
    case ShapeKind::Polygon: {
      Json vertices = Json::array();
      for (const Vec2d& v : body.vertices) vertices.push_back(vec2(v));
      return Json::object({{"vertices", std::move(vertices)}});
    }
  }
  return {};
}

const char* shape_key(ShapeKind kind) {
  switch (kind) {
    case ShapeKind::Circle:
      return "circle";
    case ShapeKind::Segment:
      return "segment";
    case ShapeKind::Polygon:
      return "polygon";
  }
  return "";
}

// Whether a body has anything of rotation (pge-scene/2), bitwise: -0.0 too must round-trip.
bool has_rotation(const BodyDesc& body) {
  const BodyDesc defaults;
  return body.rotates != defaults.rotates || !same_bits(body.angle, defaults.angle) ||
         !same_bits(body.angular_velocity, defaults.angular_velocity) || !same_bits(body.inertia, defaults.inertia);
}

// A fixed body's velocity, acceleration and mass are written only when they are not the
// defaults, which the reader then rejects: better a loud file than a silently changed scene.
// `rotation`: the file is pge-scene/2, whose default for "rotates" depends on the body.
Json body_json(const BodyDesc& body, bool rotation) {
  const BodyDesc defaults;
  Json out = Json::object();
  out["id"] = body.id;
  out[shape_key(body.shape)] = shape_json(body);
  if (!same_bits(body.position, defaults.position)) out["position"] = vec2(body.position);
  if (!same_bits(body.velocity, defaults.velocity)) out["velocity"] = vec2(body.velocity);
  if (!same_bits(body.acceleration, defaults.acceleration))
    out["acceleration"] = vec2(body.acceleration);
  if (body.fixed) out["fixed"] = true;
  if (!body.fixed || !same_bits(body.mass, defaults.mass)) out["mass"] = body.mass;
  if (body.gravity != defaults.gravity) out["gravity"] = body.gravity;
  // Any negative restitution means "the world's" (BodyDesc), which a file says by leaving the key
  // out: written as it is, it would not read back (found by fuzz_engine, whose byte decoder
  // gives bodies negative restitutions; the failing scene it printed was unreadable).
  if (!(body.restitution < 0)) out["restitution"] = body.restitution;
  if (rotation) {
    const bool rotates_by_default = !body.fixed && body.shape != ShapeKind::Circle;
    if (body.rotates != rotates_by_default) out["rotates"] = body.rotates;
    if (!same_bits(body.angle, defaults.angle)) out["angle"] = body.angle;
    if (!same_bits(body.angular_velocity, defaults.angular_velocity))
      out["angular_velocity"] = body.angular_velocity;
    if (!same_bits(body.inertia, defaults.inertia)) out["inertia"] = body.inertia;
  }
  return out;
}

// Compact JSON with a space after ':' and ','; nlohmann's dump writes each scalar, and writes a
// double as the shortest text that reads back to the same bits.
void append_inline(const Json& value, std::string& out) {
  if (value.is_object()) {
    out += '{';
    const char* separator = "";
    for (const auto& [key, item] : value.items()) {
      out += separator;
      out += Json(key).dump();
      out += ": ";
      append_inline(item, out);
      separator = ", ";
    }
    out += '}';
  } else if (value.is_array()) {
    out += '[';
    const char* separator = "";
    for (const Json& item : value) {
      out += separator;
      append_inline(item, out);
      separator = ", ";
    }
    out += ']';
  } else {
    out += value.dump();
  }
}

std::string inline_json(const Json& value) {
  std::string out;
  append_inline(value, out);
  return out;
}

std::string_view trimmed(std::string_view text) {
  const std::size_t begin = text.find_first_not_of(kWhitespace);
  if (begin == std::string_view::npos) return {};
  return text.substr(begin, text.find_last_not_of(kWhitespace) + 1 - begin);
}

}  // namespace

std::string write_scene(const Scene& scene, std::string_view expect_json) {
  const std::string_view expect = trimmed(expect_json);
  if (!expect.empty() && !Json::accept(expect))
    throw std::invalid_argument("write_scene: expect_json is not valid JSON");
  if (!expect.empty() && expect.front() != '{')
    throw std::invalid_argument("write_scene: expect_json must be a JSON object");

  const Json world = Json::object(
      {{"gravity", vec2(scene.world.gravity)}, {"restitution", scene.world.restitution}});
  Json run = Json::object({{"until", scene.run.until}, {"max_events", scene.run.max_events}});
  if (!same_bits(scene.run.frames_per_second, RunDesc{}.frames_per_second))
    run["frames_per_second"] = scene.run.frames_per_second;
  if (scene.run.solver != RunDesc{}.solver) run["solver"] = std::string(solver_name(scene.run.solver));

  const bool rotation = std::any_of(scene.bodies.begin(), scene.bodies.end(), has_rotation);
  try {
    std::string out = "{\n";
    out += fmt::format("  \"format\": \"{}\",\n", rotation ? "pge-scene/2" : "pge-scene/1");
    out += fmt::format("  \"name\": {},\n", Json(scene.name).dump());
    out += fmt::format("  \"world\": {},\n", inline_json(world));
    if (scene.bodies.empty()) {
      out += "  \"bodies\": [],\n";
    } else {
      out += "  \"bodies\": [\n";
      for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
        out += "    " + inline_json(body_json(scene.bodies[i], rotation));
        out += i + 1 < scene.bodies.size() ? ",\n" : "\n";
      }
      out += "  ],\n";
    }
    out += fmt::format("  \"run\": {}", inline_json(run));
    if (!expect.empty()) out += fmt::format(",\n  \"expect\": {}", expect);
    out += "\n}\n";
    return out;
  } catch (const Json::type_error& error) {
    // The one way dump fails: a name or id that is not valid UTF-8.
    throw std::invalid_argument(fmt::format("write_scene: {}", error.what()));
  }
}

void write_scene_file(const Scene& scene, const std::string& path, std::string_view expect_json) {
  const std::string text = write_scene(scene, expect_json);
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out)
    throw SceneError(path, fmt::format("cannot open for writing: {}", std::strerror(errno)));
  out << text;
  out.close();
  if (!out) throw SceneError(path, fmt::format("cannot write: {}", std::strerror(errno)));
}

}  // namespace pge
