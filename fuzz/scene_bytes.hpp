// The byte format of the fuzz_engine target: a documented, total decoding of any byte string
// into a Scene (fuzz/README.md, "Byte format"), and its inverse for seeding the corpus from
// fixture scenes. Every byte string decodes to some scene; whether that scene is valid is
// validate_scene's to say, and the fuzz target skips the invalid ones.
#pragma once

#include "pge/scene.hpp"

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace pge::fuzz {

// At most this many bodies per decoded scene: enough for every contact category and for chains
// of simultaneous contacts, few enough that the O(n^2) overlap check after every event keeps
// executions fast.
inline constexpr std::size_t kMaxDecodedBodies = 12;
// A polygon has 3 + (count byte % kPolygonVertexChoices) vertices: 3 to 32.
inline constexpr std::size_t kPolygonVertexChoices = 30;

// Decodes bytes into a scene; missing trailing bytes read as zero. Body ids are "b0", "b1", ...
Scene decode_scene(std::span<const std::uint8_t> bytes);

// Whether encode_scene can carry the scene: every polygon among the first kMaxDecodedBodies
// bodies has at most 3 + kPolygonVertexChoices - 1 vertices.
bool encodable(const Scene& scene);

// The inverse of decode_scene, for encodable scenes: decoding the result gives back the scene
// bit for bit, except that ids become "b0", "b1", ..., the name is dropped, run.max_events and
// run.frames_per_second take their defaults, and only the first kMaxDecodedBodies bodies are
// kept (a subset of a valid scene is valid: fewer bodies cannot overlap more).
std::vector<std::uint8_t> encode_scene(const Scene& scene);

}  // namespace pge::fuzz
