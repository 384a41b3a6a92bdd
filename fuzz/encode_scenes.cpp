// Seeds the fuzz_engine corpus: encodes scene files into the target's byte format
// (scene_bytes.hpp) and checks that each decodes back to the same scene.
// Usage: pge_fuzz_encode OUT_DIR SCENE.json...
#include "scene_bytes.hpp"

#include "pge/scene_io.hpp"

#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <span>
#include <string>

namespace {

// What decode(encode(s)) gives back: s with the parts the byte format does not carry reset.
pge::Scene carried_part(const pge::Scene& s) {
  pge::Scene out = s;
  out.name.clear();
  out.run.max_events = pge::RunDesc{}.max_events;
  out.run.frames_per_second = pge::RunDesc{}.frames_per_second;
  if (out.bodies.size() > pge::fuzz::kMaxDecodedBodies) out.bodies.resize(pge::fuzz::kMaxDecodedBodies);
  for (std::size_t i = 0; i < out.bodies.size(); ++i) out.bodies[i].id = "b" + std::to_string(i);
  return out;
}

}  // namespace

// --decode FILE...: prints the scene each input decodes to, as JSON (to turn a libFuzzer
// artifact into a fixture).
int decode_files(int argc, char** argv) {
  for (int i = 2; i < argc; ++i) {
    std::ifstream in(argv[i], std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const auto* data = reinterpret_cast<const std::uint8_t*>(bytes.data());
    std::fputs(pge::write_scene(pge::fuzz::decode_scene(std::span<const std::uint8_t>(data, bytes.size()))).c_str(),
               stdout);
  }
  return 0;
}

int main(int argc, char** argv) {
  if (argc >= 2 && std::string(argv[1]) == "--decode") return decode_files(argc, argv);
  if (argc < 3) {
    std::fprintf(stderr, "usage: %s OUT_DIR SCENE.json...\n       %s --decode INPUT...\n", argv[0], argv[0]);
    return 2;
  }
  const std::filesystem::path out_dir = argv[1];
  std::filesystem::create_directories(out_dir);
  int written = 0, failed = 0;
  for (int i = 2; i < argc; ++i) {
    try {
      const pge::Scene scene = pge::read_scene_file(argv[i]).scene;
      if (!pge::fuzz::encodable(scene)) {
        std::fprintf(stderr, "%s: skipped: a polygon has more vertices than the byte format carries\n", argv[i]);
        continue;
      }
      const auto bytes = pge::fuzz::encode_scene(scene);
      const pge::Scene back = pge::fuzz::decode_scene(bytes);
      if (pge::write_scene(back) != pge::write_scene(carried_part(scene))) {
        std::fprintf(stderr, "%s: encoding does not decode to the same scene\n", argv[i]);
        ++failed;
        continue;
      }
      const auto path = out_dir / (std::filesystem::path(argv[i]).stem().string() + ".bin");
      std::ofstream f(path, std::ios::binary);
      f.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
      if (!f) {
        std::fprintf(stderr, "%s: cannot write\n", path.c_str());
        ++failed;
        continue;
      }
      ++written;
    } catch (const std::exception& e) {
      std::fprintf(stderr, "%s\n", e.what());  // a bad fixture is not a seed
    }
  }
  std::printf("%d seeds written to %s\n", written, out_dir.c_str());
  return failed == 0 ? 0 : 1;
}
