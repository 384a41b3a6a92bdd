#include "check.hpp"

#include "check_report.hpp"
#include "exit_codes.hpp"
#include "expect.hpp"
#include "scene_files.hpp"
#include "stdout.hpp"

#include "pge/oracle.hpp"
#include "pge/scene_io.hpp"
#include "pge/step_loop.hpp"
#include "pge/tunnel.hpp"
#include "pge/world.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <ostream>
#include <optional>
#include <stdexcept>

namespace pge::cli {
namespace {

using Clock = std::chrono::steady_clock;

// Seconds between progress lines on a terminal.
constexpr auto kProgressInterval = std::chrono::milliseconds(500);

struct Progress {
  bool on = false;
  std::string label;
  Clock::time_point next = Clock::now() + kProgressInterval;

  template <class T> void tick(const World<T>& w, std::uint64_t events, bool judged) {
    if (!on || Clock::now() < next) return;
    next = Clock::now() + kProgressInterval;
    fmt::print(stderr, "\r{}: t = {:.6g} / {:.6g}, {} events{}   ", label, to_double(w.time()), to_double(w.horizon()),
               events, judged ? " judged" : "");
  }
  void clear() const {
    if (on) fmt::print(stderr, "\r{:80}\r", "");
  }
};

constexpr std::array<SolverKind, 3> kAllSolvers{SolverKind::Fast, SolverKind::Robust, SolverKind::Certified};

// Why a run is not the one the scene's expect block describes ("" if it is): the block states
// what happens over the scene's own horizon and event budget, in doubles.
std::string deviation(const Scene& scene, const CheckOptions& opt) {
  if (opt.until >= 0 && opt.until != scene.run.until)
    return fmt::format("--until {} changes the run the expect block describes", opt.until);
  if (opt.max_events != 0 && opt.max_events != scene.run.max_events)
    return fmt::format("--max-events {} changes the run the expect block describes", opt.max_events);
  if (opt.scalar != "double") return fmt::format("the expect block is stated for double, not {}", opt.scalar);
  return {};
}

// How far the run of `solver` is held to the block (see Enforcement).
ExpectOutcome plan(const Expect& e, SolverKind solver, bool several_solvers, const std::string& deviated) {
  ExpectOutcome o;
  o.storm_expected = e.present && e.stop == StopReason::EventStorm;
  if (!e.present) {
    // Without a block, a run the user asked for is judged as always; beside the solvers a block
    // lists by default, fast runs for contrast.
    if (several_solvers && !e.lists(solver)) {
      o.enforcement = Enforcement::Contrast;
      o.why = fmt::format("{} runs for contrast; without an expect block robust and certified are enforced",
                          solver_name(solver));
    }
    return o;
  }
  if (!e.lists(solver)) {
    o.enforcement = Enforcement::Contrast;
    o.why = fmt::format("{} is not among the expect block's solvers", solver_name(solver));
  } else if (!deviated.empty()) {
    o.enforcement = Enforcement::Verdicts;
    o.why = deviated;
  } else {
    o.enforcement = Enforcement::Full;
  }
  return o;
}

template <class T>
SceneCheck check_scene(const LoadedScene& loaded, const Expect& expect, SolverKind solver, ExpectOutcome outcome,
                       const CheckOptions& opt, Progress& progress) {
  WorldOptions wo;
  wo.until = opt.until;
  wo.max_events = opt.max_events;
  wo.solver = solver;
  wo.frames_per_second = 0;  // frames change nothing the oracle judges
  wo.watch_tunnels = true;   // a body through a fixed body, as pge run finds it (pge/tunnel.hpp)
  World<T> world(loaded.scene, wo);

  SceneCheck c;
  c.path = loaded.path;
  c.name = loaded.scene.name;
  c.bodies = loaded.scene.bodies.size();
  c.scalar = std::string(scalar_name(ScalarTraits<T>::kind));
  c.solver = std::string(solver_name(world.solver()));
  c.time_bound_ulps = promised_time_error_ulps(world.solver());
  c.rotating_time_bound_ulps = promised_rotating_time_error_ulps(world.solver());
  c.filter = !opt.no_filter;
  // The block may turn the oracle off for the scene's own run; a shorter run is judged as always.
  const bool measured = expect.present && outcome.enforcement != Enforcement::Verdicts;
  c.judged = !(measured && !expect.oracle);

  ExpectTracker tracker(expect, c.bodies);
  const auto observe = [&c, &tracker](const CollisionInfo<T>& info) {
    ++c.contact_events;
    tracker.observe(to_double(info.time), info.a, info.b);
  };
  std::optional<oracle::Referee> referee;
  if (c.judged) {
    referee.emplace(oracle::exact_state(world), oracle::RefereeOptions{!opt.no_filter, oracle::kAgreeUlps});
    const bool decimals = !opt.json.empty();  // only the JSON writes every event's exact time
    // Room for the run's records at once (up to 2^16 of them, 12 MB, touched only as they come):
    // growing by doubling copied them and faulted in fresh pages at every step.
    const std::uint64_t most = opt.max_events ? opt.max_events : loaded.scene.run.max_events;
    c.events.reserve(static_cast<std::size_t>(std::min<std::uint64_t>(most, 1u << 16)));
    oracle::follow(world, *referee,
                   [&c, &observe, &world, decimals](const CollisionInfo<T>& info, const oracle::ExactEvent& e,
                                                    const oracle::Judgement& j) {
      c.events.push_back(make_record(c.events.size(), to_double(info.time), e, j, decimals));
      c.events.back().rotating = world.rotates(info.a) || world.rotates(info.b);
      observe(info);
    });
  } else {
    world.on_collision(observe);
  }
  const auto stepped =
      step_to_end(world, world_totals<T>, [&](const World<T>& w) { progress.tick(w, c.contact_events, c.judged); });
  progress.clear();
  c.energy_start = to_double(stepped.start.energy());
  c.momentum_start = vec_cast<double>(stepped.start.momentum);
  const double oracle_seconds = referee ? referee->stats().seconds : 0.0;
  c.engine_seconds = stepped.wall_seconds - oracle_seconds;
  c.predictions = world.counts().predictions;
  c.stop_reason = world.stop_reason();
  c.stop = std::string(stop_reason_name(world.stop_reason()));
  c.time = to_double(world.time());
  c.horizon = to_double(world.horizon());
  if (world.stop_reason() == StopReason::EventStorm) {
    c.storm_a = world.storm().a;
    c.storm_b = world.storm().b;
  }
  if (referee && world.stop_reason() == StopReason::ReachedUntil) {
    c.end_checked = true;
    c.end = referee->judge_end();
  }
  if (referee) {
    c.oracle = referee->stats();
    c.motion_misses = referee->motion_misses();
  }
  c.energy_end = to_double(stepped.end.energy());
  c.momentum_end = vec_cast<double>(stepped.end.momentum);
  c.final_states.reserve(c.bodies);
  for (BodyIndex i = 0; i < c.bodies; ++i) {
    const BodySnapshot<T> s = world.snapshot(i);
    c.final_states.push_back({vec_cast<double>(s.position), vec_cast<double>(s.velocity), to_double(s.angle),
                              to_double(s.angular_velocity)});
  }
  c.largest_contact_overlap = to_double(world.largest_contact_overlap().relative);
  c.tunnels = world.tunnels();
  c.expect = std::move(outcome);
  if (measured) evaluate(expect, loaded.scene, tracker, c, c.expect);
  return c;
}

SceneCheck check_any(const LoadedScene& loaded, const Expect& expect, SolverKind solver, ExpectOutcome outcome,
                     const CheckOptions& opt, Progress& progress) {
  ScalarKind scalar = ScalarKind::Double;
  if (!parse_scalar_kind(opt.scalar, scalar)) throw std::invalid_argument("unknown scalar type " + opt.scalar);
  return with_scalar(scalar, [&](auto type) {
    return check_scene<typename decltype(type)::type>(loaded, expect, solver, std::move(outcome), opt, progress);
  });
}

// A run's exit code: a contrast run never fails; an unexpected storm keeps its own code.
int exit_code_of(const SceneCheck& c) {
  if (c.expect.enforcement == Enforcement::Contrast || failure_reasons(c).empty()) return kExitOk;
  const bool storm = c.stop_reason == StopReason::EventStorm && !c.expect.storm_expected;
  return storm ? kExitStorm : kExitCheckFailed;
}

// What is printed and written across scenes.
struct Output {
  bool summaries = true;
  std::optional<OutputFile> json;
  bool first_json = true;
  std::vector<TableRow> table;
};

void report_run(const std::string& file, const LoadedScene& loaded, const SceneCheck& c, Output& out) {
  if (out.summaries) print_summary(c, loaded.scene);
  if (out.json) {
    out.json->stream() << (out.first_json ? "\n" : ",\n");
    write_json(out.json->stream(), c, loaded.scene);
    out.first_json = false;
  }
  if (c.expect.enforcement == Enforcement::Full) {
    for (const ExpectFailure& f : c.expect.failures) fmt::print(stderr, "pge check: {}: {}: {}\n", file, c.solver, f.text);
  } else if (c.expect.enforcement != Enforcement::Contrast && c.stop_reason == StopReason::EventStorm &&
             !c.expect.storm_expected) {
    fmt::print(stderr, "pge check: {}: {}: the run stopped on an event storm at t = {:.17g} (bodies {})\n", file, c.solver,
               c.time, pair_text(loaded.scene, c.storm_a, c.storm_b));
  }
  if (c.expect.enforcement != Enforcement::Contrast && !c.expect.evaluated)
    for (const Tunnel& t : c.tunnels)
      fmt::print(stderr, "pge check: {}: {}: {}\n", file, c.solver,
                 tunnel_text(t, loaded.scene.bodies[t.body].id, loaded.scene.bodies[t.fixed].id));
  if (c.expect.enforcement != Enforcement::Contrast && !c.expect.evaluated && past_time_bound(c) > 0)
  {
    // Turning pairs have their own promise (promised_rotating_time_error_ulps): both are named
    // when the run has turning events, so a rotating time past 4 ulps is not said to be past 0.
    const bool turning = std::any_of(c.events.begin(), c.events.end(), [](const EventRecord& r) { return r.rotating; });
    const std::string bound = turning && c.rotating_time_bound_ulps
                                  ? fmt::format("{} ulps ({} on turning pairs)", *c.time_bound_ulps, *c.rotating_time_bound_ulps)
                                  : fmt::format("{} ulps", *c.time_bound_ulps);
    fmt::print(stderr, "pge check: {}: {}: {} event times off by more than the {} {} promises (largest {} ulps)\n",
               file, c.solver, past_time_bound(c), bound, c.solver, largest_abs_ulps(c));
  }
}

// One scene, with one solver or all three: its exit code (0, or the first failure's).
int check_file(const std::string& file, const CheckOptions& opt, const std::string& label, Output& out) {
  TableRow* row = nullptr;
  if (opt.table) {
    const std::filesystem::path path(file);
    out.table.push_back({path.parent_path().filename().string(), path.stem().string(), {}});
    row = &out.table.back();
  }
  const auto fail_row = [row](const std::string& why) {
    if (row)
      for (TableCell& cell : row->cells) cell.result = why;
  };
  Expect expect;
  const std::optional<LoadedScene> read =
      load_scene("check", file, [&expect](const LoadedScene& l) { expect = parse_expect(l); });
  if (!read) {
    fail_row("error: bad scene file");
    return kExitBadScene;
  }
  const LoadedScene& loaded = *read;
  std::vector<SolverKind> solvers{loaded.scene.run.solver};
  if (opt.all_solvers) solvers.assign(kAllSolvers.begin(), kAllSolvers.end());
  if (!opt.solver.empty()) parse_solver_kind(opt.solver, solvers[0]);
  const std::string deviated = deviation(loaded.scene, opt);
  int exit_code = kExitOk;
  for (const SolverKind solver : solvers) {
    Progress progress{opt.progress, solvers.size() > 1 ? fmt::format("{} ({})", label, solver_name(solver)) : label};
    const auto run = [&] {
      const SceneCheck c = check_any(loaded, expect, solver, plan(expect, solver, solvers.size() > 1, deviated), opt, progress);
      report_run(file, loaded, c, out);
      if (row) row->cells[static_cast<std::size_t>(solver)] = table_cell(c);
      if (exit_code == kExitOk) exit_code = exit_code_of(c);
    };
    try {
      const int refused = simulate_scene("check", file, run, [&progress] { progress.clear(); });
      if (refused != kExitOk) {
        fail_row(refused == kExitUnsupported ? "error: unsupported" : "error: invalid scene");
        return refused;
      }
    } catch (const std::logic_error& e) {
      // The engine's own validation (PGE_VALIDATE builds) stopped the run: an overlap past the
      // bound, say, as when fast lets a box fall through the box it rests on. A failure of that
      // run, reported as one; a contrast run's does not fail the check.
      progress.clear();
      const bool contrast = plan(expect, solver, solvers.size() > 1, deviated).enforcement == Enforcement::Contrast;
      fmt::print(stderr, "pge check: {}: {}{}: the run failed the engine's validation: {}\n", file, solver_name(solver),
                 contrast ? " (contrast)" : "", e.what());
      if (row) {
        TableCell& cell = row->cells[static_cast<std::size_t>(solver)];
        cell.events = cell.ulps = cell.drift = "-";
        cell.result = contrast ? "n/a (contrast: fails validation)" : "FAIL: validation";
      }
      if (!contrast && exit_code == kExitOk) exit_code = kExitCheckFailed;
    }
  }
  return exit_code;
}

}  // namespace

SceneCheck judged_run(const LoadedScene& loaded, SolverKind solver, const std::string& scalar, double until,
                      std::uint64_t max_events) {
  CheckOptions opt;
  opt.scalar = scalar;
  opt.until = until;
  opt.max_events = max_events;
  Progress quiet;
  return check_any(loaded, Expect{}, solver, ExpectOutcome{}, opt, quiet);
}

int check_command(const CheckOptions& opt) {
  const std::optional<std::vector<std::string>> listed = scene_files("check", opt.scenes);
  if (!listed) return kExitBadScene;
  const std::vector<std::string>& files = *listed;
  Output out;
  out.summaries = !opt.quiet && !(opt.table && opt.table_out.empty());
  if (!opt.json.empty()) {
    out.json.emplace(opt.json);
    if (!out.json->is_open()) {
      fmt::print(stderr, "pge check: cannot write {}\n", opt.json);
      return kExitOutput;
    }
    out.json->stream() << "{\"format\":\"pge-check/1\",\"scenes\":[";
  }
  int exit_code = kExitOk;
  for (std::size_t k = 0; k < files.size(); ++k) {
    const std::string label = files.size() > 1 ? fmt::format("[{}/{}] {}", k + 1, files.size(), files[k]) : files[k];
    const int code = check_file(files[k], opt, label, out);
    if (exit_code == kExitOk) exit_code = code;
  }
  const auto output_failed = [&exit_code](const std::string& what) {
    fmt::print(stderr, "pge check: error writing {}\n", what);
    if (exit_code == kExitOk) exit_code = kExitOutput;
  };
  if (out.json) {
    out.json->stream() << "\n]}\n";
    if (!out.json->close()) output_failed(opt.json);
  }
  if (opt.table) {
    if (opt.table_out.empty()) {
      write_table(pge_stdout(), out.table);
      pge_stdout().flush();
    } else {
      std::ofstream table(opt.table_out);
      write_table(table, out.table);
      table.close();
      if (!table) output_failed(opt.table_out);
    }
  }
  return exit_code;
}

}  // namespace pge::cli
