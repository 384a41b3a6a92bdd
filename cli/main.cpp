// The `pge` command.
#include "check.hpp"
#include "compare.hpp"
#include "exit_codes.hpp"
#include "fuzz.hpp"
#include "generate.hpp"
#include "judge.hpp"
#include "render.hpp"
#include "report.hpp"
#include "run.hpp"
#include "stdout.hpp"

#include "pge/oracle_exact.hpp"
#include "pge/peers.hpp"

#include <CLI/CLI.hpp>
#include <fmt/core.h>

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <sstream>
#include <string>
#include <unistd.h>

namespace {
// CLI11's own range checks print the whole range of double; these say what is meant.
const CLI::Validator kPositive(
    [](const std::string& text) {
      double x = 0;
      return CLI::detail::lexical_cast(text, x) && x > 0 && std::isfinite(x) ? std::string{}
                                                                              : "must be a positive number, got " + text;
    },
    "POSITIVE");
const CLI::Validator kNonNegative(
    [](const std::string& text) {
      double x = 0;
      return CLI::detail::lexical_cast(text, x) && x >= 0 && std::isfinite(x) ? std::string{}
                                                                               : "must be a number >= 0, got " + text;
    },
    "NONNEGATIVE");

// An event count: 1 to 2^64 - 1, in decimal. CLI11 reads integers with strtoull, which turns any
// number past 2^64 - 1 into 2^64 - 1 without a word (a scene's run.max_events that large is an
// error), and reads "010" as octal 8 and "0x10" as 16; the text is checked here and rewritten to
// the decimal number read.
const CLI::Validator kEventCount(
    [](std::string& text) {
      std::uint64_t n = 0;
      const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), n);
      if (ec == std::errc::result_out_of_range)
        return fmt::format("must be at most {} (2^64 - 1), got {}", UINT64_MAX, text);
      if (ec != std::errc{} || end != text.data() + text.size() || n == 0)
        return "must be a positive integer, got " + text;
      text = std::to_string(n);
      return std::string{};
    },
    "COUNT");

// "i/n" with 0 <= i < n; false otherwise.
bool parse_shard(const std::string& text, unsigned& shard, unsigned& shards) {
  char slash = 0;
  std::istringstream in(text);
  return (in >> shard >> slash >> shards) && slash == '/' && shards > 0 && shard < shards && in.eof();
}

std::string command_line(int argc, char** argv) {
  std::string out = "pge";
  for (int i = 1; i < argc; ++i) out += std::string(" ") + argv[i];
  return out;
}
}  // namespace

