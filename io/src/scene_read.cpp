// Reading "pge-scene/1" and "pge-scene/2" files. The format is documented in fixtures/README.md.
#include "json_path.hpp"
#include "json_text.hpp"
#include "pge/scene_io.hpp"
#include "pge/validate.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <initializer_list>
#include <iterator>
#include <map>

namespace pge {
namespace {

using Json = nlohmann::json;

// pge-scene/2 adds the rotation keys, and makes moving polygons and segments rotate unless they
// say "rotates": false; every pge-scene/1 body is translate-only.
constexpr std::string_view kFormat1 = "pge-scene/1";
constexpr std::string_view kFormat2 = "pge-scene/2";
constexpr std::array<const char*, 4> kRotationKeys = {"rotates", "angle", "angular_velocity", "inertia"};
// The deepest nesting of [ and { a file may have (documented in fixtures/README.md). A scene
// needs 6 (the file, "bodies", a body, "polygon", "vertices", a vertex) and an expect block
// about as many; the limit is far above both and far below what would make a 100,000-deep
// file slow or its messages huge (see nesting_too_deep).
constexpr int kMaxDepth = 64;
// max_events may also be written as an integral float (1e6); below 2^64 it converts exactly.
constexpr double kMaxEventsLimit = 18446744073709551616.0;

std::string quoted_list(std::initializer_list<std::string_view> names) {
  std::string out;
  for (std::string_view name : names) out += fmt::format("{}\"{}\"", out.empty() ? "" : ", ", name);
  return out;
}

// Whether `path` is in a body, bodies[i] or below it.
bool in_body(const JsonPath& path) {
  return path.size() >= 2 && path[0].index < 0 && path[0].key == "bodies" && path[1].index >= 0;
}

class SceneReader {
 public:
  SceneReader(std::string_view text, const std::string& origin) : text_(text), origin_(origin) {}

  LoadedScene read() {
    const Json root = parse_json();
    LoadedScene loaded;
    loaded.path = origin_;
    loaded.scene = read_scene(root);
    if (root.contains("expect")) {
      const JsonPath path = JsonPath{} + "expect";
      object_at(root["expect"], path);
      const std::size_t begin = find_value(text_, path);
      loaded.expect_json = std::string(text_.substr(begin, value_end(text_, begin) - begin));
    }
    if (const auto problem = validate_scene(loaded.scene)) report(*problem, loaded.scene);
    return loaded;
  }

 private:
  // --- errors --------------------------------------------------------------------------------

  // The place of an error at `path` and `offset`. The body's id is the last "id" at its path in
  // text_[0, id_end): the whole text when it is valid JSON.
  SceneErrorPlace place(const JsonPath& path, std::size_t offset,
                        std::size_t id_end = std::string_view::npos) const {
    SceneErrorPlace where;
    where.file = origin_;
    if (offset != std::string_view::npos) {
      const TextPosition pos = text_position(text_, offset);
      where.line = pos.line;
      where.column = pos.column;
    }
    if (in_body(path)) {
      where.body_index = path[1].index;
      const std::string_view text = text_.substr(0, id_end);
      const std::size_t id = find_value(text, JsonPath{path[0], path[1]} + "id");
      if (id != std::string_view::npos) where.body_id = string_literal(text, id);
    }
    where.field = dotted(path, in_body(path) ? 2 : 0);
    return where;
  }

  // Where the value at `path` starts or, when it is absent, the nearest enclosing value:
  // a missing key is reported at the object that lacks it.
  std::size_t locate(JsonPath path) const {
    for (;; path.pop_back()) {
      const std::size_t offset = find_value(text_, path);
      if (offset != std::string_view::npos || path.empty()) return offset;
    }
  }

  [[noreturn]] void fail(const JsonPath& path, const std::string& reason) const {
    throw SceneError(place(path, locate(path)), reason);
  }

  // An error at `offset` in a file that parsed (a duplicate key, a number out of range).
  [[noreturn]] void fail_at(std::size_t offset, const std::string& reason) const {
    const JsonPath path =
        walk_json(text_, offset, [](const JsonToken&, const JsonPath&) { return true; });
    throw SceneError(place(path, offset), reason);
  }

