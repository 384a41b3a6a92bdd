#include "judge.hpp"

#include "check_report.hpp"
#include "exit_codes.hpp"
#include "scene_files.hpp"
#include "stdout.hpp"

#include "pge/judge.hpp"
#include "pge/trace_io.hpp"

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include <limits>
#include <optional>

namespace pge::cli {
namespace {

using Json = nlohmann::ordered_json;

// Failures printed on stdout after the summary; the JSON holds every verdict.
constexpr std::size_t kFailuresShown = 10;

std::string label_of(const Trace& trace) { return trace.engine.empty() ? std::string("(unnamed engine)") : trace.engine; }

// The events judgement as a `pge check` run, so that both print and write it the same way.
SceneCheck as_check(const LoadedScene& loaded, const Trace& trace, const oracle::EventJudgement& j) {
  SceneCheck c;
  c.path = loaded.path;
  c.name = loaded.scene.name;
  c.bodies = loaded.scene.bodies.size();
  c.scalar = "double";
  c.solver = label_of(trace);
  c.horizon = loaded.scene.run.until;
  c.stop = trace.end ? (trace.end->reached_until ? "reached-until" : "stopped") : "no end record";
  c.stop_reason = trace.end && trace.end->reached_until ? StopReason::ReachedUntil : StopReason::MaxEvents;
  c.time = trace.end ? trace.end->t : (trace.collisions.empty() ? 0.0 : trace.collisions.back().t);
  if (trace.end && trace.end->reached_until) c.horizon = trace.end->t;
  for (const oracle::EventVerdict& v : j.events) {
    EventRecord r = make_record(v.index, v.t, v.event, v.judgement, true);
    if (trace.collisions[v.index].contact.empty()) {  // features not named: not judged
      r.features_match = true;
      r.gap = std::numeric_limits<double>::quiet_NaN();
    }
    c.events.push_back(std::move(r));
  }
  c.contact_events = c.events.size();
  c.end_checked = j.end.has_value();
  if (j.end) c.end = *j.end;
  c.oracle = j.stats;
  c.energy_start = j.energy_start;
  c.energy_end = j.energy_end;
  c.momentum_start = j.momentum_start;
  c.momentum_end = j.momentum_end;
  return c;
}

void print_steps(const std::string& path, const LoadedScene& loaded, const Trace& trace, const oracle::StepJudgement& j) {
  const oracle::StepSummary& s = j.summary;
  fmt::print("trace {} ({}, steps): scene {} (\"{}\"), {} steps to t = {:.17g}\n", path, label_of(trace), loaded.path,
             loaded.scene.name, s.steps, trace.steps.empty() ? 0.0 : trace.steps.back().t);
  fmt::print("  contacts: {} exact: on time {}, late {} (at most {} steps), missed {} ({} pass-through), phantom {}; {} "
             "reports of pairs already overlapping or touching, {} of pairs whose body's path changed in the step\n",
             s.contacts, s.on_time, s.late, s.largest_late_steps, s.missed, s.tunnelled, s.phantom, s.continuing_reports,
             s.unfollowed_reports);
  if (s.undecided > 0)
    fmt::print("  undecided: {} pair-steps with a rotating body whose contact the referee could not decide (counted "
               "apart, neither agreement nor failure)\n",
               s.undecided);
  std::size_t deepest = 0;
  for (std::size_t k = 0; k < j.depth.size(); ++k)
    if (j.depth[k] > j.depth[deepest]) deepest = k;
  if (s.largest_depth > 0)
    fmt::print("  overlap: deepest {:.3g} at the end of step {} (t = {:.17g}); largest relative {:.3g} of the contact distance\n",
               s.largest_depth, deepest, trace.steps[deepest].t, s.largest_relative_depth);
  else
    fmt::print("  overlap: none at any step's end\n");
  fmt::print("  energy {:.17g} -> {:.17g}, largest relative drift {:.3g}; momentum largest relative drift {:.3g}\n",
             s.energy_start, s.energy_end, s.largest_energy_drift, s.largest_momentum_drift);
  std::size_t shown = 0;
  for (const oracle::StepContact& c : j.contacts)
    if ((c.verdict == oracle::StepVerdict::Missed || c.verdict == oracle::StepVerdict::Phantom) && shown++ < kFailuresShown)
      fmt::print("  FAIL: {}; the step ends at t = {:.17g}\n", oracle::contact_text(c), trace.steps[c.step].t);
  fmt::print("  result: {}\n", j.failed() ? "FAIL" : "pass");
}

Json steps_json(const Trace& trace, const oracle::StepJudgement& j) {
  const oracle::StepSummary& s = j.summary;
  Json out;
  out["summary"] = {{"steps", s.steps},
                    {"contacts", s.contacts},
                    {"on_time", s.on_time},
                    {"late", s.late},
                    {"missed", s.missed},
                    {"phantom", s.phantom},
                    {"undecided", s.undecided},
                    {"tunnelled", s.tunnelled},
                    {"continuing_reports", s.continuing_reports},
                    {"unfollowed_reports", s.unfollowed_reports},
                    {"largest_late_steps", s.largest_late_steps},
                    {"largest_depth", s.largest_depth},
                    {"largest_relative_depth", s.largest_relative_depth},
                    {"energy_start", s.energy_start},
                    {"energy_end", s.energy_end},
                    {"largest_energy_drift", s.largest_energy_drift},
                    {"largest_momentum_drift", s.largest_momentum_drift},
                    {"failed", j.failed()}};
  Json contacts = Json::array();
  for (const oracle::StepContact& c : j.contacts) {
    Json x = {{"a", c.a}, {"b", c.b}, {"step", c.step}, {"t_step", trace.steps[c.step].t},
              {"verdict", oracle::step_verdict_name(c.verdict)}};
    x["exact_time"] = c.exact_time ? Json(*c.exact_time) : Json(nullptr);
    x["off_path"] = c.off_path;
    if (c.verdict == oracle::StepVerdict::Late) x["late_steps"] = c.late_steps;
    x["reported_step"] = c.reported_step ? Json(*c.reported_step) : Json(nullptr);
    if (c.verdict == oracle::StepVerdict::Missed) x["miss"] = oracle::miss_kind_name(c.miss);
    if (c.verdict == oracle::StepVerdict::Undecided) x["undecided_reason"] = c.undecided_reason;
    x["depth"] = c.depth;
    x["relative_depth"] = c.relative_depth;
    contacts.push_back(std::move(x));
  }
  out["contacts"] = std::move(contacts);
  Json steps = Json::array();
  for (std::size_t k = 0; k < j.depth.size(); ++k)
    steps.push_back({{"t", trace.steps[k].t}, {"depth", j.depth[k]}, {"energy_drift", j.energy_drift[k]}});
  out["steps"] = std::move(steps);
  return out;
}

int write_json_file(const JudgeCommandOptions& opt, const LoadedScene& loaded, const Trace& trace,
                    const oracle::TraceJudgement& j) {
  OutputFile file(opt.json);
  if (!file.is_open()) {
    fmt::print(stderr, "pge judge: cannot write {}\n", opt.json);
    return kExitOutput;
  }
  std::ostream& out = file.stream();
  const bool steps = trace.mode == TraceMode::Steps;
  const Json head = {{"format", "pge-judge/1"}, {"trace", opt.trace},  {"scene", loaded.path},
                     {"engine", trace.engine},  {"mode", steps ? "steps" : "events"}};
  std::string text = head.dump();
  text.pop_back();  // the closing brace: the result follows
  out << text << ",\"result\":";
  if (steps) {
    out << steps_json(trace, j.steps).dump();
  } else {
    write_json(out, as_check(loaded, trace, j.events), loaded.scene);
  }
  out << "}\n";
  if (!file.close()) {
    fmt::print(stderr, "pge judge: error writing {}\n", opt.json);
    return kExitOutput;
  }
  return kExitOk;
}

}  // namespace

int judge_command(const JudgeCommandOptions& opt) {
  const std::optional<LoadedScene> loaded = load_scene("judge", opt.scene);
  if (!loaded) return kExitBadScene;
  Trace trace;
  try {
    trace = read_trace_file(opt.trace);
  } catch (const TraceError& e) {
    fmt::print(stderr, "pge judge: {}\n", e.what());
    return kExitBadTrace;
  }
  oracle::JudgeOptions options;
  options.overlap_bound = opt.overlap_bound;
  oracle::TraceJudgement j;
  try {
    const int refused = simulate_scene("judge", opt.scene, [&] { j = oracle::judge_trace(loaded->scene, trace, options); });
    if (refused != kExitOk) return refused;
  } catch (const TraceError& e) {
    fmt::print(stderr, "pge judge: {}\n", e.what());
    return kExitBadTrace;
  }
  if (!opt.quiet) {
    if (trace.mode == TraceMode::Steps) {
      print_steps(opt.trace, *loaded, trace, j.steps);
    } else {
      fmt::print("trace {} ({}, events):\n", opt.trace, label_of(trace));
      print_summary(as_check(*loaded, trace, j.events), loaded->scene);
      fmt::print("  result: {}\n", j.failed() ? "FAIL" : "pass");
    }
  }
  if (!opt.json.empty())
    if (const int code = write_json_file(opt, *loaded, trace, j); code != kExitOk) return code;
  if (j.failed()) {
    // One line on stderr whatever --quiet says, as pge check's failed expectations.
    fmt::print(stderr, "pge judge: {}: {}\n", opt.trace, oracle::failure_text(j).substr(0, oracle::failure_text(j).find('\n')));
    return kExitCheckFailed;
  }
  return kExitOk;
}

}  // namespace pge::cli
