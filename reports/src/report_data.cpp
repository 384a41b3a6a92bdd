#include "pge/report_data.hpp"

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

namespace pge::report {

using nlohmann::json;

int rel_bucket(double e) {
  if (!(e > 0)) return 0;  // 0, and NaN (which no judged event has) kept out of the scale
  const int exp = std::ilogb(e);  // e in [2^exp, 2^(exp+1))
  return std::clamp(exp - kRelMinExp + 1, 1, kRelBuckets - 1);
}

double rel_bucket_upper(int bucket) { return bucket <= 0 ? 0.0 : std::ldexp(1.0, bucket + kRelMinExp); }

const char* row_kind_name(RowKind k) {
  switch (k) {
    case RowKind::Accuracy: return "accuracy";
    case RowKind::Scaling: return "scaling";
    case RowKind::Drift: return "drift";
    case RowKind::Peer: return "peer";
  }
  return "?";
}

RowKind parse_row_kind(const std::string& name) {
  for (RowKind k : {RowKind::Accuracy, RowKind::Scaling, RowKind::Drift, RowKind::Peer})
    if (name == row_kind_name(k)) return k;
  throw ReportError("unknown row kind \"" + name + "\"");
}

std::string Row::scene_key() const { return fmt::format("{}/{}/{}", row_kind_name(kind), family, scene); }
std::string Row::key() const { return fmt::format("{}/{}/{}", scene_key(), solver, scalar); }

namespace {

// JSON has no infinities or NaN (nlohmann would write null): they are written as strings. A
// relative time error is infinite when the exact time is 0 and the engine's is not.
json jnum(double x) {
  if (std::isfinite(x)) return x;
  return std::isnan(x) ? "nan" : x > 0 ? "inf" : "-inf";
}

json row_json(const Row& r) {
  json j{{"kind", row_kind_name(r.kind)}, {"family", r.family}, {"scene", r.scene}, {"scene_hash", r.scene_hash}, {"solver", r.solver},
         {"scalar", r.scalar}, {"bodies", r.bodies}, {"events", r.events}, {"predictions", r.predictions},
         {"stop", r.stop}, {"error", r.error}, {"elastic", r.elastic}, {"judged_events", r.judged_events}, {"misses", r.misses},
         {"phantoms", r.phantoms}, {"misorders", r.misorders}, {"ulps_median", jnum(r.ulps_median)},
         {"ulps_p99", jnum(r.ulps_p99)}, {"ulps_max", jnum(r.ulps_max)}, {"rel_p99", jnum(r.rel_p99)}, {"rel_max", jnum(r.rel_max)},
         {"energy_drift", jnum(r.energy_drift)}, {"momentum_drift", jnum(r.momentum_drift)}, {"overlap", jnum(r.overlap)}, {"tunnelled", r.tunnelled}, {"final_error", jnum(r.final_error)},
         {"repeats", r.repeats}, {"wall_seconds", jnum(r.wall_seconds)}, {"wall_min_seconds", jnum(r.wall_min_seconds)},
         {"events_per_second", jnum(r.events_per_second)}, {"ns_per_prediction", jnum(r.ns_per_prediction)},
         {"timed_in_judged_run", r.timed_in_judged_run}, {"cost_seconds", jnum(r.cost_seconds)}, {"cost_cpu_seconds", jnum(r.cost_cpu_seconds)}};
  // The histogram sparsely ([bucket, count] pairs) and the series as pairs.
  json hist = json::array();
  for (std::size_t b = 0; b < r.rel_hist.size(); ++b)
    if (r.rel_hist[b] != 0) hist.push_back({b, r.rel_hist[b]});
  j["rel_hist"] = hist;
  json series = json::array();
  for (const auto& [x, y] : r.series) series.push_back({jnum(x), jnum(y)});
  j["series"] = series;
  return j;
}

// JSON numbers that must be finite: nlohmann writes NaN and infinities as null.
double number(const json& v) {
  if (v.is_string()) {
    const std::string s = v.get<std::string>();
    if (s == "inf") return HUGE_VAL;
    if (s == "-inf") return -HUGE_VAL;
    if (s == "nan") return std::nan("");
    throw ReportError("\"" + s + "\" is not a number");
  }
  return v.get<double>();
}
double number(const json& j, const char* key) { return number(j.at(key)); }

Row row_from(const json& j) {
  Row r;
  r.kind = parse_row_kind(j.at("kind").get<std::string>());
  r.family = j.at("family").get<std::string>();
  r.scene = j.at("scene").get<std::string>();
  r.scene_hash = j.value("scene_hash", std::string());  // absent in reports made before it existed
  r.solver = j.at("solver").get<std::string>();
  r.scalar = j.at("scalar").get<std::string>();
  r.bodies = j.at("bodies").get<std::uint64_t>();
  r.events = j.at("events").get<std::uint64_t>();
  r.predictions = j.at("predictions").get<std::uint64_t>();
  r.stop = j.at("stop").get<std::string>();
  r.error = j.at("error").get<std::string>();
  r.elastic = j.at("elastic").get<bool>();
  r.judged_events = j.at("judged_events").get<std::uint64_t>();
  r.misses = j.at("misses").get<std::uint64_t>();
  r.phantoms = j.at("phantoms").get<std::uint64_t>();
  r.misorders = j.at("misorders").get<std::uint64_t>();
  r.ulps_median = number(j, "ulps_median");
  r.ulps_p99 = number(j, "ulps_p99");
  r.ulps_max = number(j, "ulps_max");
  r.rel_p99 = number(j, "rel_p99");
  r.rel_max = number(j, "rel_max");
  r.energy_drift = number(j, "energy_drift");
  r.momentum_drift = number(j, "momentum_drift");
  r.overlap = number(j, "overlap");
  r.tunnelled = j.at("tunnelled").get<std::uint64_t>();
  r.final_error = number(j, "final_error");
  r.repeats = j.at("repeats").get<unsigned>();
  r.wall_seconds = number(j, "wall_seconds");
  r.wall_min_seconds = number(j, "wall_min_seconds");
  r.events_per_second = number(j, "events_per_second");
  r.ns_per_prediction = number(j, "ns_per_prediction");
  // Absent in reports made before they existed.
  r.timed_in_judged_run = j.value("timed_in_judged_run", false);
  if (j.contains("cost_seconds")) r.cost_seconds = number(j, "cost_seconds");
  if (j.contains("cost_cpu_seconds")) r.cost_cpu_seconds = number(j, "cost_cpu_seconds");
  for (const json& pair : j.at("rel_hist")) {
    const auto b = pair.at(0).get<std::size_t>();
    if (b >= static_cast<std::size_t>(kRelBuckets)) throw ReportError(fmt::format("histogram bucket {} out of range", b));
    if (r.rel_hist.empty()) r.rel_hist.assign(kRelBuckets, 0);
    r.rel_hist[b] += pair.at(1).get<std::uint64_t>();
  }
  for (const json& pair : j.at("series")) r.series.emplace_back(number(pair.at(0)), number(pair.at(1)));
  return r;
}

json meta_json(const Meta& m) {
  return json{{"format", m.format}, {"created", m.created}, {"commit", m.commit}, {"dirty", m.dirty},
              {"compiler", m.compiler}, {"build_type", m.build_type}, {"validate", m.validate},
              {"sanitize", m.sanitize}, {"cpu", m.cpu}, {"os", m.os}, {"cores", m.cores}, {"quick", m.quick},
              {"seed", m.seed}, {"shard", m.shard}, {"shards", m.shards}, {"shards_merged", m.shards_merged},
              {"injected", m.injected}, {"calibration_seconds", m.calibration_seconds}, {"items", m.items},
              {"jobs", m.jobs}};
}

Meta meta_from(const json& j) {
  Meta m;
  m.format = j.at("format").get<std::string>();
  if (m.format != kFormat) throw ReportError("format is \"" + m.format + "\", expected \"" + kFormat + "\"");
  m.created = j.at("created").get<std::string>();
  m.commit = j.at("commit").get<std::string>();
  m.dirty = j.at("dirty").get<bool>();
  m.compiler = j.at("compiler").get<std::string>();
  m.build_type = j.at("build_type").get<std::string>();
  m.validate = j.at("validate").get<bool>();
  m.sanitize = j.at("sanitize").get<bool>();
  m.cpu = j.at("cpu").get<std::string>();
  m.os = j.at("os").get<std::string>();
  m.cores = j.at("cores").get<unsigned>();
  m.quick = j.at("quick").get<bool>();
  m.seed = j.at("seed").get<std::uint64_t>();
  m.shard = j.at("shard").get<unsigned>();
  m.shards = j.at("shards").get<unsigned>();
  m.shards_merged = j.at("shards_merged").get<std::vector<unsigned>>();
  m.injected = j.at("injected").get<std::string>();
  m.calibration_seconds = number(j, "calibration_seconds");
  m.items = j.at("items").get<std::uint64_t>();
  m.jobs = j.value("jobs", 1u);  // absent in reports made before --jobs: one at a time
  if (m.shards == 0 || m.shard >= m.shards) throw ReportError(fmt::format("shard {}/{} is not a shard", m.shard, m.shards));
  return m;
}

}  // namespace

std::string to_json_text(const Results& r) {
  // One row per line: diffs of a committed baseline stay readable.
  std::string out = "{\"meta\": " + meta_json(r.meta).dump() + ",\n\"rows\": [";
  for (std::size_t i = 0; i < r.rows.size(); ++i) out += (i ? ",\n" : "\n") + row_json(r.rows[i]).dump();
  out += "\n]}\n";
  return out;
}

Results from_json_text(const std::string& text, const std::string& origin) {
  try {
    const json j = json::parse(text);
    Results r;
    r.meta = meta_from(j.at("meta"));
    // Iterating null or an object would give no rows, and the gate nothing to compare.
    const json& rows = j.at("rows");
    if (!rows.is_array()) throw ReportError(fmt::format("\"rows\" is {}, not an array", rows.type_name()));
    std::set<std::string> keys;
    for (const json& row : rows) {
      r.rows.push_back(row_from(row));
      if (!keys.insert(r.rows.back().key()).second) throw ReportError("row " + r.rows.back().key() + " appears twice");
    }
    return r;
  } catch (const ReportError& e) {
    throw ReportError(origin + ": " + e.what());
  } catch (const json::exception& e) {
    throw ReportError(origin + ": not a pge-report/1 results file: " + e.what());
  }
}

std::string row_to_json_line(const Row& row) { return row_json(row).dump(); }

Row row_from_json_line(const std::string& line) {
  try {
    return row_from(json::parse(line));
  } catch (const json::exception& e) {
    throw ReportError(std::string("not a pge-report/1 row: ") + e.what());
  }
}

Results read_results(const std::string& path) {
  const std::string text = read_text_file(path);
  if (text.empty()) throw ReportError(path + ": empty file");
  return from_json_text(text, path);
}

void write_results(const std::string& path, const Results& r) { write_text_file_atomically(path, to_json_text(r)); }

std::string read_text_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ReportError("cannot read " + path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

void write_text_file_atomically(const std::string& path, const std::string& text) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary);
    out << text;
    out.close();
    if (!out) throw ReportError("cannot write " + tmp);
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) throw ReportError("cannot rename " + tmp + " to " + path);
}

