// Scene files (pge/scene_io.hpp): parse a pge-scene/1 text, write it back and read that again,
// and the one-line error a bad scene gets. Links pge::io.
//
// Expected output, by hand: the scene has two bodies, a circle of mass 2 kg and a fixed segment;
// what the file leaves out takes the defaults of pge/scene.hpp: restitution -1 (the world's), a
// fixed body's mass the default 1 (unused: fixed is infinite mass), run.until 10 s. write_scene
// writes every double so that it reads back bit for bit: the same radius 0.1 and position. The
// bad scene's radius is -1: the error names the origin, the line and column of the value (line 4
// of kBadScene; the -1 starts at its 39th character), the body and the field.
#include "pge/scene_io.hpp"

#include <cstdio>
#include <string>

namespace {

constexpr const char* kScene = R"({
  "format": "pge-scene/1", "name": "drop",
  "world": {"gravity": [0, -9.81]},
  "bodies": [{"id": "ball", "circle": {"radius": 0.1}, "position": [0, 5.1], "mass": 2},
             {"id": "floor", "segment": {"a": [-1, 0], "b": [1, 0]}, "fixed": true}]
})";

constexpr const char* kBadScene = R"({
  "format": "pge-scene/1", "name": "bad",
  "bodies": [
  {"id": "ball", "circle": {"radius": -1}, "mass": 1}]
})";

}  // namespace

int main() {
  const pge::LoadedScene loaded = pge::parse_scene(kScene, "drop.json");
  const pge::Scene& s = loaded.scene;
  std::printf("%s: %zu bodies, until %g s, gravity %g m/s^2\n", s.name.c_str(), s.bodies.size(), s.run.until,
              s.world.gravity.y);
  for (const pge::BodyDesc& b : s.bodies) {
    std::printf("  %s: %s, mass %g, restitution %g\n", b.id.c_str(), b.fixed ? "fixed" : "moving", b.mass,
                b.restitution);
  }

  // Written and read back: the same doubles.
  const std::string text = pge::write_scene(s);
  const pge::Scene again = pge::parse_scene(text, "written.json").scene;
  std::printf("read back: radius %g, position (%g, %g), same: %s\n", again.bodies[0].radius,
              again.bodies[0].position.x, again.bodies[0].position.y,
              again.bodies[0].radius == s.bodies[0].radius && again.bodies[0].position == s.bodies[0].position
                  ? "yes"
                  : "no");

  try {
    pge::parse_scene(kBadScene, "bad.json");
  } catch (const pge::SceneError& e) {
    std::printf("error: %s\n", e.what());
    std::printf("  line %d, body \"%s\", field \"%s\"\n", e.line(), e.body_id().c_str(), e.field().c_str());
  }
}
