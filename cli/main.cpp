// The `pge` command.
#include "check.hpp"
#include "exit_codes.hpp"
#include "fuzz.hpp"
#include "generate.hpp"
#include "run.hpp"

#include <CLI/CLI.hpp>
#include <fmt/core.h>

#include <cmath>
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
}  // namespace

int main(int argc, char** argv) {
  using namespace pge::cli;
  CLI::App app{"pge: an event-driven 2D physics engine and the harness that checks it.\n"};
  app.footer(kExitCodeHelp);
  app.require_subcommand(1);
  app.set_version_flag("--version", "pge 0.1.0");

  RunOptions run;
  std::string scalar = "double";
  CLI::App* run_cmd = app.add_subcommand("run", "Simulate scenes: print a summary per scene and write event traces.");
  run_cmd->add_option("scenes", run.scenes, "Scene files (pge-scene/1 JSON) or directories of them")->required();
  run_cmd->add_option("--until", run.until, "Simulated seconds (default: each scene's run.until)")->check(kPositive);
  run_cmd->add_option("--max-events", run.max_events, "Stop after this many collisions (default: the scene's run.max_events)")
      ->check(kPositive);
  run_cmd->add_option("--frames", run.frames, "Frame events per simulated second, sampled into the trace (default: the scene's; 0: none)")
      ->check(kNonNegative);
  run_cmd->add_option("--trace", run.trace, "Write the event trace of the (single) scene to FILE as JSON Lines");
  run_cmd->add_option("--trace-dir", run.trace_dir, "Write each scene's trace to DIR/<scene>.jsonl");
  run_cmd->add_option("--json", run.json_summary, "Also write the summaries as a JSON array to FILE");
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
      "block; exit 7 on a miss, a phantom or a failed expectation.");
  check_cmd->footer(std::string(
      "Expectations (the scene's \"expect\" block, fixtures/README.md): enforced when the run's solver is among\n"
      "  the block's \"solvers\" (default robust, certified) and the run is the scene's own (no --until or\n"
      "  --max-events, scalar double); otherwise a listed solver's run is judged by the oracle only, and an\n"
      "  unlisted solver's run is shown for contrast and never fails. Each failed expectation is one line on\n"
      "  stderr, \"pge check: FILE: SOLVER: expected ..., measured ...\" (exit 7); a storm the block expects\n"
      "  (\"stop\": \"event-storm\") is no failure; \"oracle\": false runs the engine alone (faster); a malformed\n"
      "  block is a bad scene (exit 3).\n") + kExitCodeHelp);
  check_cmd->add_option("scenes", check.scenes, "Scene files (pge-scene/1 JSON) or directories of them (searched recursively)")
      ->required();
  check_cmd->add_option("--until", check.until, "Simulated seconds (default: each scene's run.until)")->check(kPositive);
  check_cmd->add_option("--max-events", check.max_events, "Stop after this many collisions (default: the scene's run.max_events)")
      ->check(kPositive);
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
  check_cmd->add_option("--json", check.json, "Write the summaries and every event's verdict to FILE (JSON)");
  check_cmd->add_flag("--no-filter", check.no_filter, "Solve every pair exactly, without the interval filter (slow; same verdicts)");
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
  gen_cmd->add_option("--max-events", gen.gas.max_events, "The scene's run.max_events")->check(kPositive);
  gen_cmd->add_option("--seed", gen.gas.seed, "Seed of the generator");
  gen_cmd->add_option("-o,--out", gen.out, "Output file (default: stdout)");

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
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
      if (!run.progress) run.progress = isatty(fileno(stderr)) != 0 && !run.quiet;
      return run_command(run);
    }
    if (check_cmd->parsed()) {
      if (!check.table_out.empty()) check.table = true;
      if (check.table) check.all_solvers = true;
      if (!check.progress) check.progress = isatty(fileno(stderr)) != 0 && !check.quiet;
      return check_command(check);
    }
    if (gen_cmd->parsed()) return generate_command(gen);
    if (fuzz_cmd->parsed()) {
      unsigned shard = 0, shards = 0;
      char slash = 0;
      std::istringstream in(fuzz_shard);
      if (!(in >> shard >> slash >> shards) || slash != '/' || shards == 0 || shard >= shards || !in.eof()) {
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
