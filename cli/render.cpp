// `pge render`: the command (the output's form from its extension, the options, writing the
// file). The parts: render_parts.hpp.
#include "render.hpp"

#include "exit_codes.hpp"
#include "render_parts.hpp"
#include "scene_files.hpp"

#include "pge/scene_io.hpp"
#include "pge/world.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>

namespace pge::cli {
namespace {

namespace fs = std::filesystem;
using render::kSvgWidthPx;

enum class Form { Svg, Html };

std::optional<Form> form_of(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == ".svg") return Form::Svg;
  if (ext == ".html") return Form::Html;
  return std::nullopt;
}

// Writes `text` to `path`; "" or what went wrong.
std::string write_file(const std::string& path, const std::string& text) {
  errno = 0;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (out) out.write(text.data(), static_cast<std::streamsize>(text.size()));
  if (out) out.close();
  if (out) return {};
  return errno ? std::strerror(errno) : "write failed";
}

}  // namespace

int render_command(const RenderOptions& options) {
  const std::optional<Form> form = form_of(options.out);
  if (!form) {
    fmt::print(stderr, "pge render: the output file must end in .svg (a picture) or .html (an animation), got \"{}\"\n",
               options.out);
    return kExitUsage;
  }
  if (!(options.frames > 0) || !std::isfinite(options.frames)) {
    fmt::print(stderr, "pge render: --frames must be a positive number of samples per second, got {}\n", options.frames);
    return kExitUsage;
  }
  WorldOptions wo;
  wo.until = options.until;
  wo.max_events = options.max_events;
  wo.frames_per_second = options.frames;
  if (!options.solver.empty()) {
    SolverKind kind{};
    if (!parse_solver_kind(options.solver, kind)) {
      fmt::print(stderr, "pge render: unknown solver \"{}\" (fast, robust, certified)\n", options.solver);
      return kExitUsage;
    }
    wo.solver = kind;
  }

  // A missing directory is found before a long simulation, not after it.
  std::error_code ec;
  if (const fs::path dir = fs::path(options.out).parent_path(); !dir.empty() && !fs::is_directory(dir, ec)) {
    fmt::print(stderr, "pge render: cannot write {}: no such directory {}\n", options.out, dir.string());
    return kExitOutput;
  }

  const std::optional<LoadedScene> loaded = load_scene("render", options.scene);
  if (!loaded) return kExitBadScene;
  render::Run run;
  if (const int refused = simulate_scene("render", options.scene, [&] { run = render::simulate(*loaded, wo); });
      refused != kExitOk)
    return refused;

  const render::View view = render::fit_view(run);
  const std::string text = *form == Form::Svg
                               ? "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n" + render::svg_picture(run, view, kSvgWidthPx)
                               : render::html_page(run, view);
  if (const std::string error = write_file(options.out, text); !error.empty()) {
    fmt::print(stderr, "pge render: cannot write {}: {}\n", options.out, error);
    return kExitOutput;
  }
  if (!options.quiet) {
    fmt::print("render: {} -> {}: {} bodies, {} collisions, t = {:.9g} ({}){}\n", options.scene, options.out,
               run.scene().bodies.size(), run.collisions, run.end, run.solver,
               run.stop == StopReason::ReachedUntil ? "" : fmt::format(", stopped: {}", stop_reason_name(run.stop)));
  }
  if (run.stop == StopReason::EventStorm) {
    const auto name = [&](BodyIndex i) { return i < run.scene().bodies.size() ? run.scene().bodies[i].id : "?"; };
    fmt::print(stderr,
               "pge render: {}: event storm at t = {:.17g}: bodies \"{}\" and \"{}\", {} collisions; run stopped, "
               "{} shows the run up to there\n",
               options.scene, run.storm.time, name(run.storm.a), name(run.storm.b), run.storm.collisions, options.out);
    return kExitStorm;
  }
  return kExitOk;
}

}  // namespace pge::cli
