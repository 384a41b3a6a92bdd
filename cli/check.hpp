// `pge check`: run the engine on scenes and judge every event against the exact oracle.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace pge::cli {

struct CheckOptions {
  std::vector<std::string> scenes;   // files or directories (every *.json inside, sorted)
  double until = -1;                 // < 0: each scene's run.until
  std::uint64_t max_events = 0;      // 0: each scene's run.max_events
  std::string scalar = "double";     // float, double, long-double, quad
  std::string solver;                // fast, robust, certified; empty: each scene's run.solver
  std::string json;                  // summaries and per-event verdicts as one JSON document
  bool no_filter = false;            // solve every pair exactly (slow; same verdicts)
  bool quiet = false;                // no summary on stdout
  bool progress = false;             // progress line on stderr
};

int check_command(const CheckOptions& options);

}  // namespace pge::cli
