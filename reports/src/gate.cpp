#include "pge/gate.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <map>
#include <ostream>

namespace pge::report {

bool GateResult::pass() const { return failures() == 0; }

std::size_t GateResult::failures() const {
  std::size_t n = 0;
  for (const GateCheck& c : checks) n += c.status == Status::Fail ? 1 : 0;
  return n;
}

double scalar_epsilon(const std::string& scalar) {
  if (scalar == "float") return FLT_EPSILON;
  if (scalar == "long-double") return LDBL_EPSILON;
  if (scalar == "quad") return std::ldexp(1.0, -112);  // IEEE binary128: 113 significant bits
  return DBL_EPSILON;
}

namespace {

GateResult closed(const std::string& name, const std::string& why) {
  GateResult g;
  g.checks.push_back({"results", name, Status::Fail, why});
  g.closed = true;
  return g;
}

std::string num(double x) { return fmt::format("{:.4g}", x); }

bool positive_seconds(double s) { return std::isfinite(s) && s > 0; }

// Rows whose wall time the speed checks use (drift rows are not timed; peers are not PGE's); in
// inputs the gate accepts (unusable_results) their wall time is positive.
bool timed(const Row& x) { return x.kind != RowKind::Drift && x.kind != RowKind::Peer && x.error.empty(); }

}  // namespace

GateResult unreadable(const std::string& what) { return closed("results readable", what); }

GateResult unusable(const std::string& why) { return closed("results usable", why); }

std::string unusable_results(const Results& r) {
  if (r.rows.empty()) return "no rows: nothing to gate";
  if (!positive_seconds(r.meta.calibration_seconds))
    return fmt::format("calibration_seconds is {}, not a measured time: speed cannot be compared",
                       num(r.meta.calibration_seconds));
  for (const Row& x : r.rows)
    if (timed(x) && !positive_seconds(x.wall_seconds))
      return fmt::format("row {}: wall_seconds is {}, not a measured time: its speed cannot be compared", x.key(),
                         num(x.wall_seconds));
  return {};
}

std::string unusable_baseline(const Results& b) {
  if (std::string why = unusable_results(b); !why.empty()) return why;
  const bool gated = std::any_of(b.rows.begin(), b.rows.end(),
                                 [](const Row& x) { return x.kind != RowKind::Peer && x.error.empty(); });
  if (!gated)
    return fmt::format("none of its {} rows can be gated against: each is a failed run or a peer's", b.rows.size());
  return {};
}

namespace {

struct Gater {
  const GatePolicy& policy;
  GateResult out;

  void check(const std::string& group, const std::string& name, bool ok, std::string message) {
    out.checks.push_back({group, name, ok ? Status::Pass : Status::Fail, std::move(message)});
  }

  // A count that may not grow (misses, phantoms, misorders).
  void count(const Row& r, const char* what, std::uint64_t base, std::uint64_t now) {
    check("accuracy." + r.config(), r.family + "/" + r.scene + ": " + what, now <= base,
          fmt::format("{} {} (baseline {}; may not grow)", now, what, base));
  }

