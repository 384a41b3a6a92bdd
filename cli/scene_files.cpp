#include "scene_files.hpp"

#include <algorithm>
#include <filesystem>

namespace pge::cli {

namespace fs = std::filesystem;

std::vector<std::string> expand_scene_paths(const std::vector<std::string>& paths) {
  std::vector<std::string> out;
  for (const std::string& p : paths) {
    std::error_code ec;
    if (fs::is_directory(p, ec)) {
      std::vector<std::string> found;
      for (const auto& entry : fs::recursive_directory_iterator(p))
        if (entry.is_regular_file() && entry.path().extension() == ".json") found.push_back(entry.path().string());
      std::sort(found.begin(), found.end());
      if (found.empty()) throw std::runtime_error(p + ": directory holds no *.json scene files");
      out.insert(out.end(), found.begin(), found.end());
    } else if (fs::exists(p, ec)) {
      out.push_back(p);
    } else {
      throw std::runtime_error(p + ": no such file or directory");
    }
  }
  return out;
}

int bad_scene(std::string_view command, const std::exception& e) {
  fmt::print(stderr, "pge {}: {}\n", command, e.what());
  return kExitBadScene;
}

std::optional<std::vector<std::string>> scene_files(std::string_view command, const std::vector<std::string>& paths) {
  try {
    return expand_scene_paths(paths);
  } catch (const std::exception& e) {
    bad_scene(command, e);
    return std::nullopt;
  }
}

std::optional<LoadedScene> load_scene(std::string_view command, const std::string& path,
                                      const std::function<void(const LoadedScene&)>& also) {
  try {
    LoadedScene loaded = read_scene_file(path);
    if (also) also(loaded);
    return loaded;
  } catch (const SceneError& e) {
    bad_scene(command, e);
    return std::nullopt;
  }
}

}  // namespace pge::cli
