// `pge check`: run the engine on scenes, judge every event against the exact oracle, and hold
// each run to its scene's expect block (fixtures/README.md, "Expectations").
#pragma once

#include "pge/roots.hpp"
#include "pge/scene_io.hpp"

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
  bool all_solvers = false;          // run each scene with fast, robust and certified
  bool table = false;                // a Markdown table, one row per scene (implies all_solvers)
  std::string table_out;             // write the table to this file; empty: stdout, instead of the summaries
  std::string json;                  // summaries and per-event verdicts as one JSON document
  bool no_filter = false;            // solve every pair exactly (slow; same verdicts)
  bool quiet = false;                // no summary on stdout
  bool progress = false;             // progress line on stderr
};

int check_command(const CheckOptions& options);

struct SceneCheck;
// One run of `loaded` with `solver` in `scalar`, every event judged by the oracle, without an
// expect block and without printing: what `pge report` measures accuracy with. Throws what the
// engine throws (UnsupportedScene, std::invalid_argument, std::logic_error from validation).
SceneCheck judged_run(const LoadedScene& loaded, SolverKind solver, const std::string& scalar, double until,
                      std::uint64_t max_events);

}  // namespace pge::cli
