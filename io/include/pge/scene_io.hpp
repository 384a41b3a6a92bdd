// Reading and writing scene files (JSON, format "pge-scene/1", or "pge-scene/2" with rotation; see fixtures/README.md): the
// pge::Scene (pge/scene.hpp) that World, the referee and judge_trace take. Units are the file's:
// seconds, metres, kilograms (m/s, m/s^2); nothing is converted. Link pge::io.
//
//   try {
//     const pge::LoadedScene loaded = pge::read_scene_file("drop.json");
//     pge::World<double> world(loaded.scene);
//   } catch (const pge::SceneError& e) {
//     std::cerr << e.what() << "\n";   // drop.json:4:39: body "ball" (bodies[0]): field ...
//   }
//
// A whole program (parse, write back, a bad scene's error) with its output: docs/api.md,
// "pge/scene_io.hpp" (docs/examples/scene_io.cpp).
#pragma once

#include "pge/scene.hpp"

#include <stdexcept>
#include <string>
#include <string_view>

namespace pge {

// Where a scene error is; each part is optional except the file.
struct SceneErrorPlace {
  std::string file;     // path or origin name
  int line = 0;         // 1-based; 0 when unknown
  int column = 0;       // 1-based, in bytes; 0 when unknown
  int body_index = -1;  // index into "bodies"; -1 when the error is not inside a body
  std::string body_id;  // "" when the body has no readable id
  std::string field;    // dotted path, relative to the body when inside one: "circle.radius",
                        // "velocity[1]", "world.gravity[0]", "run.until"; may be ""
};

// A bad scene. what() is one line:
//   FILE:LINE:COL: body "ID" (bodies[3]): field "circle.radius": must be positive and finite, got -1
// with the parts that are unknown left out.
class SceneError : public std::runtime_error {
 public:
  SceneError(SceneErrorPlace place, std::string reason);
  // An error about the file as a whole (cannot be opened, read or written).
  SceneError(const std::string& file, std::string reason);

  const std::string& file() const { return place_.file; }
  int line() const { return place_.line; }
  int column() const { return place_.column; }
  int body_index() const { return place_.body_index; }
  const std::string& body_id() const { return place_.body_id; }
  const std::string& field() const { return place_.field; }
  const std::string& reason() const { return reason_; }

 private:
  SceneErrorPlace place_;
  std::string reason_;
};

// Longest excerpt of a value, key, id or field quoted in a scene error (the reader's, and the
// expect block's in `pge check`): a message stays one readable line whatever the file holds.
constexpr std::size_t kMaxQuoted = 80;
// `text` itself if it has at most kMaxQuoted bytes; else its first kMaxQuoted bytes (fewer, to
// end on a whole UTF-8 character) and "...".
std::string excerpt(std::string_view text);

struct LoadedScene {
  Scene scene;
  std::string expect_json;  // the "expect" object's text exactly as in the file; "" if absent
  std::string path;         // where it was read from (the origin given to parse_scene)
};

// Both throw SceneError for anything wrong: unreadable file, malformed JSON, a format violation,
// or a problem found by validate_scene. A scene they return is valid: World accepts it (or
// throws UnsupportedScene for what this engine version does not simulate). Left-out fields take
// the defaults of pge/scene.hpp. `origin` is the name errors give the text (a path, "<stdin>").
LoadedScene read_scene_file(const std::string& path);
LoadedScene parse_scene(std::string_view text, const std::string& origin);

// Pretty JSON, one body per line. Every double is written in shortest round-trip form, so that
// parse_scene(write_scene(s, e)) gives back s bit for bit and e (trimmed) as expect_json, for
// every scene the reader accepts. Fields equal (bitwise) to their defaults are left out.
// `expect_json` is "" or the text of a JSON object, embedded as it is. Throws
// std::invalid_argument for any other expect_json, or for a name or id that is not UTF-8.
std::string write_scene(const Scene& scene, std::string_view expect_json = {});
// Throws SceneError if the file cannot be written.
void write_scene_file(const Scene& scene, const std::string& path,
                      std::string_view expect_json = {});

}  // namespace pge