  // A nonnegative error that may grow to factor x baseline, or baseline + floor.
  void error(const Row& r, const char* what, double base, double now, double floor, const char* unit) {
    const double allowed = std::max(policy.error_factor * base, base + floor);
    // An infinite error (an exact time of 0 against a later engine time, in relative terms) may
    // stay infinite; NaN never passes.
    const bool ok = !std::isnan(now) && (now <= allowed || (std::isinf(now) && std::isinf(base)));
    check("accuracy." + r.config(), r.family + "/" + r.scene + ": " + what, ok,
          fmt::format("{} {} (baseline {}, allowed up to {})", num(now), unit, num(base), num(allowed)));
  }
};

}  // namespace

GateResult gate(const Results& baseline, const Results& results, const GatePolicy& policy) {
  // Fail closed: an empty or unmeasured input would otherwise pass with nothing compared.
  if (const std::string why = unusable_baseline(baseline); !why.empty()) return unusable("baseline: " + why);
  if (const std::string why = unusable_results(results); !why.empty()) return unusable("results: " + why);
  Gater g{policy, {}};
  const Meta& bm = baseline.meta;
  const Meta& rm = results.meta;
  // The two must be the same sweep.
  g.check("results", "same sweep (quick or full)", bm.quick == rm.quick,
          fmt::format("results are a {} report, the baseline a {} one", rm.quick ? "quick" : "full",
                      bm.quick ? "quick" : "full"));
  g.check("results", "same random scenes (seed)", bm.seed == rm.seed,
          fmt::format("results use seed {}, the baseline seed {}", rm.seed, bm.seed));
  g.check("results", "complete (every shard)", rm.shards == 1 || rm.shards_merged.size() == rm.shards,
          fmt::format("results hold {} of {} shards", rm.shards_merged.empty() ? 1 : rm.shards_merged.size(), rm.shards));
  g.check("results", "baseline has no injected regression", bm.injected.empty(),
          "the baseline was made with --inject-regression " + bm.injected);
  if (!rm.injected.empty()) g.out.notes.push_back("the results were made with --inject-regression " + rm.injected);

  std::map<std::string, const Row*> now;
  for (const Row& r : results.rows) now[r.key()] = &r;
  std::map<std::string, bool> matched;

  // Speed. A configuration's time on a scene divided by the reference configuration's time on
  // the same scene in the same invocation, against that quotient in the baseline: a busy or
  // slower machine slows both alike. The geometric mean over the configuration's scenes may grow
  // to speed_factor. The reference configuration itself (and every configuration when the
  // reference did not run) is compared by wall time / calibration time instead, to
  // calibrated_factor: the calibration workload was measured to vary by 2x with the load on a
  // sibling hyperthread, so only a gross slowdown of everything shows there.
  struct Speed {
    double log_sum = 0;
    int n = 0;
  };
  std::map<std::string, Speed> relative, calibrated_speed;
  const bool comparable_build =
      bm.validate == rm.validate && bm.sanitize == rm.sanitize && bm.build_type == rm.build_type;
  std::map<std::string, double> reference_now, reference_base;  // by scene key
  for (const Row& x : results.rows)
    if (timed(x) && x.config() == policy.reference) reference_now[x.scene_key()] = x.wall_seconds;
  for (const Row& x : baseline.rows)
    if (timed(x) && x.config() == policy.reference) reference_base[x.scene_key()] = x.wall_seconds;

  for (const Row& b : baseline.rows) {
    const auto it = now.find(b.key());
    const std::string group = "accuracy." + b.config();
    const std::string where = b.family + "/" + b.scene;
    if (it == now.end()) {
      g.check(group, where + ": present", false, "the baseline has this row and the results do not (fail closed)");
      continue;
    }
    matched[b.key()] = true;
    const Row& r = *it->second;
    // The same name on another scene (an edited fixture, a changed generator) compares nothing.
    if (!b.scene_hash.empty() && !r.scene_hash.empty() && b.scene_hash != r.scene_hash) {
      g.check("results", fmt::format("{} ({}): same scene", where, b.config()), false,
              fmt::format("the scene is not the baseline's (hash {}, baseline {}): it was edited or its generator "
                          "changed; make a new baseline on purpose (pge gate --update) with that change",
                          r.scene_hash, b.scene_hash));
      continue;
    }
    if (b.kind == RowKind::Peer) continue;  // Box2D and Chipmunk for comparison: not PGE's to gate
    if (!b.error.empty()) {
      g.out.notes.push_back(fmt::format("{} ({}): the baseline run failed ({}); not gated", where, b.config(), b.error));
      continue;
    }
    g.check(group, where + ": ran", r.error.empty(), r.error.empty() ? "ran" : "the run failed: " + r.error);
    if (!r.error.empty()) continue;
    g.check(group, where + ": stop", r.stop == b.stop,
            fmt::format("stopped on {} (baseline {})", r.stop, b.stop));
    if (r.events != b.events)
      g.out.notes.push_back(fmt::format("{} ({}): {} events, baseline {}", where, b.config(), r.events, b.events));
    const double drift_floor = policy.drift_eps_floor * scalar_epsilon(b.scalar);
    if (b.kind == RowKind::Accuracy) {
      g.count(r, "misses", b.misses, r.misses);
      g.count(r, "phantoms", b.phantoms, r.phantoms);
      g.count(r, "misorders", b.misorders, r.misorders);
      g.count(r, "tunnelled", b.tunnelled, r.tunnelled);
      if (b.judged_events > 0 || r.judged_events > 0) {
        g.error(r, "largest time error", b.ulps_max, r.ulps_max, policy.ulps_floor, "ulps");
        g.error(r, "p99 time error", b.ulps_p99, r.ulps_p99, policy.ulps_floor, "ulps");
      }
      g.error(r, "energy drift", std::abs(b.energy_drift), std::abs(r.energy_drift), drift_floor, "relative");
      g.error(r, "momentum drift", b.momentum_drift, r.momentum_drift, drift_floor, "relative");
    } else if (b.kind == RowKind::Drift && !b.series.empty() && !r.series.empty()) {
      g.error(r, "energy drift at the end", std::abs(b.series.back().second), std::abs(r.series.back().second),
              drift_floor, "relative");
    }
    if (timed(b) && timed(r)) {
      const std::string scene_key = b.scene_key();
      const auto ref_now = reference_now.find(scene_key), ref_base = reference_base.find(scene_key);
      if (b.config() != policy.reference && ref_now != reference_now.end() && ref_base != reference_base.end()) {
        Speed& s = relative[b.config()];
        s.log_sum += std::log((r.wall_seconds / ref_now->second) / (b.wall_seconds / ref_base->second));
        ++s.n;
      } else {
        Speed& s = calibrated_speed[b.config()];
        s.log_sum += std::log((r.wall_seconds / rm.calibration_seconds) / (b.wall_seconds / bm.calibration_seconds));
        ++s.n;
      }
    }
  }
  for (const Row& r : results.rows)
    if (!matched.count(r.key())) g.out.notes.push_back(fmt::format("{}: new, not in the baseline; not gated", r.key()));

  if (!comparable_build) {
    g.check("speed", "same build", false,
            fmt::format("speed cannot be compared: results from a {}{}{} build, the baseline from a {}{}{} one; run "
                        "the gate with the baseline's build or make a baseline with this one (pge gate --update)",
                        rm.build_type, rm.validate ? " +validate" : "", rm.sanitize ? " +sanitize" : "", bm.build_type,
                        bm.validate ? " +validate" : "", bm.sanitize ? " +sanitize" : ""));
  } else {
    for (const auto& [config, s] : relative) {
      const double factor = std::exp(s.log_sum / s.n);
      g.check("speed", config + ": speed", factor <= policy.speed_factor,
              fmt::format("{}x the baseline's time relative to {} on the same scenes, over {} scenes (allowed up to {}x)",
                          num(factor), policy.reference, s.n, num(policy.speed_factor)));
    }
    for (const auto& [config, s] : calibrated_speed) {
      const double factor = std::exp(s.log_sum / s.n);
      g.check("speed", config + ": speed (calibrated)", factor <= policy.calibrated_factor,
              fmt::format("{}x the baseline's wall time / calibration time, over {} scenes (allowed up to {}x)",
                          num(factor), s.n, num(policy.calibrated_factor)));
    }
  }
  return g.out;
}

namespace {

std::string xml_escaped(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default:
        // XML 1.0 forbids most control characters; none belongs in a message.
        if (static_cast<unsigned char>(c) < 0x20 && c != '\n' && c != '\t') out += '?';
        else out += c;
    }
  }
  return out;
}

}  // namespace

