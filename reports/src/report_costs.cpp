#include "pge/report_costs.hpp"

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>

namespace pge::report {

using json = nlohmann::json;

std::optional<RowCosts> read_costs(const std::string& path, bool quick, std::uint64_t max_events) {
  const std::string text = read_text_file(path);
  // A cost: a finite number of seconds, at least 0.
  const auto seconds_of = [&path](const json& value, const std::string& what) {
    const double seconds = value.get<double>();
    if (!(seconds >= 0) || !std::isfinite(seconds))
      throw ReportError(fmt::format("{}: {}: the cost must be a finite number of seconds, at least 0", path, what));
    return seconds;
  };
  try {
    const json j = json::parse(text);
    if (!j.is_object() || j.value("format", std::string()) != kCostsFormat)
      throw ReportError(fmt::format("{}: not a costs file (format \"{}\" expected)", path, kCostsFormat));
    if (j.at("quick").get<bool>() != quick || j.at("max_events").get<std::uint64_t>() != max_events) return std::nullopt;
    RowCosts costs;
    costs.origin = path;
    for (const auto& [key, value] : j.at("rows").items()) costs.cpu_seconds[key] = seconds_of(value, "row \"" + key + "\"");
    if (j.contains("rest"))
      for (const auto& [kind, rest] : j.at("rest").items()) {
        const auto rows = rest.at("rows").get<std::uint64_t>();
        const double seconds = seconds_of(rest.at("cpu_seconds"), "rest \"" + kind + "\"");
        if (rows > 0) costs.rest_mean[kind] = seconds / static_cast<double>(rows);
      }
    return costs;
  } catch (const json::exception& e) {
    throw ReportError(fmt::format("{}: {}", path, e.what()));
  }
}

void write_costs(const std::string& path, const Results& results, std::uint64_t max_events) {
  json rows = json::object();
  std::map<std::string, std::pair<std::uint64_t, double>> rest;  // by kind: rows, seconds
  for (const Row& r : results.rows) {
    if (!r.error.empty()) continue;
    if (r.cost_cpu_seconds >= kCostsLeastSeconds) {
      rows[r.key()] = std::round(r.cost_cpu_seconds * 1000) / 1000;
    } else {
      auto& [count, seconds] = rest[row_kind_name(r.kind)];
      ++count;
      seconds += r.cost_cpu_seconds;
    }
  }
  json rest_json = json::object();
  for (const auto& [kind, totals] : rest)
    rest_json[kind] = {{"rows", totals.first}, {"cpu_seconds", std::round(totals.second * 1000) / 1000}};
  const json j{{"format", kCostsFormat},
               {"note", fmt::format("CPU seconds each row of this sweep cost to measure (rows of at least {} s; the "
                                    "others' count and sum by kind under rest): pge report's order of work and "
                                    "estimate of the time left, nothing else",
                                    kCostsLeastSeconds)},
               {"quick", results.meta.quick},
               {"max_events", max_events},
               {"commit", results.meta.commit},
               {"created", results.meta.created},
               {"cpu", results.meta.cpu},
               {"build_type", results.meta.build_type},
               {"jobs", results.meta.jobs},
               {"rows", rows},
               {"rest", rest_json}};
  write_text_file_atomically(path, j.dump(1) + "\n");
}

std::vector<std::size_t> longest_first(const std::vector<double>& expected, std::vector<std::size_t> order) {
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return expected[a] > expected[b]; });
  return order;
}

}  // namespace pge::report
