// The check both fuzz targets run on a scene: the same invariants as the property tests and
// `pge fuzz` (properties/include/pge/invariants.hpp), on a short run.
#pragma once

#include "pge/scene.hpp"

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace pge::fuzz {

// Limits of one fuzz execution: libFuzzer wants thousands of executions per second, and a
// scene that misbehaves shows it within a few hundred events. A scene's own horizon and budget
// are kept when they are smaller.
inline constexpr double kFuzzUntil = 10;               // simulated seconds
inline constexpr std::uint64_t kFuzzMaxEvents = 500;   // collisions and grazes
// Scenes with more bodies are not run (the reader target still checks the round trip): the
// overlap check after each event is O(n^2).
inline constexpr std::size_t kFuzzMaxBodies = 64;

// Scenes validate_scene rejects are skipped (false). Otherwise runs the scene within the
// limits above and checks the invariants after every event; an event storm is not a failure
// (resting contact is not simulated yet). On a failure, prints what failed and the scene as
// JSON to stderr and aborts, which libFuzzer reports as a crash with the input saved.
bool check_scene(const Scene& scene, std::string_view target);

// Prints `what` and the scene (as JSON if it can be written) to stderr, then aborts.
[[noreturn]] void fail_with_scene(std::string_view target, const std::string& what, const Scene& scene);

}  // namespace pge::fuzz
