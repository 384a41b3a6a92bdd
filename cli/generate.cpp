#include "generate.hpp"

#include "exit_codes.hpp"

#include "pge/scene_io.hpp"
#include "pge/validate.hpp"

#include <fmt/core.h>

namespace pge::cli {

int generate_command(const GenerateOptions& opt) {
  const Scene scene = opt.family == "pegs"       ? make_pegs(opt.gas)
                      : opt.family == "polygons" ? make_polygons(opt.gas)
                                                 : make_gas(opt.gas);
  if (auto problem = validate_scene(scene)) {
    fmt::print(stderr, "pge generate: these parameters give an invalid scene: {}: {}\n", problem->field,
               problem->message);
    return kExitUsage;
  }
  if (opt.out.empty() || opt.out == "-") {
    fmt::print("{}", write_scene(scene));
    return kExitOk;
  }
  try {
    write_scene_file(scene, opt.out);
  } catch (const SceneError& e) {
    fmt::print(stderr, "pge generate: {}\n", e.what());
    return kExitOutput;
  }
  return kExitOk;
}

}  // namespace pge::cli
