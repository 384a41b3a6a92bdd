#include "check.hpp"

#include "check_report.hpp"
#include "exit_codes.hpp"
#include "run.hpp"

#include "pge/oracle.hpp"
#include "pge/scene_io.hpp"
#include "pge/world.hpp"

#include <fmt/core.h>

#include <chrono>
#include <cstdio>
#include <fstream>
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

  template <class T> void tick(const World<T>& w, std::size_t judged) {
    if (!on || Clock::now() < next) return;
    next = Clock::now() + kProgressInterval;
    fmt::print(stderr, "\r{}: t = {:.6g} / {:.6g}, {} events judged   ", label, to_double(w.time()), to_double(w.horizon()),
               judged);
  }
  void clear() const {
    if (on) fmt::print(stderr, "\r{:80}\r", "");
  }
};

template <class T> SceneCheck check_scene(const LoadedScene& loaded, const CheckOptions& opt, Progress& progress) {
  WorldOptions wo;
  wo.until = opt.until;
  wo.max_events = opt.max_events;
  SolverKind solver{};
  if (parse_solver_kind(opt.solver, solver)) wo.solver = solver;
  wo.frames_per_second = 0;  // frames change nothing the oracle judges
  World<T> world(loaded.scene, wo);
  oracle::Referee referee(oracle::exact_state(world), {!opt.no_filter, oracle::kAgreeUlps});

  SceneCheck c;
  c.path = loaded.path;
  c.name = loaded.scene.name;
  c.bodies = loaded.scene.bodies.size();
  c.scalar = std::string(scalar_name(ScalarTraits<T>::kind));
  c.solver = std::string(solver_name(world.solver()));
  c.filter = !opt.no_filter;
  oracle::follow(world, referee, [&c](const CollisionInfo<T>& info, const oracle::ExactEvent& e,
                                      const oracle::Judgement& j) {
    c.events.push_back(make_record(c.events.size(), to_double(info.time), e, j));
  });
  const auto start = Clock::now();
  while (world.step()) progress.tick(world, c.events.size());
  progress.clear();
  c.engine_seconds = std::chrono::duration<double>(Clock::now() - start).count() - referee.stats().seconds;
  c.stop = std::string(stop_reason_name(world.stop_reason()));
  c.time = to_double(world.time());
  c.horizon = to_double(world.horizon());
  if (world.stop_reason() == StopReason::ReachedUntil) {
    c.end_checked = true;
    c.end = referee.judge_end();
  }
  c.oracle = referee.stats();
  return c;
}

SceneCheck check_any(const LoadedScene& loaded, const CheckOptions& opt, Progress& progress) {
  ScalarKind scalar = ScalarKind::Double;
  if (!parse_scalar_kind(opt.scalar, scalar)) throw std::invalid_argument("unknown scalar type " + opt.scalar);
  switch (scalar) {
    case ScalarKind::Float: return check_scene<float>(loaded, opt, progress);
    case ScalarKind::Double: return check_scene<double>(loaded, opt, progress);
    case ScalarKind::LongDouble: return check_scene<long double>(loaded, opt, progress);
    case ScalarKind::QuadPrecision: return check_scene<Quad>(loaded, opt, progress);
  }
  throw std::logic_error("unknown scalar kind");
}

// One scene: its exit code (0, or the first failure's), its JSON.
int check_file(const std::string& file, const CheckOptions& opt, Progress& progress, std::ofstream& json,
               bool& first_json) {
  LoadedScene loaded;
  try {
    loaded = read_scene_file(file);
  } catch (const SceneError& e) {
    fmt::print(stderr, "pge check: {}\n", e.what());
    return kExitBadScene;
  }
  try {
    const SceneCheck c = check_any(loaded, opt, progress);
    if (!opt.quiet) print_summary(c, loaded.scene);
    if (json.is_open()) {
      json << (first_json ? "\n" : ",\n");
      write_json(json, c, loaded.scene);
      first_json = false;
    }
    if (c.stop == stop_reason_name(StopReason::EventStorm)) {
      fmt::print(stderr, "pge check: {}: the run stopped on an event storm at t = {:.17g}\n", file, c.time);
      return kExitStorm;
    }
    return has_failure(c) ? kExitCheckFailed : kExitOk;
  } catch (const UnsupportedScene& e) {
    progress.clear();
    fmt::print(stderr, "pge check: {}: {}\n", file, e.what());
    return kExitUnsupported;
  } catch (const std::invalid_argument& e) {
    progress.clear();
    fmt::print(stderr, "pge check: {}: {}\n", file, e.what());
    return kExitBadScene;
  }
}

}  // namespace

int check_command(const CheckOptions& opt) {
  std::vector<std::string> files;
  try {
    files = expand_scene_paths(opt.scenes);
  } catch (const std::exception& e) {
    fmt::print(stderr, "pge check: {}\n", e.what());
    return kExitBadScene;
  }
  std::ofstream json;
  if (!opt.json.empty()) {
    json.open(opt.json);
    if (!json) {
      fmt::print(stderr, "pge check: cannot write {}\n", opt.json);
      return kExitOutput;
    }
    json << "{\"format\":\"pge-check/1\",\"scenes\":[";
  }
  int exit_code = kExitOk;
  bool first_json = true;
  for (std::size_t k = 0; k < files.size(); ++k) {
    Progress progress{opt.progress, files.size() > 1 ? fmt::format("[{}/{}] {}", k + 1, files.size(), files[k]) : files[k]};
    const int code = check_file(files[k], opt, progress, json, first_json);
    if (exit_code == kExitOk) exit_code = code;
  }
  if (json.is_open()) {
    json << "\n]}\n";
    json.close();
    if (!json) {
      fmt::print(stderr, "pge check: error writing {}\n", opt.json);
      if (exit_code == kExitOk) exit_code = kExitOutput;
    }
  }
  return exit_code;
}

}  // namespace pge::cli
