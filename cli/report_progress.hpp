// What `pge report` says while it measures and when it is done: progress (rows done per part,
// time elapsed and left) and the headline numbers of the configurations.
#pragma once

#include "pge/report_data.hpp"

#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace pge::cli {

enum class ProgressStyle {
  None,
  Terminal,  // one line on stderr, redrawn in place: rows done, the part, elapsed, time left, the row at work
  Lines,     // for logs: a line per part every 30 s and when the part ends, nothing redrawn
};

// Time in a short human form: "45s", "3m05s", "1h02m".
std::string short_duration(double seconds);

class ReportProgress {
 public:
  // What is to be measured, in order (the items of a part together): each item's part and its
  // scalar (quad rows take about 3 times as long as double rows, long double 1.5).
  struct Planned {
    report::RowKind kind;
    std::string scalar;
  };
  // quick: the sweep (it sets the prior cost of a row in a part not yet started).
  ReportProgress(ProgressStyle style, const std::vector<Planned>& plan, bool quick);
  ~ReportProgress();
  ReportProgress(const ReportProgress&) = delete;
  ReportProgress& operator=(const ReportProgress&) = delete;
  // Before item k (0-based, in the order above) is measured; label: what it is.
  void begin(std::size_t k, const std::string& label);
  // After it was measured.
  void end();
  // Before anything else goes to stderr mid-sweep (an error line): clears the redrawn line.
  void interrupt();
  // After the last item: stops the ticker, clears the redrawn line.
  void finish();

 private:
  using Clock = std::chrono::steady_clock;
  struct Part {
    report::RowKind kind;
    std::size_t rows = 0, done = 0;
    double weight = 0, done_weight = 0;  // of its rows, of its done rows (a double row weighs 1)
    double seconds = 0;                  // spent on its done rows
  };
  double elapsed() const;
  double seconds_left() const;  // estimated, every part
  double part_rate(const Part& p) const;  // estimated seconds per weight of its rows
  std::string part_line(const Part& p) const;
  void draw();  // the redrawn line (Terminal), with mutex_ held

  ProgressStyle style_;
  bool quick_;
  std::vector<Part> parts_;
  std::vector<std::size_t> part_of_;  // item -> index in parts_
  std::vector<double> weight_;        // item -> its weight
  std::size_t current_ = 0, done_ = 0;
  std::string label_;  // the row at work
  Clock::time_point start_, item_start_, last_line_;
  bool drawn_ = false;
  // The ticker thread redraws the terminal's line every second and prints a log's line every
  // 30 s, also while one row takes long; mutex_ guards everything above against it.
  std::mutex mutex_;
  std::condition_variable cv_;
  bool stop_ = false;
  std::thread ticker_;
};

// The headline numbers of a report, one line per solver x scalar: misses, phantoms and
// misorders (per the exact oracle), p99 and worst relative time error, the worst error in ulps,
// events per second (engine alone), and whether it is on the Pareto front.
void print_headline(std::FILE* out, const report::Results& results);

}  // namespace pge::cli
