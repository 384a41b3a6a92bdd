// The `pge` command.
#include "exit_codes.hpp"
#include "generate.hpp"
#include "run.hpp"

#include <CLI/CLI.hpp>
#include <fmt/core.h>

#include <cmath>
#include <cstdio>
#include <exception>
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
  run_cmd->add_flag("--quiet,-q", run.quiet, "Print no summary (errors still go to stderr)");
  run_cmd->add_flag("--progress", run.progress, "Show progress on stderr (default: only when stderr is a terminal)");

  GenerateOptions gen;
  CLI::App* gen_cmd = app.add_subcommand("generate", "Write a scene of a deterministic family (same seed, same scene).");
  gen_cmd->add_option("family", gen.family, "Scene family: gas (equal elastic discs in a square box)")
      ->check(CLI::IsMember({"gas"}));
  gen_cmd->add_option("--bodies", gen.gas.bodies, "Number of discs")->check(CLI::Range(1u, 10000000u));
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
      if (!run.progress) run.progress = isatty(fileno(stderr)) != 0 && !run.quiet;
      return run_command(run);
    }
    if (gen_cmd->parsed()) return generate_command(gen);
  } catch (const std::exception& e) {
    fmt::print(stderr, "pge: internal error: {}\n", e.what());
    return kExitInternal;
  }
  return kExitUsage;
}
