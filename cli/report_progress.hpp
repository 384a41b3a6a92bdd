// What `pge report` says while it measures and when it is done: progress (rows done per part,
// time elapsed and left) and the headline numbers of the configurations.
#pragma once

#include "pge/report_data.hpp"

#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <functional>
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

// A row's expected cost relative to others of its part (a double row of a few bodies weighs
// about 1): quad rows weigh 8 (software arithmetic), long double 2.5, and larger scenes more (the
// oracle's work per event grows with the bodies, and a peer scene's steps with them). Where no
// earlier run of the sweep says what a row costs (pge/report_costs.hpp), the report hands rows to
// its workers the heaviest first by it, and the estimate of the time left weighs rows so.
double row_weight(report::RowKind kind, const std::string& scalar, std::size_t bodies);

// A row's cost in seconds as expected before anything is measured: its row_weight times its
// part's prior seconds per weight (measured once on the bundled scenes). Rows of every part compare
// by it.
double expected_row_seconds(report::RowKind kind, const std::string& scalar, std::size_t bodies, bool quick);

// Time in a short human form: "45s", "3m05s", "1h02m".
std::string short_duration(double seconds);

class ReportProgress {
 public:
  // What is to be measured, in order (the items of a part together): each item's part and what
  // it is expected to cost (an earlier run's, pge/report_costs.hpp, or expected_row_seconds),
  // which weighs it as that many seconds at its part's prior pace.
  struct Planned {
    report::RowKind kind;
    double expected_seconds = 0;
  };
  // quick: the sweep (it sets the prior cost of a row in a part not yet started); workers: how
  // many items are measured at once (pge report --jobs), which divides the time left.
  ReportProgress(ProgressStyle style, const std::vector<Planned>& plan, bool quick, unsigned workers = 1);
  ~ReportProgress();
  ReportProgress(const ReportProgress&) = delete;
  ReportProgress& operator=(const ReportProgress&) = delete;
  // Before item k (0-based, in the order above) is measured; label: what it is. Up to `workers`
  // items are at work at once, begun and ended in any order.
  void begin(std::size_t k, const std::string& label);
  // After item k was measured.
  void end(std::size_t k);
  // Runs f while the ticker can print nothing (it prints holding the same lock): a process forked
  // in f finds no stdio lock taken.
  void hold(const std::function<void()>& f);
  // Before anything else goes to stderr mid-sweep (an error line): clears the redrawn line.
  void interrupt();
  // After the last item: stops the ticker, clears the redrawn line.
  void finish();

 private:
  using Clock = std::chrono::steady_clock;
  struct Part {
    report::RowKind kind;
    std::size_t rows = 0, done = 0;
    double weight = 0, done_weight = 0;  // of its rows, of its done rows (Planned's weights)
    double seconds = 0;                  // spent on its done rows
  };
  double elapsed() const;
  double seconds_left() const;  // estimated, every part
  double part_rate(const Part& p) const;  // estimated seconds per weight of its rows
  std::string part_line(const Part& p) const;
  void draw();  // the redrawn line (Terminal), with mutex_ held
  const Part* part_at_work() const;  // the part of the item at work longest (nullptr: none)

  struct AtWork {
    std::size_t item;
    std::string label;
    Clock::time_point start;
  };

  ProgressStyle style_;
  bool quick_;
  unsigned workers_;
  std::vector<Part> parts_;
  std::vector<std::size_t> part_of_;  // item -> index in parts_
  std::vector<double> weight_;        // item -> its weight
  std::size_t done_ = 0;
  std::vector<AtWork> at_work_;  // the items being measured, the longest at work first
  Clock::time_point start_, last_line_;
  bool drawn_ = false;
  // The ticker thread redraws the terminal's line every second and prints a log's line every
  // 30 s, also while one row takes long; mutex_ guards everything above against it.
  std::mutex mutex_;
  std::condition_variable cv_;
  bool stop_ = false;
  // Set by the ticker once it runs (holding mutex_): the constructor waits for it, so that no
  // thread is being started when `hold` forks a worker (a thread's start takes allocator locks
  // that a forked child would find held: AddressSanitizer's allocator is not fork-safe).
  bool started_ = false;
  std::thread ticker_;
};

// The headline numbers of a report, one line per solver x scalar: misses, phantoms and
// misorders (per the exact oracle), p99 and worst relative time error, the worst error in ulps,
// events per second (engine alone), and whether it is on the Pareto front.
void print_headline(std::FILE* out, const report::Results& results);

}  // namespace pge::cli
