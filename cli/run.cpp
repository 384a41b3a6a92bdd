#include "run.hpp"

#include "exit_codes.hpp"
#include "scene_files.hpp"
#include "stdout.hpp"
#include "trace.hpp"

#include "pge/constants.hpp"
#include "pge/scene_io.hpp"
#include "pge/step_loop.hpp"
#include "pge/tunnel.hpp"
#include "pge/world.hpp"

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <map>
#include <set>
#include <stdexcept>

namespace pge::cli {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

// Above this many bodies the O(n^2) end-of-run overlap scan is skipped (it would dominate).
constexpr std::size_t kFullOverlapScanMaxBodies = 20000;

struct SceneResult {
  int exit_code = kExitOk;
  nlohmann::json summary;
};

std::string body_name(const Scene& s, BodyIndex i) { return i < s.bodies.size() ? s.bodies[i].id : "?"; }

template <class T>
SceneResult simulate(const LoadedScene& loaded, const RunOptions& opt, TraceWriter* trace, const std::string& label) {
  const Scene& scene = loaded.scene;
  WorldOptions wo;
  wo.until = opt.until;
  wo.max_events = opt.max_events;
  wo.frames_per_second = opt.frames;
  wo.solver = opt.solver;
  wo.broad_phase = opt.broad_phase;
  // Every path a body takes, from one motion change to the next, is tested against the fixed
  // bodies (pge/tunnel.hpp): a few box tests per motion change.
  wo.watch_tunnels = true;
  World<T> world(scene, wo);

  if (trace) {
    trace->header(scene, scalar_name(ScalarTraits<T>::kind), solver_name(world.solver()), to_double(world.horizon()));
    world.on_collision([&](const CollisionInfo<T>& c) { trace->collision(scene, world, c); });
    world.on_frame([&](const World<T>& w, T t) { trace->frame(w, t); });
  }

  const auto t_start = Clock::now();
  auto next_progress = t_start + std::chrono::milliseconds(500);
  std::uint64_t steps = 0;
  const auto progress = [&](const World<T>& w) {
    if (opt.progress && (++steps & 1023) == 0 && Clock::now() >= next_progress) {
      next_progress = Clock::now() + std::chrono::milliseconds(500);
      const double secs = std::chrono::duration<double>(Clock::now() - t_start).count();
      fmt::print(stderr, "\r{}: t = {:.6g} / {:.6g}, {} collisions, {:.0f} events/s   ", label, to_double(w.time()),
                 to_double(w.horizon()), w.counts().collisions, static_cast<double>(w.counts().collisions) / secs);
    }
  };
  const auto stepped = step_to_end(world, world_totals<T>, progress);
  const double wall = stepped.wall_seconds;
  if (opt.progress) fmt::print(stderr, "\r{:80}\r", "");
  const WorldTotals<double> start = in_double(stepped.start), end = in_double(stepped.end);
  const std::vector<Tunnel>& tunnels = world.tunnels();
  const EventCounts& n = world.counts();
  const auto contact_overlap = world.largest_contact_overlap();
  const bool full_scan = world.body_count() <= kFullOverlapScanMaxBodies;
  const auto final_overlap = full_scan ? world.largest_overlap() : typename World<T>::Overlap{};
  const std::uint64_t hash = world.state_hash();
  if (trace) trace->end(world, hash);

  SceneResult result;
  nlohmann::json& j = result.summary;
  j["scene"] = loaded.path;
  j["name"] = scene.name;
  j["bodies"] = scene.bodies.size();
  j["scalar"] = scalar_name(ScalarTraits<T>::kind);
  j["solver"] = solver_name(world.solver());
  j["stop"] = stop_reason_name(world.stop_reason());
  j["time"] = to_double(world.time());
  j["horizon"] = to_double(world.horizon());
  j["collisions"] = n.collisions;
  j["overlap_rule_collisions"] = n.overlap_starts;
  j["grazes"] = n.grazes;
  j["timers"] = n.timers;
  j["frames"] = n.frames;
  j["stale"] = n.stale;
  j["predictions"] = n.predictions;
  j["undecided_roundings"] = n.undecided_roundings;
  j["impulse_lifts"] = n.impulse_lifts;
  j["broad_phase"] = broad_phase_name(world.broad_phase());
  j["cell_crossings"] = n.crossings;
  j["global_bodies"] = n.global_bodies;
  j["energy_start"] = {{"kinetic", start.kinetic}, {"potential", start.potential}};
  j["energy_end"] = {{"kinetic", end.kinetic}, {"potential", end.potential}};
  j["momentum_start"] = {start.momentum.x, start.momentum.y};
  j["momentum_end"] = {end.momentum.x, end.momentum.y};
  j["largest_contact_overlap"] = {{"depth", to_double(contact_overlap.depth)},
                                  {"relative", to_double(contact_overlap.relative)},
                                  {"ulps", to_double(contact_overlap.ulps)}};
  if (full_scan)
    j["largest_final_overlap"] = {{"depth", to_double(final_overlap.depth)},
                                  {"relative", to_double(final_overlap.relative)},
                                  {"ulps", to_double(final_overlap.ulps)}};
  j["overlap_bound_ulps"] = kOverlapBoundUlps;
  j["state_hash"] = fmt::format("{:#018x}", hash);
  j["wall_seconds"] = wall;
  j["events_per_second"] = wall > 0 ? static_cast<double>(n.collisions) / wall : 0.0;

  j["tunnels"] = nlohmann::json::array();
  for (const Tunnel& t : tunnels)
    j["tunnels"].push_back({{"body", body_name(scene, t.body)}, {"fixed", body_name(scene, t.fixed)},
                            {"from", t.from}, {"to", t.to}});
  if (!tunnels.empty()) result.exit_code = kExitTunnel;

  if (world.stop_reason() == StopReason::EventStorm) {
    const auto& s = world.storm();
    j["storm"] = {{"time", to_double(s.time)}, {"a", body_name(scene, s.a)}, {"b", body_name(scene, s.b)},
                  {"collisions", s.collisions}};
    result.exit_code = kExitStorm;
  }

  if (!opt.quiet) {
    const double e0 = start.kinetic + start.potential, e1 = end.kinetic + end.potential;
    const double de = e1 - e0;
    fmt::print("scene {} (\"{}\"): {} bodies, scalar {}, solver {}\n", loaded.path, scene.name, scene.bodies.size(),
               scalar_name(ScalarTraits<T>::kind), solver_name(world.solver()));
    fmt::print("  stopped: {} at t = {:.17g} (horizon {:.17g})\n", stop_reason_name(world.stop_reason()),
               to_double(world.time()), to_double(world.horizon()));
    fmt::print("  events: {} collisions ({} by the overlap rule), {} grazes, {} timers, {} frames\n", n.collisions,
               n.overlap_starts, n.grazes, n.timers, n.frames);
    fmt::print("  energy: kinetic {:.17g} -> {:.17g}, potential {:.17g} -> {:.17g}\n", start.kinetic, end.kinetic,
               start.potential, end.potential);
    fmt::print("  energy: total {:.17g} -> {:.17g} (change {:.3g}, relative {:.3g})\n", e0, e1, de,
               e0 != 0 ? de / std::abs(e0) : 0.0);
    fmt::print("  momentum: ({:.17g}, {:.17g}) -> ({:.17g}, {:.17g}) (change {:.3g}, {:.3g})\n", start.momentum.x,
               start.momentum.y, end.momentum.x, end.momentum.y, end.momentum.x - start.momentum.x,
               end.momentum.y - start.momentum.y);
    fmt::print("  overlap: largest at a contact {:.3g} (relative {:.3g}, {:.3g} ulps)", to_double(contact_overlap.depth),
               to_double(contact_overlap.relative), to_double(contact_overlap.ulps));
    if (full_scan)
      fmt::print("; at the end {:.3g} ({:.3g} ulps)", to_double(final_overlap.depth), to_double(final_overlap.ulps));
    else
      fmt::print("; end-of-run scan skipped above {} bodies", kFullOverlapScanMaxBodies);
    const double worst_ulps = std::max(to_double(contact_overlap.ulps), to_double(final_overlap.ulps));
    fmt::print("; bound {:g} ulps: {}\n", kOverlapBoundUlps, worst_ulps <= kOverlapBoundUlps ? "ok" : "EXCEEDED");
    fmt::print("  tunnelling: {}\n", tunnels.empty() ? "none (no body passed through a fixed body)"
                                                    : fmt::format("{} {} passed through a fixed body (exit 11)",
                                                                  tunnels.size(), tunnels.size() == 1 ? "body" : "bodies"));
    fmt::print("  state hash: {:#018x}\n", hash);
    fmt::print("  speed: {} collisions in {:.3f} s: {:.0f} events/s ({} predictions, {} stale queue entries)\n",
               n.collisions, wall, wall > 0 ? static_cast<double>(n.collisions) / wall : 0.0, n.predictions, n.stale);
    if (n.undecided_roundings > 0)
      fmt::print("  undecided roundings: {} rotating contact times kept robust's placement (certified could not "
                 "decide their rounding)\n", n.undecided_roundings);
    if (n.impulse_lifts > 0)
      fmt::print("  impulse lifts: {} turning impulses grown by a few ulps (the struck point still approached by "
                 "the exact paths)\n", n.impulse_lifts);
    if (world.broad_phase() == BroadPhase::Grid)
      fmt::print("  broad phase: grid, {} cell crossings, {} bodies outside the grid\n", n.crossings, n.global_bodies);
  }
  if (world.stop_reason() == StopReason::EventStorm) {
    const auto& s = world.storm();
    fmt::print(stderr, "pge: {}: event storm at t = {:.17g}: bodies \"{}\" and \"{}\", {} collisions in a window of "
               "{:.3g} s; run stopped\n",
               loaded.path, to_double(s.time), body_name(scene, s.a), body_name(scene, s.b), s.collisions,
               1e-9 * std::max(1.0, std::abs(to_double(s.time))));
  }
  for (const Tunnel& t : tunnels)
    fmt::print(stderr, "pge run: {}: {}\n", loaded.path, tunnel_text(t, body_name(scene, t.body), body_name(scene, t.fixed)));
  return result;
}

SceneResult simulate_any(const LoadedScene& loaded, const RunOptions& opt, TraceWriter* trace, const std::string& label) {
  return with_scalar(opt.scalar, [&](auto type) {
    return simulate<typename decltype(type)::type>(loaded, opt, trace, label);
  });
}

// The trace file names for --trace-dir: each scene's file stem, and for stems that two scenes
// share, the folder's name before it ("games-pool.jsonl"), then a count after it if that is
// shared too ("games-pool-2.jsonl"): no trace overwrites another.
std::vector<std::string> trace_names(const std::vector<std::string>& files) {
  std::map<std::string, int> stems;
  for (const std::string& f : files) ++stems[fs::path(f).stem().string()];
  std::vector<std::string> names;
  std::set<std::string> taken;
  for (const std::string& f : files) {
    const fs::path path(f);
    std::string name = path.stem().string();
    if (stems[name] > 1) name = fs::absolute(path).parent_path().filename().string() + "-" + name;
    std::string unique = name;
    for (int k = 2; !taken.insert(unique).second; ++k) unique = fmt::format("{}-{}", name, k);
    names.push_back(unique + ".jsonl");
  }
  return names;
}

}  // namespace