  // An error at `offset` in text that did not parse: a syntax error, or nesting past the limit.
  // Past the error the walk's indices drift from the file's (a missing comma does not advance
  // them), so the last "id" at bodies[i] in the whole text may be another body's: an error just
  // after body 1 was named body "c" (bodies[1]). The body named is the last one begun before the
  // error, with the id inside its own braces; an error between two bodies (after one closed,
  // before the next opens) names the one before it.
  [[noreturn]] void fail_unparsed(std::size_t offset, const std::string& reason) const {
    int body = -1;
    std::size_t body_begin = std::string_view::npos;
    JsonPath path = walk_json(text_, offset, [&](const JsonToken& token, const JsonPath& at) {
      if (!token.is_key && at.size() == 2 && in_body(at) && text_[token.begin] == '{') {
        body = at[1].index;
        body_begin = token.begin;
      }
      return true;
    });
    if (path.size() == 2 && in_body(path) && body >= 0) path[1].index = body;
    const bool begun = in_body(path) && path[1].index == body;
    throw SceneError(place(path, offset, begun ? value_end(text_, body_begin) : 0), reason);
  }

  [[noreturn]] void report(const SceneProblem& problem, const Scene& scene) const {
    JsonPath path = parse_dotted(problem.field);
    if (problem.body >= 0)
      path.insert(path.begin(), {PathStep{"bodies", -1}, PathStep{"", problem.body}});
    SceneErrorPlace where = place(path, locate(path));
    where.field = problem.field;  // as the engine named it
    if (problem.body >= 0 && problem.body < static_cast<int>(scene.bodies.size()))
      where.body_id = scene.bodies[static_cast<std::size_t>(problem.body)].id;
    throw SceneError(where, problem.message);
  }

  // --- text level ----------------------------------------------------------------------------

  Json parse_json() const {
    if (const std::size_t deep = nesting_too_deep(text_, kMaxDepth); deep != std::string_view::npos)
      fail_unparsed(deep,
                    fmt::format("nested more than {} levels deep (a scene needs 6)", kMaxDepth));
    Json root;
    bool overflow = false;
    try {
      root = Json::parse(text_.begin(), text_.end());
    } catch (const Json::parse_error& error) {
      const std::size_t offset =
          std::min<std::size_t>(error.byte > 0 ? error.byte - 1 : 0, text_.size());
      if (is_nan_or_infinity(word_at(text_, offset)))
        fail_unparsed(offset,
                      fmt::format("{} is not a JSON number; NaN and infinities are not allowed",
                                  word_at(text_, offset)));
      fail_unparsed(offset, syntax_reason(error));
    } catch (const Json::out_of_range&) {
      overflow = true;  // located by check_tokens
    }
    check_tokens();
    if (overflow) fail_at(0, "a number is out of range for a double");
    return root;
  }

  // What the parser accepts silently but a scene must not: duplicate keys (the parser keeps the
  // last, hiding the first) and numbers no double can hold.
  void check_tokens() const {
    if (const auto problem = token_problem(text_)) fail_at(problem->offset, problem->reason);
  }

  // --- values --------------------------------------------------------------------------------

  const Json& object_at(const Json& value, const JsonPath& path) const {
    if (!value.is_object()) fail(path, "must be an object {...}, got " + describe(value));
    return value;
  }

  void allow_keys(const Json& object, const JsonPath& path,
                  std::initializer_list<std::string_view> known) const {
    for (const auto& [key, value] : object.items()) {
      if (std::find(known.begin(), known.end(), key) == known.end())
        fail(path + key, fmt::format("unknown key \"{}\"; known keys are {}", excerpt(key),
                                     quoted_list(known)));
    }
  }

  const Json& required(const Json& object, const JsonPath& path, const char* key) const {
    if (!object.contains(key)) fail(path + key, "missing; it is required");
    return object[key];
  }

  double number_at(const Json& value, const JsonPath& path) const {
    // Parsed JSON numbers are always finite: NaN, infinities and overflow fail in parse_json.
    if (!value.is_number()) fail(path, "must be a number, got " + describe(value));
    return value.get<double>();
  }

  double fraction_at(const Json& value, const JsonPath& path) const {
    const double x = number_at(value, path);
    if (!(x >= 0 && x <= 1)) fail(path, "must be in [0, 1], got " + describe(value));
    return x;
  }

  Vec2d vec2_at(const Json& value, const JsonPath& path) const {
    if (!value.is_array() || value.size() != 2)
      fail(path, "must be an array [x, y] of 2 numbers, got " + describe(value));
    return {number_at(value[0], path + 0), number_at(value[1], path + 1)};
  }

  bool bool_at(const Json& value, const JsonPath& path) const {
    if (!value.is_boolean()) fail(path, "must be true or false, got " + describe(value));
    return value.get<bool>();
  }

  std::string string_at(const Json& value, const JsonPath& path) const {
    if (!value.is_string()) fail(path, "must be a string, got " + describe(value));
    return value.get<std::string>();
  }

  // --- the scene -----------------------------------------------------------------------------