void write_csv(std::ostream& out, const Results& r) {
  const auto field = [](const std::string& s) {
    if (s.find_first_of(",\"\n") == std::string::npos) return s;
    std::string q = "\"";
    for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
    return q + "\"";
  };
  out << "kind,family,scene,solver,scalar,bodies,elastic,events,predictions,stop,error,judged_events,misses,phantoms,"
         "misorders,ulps_median,ulps_p99,ulps_max,rel_p99,rel_max,energy_drift,momentum_drift,overlap,tunnelled,"
         "final_error,repeats,"
         "wall_seconds,wall_min_seconds,events_per_second,ns_per_prediction,commit\n";
  for (const Row& x : r.rows) {
    out << fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n",
                       row_kind_name(x.kind), field(x.family), field(x.scene), x.solver, x.scalar, x.bodies,
                       x.elastic ? 1 : 0, x.events,
                       x.predictions, x.stop, field(x.error), x.judged_events, x.misses, x.phantoms, x.misorders,
                       x.ulps_median, x.ulps_p99, x.ulps_max, x.rel_p99, x.rel_max, x.energy_drift, x.momentum_drift,
                       x.overlap, x.tunnelled, x.final_error, x.repeats, x.wall_seconds, x.wall_min_seconds, x.events_per_second,
                       x.ns_per_prediction, r.meta.commit);
  }
}

