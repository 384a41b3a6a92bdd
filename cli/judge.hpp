// `pge judge TRACE --scene SCENE`: another engine's trace (pge-trace/2, events or steps mode)
// judged by the exact referee (pge/judge.hpp); a summary, per-contact verdicts in JSON.
#pragma once

#include <string>

namespace pge::cli {

struct JudgeCommandOptions {
  std::string trace;  // a pge-trace/2 file
  std::string scene;  // the scene it is a run of
  std::string json;   // also write the summary and every verdict here; "" for none
  double overlap_bound = 0.5;  // JudgeOptions::overlap_bound
  bool quiet = false;
};

// Exit codes (exit_codes.hpp): 0 when nothing failed; 7 for a miss or a phantom (as pge check);
// 3 for a bad scene, 5 for a scene PGE does not model, 12 for a bad trace, 6 when --json cannot
// be written.
int judge_command(const JudgeCommandOptions& options);

}  // namespace pge::cli
