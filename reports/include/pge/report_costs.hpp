// What each row of a sweep cost to measure, kept from an earlier run of the same sweep: the
// order in which `pge report` hands rows to its workers (the longest first) and its estimate of
// the time left. Only a hint: a row it does not list counts at its kind's mean (or, without one,
// by row_weight), and no figure of the report depends on it.
#pragma once

#include "pge/report_data.hpp"

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace pge::report {

inline constexpr const char* kCostsFormat = "pge-report-costs/1";
// Rows that cost less are not listed one by one: the mean of their part's stands for each.
inline constexpr double kCostsLeastSeconds = 0.5;

struct RowCosts {
  std::map<std::string, double> cpu_seconds;  // by Row::key(): the rows of kCostsLeastSeconds or more
  // By row kind (row_kind_name): the mean CPU seconds of its rows not listed (below
  // kCostsLeastSeconds); absent where the sweep had none.
  std::map<std::string, double> rest_mean;
  std::string origin;  // the file they came from
};

// Reads a costs file. Throws ReportError naming the file when it cannot be read or is not
// one; nullopt when it is of another sweep (quick against full, other events per scene).
std::optional<RowCosts> read_costs(const std::string& path, bool quick, std::uint64_t max_events);

// Writes the rows' CPU costs (those of at least kCostsLeastSeconds one by one, the others as each
// kind's count and sum) with the sweep they belong to. Failed rows are left out.
// Throws ReportError when the file cannot be written.
void write_costs(const std::string& path, const Results& results, std::uint64_t max_events);

// `order` sorted by `expected[k]` (seconds), the longest first; ties keep their order.
std::vector<std::size_t> longest_first(const std::vector<double>& expected, std::vector<std::size_t> order);

}  // namespace pge::report
