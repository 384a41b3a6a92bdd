// `pge render`: a picture of a scene and its trajectory, collision points marked: a static SVG,
// or a self-contained HTML page that animates it (no network, no external files).
#pragma once

#include "pge/scene_io.hpp"

#include <cstdint>
#include <string>

namespace pge::cli {

struct RenderOptions {
  std::string scene;             // one scene file
  double until = -1;             // < 0: the scene's run.until
  std::uint64_t max_events = 0;  // 0: the scene's run.max_events
  std::string out;               // FILE.svg or FILE.html (the extension chooses the form)
  std::string solver;            // fast, robust, certified; empty: the scene's run.solver
  double frames = 60;            // trajectory samples per simulated second (>0)
  bool quiet = false;            // no one-line summary on stdout
};

int render_command(const RenderOptions& options);

// What `pge report` embeds for a fixture family: the SVG document (an <svg> element, no XML
// prolog) of `loaded` simulated with the robust solver in double up to `until` (< 0: the scene's
// run.until), at most `max_events` collisions (0: the scene's). Throws what the engine throws.
std::string render_svg(const LoadedScene& loaded, double until, std::uint64_t max_events, int width_px);

}  // namespace pge::cli
