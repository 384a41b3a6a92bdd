#include "report_progress.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <condition_variable>
#include <sys/ioctl.h>
#include <unistd.h>

namespace pge::cli {
namespace {

using report::RowKind;

// The part names the user reads (the row kinds, "peers" as in --parts).
const char* part_name(RowKind k) { return k == RowKind::Peer ? "peers" : report::row_kind_name(k); }

// Seconds per row of weight 1 (a double row) of a part not yet started, before a row of it says
// how fast it goes: from the bundled quick sweep on 2 busy cores (AMD EPYC, RelWithDebInfo, load
// 6: 195 s for 780 accuracy rows, 3 s for 6 scaling rows, 21 s for 12 drift rows, 3 s for the 96
// rows of the small peer scenes), the full sweep's guessed from its larger budgets. Only the
// estimate of the time left uses them, scaled by how this run's finished parts compare with them.
double prior_seconds(RowKind k, bool quick) {
  switch (k) {
    case RowKind::Accuracy: return quick ? 0.15 : 0.6;
    case RowKind::Scaling: return quick ? 0.5 : 5.0;
    case RowKind::Drift: return quick ? 1.1 : 11.0;
    case RowKind::Peer: return quick ? 0.05 : 3.0;
  }
  return 1;
}

int terminal_columns() {
  winsize w{};
  if (ioctl(STDERR_FILENO, TIOCGWINSZ, &w) == 0 && w.ws_col >= 40) return w.ws_col;
  return 100;
}

}  // namespace

std::string short_duration(double seconds) {
  if (!(seconds >= 0) || !std::isfinite(seconds)) return "?";
  const auto s = static_cast<long long>(std::llround(seconds));
  if (s < 60) return fmt::format("{}s", s);
  if (s < 3600) return fmt::format("{}m{:02d}s", s / 60, s % 60);
  return fmt::format("{}h{:02d}m", s / 3600, (s % 3600) / 60);
}

ReportProgress::ReportProgress(ProgressStyle style, const std::vector<Planned>& plan, bool quick)
    : style_(style), quick_(quick), start_(Clock::now()), item_start_(start_), last_line_(start_) {
  for (const Planned& item : plan) {
    if (parts_.empty() || parts_.back().kind != item.kind) parts_.push_back({item.kind});
    const double w = item.scalar == "quad" ? 3 : item.scalar == "long-double" ? 1.5 : 1;
    ++parts_.back().rows;
    parts_.back().weight += w;
    part_of_.push_back(parts_.size() - 1);
    weight_.push_back(w);
  }
  if (style_ == ProgressStyle::None || parts_.empty()) return;
  if (style_ == ProgressStyle::Lines) {
    std::string what;
    for (const Part& p : parts_) what += fmt::format("{}{} {} rows", what.empty() ? "" : ", ", part_name(p.kind), p.rows);
    fmt::print(stderr, "measuring: {}\n", what);
    std::fflush(stderr);
  }
  // A row can take minutes (a 1,000-ball peer scene in quad): the ticker keeps the redrawn line's
  // clock going every second, and a log's line coming every 30 s, whatever the rows do.
  ticker_ = std::thread([this] {
    std::unique_lock<std::mutex> lock(mutex_);
    const auto every = style_ == ProgressStyle::Terminal ? std::chrono::seconds(1) : std::chrono::seconds(30);
    while (!stop_) {
      const auto due = style_ == ProgressStyle::Terminal ? Clock::now() + every : last_line_ + every;
      if (cv_.wait_until(lock, due, [this] { return stop_; })) break;
      if (style_ == ProgressStyle::Terminal) {
        if (drawn_) draw();
      } else if (Clock::now() >= last_line_ + every && current_ < part_of_.size()) {
        fmt::print(stderr, "{}\n", part_line(parts_[part_of_[current_]]));
        std::fflush(stderr);
        last_line_ = Clock::now();
      }
    }
  });
}

ReportProgress::~ReportProgress() { finish(); }

double ReportProgress::elapsed() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }

double ReportProgress::part_rate(const Part& p) const {
  // This run's pace in the part once it has one, else the prior scaled by the pace of the parts
  // done so far against their priors.
  if (p.done > 0) return p.seconds / p.done_weight;
  double spent = 0, expected = 0;
  for (const Part& q : parts_)
    if (q.done > 0) {
      spent += q.seconds;
      expected += prior_seconds(q.kind, quick_) * q.done_weight;
    }
  return (expected > 0 ? spent / expected : 1) * prior_seconds(p.kind, quick_);
}

