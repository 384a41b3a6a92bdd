// `pge compare SCENE [--peers box2d,chipmunk]`: one scene run by PGE and by the installed peers at
// their default settings (pge/peers.hpp), as a Markdown table (and JSON); each peer's run is
// recorded as a step trace and judged by the exact referee (pge/judge.hpp), contact by contact.
#pragma once

#include <string>
#include <vector>

namespace pge::cli {

struct CompareOptions {
  std::string scene;                                    // a scene file
  std::vector<std::string> peers{"box2d", "chipmunk"};  // peers to run beside PGE
  std::vector<std::string> solvers{"robust", "certified"};  // PGE's rows: every solver x scalar given
  std::vector<std::string> scalars{"double"};
  double until = 0;                                     // simulated seconds; <= 0: the scene's run.until
  std::string json;                                     // also write the rows here (JSON array); "" for none, "-" stdout
  bool quiet = false;                                   // no table on stdout
  bool no_judge = false;                                // leave out the exact referee's verdicts on the peers
  std::string trace_dir;                                // write each peer's step trace into this folder; "" for none
};

// Exit codes (exit_codes.hpp): 0 when PGE's rows ran (a peer that is not installed is skipped
// with a message), 2 for an unknown peer name, 3 for a bad scene, 5 for a scene PGE does not
// simulate, 6 when --json or a --trace-dir file cannot be written. The referee's verdicts on the
// peers (misses, phantoms) are findings, not failures: they do not change the exit code.
int compare_command(const CompareOptions& options);

}  // namespace pge::cli