int run_command(const RunOptions& opt) {
  const std::optional<std::vector<std::string>> listed = scene_files("run", opt.scenes);
  if (!listed) return kExitBadScene;
  const std::vector<std::string>& files = *listed;
  if (!opt.trace.empty() && files.size() != 1) {
    fmt::print(stderr, "pge run: --trace takes exactly one scene ({} given); use --trace-dir for several\n", files.size());
    return kExitUsage;
  }
  if (!opt.trace_dir.empty()) {
    std::error_code ec;
    fs::create_directories(opt.trace_dir, ec);
    if (ec) {
      fmt::print(stderr, "pge run: cannot create trace directory {}: {}\n", opt.trace_dir, ec.message());
      return kExitOutput;
    }
  }

  const std::vector<std::string> trace_file = trace_names(files);
  int exit_code = kExitOk;
  auto fail = [&](int code) {
    if (exit_code == kExitOk) exit_code = code;
  };
  nlohmann::json all = nlohmann::json::array();
  for (std::size_t k = 0; k < files.size(); ++k) {
    const std::string& file = files[k];
    const std::string label = files.size() > 1 ? fmt::format("[{}/{}] {}", k + 1, files.size(), file) : file;
    const std::optional<LoadedScene> loaded = load_scene("run", file);
    if (!loaded) {
      fail(kExitBadScene);
      continue;
    }
    std::string trace_path = opt.trace;
    if (!opt.trace_dir.empty()) trace_path = (fs::path(opt.trace_dir) / trace_file[k]).string();
    std::unique_ptr<TraceWriter> trace;
    if (!trace_path.empty()) {
      trace = std::make_unique<TraceWriter>();
      if (!trace->open(trace_path)) {
        fmt::print(stderr, "pge run: cannot write trace {}: {}\n", trace_path, trace->error());
        fail(kExitOutput);
        continue;
      }
    }
    fail(simulate_scene("run", file, [&] {
      SceneResult r;
      try {
        r = simulate_any(*loaded, opt, trace.get(), label);
      } catch (const TunnelError& e) {
        // PGE_VALIDATE builds stop robust and certified at the first pass-through.
        if (opt.progress) fmt::print(stderr, "\r{:80}\r", "");
        fmt::print(stderr, "pge run: {}: {}\n", file, e.what());
        fail(kExitTunnel);
        return;
      }
      if (trace && !trace->close()) {
        fmt::print(stderr, "pge run: error writing trace {}: {}\n", trace_path, trace->error());
        fail(kExitOutput);
      } else if (trace && !opt.quiet) {
        fmt::print("  trace: {}\n", trace_path);
      }
      all.push_back(std::move(r.summary));
      fail(r.exit_code);
    }));
  }
  if (!opt.json_summary.empty()) {
    OutputFile out(opt.json_summary);
    out.stream() << all.dump(2) << '\n';
    if (!out.close()) {
      fmt::print(stderr, "pge run: cannot write {}\n", opt.json_summary);
      fail(kExitOutput);
    }
  }
  return exit_code;
}

}  // namespace pge::cli
