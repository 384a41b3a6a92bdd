#include "compare.hpp"

#include "exit_codes.hpp"
#include "scene_files.hpp"
#include "stdout.hpp"

#include "pge/judge.hpp"
#include "pge/peers.hpp"
#include "pge/scene_io.hpp"
#include "pge/trace_io.hpp"
#include "pge/world.hpp"

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <ostream>
#include <set>
#include <stdexcept>
#include <string>
#include <system_error>
#include <utility>

namespace pge::cli {
namespace {

using Clock = std::chrono::steady_clock;

// Why PGE's rows have no referee columns.
constexpr const char* kPgeNotJudged = "PGE's events are judged one by one by pge check, not as steps";
constexpr const char* kNotAsked = "not judged (--no-judge)";

// One setting's outcome and the exact referee's verdicts on its step trace (peers), or why there
// are none.
struct Row {
  peers::Outcome outcome;
  std::optional<oracle::StepSummary> referee;
  double judge_seconds = 0;  // the referee's time, apart from the outcome's wall_seconds
  std::string note;          // no verdicts: why
  std::string trace_file;    // where the step trace was written ("": nowhere)
};

std::string cell(double x) { return fmt::format("{:.3g}", x); }

std::string referee_cells(const Row& r) {
  if (!r.referee) return "- | - | - | -";
  const oracle::StepSummary& s = *r.referee;
  return fmt::format("{} | {} | {} | {}", s.on_time, s.late, s.missed, s.phantom);
}

std::string row_text(const Row& r) {
  const peers::Outcome& o = r.outcome;
  if (!o.error.empty())
    return fmt::format("| {} | {} | not run: {} | | | | | | | | | |", o.setting.engine, o.setting.label, o.error);
  return fmt::format("| {} | {} | {:.3f} | {} | {} | {} | {} | {} | {} |", o.setting.engine, o.setting.label, o.wall_seconds,
                     cell(o.energy_drift), cell(o.momentum_drift), cell(o.penetration), o.tunnelled, cell(o.final_error),
                     referee_cells(r));
}

nlohmann::json to_json(const Row& r) {
  const peers::Outcome& o = r.outcome;
  nlohmann::json j = {{"engine", o.setting.engine},   {"label", o.setting.label},
                      {"hz", o.setting.hz},           {"velocity_iterations", o.setting.velocity_iterations},
                      {"position_iterations", o.setting.position_iterations},
                      {"solver", o.setting.solver},   {"scalar", o.setting.scalar},
                      {"scene", o.scene},             {"horizon", o.horizon},
                      {"wall_seconds", o.wall_seconds}, {"energy_drift", o.energy_drift},
                      {"momentum_drift", o.momentum_drift}, {"penetration", o.penetration},
                      {"tunnelled", o.tunnelled},     {"final_error", o.final_error},
                      {"reference", o.reference}};
  if (r.referee) {
    const oracle::StepSummary& s = *r.referee;
    j["referee"] = {{"steps", s.steps},
                    {"contacts", s.contacts},
                    {"on_time", s.on_time},
                    {"late", s.late},
                    {"missed", s.missed},
                    {"phantom", s.phantom},
                    {"undecided", s.undecided},
                    {"unfollowed_reports", s.unfollowed_reports},
                    {"pass_through", s.tunnelled},
                    {"continuing_reports", s.continuing_reports},
                    {"largest_late_steps", s.largest_late_steps},
                    {"largest_relative_depth", s.largest_relative_depth},
                    {"seconds", r.judge_seconds}};
  } else {
    j["referee"] = nullptr;
    j["referee_note"] = r.note;
  }
  if (!r.trace_file.empty()) j["trace"] = r.trace_file;
  if (!o.error.empty()) j["error"] = o.error;
  return j;
}

// A file name for a setting's trace: "box2d-60hz-8+3.jsonl", "chipmunk-1000hz-50.jsonl".
std::string trace_file_name(const peers::Setting& s) {
  std::string name = fmt::format("{}-{}hz-{}", s.engine, static_cast<long long>(s.hz), s.velocity_iterations);
  if (s.engine == "box2d") name += fmt::format("+{}", s.position_iterations);
  return name + ".jsonl";
}

// Writes the row's trace into dir; false (with a message) when it cannot.
bool write_trace_file(Row& r, const std::string& dir) {
  const std::string path = dir + "/" + trace_file_name(r.outcome.setting);
  std::ofstream out(path);
  if (out) write_trace(out, *r.outcome.trace);
  out.close();
  if (!out) {
    fmt::print(stderr, "pge compare: cannot write {}\n", path);
    return false;
  }
  r.trace_file = path;
  return true;
}

// The referee's verdicts on the row's trace.
void judge_row(Row& r, const Scene& scene) {
  const auto start = Clock::now();
  try {
    const oracle::StepJudgement j = oracle::judge_steps(scene, *r.outcome.trace);
    r.referee = j.summary;
  } catch (const std::exception& e) {  // TraceError: a state the referee cannot take (NaN, ...)
    r.note = std::string("the referee refused the trace: ") + e.what();
    fmt::print(stderr, "pge compare: {}: {}\n", r.outcome.setting.label, r.note);
  }
  r.judge_seconds = std::chrono::duration<double>(Clock::now() - start).count();
}

int write_json(const std::vector<Row>& rows, const std::string& path) {
  nlohmann::json all = nlohmann::json::array();
  for (const Row& r : rows) all.push_back(to_json(r));
  OutputFile out(path);
  out.stream() << all.dump(2) << '\n';
  if (!out.close()) {
    fmt::print(stderr, "pge compare: cannot write {}\n", path);
    return kExitOutput;
  }
  return kExitOk;
}

bool has_rotation(const Scene& scene) {
  return std::any_of(scene.bodies.begin(), scene.bodies.end(), [](const BodyDesc& b) { return b.rotates; });
}

void print_table(const CompareOptions& opt, const LoadedScene& scene, double horizon, const std::vector<Row>& rows) {
  fmt::print("Scene {} (\"{}\"), {} bodies, {:g} simulated s; reference: PGE certified double.\n\n", opt.scene,
             scene.scene.name, scene.scene.bodies.size(), horizon);
  fmt::print("| engine | setting | wall time (s) | energy drift | momentum drift | penetration | tunnelled | final-state error "
             "| contacts on time | late | missed | phantom |\n");
  fmt::print("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n");
  for (const Row& r : rows) fmt::print("{}\n", row_text(r));
  fmt::print("\nEnergy drift (E_end - E_start)/|E_start|; momentum drift |P_end - P_start|/|P_start|; penetration: the "
             "largest overlap at a step end (PGE: at a contact) / the smaller body's size; tunnelled: moving bodies "
             "that passed through a fixed body (along PGE's arcs, along each peer step) or ended inside one or "
             "outside the fixed bodies' box; final-state error: RMS position error / the scene's extent.\n");
  fmt::print("Contacts (the exact referee on each peer's step trace, as pge judge): on time, reported in the step where "
             "the contact exactly happens; late, reported steps later; missed, never reported (passed through, sunk "
             "past half the contact distance, or the run ended); phantom, reported while the pair stays apart "
             "through the step on the paths from the step's start (reports of a pair one of whose bodies had another "
             "contact in the step, whose changed path the referee does not follow, are no phantoms: the JSON's "
             "referee.unfollowed_reports counts them). "
             "PGE rows: - ({}).\n",
             opt.no_judge ? kNotAsked : kPgeNotJudged);
  if (has_rotation(scene.scene))
    fmt::print("Rotation: bodies that turn in PGE turn in the peers, about PGE's pivot with PGE's moment of inertia; "
               "energies include I omega^2 / 2; positions are the scene's reference points. The referee follows a "
               "turning body between steps at the angle and angular velocity the peer recorded; a contact it "
               "cannot decide (a tangency, a corner at an edge's very end) is undecided, counted apart below.\n");
  std::string undecided;
  for (const Row& r : rows)
    if (r.referee && r.referee->undecided > 0)
      undecided += fmt::format("{}{}: {}", undecided.empty() ? "" : "; ", r.outcome.setting.label, r.referee->undecided);
  if (!undecided.empty())
    fmt::print("Undecided (pair-steps whose contact the referee could not decide; neither agreement nor failure): {}.\n",
               undecided);
}

}  // namespace

int compare_command(const CompareOptions& opt) {
  for (const std::string& p : opt.peers)
    if (p != "box2d" && p != "chipmunk" && p != "box2d3") {
      fmt::print(stderr, "pge compare: unknown peer \"{}\" (known: box2d, chipmunk, box2d3)\n", p);
      return kExitUsage;
    }
  const std::optional<LoadedScene> read = load_scene("compare", opt.scene);
  if (!read) return kExitBadScene;
  const LoadedScene& scene = *read;
  const double horizon = opt.until > 0 ? opt.until : scene.scene.run.until;

  std::vector<peers::Setting> settings;
  for (const std::string& solver : opt.solvers)
    for (const std::string& scalar : opt.scalars) settings.push_back(peers::pge_setting(solver, scalar));
  for (const std::string& p : opt.peers) {
    if (!peers::available(p)) {
      fmt::print(stderr, "pge compare: {} is not installed ({}{}); skipped\n", p, p == "box2d3" ? "" : "Debian: ",
                 peers::peer_package(p));
      continue;
    }
    for (const peers::Setting& s : peers::default_settings(p)) settings.push_back(s);
  }

  std::vector<Vec2d> reference;
  if (const int refused = simulate_scene("compare", opt.scene,
                                         [&] { reference = peers::reference_positions(scene.scene, horizon); });
      refused != kExitOk)
    return refused;

  if (!opt.trace_dir.empty()) {
    std::error_code ec;
    std::filesystem::create_directories(opt.trace_dir, ec);
    if (ec) {
      fmt::print(stderr, "pge compare: cannot make --trace-dir {}: {}\n", opt.trace_dir, ec.message());
      return kExitOutput;
    }
  }
  const bool judge = !opt.no_judge;
  const bool record = judge || !opt.trace_dir.empty();
  std::vector<Row> rows;
  for (const peers::Setting& s : settings) {
    Row& r = rows.emplace_back();
    r.outcome = peers::run_setting(scene, s, horizon, reference, record ? peers::Record::StepTrace : peers::Record::Nothing);
    if (!r.outcome.error.empty()) fmt::print(stderr, "pge compare: {}: {}\n", s.label, r.outcome.error);
    r.note = s.engine == "pge"            ? kPgeNotJudged
             : !r.outcome.error.empty() ? "not run"
             : opt.no_judge             ? kNotAsked
                                        : "";
    if (!r.outcome.trace) continue;
    if (!opt.trace_dir.empty() && !write_trace_file(r, opt.trace_dir)) return kExitOutput;
    if (judge) judge_row(r, scene.scene);
    r.outcome.trace.reset();  // a gas at 1000 Hz holds a million states a simulated second
  }

  if (!opt.quiet && !OutputFile::names_stdout(opt.json)) print_table(opt, scene, horizon, rows);
  if (!opt.json.empty())
    if (const int code = write_json(rows, opt.json); code != kExitOk) return code;
  const bool pge_ran = std::any_of(rows.begin(), rows.end(), [](const Row& r) {
    return r.outcome.setting.engine == "pge" && r.outcome.error.empty();
  });
  return pge_ran ? kExitOk : kExitStorm;
}

}  // namespace pge::cli
