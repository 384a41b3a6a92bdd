// libFuzzer target: bytes -> scene (scene_bytes.hpp) -> a short run with every invariant
// checked after each event (fuzz_check.hpp). Invalid scenes are skipped, not failures.
#include "fuzz_check.hpp"
#include "scene_bytes.hpp"

#include <cstddef>
#include <cstdint>
#include <span>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const pge::Scene scene = pge::fuzz::decode_scene(std::span<const std::uint8_t>(data, size));
  pge::fuzz::check_scene(scene, "fuzz_engine");
  return 0;
}