int main(int argc, char** argv) {
  using namespace pge::cli;
  send_library_stdout_to_stderr();
  pge::oracle::use_pooled_gmp_allocation();  // the referee's exact numbers: see oracle_exact.hpp
  CLI::App app{"pge: an event-driven 2D physics engine and the harness that checks it.\n"};
  app.footer(kExitCodeHelp);
  app.require_subcommand(1);
  app.set_version_flag("--version", "pge 0.1.0");

  RunOptions run;
  std::string scalar = "double";
  CLI::App* run_cmd = app.add_subcommand("run", "Simulate scenes: print a summary per scene and write event traces; exit 11 when a body passed through a fixed "
      "body (tunnelling).");
  run_cmd->add_option("scenes", run.scenes, "Scene files (pge-scene JSON) or directories of them")->required();
  run_cmd->add_option("--until", run.until, "Simulated seconds (default: each scene's run.until)")->check(kPositive);
  run_cmd->add_option("--max-events", run.max_events, "Stop after this many collisions (default: the scene's run.max_events)")
      ->transform(kEventCount);
  run_cmd->add_option("--frames", run.frames, "Frame events per simulated second, sampled into the trace (default: the scene's; 0: none)")
      ->check(kNonNegative);
  run_cmd->add_option("--trace", run.trace, "Write the event trace of the (single) scene to FILE as JSON Lines");
  run_cmd->add_option("--trace-dir", run.trace_dir, "Write each scene's trace to DIR/<scene>.jsonl (scenes whose file names are the same: DIR/<folder>-<scene>.jsonl)");
  run_cmd->add_option("--json", run.json_summary, "Also write the summaries as a JSON array to FILE (-: stdout, instead of the summaries)");
  run_cmd->add_option("--scalar", scalar, "Number type: float, double, long-double, quad")
      ->check(CLI::IsMember({"float", "double", "long-double", "quad"}));
  std::string solver;
  run_cmd->add_option("--solver", solver, "Root solver: fast, robust, certified (default: each scene's run.solver)")
      ->check(CLI::IsMember({"fast", "robust", "certified"}));
  std::string broad_phase = "auto";
  run_cmd->add_option("--broad-phase", broad_phase,
                      "Which pairs are predicted: grid (the bodies in nearby cells), all-pairs (every body), or auto "
                      "(grid from 16 moving bodies on; the PGE_BROAD_PHASE environment variable can override auto). "
                      "The events are the same; only the cost differs")
      ->check(CLI::IsMember({"auto", "grid", "all-pairs"}));
  run_cmd->add_flag("--quiet,-q", run.quiet, "Print no summary (errors still go to stderr)");
  run_cmd->add_flag("--progress", run.progress, "Show progress on stderr (default: only when stderr is a terminal)");

  CheckOptions check;
  CLI::App* check_cmd = app.add_subcommand(
      "check",
      "Run the engine on scenes, judge every event against the exact oracle and hold each run to its scene's expect "
      "block; exit 7 on a miss, a phantom, a body through a fixed body, an event time past the solver's promise "
      "(robust, certified: 0 ulps) or a failed expectation.");
  check_cmd->footer(std::string(
      "Expectations (the scene's \"expect\" block, fixtures/README.md): enforced when the run's solver is among\n"
      "  the block's \"solvers\" (default robust, certified) and the run is the scene's own (no --until or\n"
      "  --max-events, scalar double); otherwise a listed solver's run is judged by the oracle only, and an\n"
      "  unlisted solver's run is shown for contrast and never fails. Each failed expectation is one line on\n"
      "  stderr, \"pge check: FILE: SOLVER: expected ..., measured ...\" (exit 7); a storm the block expects\n"
      "  (\"stop\": \"event-storm\") is no failure; \"oracle\": false runs the engine alone (faster); a malformed\n"
      "  block is a bad scene (exit 3).\n") + kExitCodeHelp);
  check_cmd->add_option("scenes", check.scenes, "Scene files (pge-scene JSON) or directories of them (searched recursively)")
      ->required();
  check_cmd->add_option("--until", check.until, "Simulated seconds (default: each scene's run.until)")->check(kPositive);
  check_cmd->add_option("--max-events", check.max_events, "Stop after this many collisions (default: the scene's run.max_events)")
      ->transform(kEventCount);
  check_cmd->add_option("--scalar", check.scalar, "Number type: float, double, long-double, quad")
      ->check(CLI::IsMember({"float", "double", "long-double", "quad"}));
  CLI::Option* check_solver =
      check_cmd->add_option("--solver", check.solver, "Root solver: fast, robust, certified (default: each scene's run.solver)")
          ->check(CLI::IsMember({"fast", "robust", "certified"}));
  CLI::Option* check_all = check_cmd->add_flag(
      "--all-solvers", check.all_solvers,
      "Run each scene with fast, robust and certified; the expect block holds for its solvers, the others are shown "
      "for contrast (without a block: robust and certified are enforced, fast is contrast)");
  CLI::Option* check_table = check_cmd->add_flag(
      "--table", check.table,
      "Print a Markdown table instead of the summaries, one row per scene: family (parent folder), scene, and per "
      "solver the contact events, largest time error in ulps, relative energy drift and result (pass, FAIL: reason, "
      "n/a for contrast); implies --all-solvers");
  CLI::Option* check_table_out =
      check_cmd->add_option("--table-out", check.table_out, "Write the --table table to FILE (implies --table; the summaries still print)")
          ->type_name("FILE");
  check_solver->excludes(check_all)->excludes(check_table)->excludes(check_table_out);
  check_cmd->add_option("--json", check.json, "Write the summaries and every event's verdict to FILE (JSON; -: stdout, instead of the summaries)");
  check_cmd->add_flag("--no-filter", check.no_filter,
                     "Turn off the oracle's pair filters (its spatial filter and the interval test of each feature "
                     "pair): every pair of bodies is solved exactly at every event (slow: O(N^2) per event; same verdicts)");
  check_cmd->add_flag("--quiet,-q", check.quiet, "Print no summary (errors and failed expectations still go to stderr)");
  check_cmd->add_flag("--progress", check.progress, "Show progress on stderr (default: only when stderr is a terminal)");

  FuzzOptions fuzz;
  std::string fuzz_shard = "0/1", fuzz_solver = "robust";
  CLI::App* fuzz_cmd = app.add_subcommand(
      "fuzz", "Generate scenes, check every invariant, shrink failures into regression fixtures; exit 8 on a failure.");
  fuzz_cmd->add_option("--time", fuzz.time_limit, "Seconds of wall time to fuzz (0: no limit)")->check(kNonNegative);
  fuzz_cmd->add_option("--cases", fuzz.cases, "Cases to run in this shard (0: no limit)");
  fuzz_cmd->add_option("--seed", fuzz.seed, "Campaign seed (same seed, same cases)");
  fuzz_cmd->add_option("--first", fuzz.first, "First campaign case to run (to reproduce case K: --first K --cases 1)");
  fuzz_cmd->add_option("--shard", fuzz_shard, "i/n: run the i-th of n disjoint parts of the campaign (0-based)");
  fuzz_cmd->add_option("--solver", fuzz_solver, "Root solver: fast, robust, certified")
      ->check(CLI::IsMember({"fast", "robust", "certified"}));
  fuzz_cmd->add_option("--out", fuzz.out, "Directory for shrunk failing scenes (default: fixtures/regressions)");
  fuzz_cmd->add_option("--max-failures", fuzz.max_failures, "Stop after this many failures")->check(CLI::Range(1u, 100000u));
  bool no_polygons = false;
  fuzz_cmd->add_flag("--no-polygons", no_polygons, "Generate scenes of circles and segments only");
  fuzz_cmd->add_option("--spin", fuzz.spin,
                       "Turn every moving polygon and segment at a rate in [-W, W] rad/s, drawn from its id and the "
                       "seed (0: none); judged by the referee for rotation")
      ->check(CLI::Range(0.0, 1000.0));
  fuzz_cmd->add_flag("--storms-fail", fuzz.storms_fail, "Count event storms (today: resting contact between moving bodies) as failures");
  bool no_oracle = false;
  fuzz_cmd->add_flag("--no-oracle", no_oracle,
                     "Check the invariants only, without judging every event by the exact oracle (faster); the "
                     "oracle never judges the fast solver");
  fuzz_cmd->add_flag("--quiet,-q", fuzz.quiet, "Print no summary");
  fuzz_cmd->add_flag("--progress", fuzz.progress, "Show progress on stderr (default: only when stderr is a terminal)");

  GenerateOptions gen;
  CLI::App* gen_cmd = app.add_subcommand("generate", "Write a scene of a deterministic family (same seed, same scene).");
  gen_cmd->add_option("family", gen.family,
                      "Scene family: gas (equal elastic discs in a square box), pegs (discs raining through a "
                      "lattice of fixed pegs under gravity, 1 unless --gravity), polygons (moving squares and "
                      "triangles among fixed pentagons)")
      ->check(CLI::IsMember({"gas", "pegs", "polygons"}));
  gen_cmd->add_option("--bodies", gen.gas.bodies, "Number of moving bodies")->check(CLI::Range(1u, 10000000u));
  gen_cmd->add_option("--radius", gen.gas.radius, "Disc radius")->check(kPositive);
  gen_cmd->add_option("--area-fraction", gen.gas.area_fraction, "Disc area / box area, in (0, 0.7]")
      ->check(CLI::Range(1e-6, 0.7));
  gen_cmd->add_option("--speed", gen.gas.speed, "Velocity components uniform in [-speed, speed]")->check(kNonNegative);
  gen_cmd->add_option("--gravity", gen.gas.gravity, "Downward gravity (0: none)")->check(kNonNegative);
  gen_cmd->add_option("--until", gen.gas.until, "The scene's run.until")->check(kPositive);
  gen_cmd->add_option("--max-events", gen.gas.max_events, "The scene's run.max_events")->transform(kEventCount);
  gen_cmd->add_option("--seed", gen.gas.seed, "Seed of the generator");
  gen_cmd->add_option("--spin", gen.gas.spin,
                      "polygons: every moving polygon turns, its angular velocity uniform in [-spin, spin] rad/s "
                      "(a pge-scene/2 file; 0: none)")
      ->check(CLI::Range(0.0, 1e4));
  gen_cmd->add_option("-o,--out", gen.out, "Output file (default: stdout)");

  ReportOptions report;
  std::string report_shard = "0/1";
  CLI::App* report_cmd = app.add_subcommand(
      "report",
      "The accuracy report: every solver x scalar over the fixture families and random scenes; speed (engine alone) "
      "against error (exact oracle); writes report.md, index.html (self-contained, plots by gnuplot), results.json "
      "and results.csv.");
  report_cmd->footer(std::string(
      "Parts: accuracy (each scene judged by the oracle, then timed alone), scaling (the elastic gas at\n"
      "  several sizes, timed), drift (energy along one long gas run), peers (the pge compare scenes,\n"
      "  fixtures/scenes/peers, by PGE in every solver x scalar asked for and by Box2D and Chipmunk at\n"
      "  every setting; full report only, unless --parts names it). Quick: 500 events per scene, 12\n"
      "  random scenes, gas at 100 and 1,000, a 20,000-event drift run (about 1 minute of CPU). Full:\n"
      "  2,000 events, 100 random scenes, gas up to 10,000, 200,000 events of drift (about 25 minutes\n"
      "  of CPU, most of it quad and the peers part's 1,000-ball gases; shared by the cores, --jobs:\n"
      "  13 minutes on 2). A judged run of minutes is the row's timing too (timed_in_judged_run).\n"
      "Progress: on a terminal (or with --progress), one line redrawn in place: rows done, the part,\n"
      "  time elapsed and an estimate of the time left; with --progress-lines, for logs, a line per part\n"
      "  every 30 s and when it ends. At the end: the path of index.html and the headline numbers, a\n"
      "  line per solver x scalar (misses, p99 and worst time error, worst ulps, events/s, Pareto).\n"
      "Parallel: --jobs N (default: one per core) measures N rows at once, each in a worker process\n"
      "  forked from the report, the longest rows first (--costs); the rows, their order and every\n"
      "  figure but the timings are those of --jobs 1. A timed run runs beside the other workers' work\n"
      "  (meta.jobs says so; pge gate measures as its baseline was measured). A worker that dies costs\n"
      "  its row (a failed run naming the signal); the rest are written and the exit code is 1.\n"
      "Sharding: --shard i/n runs every n-th item from i and writes results.json only; join the shards\n"
      "  with --merge DIR... --out DIR, which writes the pages.\n") + kExitCodeHelp);
  report_cmd->add_option("--out,-o", report.out, "Output directory")->capture_default_str();
  report_cmd->add_flag("--quick", report.quick, "The quick sweep (CI's gate): fewer events, scenes and sizes");
  report_cmd->add_option("--scenes", report.scenes,
                         "Scene files or directories instead of the bundled families (fixtures/scenes/* but long and peers, and each family's long/; the quick sweep leaves out rotation/corner-near-misses-a-wall-for-1000-turns)");
  report_cmd->add_option("--peer-scenes", report.peer_scenes,
                         "Scene files or directories for the peers part instead of fixtures/scenes/peers");
  report_cmd->add_option("--random", report.random, "Random scenes from pge fuzz's generator (default: 12 quick, 100 full)")
      ->check(CLI::Range(0, 100000));
  report_cmd->add_option("--seed", report.seed, "Seed of the random scenes")->capture_default_str();
  report_cmd->add_option("--solvers", report.solvers, "Solvers to run (default: fast robust certified)")
      ->check(CLI::IsMember({"fast", "robust", "certified"}))
      ->delimiter(',');
  report_cmd->add_option("--scalars", report.scalars, "Scalars to run (default: float double long-double quad)")
      ->check(CLI::IsMember({"float", "double", "long-double", "quad"}))
      ->delimiter(',');
  report_cmd->add_option("--parts", report.parts, "Parts to run (default: accuracy scaling drift, and peers in the full report)")
      ->check(CLI::IsMember({"accuracy", "scaling", "drift", "peers"}))
      ->delimiter(',');
  report_cmd->add_option("--max-events", report.max_events, "Contact events per accuracy scene, at most the scene's own (default: 500 quick, 2,000 full)")
      ->transform(kEventCount);
  report_cmd->add_option("--repeats", report.repeats, "Timed runs per row, at least (default: 3 quick, 5 full; the median counts)")
      ->check(CLI::Range(1u, 1000u));
  report_cmd->add_option("--jobs,-j", report.jobs,
                         "Rows measured at once, each by a worker process (default 0: one per core; 1: one at a time, "
                         "in this process)")
      ->check(CLI::Range(0u, 256u));
  report_cmd->add_option("--shard", report_shard, "i/n: run the i-th of n disjoint parts (0-based); results.json only");
  report_cmd->add_option("--merge", report.merge, "Merge shards' results (directories holding results.json, or files) into --out");
  report_cmd->add_flag("--allow-partial", report.allow_partial, "With --merge: merge even when shards are missing");
  report_cmd->add_option("--inject-regression", report.inject,
                         "For testing the gate: fast-solver (every run uses the fast solver, labels unchanged) or slow "
                         "(every timed run does its work four times)")
      ->check(CLI::IsMember({"fast-solver", "slow"}));
  report_cmd->add_option("--costs", report.costs,
                         "What each row cost in an earlier run of the same sweep (its costs.json): the order rows are "
                         "measured in, the longest first, and the estimate of the time left (default: OUT/costs.json "
                         "if there, else the bundled reports/costs-full.json for the full sweep)");
  report_cmd->add_flag("--quiet,-q", report.quiet, "Print nothing but errors");
  report_cmd->add_flag("--progress", report.progress,
                       "Show progress on stderr, redrawn in place: rows done, the part, time elapsed and left (default: "
                       "only when stderr is a terminal)");
  report_cmd->add_flag("--progress-lines", report.progress_lines,
                       "Show progress for a log instead: a line per part every 30 s and when it ends (rows done, time "
                       "elapsed and left)");

  GateOptions gate;
  CLI::App* gate_cmd = app.add_subcommand(
      "gate",
      "The CI gate: compare results with the committed baseline, metric by metric; print a Markdown summary, write "
      "JUnit XML; exit 9 on a regression, 10 when results or baseline are missing or corrupt.");
  gate_cmd->footer(std::string(
      "Without --results the gate measures now, with the baseline's sweep (quick or full) and seed, into\n"
      "  OUT/report (without a readable baseline, with --update: the quick sweep, or --full).\n"
      "  Checks per scene x configuration: misses, phantoms, misorders and tunnelled bodies may not grow; largest\n"
      "  and p99 |time error| in ulps, energy and momentum drift may grow to --error-factor x the baseline\n"
      "  (with floors: 4 ulps, 64 epsilon of the scalar); the run must stop as before. Speed per\n"
      "  configuration: the geometric mean over its scenes of its wall time relative to the reference\n"
      "  configuration's (robust/double) on the same scene in the same run, against the baseline's, may\n"
      "  grow to --speed-factor; the reference's own wall time over a calibration workload (a fixed loop\n"
      "  timed in the same process) to --calibrated-factor. Speed is compared only between like builds\n"
      "  (build type, validation, sanitizers).\n"
      "  A baseline row missing from the results fails (closed).\n") + kExitCodeHelp);
  gate_cmd->add_option("--baseline", gate.baseline, "The committed baseline (results.json format)")->capture_default_str();
  gate_cmd->add_option("--results", gate.results, "Results to judge (results.json or its directory); default: measure now");
  gate_cmd->add_option("--out", gate.out, "Directory for a measured report, gate.md and gate.junit.xml")->capture_default_str();
  gate_cmd->add_option("--junit", gate.junit, "JUnit XML file (default: OUT/gate.junit.xml)");
  gate_cmd->add_option("--summary", gate.summary, "Markdown summary file (default: OUT/gate.md; also printed)");
  gate_cmd->add_flag("--update", gate.update, "Write the results as the new baseline (on purpose: commit it with the change)");
  gate_cmd->add_flag("--full", gate.full,
                     "When measuring without a readable baseline (a first --update): the full sweep (default: quick; "
                     "otherwise the baseline's sweep is measured)");
  gate_cmd->add_option("--error-factor", gate.policy.error_factor, "How far errors and drifts may grow")
      ->check(kPositive)
      ->capture_default_str();
  gate_cmd->add_option("--speed-factor", gate.policy.speed_factor,
                       "How far a configuration's time relative to the reference configuration may grow")
      ->check(kPositive)
      ->capture_default_str();
  gate_cmd->add_option("--calibrated-factor", gate.policy.calibrated_factor,
                       "How far the reference configuration's wall time over the calibration workload may grow")
      ->check(kPositive)
      ->capture_default_str();
  gate_cmd->add_option("--reference", gate.policy.reference, "The reference configuration, solver/scalar")
      ->capture_default_str();
  gate_cmd->add_option("--inject-regression", gate.report.inject,
                       "When measuring: a deliberate regression (fast-solver, slow), to see the gate fail")
      ->check(CLI::IsMember({"fast-solver", "slow"}));
  gate_cmd->add_option("--scenes", gate.report.scenes, "When measuring: scene files or directories (as pge report)");
  gate_cmd->add_option("--random", gate.report.random, "When measuring: random scenes (as pge report)")->check(CLI::Range(0, 100000));
  gate_cmd->add_option("--solvers", gate.report.solvers, "When measuring: solvers (as pge report)")
      ->check(CLI::IsMember({"fast", "robust", "certified"}))
      ->delimiter(',');
  gate_cmd->add_option("--scalars", gate.report.scalars, "When measuring: scalars (as pge report)")
      ->check(CLI::IsMember({"float", "double", "long-double", "quad"}))
      ->delimiter(',');
  gate_cmd->add_option("--parts", gate.report.parts, "When measuring: parts (as pge report)")
      ->check(CLI::IsMember({"accuracy", "scaling", "drift", "peers"}))
      ->delimiter(',');
  gate_cmd->add_option("--jobs,-j", gate.report.jobs,
                       "When measuring: rows at once (as pge report; default: as the baseline was measured, its "
                       "meta.jobs, 1 for a baseline older than --jobs; without a baseline, one per core)")
      ->check(CLI::Range(0u, 256u));
  gate_cmd->add_flag("--progress", gate.report.progress, "Show the measuring's progress on stderr");
  gate_cmd->add_flag("--progress-lines", gate.report.progress_lines,
                     "Show the measuring's progress for a log: a line per part every 30 s and when it ends");

  CompareOptions compare;
  CLI::App* compare_cmd = app.add_subcommand(
      "compare",
      "One scene run by PGE (by default robust and certified, double) and by Box2D and Chipmunk at several step "
      "rates and iteration counts: wall time, energy and momentum drift, penetration, tunnelling, final-state error "
      "against PGE certified double (a Markdown table).");
  compare_cmd->add_option("scene", compare.scene, "A scene file (pge-scene JSON)")->required();
  CLI::Option* compare_peers = compare_cmd->add_option("--peers", compare.peers, "Peers beside PGE: box2d, chipmunk, box2d3 (Box2D v3, when this build has it: scripts/build-box2d3.sh; then also in the default)")->delimiter(',')->capture_default_str();
  compare_cmd->add_option("--solvers", compare.solvers, "PGE's solvers: fast, robust, certified")
      ->delimiter(',')
      ->check(CLI::IsMember({"fast", "robust", "certified"}))
      ->capture_default_str();
  compare_cmd->add_option("--scalars", compare.scalars, "PGE's scalars (a row for each solver x scalar): float, double, long-double, quad")
      ->delimiter(',')
      ->check(CLI::IsMember({"float", "double", "long-double", "quad"}))
      ->capture_default_str();
  compare_cmd->add_option("--until", compare.until, "Simulated seconds (default: the scene's run.until)")->check(kPositive);
  compare_cmd->add_option("--json", compare.json, "Also write the rows as JSON to this file (-: stdout, instead of the table)");
  compare_cmd->add_flag("--quiet,-q", compare.quiet, "No table on stdout");
  compare_cmd->add_flag("--no-judge", compare.no_judge,
                        "Leave out the exact referee's verdicts on the peers' step traces (contacts on time, late, missed, phantom)");
  compare_cmd->add_option("--trace-dir", compare.trace_dir,
                          "Write each peer's step trace (pge-trace/2, steps) to DIR/<engine>-<hz>hz-<iterations>.jsonl, for pge judge");

  JudgeCommandOptions judge;
  CLI::App* judge_cmd = app.add_subcommand(
      "judge",
      "Judge another engine's trace of a scene (pge-trace/2, docs/formats.md) by the exact oracle: events mode "
      "(each collision: agree, time error, misorder, miss, phantom, as pge check) or steps mode (each exact "
      "contact: on time, late by k steps, missed, phantom; overlap depth, energy and momentum drift per step); "
      "exit 7 on a miss or a phantom, 12 on a bad trace.");
  judge_cmd->footer(std::string(
      "Steps mode: from each step's start state, every moving body on the scene's closed-form path (its\n"
      "  constant acceleration), the referee finds the exact first contact of each pair apart at the start,\n"
      "  each body followed up to its first contact in the step. A contact is on time when the engine reports\n"
      "  the pair in that step; late by k when it reports it k steps later, the pair overlapping at every\n"
      "  step end between, never deeper than --overlap-bound; missed when the pair is apart again before a\n"
      "  report (pass-through: tunnelling), overlaps deeper first, or the trace ends; phantom when reported in\n"
      "  a step the pair is apart through (at its start and end, no exact contact between). A pair found\n"
      "  overlapping at a step's end without an exact contact counts as an (off-path) contact of that step.\n"
      "Events mode: the trace's pre-collision states and post-collision velocities are the motions the\n"
      "  referee follows; a state more than 1e-6 (relative) off that path is a bad trace. An end record\n"
      "  with \"stop\": \"reached-until\" makes a contact left before its time a miss.\n") + kExitCodeHelp);
  judge_cmd->add_option("trace", judge.trace, "A trace file (pge-trace/2 JSON Lines, events or steps mode)")->required();
  judge_cmd->add_option("--scene", judge.scene, "The scene the trace is a run of (pge-scene JSON)")->required();
  judge_cmd->add_option("--json", judge.json, "Also write the summary and every verdict to FILE (JSON, pge-judge/1; -: stdout, instead of the summary)");
  judge_cmd->add_option("--overlap-bound", judge.overlap_bound,
                        "Steps mode: an unreported overlap deeper than this fraction of the pair's contact distance is a miss")
      ->check(kPositive)
      ->capture_default_str();
  judge_cmd->add_flag("--quiet,-q", judge.quiet, "Print no summary (a failure's first line still goes to stderr)");

  RenderOptions render;
  CLI::App* render_cmd = app.add_subcommand(
      "render", "A picture of a scene and its trajectory, collision points marked: FILE.svg, or FILE.html (animated).");
  render_cmd->add_option("scene", render.scene, "A scene file (pge-scene JSON)")->required();
  render_cmd->add_option("-o,--out", render.out, "Output: FILE.svg or FILE.html")->required();
  render_cmd->add_option("--until", render.until, "Simulated seconds (default: the scene's run.until)")->check(kPositive);
  render_cmd->add_option("--max-events", render.max_events, "Stop after this many collisions (default: the scene's)")
      ->transform(kEventCount);
  render_cmd->add_option("--solver", render.solver, "Root solver (default: the scene's run.solver)")
      ->check(CLI::IsMember({"fast", "robust", "certified"}));
  render_cmd->add_option("--frames", render.frames, "Trajectory samples per simulated second")->check(kPositive)->capture_default_str();
  render_cmd->add_flag("--quiet,-q", render.quiet, "Print no summary line");

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {  // help and version on the real standard output (stdout.hpp)
    return app.exit(e, pge::cli::pge_stdout());
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e, pge::cli::pge_stdout());
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e, pge::cli::pge_stdout());
  } catch (const CLI::ParseError& e) {
    fmt::print(stderr, "pge: {} (see --help)\n", e.what());
    return kExitUsage;
  }

  try {
    if (run_cmd->parsed()) {
      pge::parse_scalar_kind(scalar, run.scalar);
      if (!solver.empty()) {
        pge::SolverKind kind{};
        pge::parse_solver_kind(solver, kind);
        run.solver = kind;
      }
      pge::parse_broad_phase(broad_phase, run.broad_phase);
      if (OutputFile::names_stdout(run.json_summary)) run.quiet = true;  // stdout holds the JSON alone
      if (!run.progress) run.progress = isatty(fileno(stderr)) != 0 && !run.quiet;
      return run_command(run);
    }
    if (check_cmd->parsed()) {
      if (!check.table_out.empty()) check.table = true;
      if (check.table) check.all_solvers = true;
      if (OutputFile::names_stdout(check.json)) {
        if (check.table && check.table_out.empty()) {
          fmt::print(stderr, "pge check: --json - and --table both write to stdout: give the table a file (--table-out)\n");
          return kExitUsage;
        }
        check.quiet = true;  // stdout holds the JSON alone
      }
      if (!check.progress) check.progress = isatty(fileno(stderr)) != 0 && !check.quiet;
      return check_command(check);
    }
    if (gen_cmd->parsed()) return generate_command(gen);
    if (report_cmd->parsed()) {
      if (!parse_shard(report_shard, report.shard, report.shards)) {
        fmt::print(stderr, "pge: --shard: expected i/n with 0 <= i < n, got {} (see --help)\n", report_shard);
        return kExitUsage;
      }
      if (!report.merge.empty() && report.shards > 1) {
        fmt::print(stderr, "pge: --merge and --shard do not go together (see --help)\n");
        return kExitUsage;
      }
      if (!report.progress) report.progress = isatty(fileno(stderr)) != 0 && !report.quiet;
      report.command = command_line(argc, argv);
      return report_command(report);
    }
    if (gate_cmd->parsed()) {
      gate.report.command = command_line(argc, argv);
      return gate_command(gate);
    }
    if (render_cmd->parsed()) return render_command(render);
    if (compare_cmd->parsed()) {
      if (compare_peers->count() == 0 && pge::peers::available("box2d3")) compare.peers.emplace_back("box2d3");
      return compare_command(compare);
    }
    if (judge_cmd->parsed()) {
      if (OutputFile::names_stdout(judge.json)) judge.quiet = true;  // stdout holds the JSON alone
      return judge_command(judge);
    }
    if (fuzz_cmd->parsed()) {
      unsigned shard = 0, shards = 0;
      if (!parse_shard(fuzz_shard, shard, shards)) {
        fmt::print(stderr, "pge: --shard: expected i/n with 0 <= i < n, got {} (see --help)\n", fuzz_shard);
        return kExitUsage;
      }
      if (fuzz.cases == 0 && fuzz.time_limit == 0) fuzz.cases = 1000;
      fuzz.polygons = !no_polygons;
      fuzz.oracle = !no_oracle;
      fuzz.shard = shard;
      fuzz.shards = shards;
      pge::parse_solver_kind(fuzz_solver, fuzz.solver);
      if (!fuzz.progress) fuzz.progress = isatty(fileno(stderr)) != 0 && !fuzz.quiet;
      return fuzz_command(fuzz);
    }
  } catch (const std::exception& e) {
    fmt::print(stderr, "pge: internal error: {}\n", e.what());
    return kExitInternal;
  }
  return kExitUsage;
}