void write_junit(std::ostream& out, const GateResult& g, const std::string& suite) {
  out << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  out << fmt::format("<testsuites name=\"{}\" tests=\"{}\" failures=\"{}\">\n", xml_escaped(suite), g.checks.size(),
                     g.failures());
  out << fmt::format("  <testsuite name=\"{}\" tests=\"{}\" failures=\"{}\">\n", xml_escaped(suite), g.checks.size(),
                     g.failures());
  for (const GateCheck& c : g.checks) {
    out << fmt::format("    <testcase classname=\"{}\" name=\"{}\"", xml_escaped(c.group), xml_escaped(c.name));
    if (c.status == Status::Pass) {
      out << "/>\n";
    } else {
      out << fmt::format(">\n      <failure message=\"{}\"/>\n    </testcase>\n", xml_escaped(c.message));
    }
  }
  if (!g.notes.empty()) {
    out << "    <system-out>";
    for (const std::string& n : g.notes) out << xml_escaped(n) << "\n";
    out << "</system-out>\n";
  }
  out << "  </testsuite>\n</testsuites>\n";
}

void write_gate_markdown(std::ostream& out, const GateResult& g, const Results& baseline, const Results& results,
                         const GatePolicy& policy) {
  out << fmt::format("## pge gate: {}\n\n", g.pass() ? "PASS" : "FAIL");
  out << fmt::format("{} checks, {} failed. Results: commit {}{}; baseline: commit {}.\n\n", g.checks.size(), g.failures(),
                     results.meta.commit, results.meta.dirty ? " (dirty)" : "", baseline.meta.commit);
  out << fmt::format("Policy: errors and drifts may grow to {}x the baseline (floors: {} ulps, {} epsilon); misses, "
                     "phantoms and misorders may not grow; speed (per configuration, the geometric mean over its "
                     "scenes of its time relative to {} in the same run) may grow to {}x, and {}'s own wall time "
                     "over a calibration workload to {}x.\n\n",
                     policy.error_factor, policy.ulps_floor, policy.drift_eps_floor, policy.reference,
                     policy.speed_factor, policy.reference, policy.calibrated_factor);
  if (!g.pass()) {
    out << "| check | group | measured |\n| --- | --- | --- |\n";
    for (const GateCheck& c : g.checks)
      if (c.status == Status::Fail) out << fmt::format("| {} | {} | {} |\n", c.name, c.group, c.message);
    out << "\n";
  }
  bool any_speed = false;
  for (const GateCheck& c : g.checks) {
    if (c.group != "speed") continue;
    if (!any_speed) out << "| speed | result | measured |\n| --- | --- | --- |\n";
    any_speed = true;
    out << fmt::format("| {} | {} | {} |\n", c.name, c.status == Status::Pass ? "pass" : "FAIL", c.message);
  }
  if (any_speed) out << "\n";
  if (!g.notes.empty()) {
    out << fmt::format("Notes ({}):\n\n", g.notes.size());
    const std::size_t shown = std::min<std::size_t>(g.notes.size(), 20);
    for (std::size_t i = 0; i < shown; ++i) out << "- " << g.notes[i] << "\n";
    if (shown < g.notes.size()) out << fmt::format("- ... and {} more (in the JUnit file's system-out)\n", g.notes.size() - shown);
  }
}

}  // namespace pge::report