  Scene read_scene(const Json& root) {
    const JsonPath top;
    object_at(root, top);
    // The format first: for a file that is not a scene, the other complaints would mislead.
    const std::string format = string_at(required(root, top, "format"), top + "format");
    if (format != kFormat1 && format != kFormat2)
      fail(top + "format", fmt::format("must be \"{}\" or \"{}\", got {}", kFormat1, kFormat2,
                                       describe(root["format"])));
    rotation_ = format == kFormat2;
    allow_keys(root, top, {"format", "name", "world", "bodies", "run", "expect"});

    Scene scene;
    if (root.contains("name")) scene.name = string_at(root["name"], top + "name");
    if (root.contains("world")) scene.world = read_world(root["world"], top + "world");
    if (root.contains("run")) scene.run = read_run(root["run"], top + "run");

    const JsonPath bodies_path = top + "bodies";
    const Json& bodies = required(root, top, "bodies");
    if (!bodies.is_array()) fail(bodies_path, "must be an array [...], got " + describe(bodies));
    std::map<std::string, int> index_of_id;
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      const JsonPath path = bodies_path + static_cast<int>(i);
      BodyDesc body = read_body(bodies[i], path);
      const auto [it, fresh] = index_of_id.emplace(body.id, static_cast<int>(i));
      if (!fresh)
        fail(path + "id", fmt::format("duplicate id; bodies[{}] has it already", it->second));
      scene.bodies.push_back(std::move(body));
    }
    return scene;
  }

  WorldDesc read_world(const Json& value, const JsonPath& path) const {
    const Json& world = object_at(value, path);
    allow_keys(world, path, {"gravity", "restitution"});
    WorldDesc out;
    if (world.contains("gravity")) out.gravity = vec2_at(world["gravity"], path + "gravity");
    if (world.contains("restitution"))
      out.restitution = fraction_at(world["restitution"], path + "restitution");
    return out;
  }

  RunDesc read_run(const Json& value, const JsonPath& path) const {
    const Json& run = object_at(value, path);
    allow_keys(run, path, {"until", "max_events", "frames_per_second", "solver"});
    RunDesc out;
    if (run.contains("until")) {
      out.until = number_at(run["until"], path + "until");
      if (!(out.until > 0)) fail(path + "until", "must be positive, got " + describe(run["until"]));
    }
    if (run.contains("max_events"))
      out.max_events = read_max_events(run["max_events"], path + "max_events");
    if (run.contains("frames_per_second")) {
      out.frames_per_second = number_at(run["frames_per_second"], path + "frames_per_second");
      if (!(out.frames_per_second >= 0))
        fail(path + "frames_per_second",
             "must be 0 (no frames) or positive, got " + describe(run["frames_per_second"]));
    }
    if (run.contains("solver")) {
      const std::string name = string_at(run["solver"], path + "solver");
      if (!parse_solver_kind(name, out.solver))
        fail(path + "solver",
             "must be \"fast\", \"robust\" or \"certified\", got \"" + excerpt(name) + "\"");
    }
    return out;
  }

  std::uint64_t read_max_events(const Json& value, const JsonPath& path) const {
    std::uint64_t n = 0;
    if (value.is_number_unsigned()) {
      n = value.get<std::uint64_t>();
    } else if (value.is_number_float()) {
      const double x = value.get<double>();
      if (x >= 0 && x < kMaxEventsLimit && x == std::floor(x)) n = static_cast<std::uint64_t>(x);
    }
    if (n == 0) fail(path, "must be a positive integer, got " + describe(value));
    return n;
  }