Results merge(const std::vector<Results>& parts, bool allow_partial) {
  if (parts.empty()) throw ReportError("nothing to merge");
  Results out;
  out.meta = parts.front().meta;
  out.meta.shard = 0;
  out.meta.shards_merged.clear();
  std::set<unsigned> seen;
  std::set<std::string> keys;
  double calibration_sum = 0;
  for (const Results& p : parts) {
    const Meta& m = p.meta;
    const auto differs = [&](const char* what, const std::string& a, const std::string& b) {
      if (a != b) throw ReportError(fmt::format("cannot merge: {} differs ({} against {})", what, a, b));
    };
    differs("commit", m.commit, out.meta.commit);
    differs("quick", m.quick ? "quick" : "full", out.meta.quick ? "quick" : "full");
    differs("seed", std::to_string(m.seed), std::to_string(out.meta.seed));
    differs("shard count", std::to_string(m.shards), std::to_string(out.meta.shards));
    differs("item count", std::to_string(m.items), std::to_string(out.meta.items));
    differs("injected regression", m.injected, out.meta.injected);
    std::vector<unsigned> shards = m.shards_merged.empty() ? std::vector<unsigned>{m.shard} : m.shards_merged;
    for (unsigned s : shards)
      if (!seen.insert(s).second) throw ReportError(fmt::format("cannot merge: shard {}/{} appears twice", s, m.shards));
    for (const Row& row : p.rows) {
      if (!keys.insert(row.key()).second) throw ReportError("cannot merge: row " + row.key() + " appears twice");
      out.rows.push_back(row);
    }
    out.meta.dirty = out.meta.dirty || m.dirty;
    out.meta.jobs = std::max(out.meta.jobs, m.jobs);
    calibration_sum += m.calibration_seconds;
  }
  out.meta.calibration_seconds = calibration_sum / static_cast<double>(parts.size());
  out.meta.shards_merged.assign(seen.begin(), seen.end());
  if (!allow_partial && seen.size() != out.meta.shards) {
    std::string missing;
    for (unsigned s = 0; s < out.meta.shards; ++s)
      if (!seen.count(s)) missing += fmt::format("{}{}/{}", missing.empty() ? "" : ", ", s, out.meta.shards);
    throw ReportError("cannot merge: shard(s) " + missing + " missing");
  }
  std::stable_sort(out.rows.begin(), out.rows.end(), [](const Row& a, const Row& b) {
    if (a.kind != b.kind) return a.kind < b.kind;
    if (a.family != b.family) return a.family < b.family;
    if (a.scene != b.scene) return a.scene < b.scene;
    return config_order(a.solver, a.scalar) < config_order(b.solver, b.scalar);
  });
  return out;
}

