// `pge compare SCENE [--peers box2d,chipmunk]`: one scene run by PGE and by the installed peers at
// their default settings (pge/peers.hpp), as a Markdown table (and JSON).
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
  std::string json;                                     // also write the rows here (JSON array); "" for none
  bool quiet = false;                                   // no table on stdout
};

// Exit codes (exit_codes.hpp): 0 when PGE's rows ran (a peer that is not installed is skipped
// with a message), 2 for an unknown peer name, 3 for a bad scene, 5 for a scene PGE does not
// simulate, 6 when --json cannot be written.
int compare_command(const CompareOptions& options);

}  // namespace pge::cli
