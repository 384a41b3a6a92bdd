// Finding and reading the scene files a command is given, and the errors every command reports
// the same way: one line "pge COMMAND: ..." on stderr and the exit code of exit_codes.hpp
// (kExitBadScene for a file that cannot be read, is malformed or invalid; kExitUnsupported for a
// valid scene the engine does not simulate yet).
#pragma once

#include "exit_codes.hpp"

#include "pge/scene_io.hpp"
#include "pge/world.hpp"

#include <fmt/core.h>

#include <cstdio>
#include <exception>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace pge::cli {

// Expands files and directories into a sorted list of scene files; throws std::runtime_error
// naming a path that does not exist.
std::vector<std::string> expand_scene_paths(const std::vector<std::string>& paths);

// Prints "pge COMMAND: WHAT" on stderr; returns kExitBadScene.
int bad_scene(std::string_view command, const std::exception& e);

// expand_scene_paths, or nothing after bad_scene (the command exits kExitBadScene).
std::optional<std::vector<std::string>> scene_files(std::string_view command, const std::vector<std::string>& paths);

// The scene file read, and `also` run on it (more reading that may throw SceneError: the expect
// block, say); or nothing after bad_scene (the command's exit code is kExitBadScene).
std::optional<LoadedScene> load_scene(std::string_view command, const std::string& path,
                                      const std::function<void(const LoadedScene&)>& also = {});

// Runs `simulate` (which builds a World of the scene read from `path`): kExitOk, or, when the
// World refuses the scene, the refusal printed "pge COMMAND: PATH: WHAT" after `before_error()`
// and its exit code: UnsupportedScene kExitUnsupported, std::invalid_argument kExitBadScene.
// Other exceptions pass through.
template <class Simulate, class BeforeError = void (*)()>
int simulate_scene(std::string_view command, const std::string& path, Simulate&& simulate,
                   BeforeError&& before_error = [] {}) {
  const auto refused = [&](const std::exception& e, int code) {
    before_error();
    fmt::print(stderr, "pge {}: {}: {}\n", command, path, e.what());
    return code;
  };
  try {
    simulate();
  } catch (const UnsupportedScene& e) {
    return refused(e, kExitUnsupported);
  } catch (const std::invalid_argument& e) {
    return refused(e, kExitBadScene);
  }
  return kExitOk;
}

}  // namespace pge::cli