  BodyDesc read_body(const Json& value, const JsonPath& path) const {
    const Json& body = object_at(value, path);
    if (!rotation_) {
      for (const char* key : kRotationKeys)
        if (body.contains(key))
          fail(path + key, fmt::format("needs \"format\": \"{}\" (a {} body does not rotate)", kFormat2,
                                       kFormat1));
    }
    if (rotation_)
      allow_keys(body, path,
                 {"id", "circle", "segment", "polygon", "position", "velocity", "acceleration", "fixed", "mass",
                  "gravity", "restitution", "rotates", "angle", "angular_velocity", "inertia"});
    else
      allow_keys(body, path,
                 {"id", "circle", "segment", "polygon", "position", "velocity", "acceleration",
                  "fixed", "mass", "gravity", "restitution"});
    BodyDesc out;
    out.id = string_at(required(body, path, "id"), path + "id");
    if (out.id.empty()) fail(path + "id", "must not be empty");
    read_shape(body, path, out);
    if (body.contains("position")) out.position = vec2_at(body["position"], path + "position");
    if (body.contains("fixed")) out.fixed = bool_at(body["fixed"], path + "fixed");
    if (out.fixed) {
      // Clearer than ignoring them: a fixed body never moves, so these would be silently lost.
      for (const char* key : {"velocity", "acceleration", "mass"}) {
        if (body.contains(key)) fail(path + key, "not allowed on a fixed body (it never moves)");
      }
    } else {
      if (body.contains("velocity")) out.velocity = vec2_at(body["velocity"], path + "velocity");
      if (body.contains("acceleration"))
        out.acceleration = vec2_at(body["acceleration"], path + "acceleration");
      if (!body.contains("mass")) fail(path + "mass", "missing; required unless \"fixed\": true");
      out.mass = number_at(body["mass"], path + "mass");  // > 0 is validate_scene's to check
    }
    if (body.contains("gravity")) out.gravity = bool_at(body["gravity"], path + "gravity");
    if (body.contains("restitution"))
      out.restitution = fraction_at(body["restitution"], path + "restitution");
    if (rotation_) read_rotation(body, path, out);
    return out;
  }

  // pge-scene/2: moving polygons and segments rotate unless they say otherwise; a fixed body
  // rotates only when it says so. Ranges and where each key may appear are validate_scene's.
  void read_rotation(const Json& body, const JsonPath& path, BodyDesc& out) const {
    out.rotates = !out.fixed && out.shape != ShapeKind::Circle;
    if (body.contains("rotates")) out.rotates = bool_at(body["rotates"], path + "rotates");
    if (body.contains("angle")) out.angle = number_at(body["angle"], path + "angle");
    if (body.contains("angular_velocity"))
      out.angular_velocity = number_at(body["angular_velocity"], path + "angular_velocity");
    if (body.contains("inertia")) {
      out.inertia = number_at(body["inertia"], path + "inertia");
      // In memory 0 means "computed from the shape"; in a file it is a mistake.
      if (!(out.inertia > 0))
        fail(path + "inertia", "must be positive (leave it out for a uniform lamina), got " +
                                   describe(body["inertia"]));
    }
  }

  void read_shape(const Json& body, const JsonPath& path, BodyDesc& out) const {
    std::vector<std::string> shapes;
    for (const char* key : {"circle", "segment", "polygon"}) {
      if (body.contains(key)) shapes.emplace_back(key);
    }
    if (shapes.empty())
      fail(path, "no shape; give exactly one of \"circle\", \"segment\", \"polygon\"");
    if (shapes.size() > 1)
      fail(path + shapes[1],
           fmt::format("a second shape; \"{}\" is given already, give exactly one", shapes[0]));
    const JsonPath shape_path = path + shapes[0];
    const Json& shape = object_at(body[shapes[0]], shape_path);
    if (shapes[0] == "circle") {
      allow_keys(shape, shape_path, {"radius"});
      out.shape = ShapeKind::Circle;
      out.radius = number_at(required(shape, shape_path, "radius"), shape_path + "radius");
    } else if (shapes[0] == "segment") {
      allow_keys(shape, shape_path, {"a", "b"});
      out.shape = ShapeKind::Segment;
      out.a = vec2_at(required(shape, shape_path, "a"), shape_path + "a");
      out.b = vec2_at(required(shape, shape_path, "b"), shape_path + "b");
    } else {
      allow_keys(shape, shape_path, {"vertices"});
      out.shape = ShapeKind::Polygon;
      const JsonPath vertices_path = shape_path + "vertices";
      const Json& vertices = required(shape, shape_path, "vertices");
      if (!vertices.is_array())
        fail(vertices_path, "must be an array [[x, y], ...], got " + describe(vertices));
      for (std::size_t i = 0; i < vertices.size(); ++i)
        out.vertices.push_back(vec2_at(vertices[i], vertices_path + static_cast<int>(i)));
    }
  }

  std::string_view text_;
  std::string origin_;
  bool rotation_ = false;  // a pge-scene/2 file
};

}  // namespace

LoadedScene parse_scene(std::string_view text, const std::string& origin) {
  return SceneReader(text, origin.empty() ? "<string>" : origin).read();
}

LoadedScene read_scene_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw SceneError(path, fmt::format("cannot open: {}", std::strerror(errno)));
  std::string text;
  try {
    // libstdc++ reports a read error (say, of a directory) by throwing from the iterator.
    text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  } catch (const std::ios_base::failure&) {
    in.setstate(std::ios::badbit);
  }
  if (in.bad()) throw SceneError(path, fmt::format("cannot read: {}", std::strerror(errno)));
  return parse_scene(text, path);
}

}  // namespace pge
