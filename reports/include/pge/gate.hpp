// The CI gate: results against a committed baseline, metric by metric.
#pragma once

#include "pge/report_data.hpp"

#include <iosfwd>
#include <string>
#include <vector>

namespace pge::report {

struct GatePolicy {
  // A scene's time error (largest and p99 |ulps|) and energy and momentum drift may grow to
  // factor x the baseline's, and always by a floor (ulps, or relative drift in units of the
  // scalar's epsilon), so that 0 -> 1 ulp is no regression.
  double error_factor = 2.0;
  double ulps_floor = 4.0;
  double drift_eps_floor = 64.0;
  // A configuration's speed: the geometric mean over its scenes of its wall time relative to the
  // reference configuration's on the same scene (same invocation), now against the baseline, may
  // grow to speed_factor. The reference configuration (or any, when the reference did not run):
  // wall time / calibration time, now against the baseline, may grow to calibrated_factor (the
  // calibration varies 2x with a busy sibling hyperthread: only gross slowdowns show there).
  double speed_factor = 1.5;
  double calibrated_factor = 3.0;
  std::string reference = "robust/double";
};

enum class Status : unsigned char { Pass, Fail };

struct GateCheck {
  std::string group;  // the JUnit class name: "accuracy.robust/double", "speed", "results"
  std::string name;   // what was checked: "snooker: misses", "robust/double: speed"
  Status status = Status::Pass;
  std::string message;  // measured against allowed, said plainly
};

struct GateResult {
  std::vector<GateCheck> checks;
  std::vector<std::string> notes;  // what was not gated and why (new rows, ...)
  // The inputs could not be gated at all (unreadable or unusable; `pge gate` exits 10, not 9):
  // then `checks` holds the one failed check that says why.
  bool closed = false;
  bool pass() const;
  std::size_t failures() const;
};

// Compares; never throws on differences (they are failed checks). A row of the baseline missing
// from the results, a results row that failed to run, or a build that cannot be compared for
// speed fails closed. Inputs that unusable_baseline or unusable_results reject are not compared:
// the result is closed.
GateResult gate(const Results& baseline, const Results& results, const GatePolicy& policy);

// Why results cannot be gated, or gated against ("" when they can): they have no rows, or a
// calibration time or a timed row's wall time that is not a positive number (speed would go
// unchecked). A baseline must also have a row the gate compares: not all failed runs or peers'.
// `pge gate --update` refuses to write a baseline that unusable_baseline rejects.
std::string unusable_results(const Results& results);
std::string unusable_baseline(const Results& baseline);

void write_junit(std::ostream& out, const GateResult& g, const std::string& suite);
// A Markdown summary: the verdict first, then every failure, then the speed table.
void write_gate_markdown(std::ostream& out, const GateResult& g, const Results& baseline, const Results& results,
                         const GatePolicy& policy);
// The gate's failing check when the results could not be read at all (fail closed).
GateResult unreadable(const std::string& what);
// The same for inputs that were read but cannot be gated (see unusable_results).
GateResult unusable(const std::string& why);

// The machine epsilon of a scalar by name (float, double, long-double, quad); double's for others.
double scalar_epsilon(const std::string& scalar);

}  // namespace pge::report