double ReportProgress::seconds_left() const {
  double left = 0;
  for (const Part& p : parts_) left += part_rate(p) * (p.weight - p.done_weight);
  // The row at work has already taken some of its share (and no more than that, when it runs long).
  if (current_ < part_of_.size()) {
    const double in_row = std::chrono::duration<double>(Clock::now() - item_start_).count();
    left -= std::min(in_row, part_rate(parts_[part_of_[current_]]) * weight_[current_]);
  }
  return std::max(0.0, left);
}

std::string ReportProgress::part_line(const Part& p) const {
  return fmt::format("{}: {}/{} rows, {} elapsed, ~{} left", part_name(p.kind), p.done, p.rows, short_duration(elapsed()),
                     short_duration(seconds_left()));
}

void ReportProgress::draw() {
  const Part& p = parts_[part_of_[current_]];
  std::string line = fmt::format("[{}/{}] {} {}/{}, {} elapsed, ~{} left: {}", done_ + 1, part_of_.size(), part_name(p.kind),
                                 p.done + 1, p.rows, short_duration(elapsed()), short_duration(seconds_left()), label_);
  const auto width = static_cast<std::size_t>(terminal_columns() - 1);
  if (line.size() > width) line.resize(width);
  fmt::print(stderr, "\r{}\x1b[K", line);
  std::fflush(stderr);
  drawn_ = true;
}

void ReportProgress::begin(std::size_t k, const std::string& label) {
  const std::lock_guard<std::mutex> lock(mutex_);
  current_ = k;
  label_ = label;
  item_start_ = Clock::now();
  if (style_ == ProgressStyle::Terminal && k < part_of_.size()) draw();
}

void ReportProgress::end() {
  const std::lock_guard<std::mutex> lock(mutex_);
  if (current_ >= part_of_.size()) return;
  Part& p = parts_[part_of_[current_]];
  p.seconds += std::chrono::duration<double>(Clock::now() - item_start_).count();
  ++p.done;
  p.done_weight += weight_[current_];
  ++done_;
  if (style_ == ProgressStyle::Lines && p.done == p.rows) {
    fmt::print(stderr, "{}: {}/{} rows in {}, {} elapsed{}\n", part_name(p.kind), p.done, p.rows, short_duration(p.seconds),
               short_duration(elapsed()),
               done_ < part_of_.size() ? fmt::format(", ~{} left", short_duration(seconds_left())) : std::string());
    std::fflush(stderr);
    last_line_ = Clock::now();
  }
}

void ReportProgress::interrupt() {
  const std::lock_guard<std::mutex> lock(mutex_);
  if (drawn_) fmt::print(stderr, "\r\x1b[K");
  drawn_ = false;
}

void ReportProgress::finish() {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  cv_.notify_all();
  if (ticker_.joinable()) ticker_.join();
  if (drawn_) fmt::print(stderr, "\r\x1b[K");
  drawn_ = false;
}

void print_headline(std::FILE* out, const report::Results& results) {
  const std::vector<report::ConfigSummary> configs = report::summarize(results);
  if (configs.empty()) return;
  fmt::print(out, "{:<22} {:>7} {:>14} {:>14} {:>9} {:>11}  {}\n", "solver/scalar", "misses", "p99 rel. err", "worst rel. err",
             "worst ulp", "events/s", "Pareto");
  for (const report::ConfigSummary& c : configs) {
    const auto sci = [](double x) { return x == 0 ? std::string("0") : fmt::format("{:.2e}", x); };
    std::string misses = std::to_string(c.misses);
    if (c.phantoms || c.misorders) misses += fmt::format("+{}", c.phantoms + c.misorders);
    fmt::print(out, "{:<22} {:>7} {:>14} {:>14} {:>9.4g} {:>11.0f}  {}{}\n", c.solver + "/" + c.scalar, misses, sci(c.rel_p99),
               sci(c.rel_max), c.ulps_max, c.events_per_second, c.pareto ? "yes" : "",
               c.failed_runs ? fmt::format(" ({} runs failed)", c.failed_runs) : std::string());
  }
  fmt::print(out, "(misses per the exact oracle, +N phantoms and misorders; relative time errors against the exact "
                  "contact time over every judged event, p99 as the upper bound of its binary bucket; events/s of the "
                  "engine alone)\n");
}

}  // namespace pge::cli
