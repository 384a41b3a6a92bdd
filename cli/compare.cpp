#include "compare.hpp"

#include "exit_codes.hpp"
#include "scene_files.hpp"

#include "pge/peers.hpp"
#include "pge/scene_io.hpp"
#include "pge/world.hpp"

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <stdexcept>

namespace pge::cli {
namespace {

std::string cell(double x) { return fmt::format("{:.3g}", x); }

std::string row(const peers::Outcome& o) {
  if (!o.error.empty()) return fmt::format("| {} | {} | not run: {} | | | | | |", o.setting.engine, o.setting.label, o.error);
  return fmt::format("| {} | {} | {:.3f} | {} | {} | {} | {} | {} |", o.setting.engine, o.setting.label, o.wall_seconds,
                     cell(o.energy_drift), cell(o.momentum_drift), cell(o.penetration), o.tunnelled, cell(o.final_error));
}

nlohmann::json to_json(const peers::Outcome& o) {
  nlohmann::json j = {{"engine", o.setting.engine},   {"label", o.setting.label},
                      {"hz", o.setting.hz},           {"velocity_iterations", o.setting.velocity_iterations},
                      {"position_iterations", o.setting.position_iterations},
                      {"solver", o.setting.solver},   {"scalar", o.setting.scalar},
                      {"scene", o.scene},             {"horizon", o.horizon},
                      {"wall_seconds", o.wall_seconds}, {"energy_drift", o.energy_drift},
                      {"momentum_drift", o.momentum_drift}, {"penetration", o.penetration},
                      {"tunnelled", o.tunnelled},     {"final_error", o.final_error},
                      {"reference", o.reference}};
  if (!o.error.empty()) j["error"] = o.error;
  return j;
}

}  // namespace

int compare_command(const CompareOptions& opt) {
  for (const std::string& p : opt.peers)
    if (p != "box2d" && p != "chipmunk") {
      fmt::print(stderr, "pge compare: unknown peer \"{}\" (known: box2d, chipmunk)\n", p);
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
      fmt::print(stderr, "pge compare: {} is not installed (Debian: {}); skipped\n", p, peers::peer_package(p));
      continue;
    }
    for (const peers::Setting& s : peers::default_settings(p)) settings.push_back(s);
  }

  std::vector<Vec2d> reference;
  if (const int refused = simulate_scene("compare", opt.scene,
                                         [&] { reference = peers::reference_positions(scene.scene, horizon); });
      refused != kExitOk)
    return refused;

  std::vector<peers::Outcome> rows;
  for (const peers::Setting& s : settings) {
    rows.push_back(peers::run_setting(scene, s, horizon, reference));
    if (!rows.back().error.empty()) fmt::print(stderr, "pge compare: {}: {}\n", s.label, rows.back().error);
  }

  if (!opt.quiet) {
    fmt::print("Scene {} (\"{}\"), {} bodies, {:g} simulated s; reference: PGE certified double.\n\n", opt.scene,
               scene.scene.name, scene.scene.bodies.size(), horizon);
    fmt::print("| engine | setting | wall time (s) | energy drift | momentum drift | penetration | tunnelled | final-state error |\n");
    fmt::print("| --- | --- | --- | --- | --- | --- | --- | --- |\n");
    for (const peers::Outcome& o : rows) fmt::print("{}\n", row(o));
    fmt::print("\nEnergy drift (E_end - E_start)/|E_start|; momentum drift |P_end - P_start|/|P_start|; penetration: the "
               "largest overlap at a step end (PGE: at a contact) / the smaller body's size; tunnelled: moving bodies "
               "that passed through a fixed body (along PGE's arcs, along each peer step) or ended inside one or "
               "outside the fixed bodies' box; final-state error: RMS position error / the scene's extent.\n");
  }
  if (!opt.json.empty()) {
    nlohmann::json all = nlohmann::json::array();
    for (const peers::Outcome& o : rows) all.push_back(to_json(o));
    std::ofstream out(opt.json);
    out << all.dump(2) << '\n';
    out.close();
    if (!out) {
      fmt::print(stderr, "pge compare: cannot write {}\n", opt.json);
      return kExitOutput;
    }
  }
  const bool pge_ran = std::any_of(rows.begin(), rows.end(),
                                   [](const peers::Outcome& o) { return o.setting.engine == "pge" && o.error.empty(); });
  return pge_ran ? kExitOk : kExitStorm;
}

}  // namespace pge::cli
