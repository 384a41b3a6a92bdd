// `pge run`: simulate scenes, print a summary, write event traces.
#pragma once

#include "pge/roots.hpp"
#include "pge/scalar.hpp"
#include "pge/world.hpp"

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace pge::cli {

struct RunOptions {
  std::vector<std::string> scenes;  // files or directories (every *.json inside, sorted)
  double until = -1;                // < 0: each scene's run.until
  std::uint64_t max_events = 0;     // 0: each scene's run.max_events
  double frames = -1;               // < 0: each scene's run.frames_per_second
  std::string trace;                // one scene: its JSON Lines trace
  std::string trace_dir;            // several scenes: DIR/<scene file stem>.jsonl
  std::string json_summary;         // all summaries as one JSON array
  ScalarKind scalar = ScalarKind::Double;
  std::optional<SolverKind> solver;  // nothing: each scene's run.solver
  BroadPhase broad_phase = BroadPhase::Auto;
  bool quiet = false;               // no summary on stdout (errors still go to stderr)
  bool progress = false;            // progress line on stderr (default: when it is a terminal)
};

int run_command(const RunOptions& options);

}  // namespace pge::cli