double hist_quantile(const std::vector<std::uint64_t>& hist, double q) {
  std::uint64_t total = 0;
  for (std::uint64_t c : hist) total += c;
  if (total == 0) return 0;
  // The smallest bucket whose cumulative count reaches q of the total.
  const auto need = static_cast<std::uint64_t>(std::ceil(q * static_cast<double>(total)));
  std::uint64_t sum = 0;
  for (std::size_t b = 0; b < hist.size(); ++b) {
    sum += hist[b];
    if (sum >= std::max<std::uint64_t>(need, 1)) return rel_bucket_upper(static_cast<int>(b));
  }
  return rel_bucket_upper(static_cast<int>(hist.size()) - 1);
}

int config_order(const std::string& solver, const std::string& scalar) {
  static const std::vector<std::string> solvers{"fast", "robust", "certified"};
  static const std::vector<std::string> scalars{"float", "double", "long-double", "quad"};
  const auto at = [](const std::vector<std::string>& v, const std::string& s) {
    const auto it = std::find(v.begin(), v.end(), s);
    return static_cast<int>(it - v.begin());  // unknown: v.size()
  };
  return at(solvers, solver) * 8 + at(scalars, scalar);
}

std::vector<ConfigSummary> summarize(const Results& r) {
  using Key = std::pair<int, std::string>;  // the report's order, then the name
  std::map<Key, ConfigSummary> by;
  std::map<Key, std::uint64_t> predictions;
  for (const Row& x : r.rows) {
    if (x.kind != RowKind::Accuracy) continue;
    const Key order{config_order(x.solver, x.scalar), x.config()};
    ConfigSummary& c = by[order];
    c.solver = x.solver;
    c.scalar = x.scalar;
    ++c.scenes;
    if (!x.error.empty()) {
      ++c.failed_runs;
      continue;
    }
    c.events += x.events;
    c.judged_events += x.judged_events;
    c.misses += x.misses;
    c.phantoms += x.phantoms;
    c.misorders += x.misorders;
    if (c.rel_hist.empty()) c.rel_hist.assign(kRelBuckets, 0);
    for (std::size_t b = 0; b < x.rel_hist.size() && b < c.rel_hist.size(); ++b) c.rel_hist[b] += x.rel_hist[b];
    c.rel_max = std::max(c.rel_max, x.rel_max);
    c.ulps_max = std::max(c.ulps_max, x.ulps_max);
    if (x.elastic) c.worst_energy_drift = std::max(c.worst_energy_drift, std::abs(x.energy_drift));
    c.worst_momentum_drift = std::max(c.worst_momentum_drift, x.momentum_drift);
    c.wall_seconds += x.wall_seconds;
    predictions[order] += x.predictions;
  }
  std::vector<ConfigSummary> out;
  for (auto& [order, c] : by) {
    c.rel_p99 = hist_quantile(c.rel_hist, 0.99);
    c.events_per_second = c.wall_seconds > 0 ? static_cast<double>(c.events) / c.wall_seconds : 0;
    c.ns_per_prediction = predictions[order] ? 1e9 * c.wall_seconds / static_cast<double>(predictions[order]) : 0;
    out.push_back(c);
  }
  // Pareto: a configuration is dominated when another one is no slower, no less accurate (p99
  // relative time error, then misses + phantoms) and strictly better in one of them.
  const auto error_of = [](const ConfigSummary& c) { return std::make_pair(c.misses + c.phantoms, c.rel_p99); };
  for (ConfigSummary& c : out) {
    c.pareto = c.failed_runs == 0;
    for (const ConfigSummary& o : out) {
      if (&o == &c || o.failed_runs != 0) continue;
      const bool no_worse = o.wall_seconds <= c.wall_seconds && error_of(o) <= error_of(c);
      const bool better = o.wall_seconds < c.wall_seconds || error_of(o) < error_of(c);
      if (no_worse && better) c.pareto = false;
    }
  }
  return out;
}

}  // namespace pge::report
