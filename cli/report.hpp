// `pge report` (the accuracy report: speed against error for every solver x scalar) and
// `pge gate` (results against a committed baseline). The measuring is here; the data, pages and
// comparison are in reports/.
#pragma once

#include "pge/gate.hpp"
#include "pge/report_data.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace pge::cli {

struct ReportOptions {
  std::string out = "out/report";
  bool quick = false;
  std::vector<std::string> scenes;  // files or directories; empty: every fixtures/scenes family but long and peers
  std::vector<std::string> peer_scenes;  // the peers part's scenes; empty: fixtures/scenes/peers
  int random = -1;                  // random scenes (pge fuzz's generator); < 0: 12 quick, 100 full
  std::uint64_t seed = 1;           // of the random scenes
  std::vector<std::string> solvers, scalars;  // empty: all
  std::uint64_t max_events = 0;     // per accuracy scene (at most the scene's own); 0: 500 quick, 5,000 full
  unsigned repeats = 0;             // timed runs per row, at least; 0: 3 quick, 5 full
  std::vector<std::string> parts;   // accuracy, scaling, drift; empty: all
  unsigned shard = 0, shards = 1;
  unsigned jobs = 0;                // rows measured at once, by worker processes; 0: one per core
  std::vector<std::string> merge;   // results to merge (directories holding results.json, or files)
  bool allow_partial = false;       // merge even when shards are missing
  std::string inject;               // a deliberate regression, for testing the gate: fast-solver, slow
  bool page = true;                 // write report.md, index.html and plots (not for a shard)
  bool progress = false, quiet = false;
  bool progress_lines = false;      // progress for logs: a line per part every 30 s and at its end
  bool headline = true;             // print the configurations' headline numbers at the end
  std::string command;              // the command line, shown on the page
  std::string costs;                // an earlier run's costs.json (the order of work); empty: OUT's, else the bundled
};

int report_command(const ReportOptions& options);

// Measures (or merges) and writes DIR as `pge report` does; the results through `out`. Returns
// the exit code.
int make_report(const ReportOptions& options, report::Results& out);

struct GateOptions {
  std::string baseline = "reports/baseline.json";
  std::string results;  // a results.json (or a directory holding one); empty: measure now
  std::string out = "out/gate";  // where a measured report, gate.md and gate.junit.xml go
  std::string junit, summary;    // default: OUT/gate.junit.xml, OUT/gate.md
  bool update = false;           // write the results as the new baseline
  bool full = false;             // measure the full sweep where no baseline says which (--update)
  report::GatePolicy policy;
  ReportOptions report;  // how to measure when results is empty (quick and seed follow the baseline)
};

int gate_command(const GateOptions& options);

}  // namespace pge::cli
