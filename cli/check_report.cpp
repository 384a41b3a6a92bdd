#include "check_report.hpp"

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace pge::cli {
namespace {

// Failing events listed in the text summary (all of them are in the JSON).
constexpr std::size_t kFailuresShown = 10;

double magnitude(const oracle::ExactVec& v) {
  const double x = v.x.to_double(), y = v.y.to_double();
  return std::hypot(x, y);
}

const std::string& id_of(const Scene& s, BodyIndex i) {
  static const std::string unknown = "?";
  return i < s.bodies.size() ? s.bodies[i].id : unknown;
}

struct Extremes {
  std::vector<long long> abs_ulps;
  const EventRecord* worst_ulps = nullptr;
  double worst_relative = 0;
  const EventRecord* worst_energy = nullptr;
  const EventRecord* worst_momentum = nullptr;
  const EventRecord* worst_overlap = nullptr;
  std::uint64_t elastic = 0, two_moving = 0, mismatches = 0, no_impulse = 0, overlap_rule = 0;
};

Extremes extremes_of(const SceneCheck& c) {
  Extremes x;
  for (const EventRecord& r : c.events) {
    x.no_impulse += r.impulse ? 0 : 1;
    x.overlap_rule += r.overlap_rule ? 1 : 0;
    if (r.has_exact_time) {
      x.abs_ulps.push_back(std::llabs(r.ulps));
      if (!x.worst_ulps || std::llabs(r.ulps) > std::llabs(x.worst_ulps->ulps)) x.worst_ulps = &r;
      x.worst_relative = std::max(x.worst_relative, r.relative_error);
      x.mismatches += r.features_match ? 0 : 1;
    }
    if (r.elastic) {
      ++x.elastic;
      if (!x.worst_energy || std::abs(r.energy_change) > std::abs(x.worst_energy->energy_change)) x.worst_energy = &r;
    }
    if (r.both_moving) {
      ++x.two_moving;
      if (!x.worst_momentum || r.momentum_change > x.worst_momentum->momentum_change) x.worst_momentum = &r;
    }
    if (std::isfinite(r.gap) && (!x.worst_overlap || r.gap < x.worst_overlap->gap)) x.worst_overlap = &r;
  }
  return x;
}

long long median(std::vector<long long> v) {
  if (v.empty()) return 0;
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

std::string features_text(const oracle::FeaturePair& f) {
  return fmt::format("{} [{}, {}]", contact_kind_name(f.contact), f.feature_a, f.feature_b);
}

void print_failure(const EventRecord& r, const Scene& s) {
  std::string why;
  if (r.verdict == oracle::Verdict::Miss && !r.earliest.empty())
    why = fmt::format("pair {} touches exactly earlier", pair_text(s, r.earliest[0].first, r.earliest[0].second));
  else
    why = r.has_exact_time ? "the pair touches only at " + r.exact_time : "the pair never touches before the horizon";
  fmt::print("  FAILED: {} at event {} (t = {:.17g}, pair {}, {}): {}\n", oracle::verdict_name(r.verdict), r.index,
             r.time, pair_text(s, r.a, r.b), features_text(r.features), why);
}

void print_conservation(const Extremes& x) {
  if (x.worst_energy)
    fmt::print("  energy: largest change {:.3g} (relative {:.3g}) over {} elastic collisions (exact, from the engine's "
               "velocities and positions)\n",
               x.worst_energy->energy_change, x.worst_energy->energy_relative, x.elastic);
  if (x.worst_momentum)
    fmt::print("  momentum: largest change {:.3g} (relative {:.3g}) over {} collisions of two moving bodies\n",
               x.worst_momentum->momentum_change, x.worst_momentum->momentum_relative, x.two_moving);
}

void print_totals(const SceneCheck& c) {
  fmt::print("  engine, start -> end: energy {:.17g} -> {:.17g} (relative change {:.3g}); momentum ({:.17g}, {:.17g}) -> "
             "({:.17g}, {:.17g}) (relative drift {:.3g}); largest overlap at a contact {:.3g} of the contact distance\n",
             c.energy_start, c.energy_end, energy_relative_change(c), c.momentum_start.x, c.momentum_start.y,
             c.momentum_end.x, c.momentum_end.y, momentum_relative_drift(c), c.largest_contact_overlap);
}

std::string_view enforcement_name(Enforcement e) {
  switch (e) {
    case Enforcement::None: return "none";
    case Enforcement::Full: return "full";
    case Enforcement::Verdicts: return "verdicts";
    case Enforcement::Contrast: return "contrast";
  }
  return "?";
}

void print_expectations(const ExpectOutcome& o) {
  switch (o.enforcement) {
    case Enforcement::None: return;
    case Enforcement::Verdicts: fmt::print("  expectations: not checked: {}\n", o.why); return;
    case Enforcement::Full:
    case Enforcement::Contrast: break;
  }
  const bool contrast = o.enforcement == Enforcement::Contrast;
  if (!o.evaluated) {
    fmt::print("  not enforced: {}\n", o.why);
    return;
  }
  const std::string head = contrast ? fmt::format("expectations (contrast, not enforced: {})", o.why) : "expectations";
  if (o.failures.empty()) {
    fmt::print("  {}: {} checked, all hold\n", head, o.checked);
    return;
  }
  fmt::print("  {}: {} checked, {} {}:\n", head, o.checked, o.failures.size(), contrast ? "would fail" : "FAILED");
  for (const ExpectFailure& f : o.failures) fmt::print("    {}: {}\n", f.key, f.text);
}

void print_oracle(const SceneCheck& c) {
  const auto& o = c.oracle;
  const double share = o.pairs_examined ? 100.0 * static_cast<double>(o.pairs_filtered) / static_cast<double>(o.pairs_examined) : 0;
  fmt::print("  oracle: {} events in {:.3f} s ({:.0f} events/s; engine {:.3f} s); filter {}: {} of {} pairs ({:.5f}%) "
             "decided without exact arithmetic; {} pairs ({} feature pairs) solved exactly, the engine's own included\n",
             o.events, o.seconds, o.seconds > 0 ? static_cast<double>(o.events) / o.seconds : 0.0, c.engine_seconds,
             c.filter ? "on" : "off", o.pairs_filtered, o.pairs_examined, share, o.pairs_exact, o.features_exact);
}

}  // namespace

std::string pair_text(const Scene& s, BodyIndex a, BodyIndex b) {
  return fmt::format("\"{}\"-\"{}\"", id_of(s, a), id_of(s, b));
}

EventRecord make_record(std::uint64_t index, double time, const oracle::ExactEvent& e, const oracle::Judgement& j,
                        bool decimals) {
  EventRecord r;
  r.index = index;
  r.time = time;
  r.a = e.a;
  r.b = e.b;
  r.features = {e.contact, e.feature_a, e.feature_b};
  r.impulse = e.impulse;
  r.overlap_rule = e.overlap_rule;
  r.verdict = j.verdict;
  r.has_exact_time = j.pair_time.has_value();
  // 20 decimals: beyond double's resolution for times below 10^4 s, cheap to refine to.
  constexpr int kDecimals = 20;
  if (j.pair_time && (decimals || oracle::is_failure(j.verdict))) r.exact_time = j.pair_time->decimal(kDecimals);
  r.ulps = j.ulps;
  r.relative_error = j.relative_error;
  r.features_match = j.features_match;
  if (j.verdict != oracle::Verdict::Agree)
    for (const oracle::PairContact& p : j.earliest) r.earliest.push_back({p.a, p.b});
  const oracle::Conservation& k = j.conservation;
  r.elastic = k.elastic && e.impulse;
  r.both_moving = k.both_moving && e.impulse;
  r.energy_change = k.energy_change.to_double();
  r.energy_relative = k.kinetic_before > 0 ? std::abs(r.energy_change) / k.kinetic_before : 0;
  r.momentum_change = magnitude(k.momentum_change);
  r.momentum_relative = k.momentum_scale > 0 ? r.momentum_change / k.momentum_scale : 0;
  r.gap = j.gap;
  r.contact_distance = j.contact_distance;
  return r;
}

std::array<std::uint64_t, oracle::kVerdictCount> verdict_counts(const SceneCheck& c) {
  std::array<std::uint64_t, oracle::kVerdictCount> n{};
  for (const EventRecord& r : c.events) ++n[static_cast<std::size_t>(r.verdict)];
  if (c.end.miss) ++n[static_cast<std::size_t>(oracle::Verdict::Miss)];
  n[static_cast<std::size_t>(oracle::Verdict::Miss)] += c.oracle.misses_between_events;  // before a slide off a face
  return n;
}

bool has_failure(const SceneCheck& c) {
  const auto n = verdict_counts(c);
  return n[static_cast<std::size_t>(oracle::Verdict::Miss)] + n[static_cast<std::size_t>(oracle::Verdict::Phantom)] > 0;
}

long long largest_abs_ulps(const SceneCheck& c) {
  const Extremes x = extremes_of(c);
  return x.worst_ulps ? std::llabs(x.worst_ulps->ulps) : 0;
}

namespace {

// change / scale, where a change from 0 is infinitely large.
double relative(double change, double scale) {
  if (scale != 0) return change / scale;
  return change == 0 ? 0.0 : std::copysign(std::numeric_limits<double>::infinity(), change);
}

}  // namespace

double energy_relative_change(const SceneCheck& c) {
  return relative(c.energy_end - c.energy_start, std::abs(c.energy_start));
}

double momentum_relative_drift(const SceneCheck& c) {
  const Vec2d d = c.momentum_end - c.momentum_start;
  return relative(std::hypot(d.x, d.y), std::hypot(c.momentum_start.x, c.momentum_start.y));
}

std::uint64_t past_time_bound(const SceneCheck& c) {
  if (!c.time_bound_ulps) return 0;
  return static_cast<std::uint64_t>(std::count_if(c.events.begin(), c.events.end(), [&c](const EventRecord& r) {
    const std::optional<long long>& bound = r.rotating ? c.rotating_time_bound_ulps : c.time_bound_ulps;
    return r.has_exact_time && bound && std::llabs(r.ulps) > *bound;
  }));
}

std::vector<std::string> failure_reasons(const SceneCheck& c) {
  std::vector<std::string> why;
  if (c.expect.evaluated) {
    for (const ExpectFailure& f : c.expect.failures) why.push_back(f.key == "stop" ? "stop (" + c.stop + ")" : f.key);
    return why;
  }
  if (c.stop_reason == StopReason::EventStorm && !c.expect.storm_expected) why.push_back(c.stop);
  const auto n = verdict_counts(c);
  for (const oracle::Verdict v : {oracle::Verdict::Miss, oracle::Verdict::Phantom})
    if (const auto k = n[static_cast<std::size_t>(v)]; k > 0) why.push_back(fmt::format("{} {}", k, oracle::verdict_name(v)));
  // A solver that breaks its own promise on a time is wrong even when no event was missed.
  if (const auto k = past_time_bound(c); k > 0)
    why.push_back(fmt::format("{} past the {}-ulp time bound", k, *c.time_bound_ulps));
  if (!c.tunnels.empty()) why.push_back(fmt::format("{} tunnelled", c.tunnels.size()));
  return why;
}

void print_summary(const SceneCheck& c, const Scene& s) {
  const Extremes x = extremes_of(c);  // empty when not judged
  fmt::print("scene {} (\"{}\"): {} bodies, scalar {}, solver {}\n", c.path, c.name, c.bodies, c.scalar, c.solver);
  fmt::print("  stopped: {} at t = {:.17g} (horizon {:.17g}){}\n", c.stop, c.time, c.horizon,
             c.storm_a == kNoBody ? "" : ", bodies " + pair_text(s, c.storm_a, c.storm_b));
  if (c.judged) {
    std::string end = "not checked (the run stopped before its horizon)";
    if (c.end_checked && !c.end.miss) end = "no contact left before the horizon";
    if (c.end_checked && c.end.undecided) end = "undecided (" + c.end.undecided_reason + ")";
    if (c.end.miss && !c.end.next.pairs.empty())
      end = fmt::format("MISS: pair {} touches at {} before the horizon",
                        pair_text(s, c.end.next.pairs[0].a, c.end.next.pairs[0].b), c.end.next.time->decimal(20));
    fmt::print("  judged: {} events ({} without impulse, {} by the overlap rule); end: {}\n", c.events.size(), x.no_impulse,
               x.overlap_rule, end);
    for (const oracle::MotionMiss& m : c.motion_misses)
      if (!m.next.pairs.empty())
        fmt::print("  MISS: pair {} touches at {}, before body {} changed its motion at t = {:.17g}\n",
                   pair_text(s, m.next.pairs[0].a, m.next.pairs[0].b), m.next.time->decimal(20), id_of(s, m.body),
                   m.at.to_double());
    const auto n = verdict_counts(c);
    fmt::print("  verdicts:");
    for (int v = 0; v < oracle::kVerdictCount; ++v)
      fmt::print("{} {} {}", v ? "," : "", oracle::verdict_name(static_cast<oracle::Verdict>(v)), n[static_cast<std::size_t>(v)]);
    fmt::print("\n");
    if (x.worst_ulps)
      fmt::print("  time error: median {} ulps, largest {} ulps (event {}, pair {}), largest relative {:.3g}; {} events "
                 "with other features than the oracle's\n",
                 median(x.abs_ulps), x.worst_ulps->ulps, x.worst_ulps->index, pair_text(s, x.worst_ulps->a, x.worst_ulps->b),
                 x.worst_relative, x.mismatches);
    if (x.worst_ulps && c.time_bound_ulps)
      fmt::print("  time bound: {} ulps ({}'s promise): {}\n", *c.time_bound_ulps, c.solver,
                 past_time_bound(c) == 0 ? "ok" : fmt::format("EXCEEDED by {} events", past_time_bound(c)));
    print_conservation(x);
    if (x.worst_overlap) {
      const EventRecord& w = *x.worst_overlap;
      const double depth = std::max(0.0, -w.gap);
      fmt::print("  overlap: largest {:.3g}{} at event {} (exact contact function at the engine's time)\n", depth,
                 w.contact_distance > 0 ? fmt::format(" (relative {:.3g})", depth / w.contact_distance) : "", w.index);
    }
    print_oracle(c);
  } else {
    fmt::print("  events: {} contact events, not judged (the expect block says \"oracle\": false)\n", c.contact_events);
  }
  print_totals(c);
  if (!c.tunnels.empty())
    fmt::print("  tunnelling: {} {} passed through a fixed body\n", c.tunnels.size(), c.tunnels.size() == 1 ? "body" : "bodies");
  print_expectations(c.expect);
  std::size_t shown = 0;
  for (const EventRecord& r : c.events)
    if (oracle::is_failure(r.verdict) && shown++ < kFailuresShown) print_failure(r, s);
}

namespace {

nlohmann::json summary_json(const SceneCheck& c, const Scene& s) {
  const Extremes x = extremes_of(c);
  nlohmann::json j;
  j["scene"] = c.path;
  j["name"] = c.name;
  j["bodies"] = c.bodies;
  j["scalar"] = c.scalar;
  j["solver"] = c.solver;
  j["stop"] = c.stop;
  if (c.storm_a != kNoBody) j["storm"] = {id_of(s, c.storm_a), id_of(s, c.storm_b)};
  j["time"] = c.time;
  j["horizon"] = c.horizon;
  const auto n = verdict_counts(c);
  for (int v = 0; v < oracle::kVerdictCount; ++v)
    j["verdicts"][std::string(oracle::verdict_name(static_cast<oracle::Verdict>(v)))] = n[static_cast<std::size_t>(v)];
  j["end_checked"] = c.end_checked;
  j["end_miss"] = c.end.miss;
  j["end_undecided"] = c.end.undecided;
  if (c.end.miss && !c.end.next.pairs.empty())
    j["end_pair"] = {id_of(s, c.end.next.pairs[0].a), id_of(s, c.end.next.pairs[0].b)};
  j["motion_misses"] = nlohmann::json::array();
  for (const oracle::MotionMiss& m : c.motion_misses) {
    nlohmann::json k{{"body", id_of(s, m.body)}, {"at", m.at.to_double()}};
    if (!m.next.pairs.empty()) {
      k["pair"] = {id_of(s, m.next.pairs[0].a), id_of(s, m.next.pairs[0].b)};
      k["exact_time"] = m.next.time->decimal(20);
    }
    j["motion_misses"].push_back(k);
  }
  j["median_abs_ulps"] = median(x.abs_ulps);
  j["largest_ulps"] = x.worst_ulps ? x.worst_ulps->ulps : 0;
  j["largest_relative_time_error"] = x.worst_relative;
  j["time_bound_ulps"] = c.time_bound_ulps ? nlohmann::json(*c.time_bound_ulps) : nlohmann::json(nullptr);
  j["past_time_bound"] = past_time_bound(c);
  j["feature_mismatches"] = x.mismatches;
  j["largest_energy_change"] = x.worst_energy ? x.worst_energy->energy_change : 0.0;
  j["largest_momentum_change"] = x.worst_momentum ? x.worst_momentum->momentum_change : 0.0;
  j["largest_overlap"] = x.worst_overlap ? std::max(0.0, -x.worst_overlap->gap) : 0.0;
  j["judged"] = c.judged;
  j["contact_events"] = c.contact_events;
  j["energy_start"] = c.energy_start;
  j["energy_end"] = c.energy_end;
  j["momentum_start"] = {c.momentum_start.x, c.momentum_start.y};
  j["momentum_end"] = {c.momentum_end.x, c.momentum_end.y};
  j["largest_contact_overlap_relative"] = c.largest_contact_overlap;
  j["tunnels"] = nlohmann::json::array();
  for (const Tunnel& t : c.tunnels)
    j["tunnels"].push_back({{"body", id_of(s, t.body)}, {"fixed", id_of(s, t.fixed)}, {"from", t.from}, {"to", t.to}});
  nlohmann::json& e = j["expectations"];
  e["enforcement"] = enforcement_name(c.expect.enforcement);
  if (!c.expect.why.empty()) e["why"] = c.expect.why;
  if (c.expect.evaluated) {
    e["checked"] = c.expect.checked;
    e["failures"] = nlohmann::json::array();
    for (const ExpectFailure& f : c.expect.failures) e["failures"].push_back({{"key", f.key}, {"text", f.text}});
  }
  j["oracle"] = {{"events", c.oracle.events},         {"seconds", c.oracle.seconds},
                 {"pairs_examined", c.oracle.pairs_examined}, {"pairs_filtered", c.oracle.pairs_filtered},
                 {"pairs_exact", c.oracle.pairs_exact}, {"features_exact", c.oracle.features_exact},
                 {"filter", c.filter}};
  return j;
}

nlohmann::json event_json(const EventRecord& r, const Scene& s) {
  nlohmann::json e = {{"index", r.index},
                      {"t", r.time},
                      {"a", id_of(s, r.a)},
                      {"b", id_of(s, r.b)},
                      {"contact", contact_kind_name(r.features.contact)},
                      {"features", {r.features.feature_a, r.features.feature_b}},
                      {"impulse", r.impulse},
                      {"verdict", oracle::verdict_name(r.verdict)},
                      {"features_match", r.features_match},
                      {"energy_change", r.energy_change},
                      {"momentum_change", r.momentum_change},
                      {"gap", std::isfinite(r.gap) ? nlohmann::json(r.gap) : nlohmann::json()}};
  if (r.has_exact_time) {
    e["exact_time"] = r.exact_time;
    e["ulps"] = r.ulps;
    e["relative_error"] = r.relative_error;
  }
  if (r.verdict != oracle::Verdict::Agree) {
    nlohmann::json first = nlohmann::json::array();
    for (const auto& [a, b] : r.earliest) first.push_back({id_of(s, a), id_of(s, b)});
    e["earliest"] = first;
  }
  return e;
}

}  // namespace

void write_json(std::ostream& out, const SceneCheck& c, const Scene& s) {
  std::string head = summary_json(c, s).dump();
  head.pop_back();  // the closing brace: the events follow
  out << head << ",\"events\":[";
  for (std::size_t k = 0; k < c.events.size(); ++k) out << (k ? ",\n" : "\n") << event_json(c.events[k], s).dump();
  out << "\n]}";
}

namespace {

std::string cell_text(std::string text) {
  for (std::size_t at = text.find('|'); at != std::string::npos; at = text.find('|', at + 2)) text.insert(at, "\\");
  return text;
}

std::string brief(const std::vector<std::string>& why) {
  return why.size() == 1 ? why[0] : fmt::format("{} (+{} more)", why[0], why.size() - 1);
}

}  // namespace

TableCell table_cell(const SceneCheck& c) {
  TableCell cell;
  cell.events = fmt::format("{}", c.contact_events);
  const bool timed = std::any_of(c.events.begin(), c.events.end(), [](const EventRecord& r) { return r.has_exact_time; });
  // A phantom's pair may touch only much later: millions of ulps and more read better rounded.
  constexpr long long kExactDigitsShown = 1000000;
  const long long ulps = largest_abs_ulps(c);
  cell.ulps = !timed ? "-" : ulps < kExactDigitsShown ? fmt::format("{}", ulps) : fmt::format("{:.1e}", static_cast<double>(ulps));
  cell.drift = fmt::format("{:.2g}", std::abs(energy_relative_change(c)));
  const std::vector<std::string> why = failure_reasons(c);
  if (c.expect.enforcement == Enforcement::Contrast)
    cell.result = fmt::format("n/a (contrast: {})", why.empty() ? "pass" : "fails " + brief(why));
  else
    cell.result = why.empty() ? "pass" : "FAIL: " + brief(why);
  return cell;
}

void write_table(std::ostream& out, const std::vector<TableRow>& rows) {
  // Columns padded to their widest cell, so that the raw text reads as a table too.
  std::vector<std::vector<std::string>> lines;
  lines.push_back({"family", "scene"});
  for (const SolverKind s : {SolverKind::Fast, SolverKind::Robust, SolverKind::Certified})
    for (const char* what : {" events", " ulps", " drift", " result"}) lines[0].push_back(std::string(solver_name(s)) + what);
  for (const TableRow& row : rows) {
    std::vector<std::string> line{cell_text(row.family), "`" + cell_text(row.scene) + "`"};
    for (const TableCell& cell : row.cells)
      for (const std::string* text : {&cell.events, &cell.ulps, &cell.drift, &cell.result})
        line.push_back(cell.result.empty() ? "" : cell_text(*text));
    lines.push_back(std::move(line));
  }
  std::vector<std::size_t> width(lines[0].size(), 3);
  for (const auto& line : lines)
    for (std::size_t k = 0; k < line.size(); ++k) width[k] = std::max(width[k], line[k].size());
  const auto is_number = [](std::size_t k) { return k >= 2 && (k - 2) % 4 != 3; };
  const auto print_line = [&](const std::vector<std::string>& line) {
    out << '|';
    for (std::size_t k = 0; k < line.size(); ++k)
      out << ' ' << (is_number(k) ? fmt::format("{:>{}}", line[k], width[k]) : fmt::format("{:<{}}", line[k], width[k]))
          << " |";
    out << '\n';
  };
  print_line(lines[0]);
  out << '|';
  for (std::size_t k = 0; k < width.size(); ++k)
    out << ' ' << std::string(width[k] - (is_number(k) ? 1 : 0), '-') << (is_number(k) ? ":" : "") << " |";
  out << '\n';
  for (std::size_t r = 1; r < lines.size(); ++r) print_line(lines[r]);
  out << "\nevents: contact events (collisions and zero-impulse contacts); ulps: largest time error against the "
         "exact oracle (-: not judged); drift: |E_end - E_start| / |E_start| by the engine; n/a: not enforced, shown "
         "for contrast.\n";
}

}  // namespace pge::cli
