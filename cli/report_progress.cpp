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

// Seconds per weight (row_weight) of a part not yet started, before a row of it says how fast
// it goes: from sweeps of the bundled scenes (RelWithDebInfo with PGE_VALIDATE, CPU seconds, AMD
// EPYC; December 2026). Only the estimate of the time left uses them, scaled by how this run's
// finished parts compare with them.
double prior_seconds(RowKind k, bool quick) {
  switch (k) {
    case RowKind::Accuracy: return quick ? 0.01 : 0.04;
    case RowKind::Scaling: return quick ? 0.5 : 1.0;
    case RowKind::Drift: return quick ? 0.56 : 5.6;
    case RowKind::Peer: return quick ? 0.02 : 0.25;
  }
  return 1;
}

int terminal_columns() {
  winsize w{};
  if (ioctl(STDERR_FILENO, TIOCGWINSZ, &w) == 0 && w.ws_col >= 40) return w.ws_col;
  return 100;
}

}  // namespace

double row_weight(RowKind kind, const std::string& scalar, std::size_t bodies) {
  const auto ends_with = [&scalar](const std::string& tail) {
    return scalar.size() >= tail.size() && scalar.compare(scalar.size() - tail.size(), tail.size(), tail) == 0;
  };
  const double arithmetic = ends_with("quad") ? 8 : ends_with("long-double") ? 2.5 : 1;  // peer rows: "robust/quad"
  const double n = static_cast<double>(bodies);
  switch (kind) {
    case RowKind::Accuracy:
    case RowKind::Peer: return arithmetic * (1 + n / 20);
    case RowKind::Scaling: return arithmetic * (0.5 + n / 1000);  // 10 events per body, at least 5,000
    case RowKind::Drift: return arithmetic;
  }
  return arithmetic;
}

double expected_row_seconds(RowKind kind, const std::string& scalar, std::size_t bodies, bool quick) {
  return row_weight(kind, scalar, bodies) * prior_seconds(kind, quick);
}

std::string short_duration(double seconds) {
  if (!(seconds >= 0) || !std::isfinite(seconds)) return "?";
  const auto s = static_cast<long long>(std::llround(seconds));
  if (s < 60) return fmt::format("{}s", s);
  if (s < 3600) return fmt::format("{}m{:02d}s", s / 60, s % 60);
  return fmt::format("{}h{:02d}m", s / 3600, (s % 3600) / 60);
}

ReportProgress::ReportProgress(ProgressStyle style, const std::vector<Planned>& plan, bool quick, unsigned workers)
    : style_(style), quick_(quick), workers_(std::max(1u, workers)), start_(Clock::now()), last_line_(start_) {
  for (const Planned& item : plan) {
    if (parts_.empty() || parts_.back().kind != item.kind) parts_.push_back({item.kind});
    const double w = item.expected_seconds / prior_seconds(item.kind, quick);
    ++parts_.back().rows;
    parts_.back().weight += w;
    part_of_.push_back(parts_.size() - 1);
    weight_.push_back(w);
  }
  if (style_ == ProgressStyle::None || parts_.empty()) return;
  if (style_ == ProgressStyle::Lines) {
    std::string what;
    for (const Part& p : parts_) what += fmt::format("{}{} {} rows", what.empty() ? "" : ", ", part_name(p.kind), p.rows);
    if (workers_ > 1) what += fmt::format(" ({} at once)", workers_);
    fmt::print(stderr, "measuring: {}\n", what);
    std::fflush(stderr);
  }
  // A row can take minutes (a 1,000-ball peer scene in quad): the ticker keeps the redrawn line's
  // clock going every second, and a log's line coming every 30 s, whatever the rows do.
  ticker_ = std::thread([this] {
    std::unique_lock<std::mutex> lock(mutex_);
    started_ = true;
    cv_.notify_all();
    const auto every = style_ == ProgressStyle::Terminal ? std::chrono::seconds(1) : std::chrono::seconds(30);
    while (!stop_) {
      const auto due = style_ == ProgressStyle::Terminal ? Clock::now() + every : last_line_ + every;
      if (cv_.wait_until(lock, due, [this] { return stop_; })) break;
      if (style_ == ProgressStyle::Terminal) {
        if (drawn_) draw();
      } else if (Clock::now() >= last_line_ + every && part_at_work()) {
        fmt::print(stderr, "{}\n", part_line(*part_at_work()));
        std::fflush(stderr);
        last_line_ = Clock::now();
      }
    }
  });
  std::unique_lock<std::mutex> lock(mutex_);
  cv_.wait(lock, [this] { return started_; });
}

ReportProgress::~ReportProgress() { finish(); }

double ReportProgress::elapsed() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }

const ReportProgress::Part* ReportProgress::part_at_work() const {
  return at_work_.empty() ? nullptr : &parts_[part_of_[at_work_.front().item]];
}

double ReportProgress::part_rate(const Part& p) const {
  // This run's pace in the part once it has one, else the prior scaled by the pace of the parts
  // done so far against their priors. A pace is a worker's seconds per weight.
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
  // The work left in a worker's seconds, shared by the workers; but no sooner than the row at
  // work that has the most of its own share left.
  double work = 0, longest = 0;
  for (const Part& p : parts_) work += part_rate(p) * (p.weight - p.done_weight);
  for (const AtWork& a : at_work_) {
    // A row at work has already taken some of its share (and no more than that, when it runs long).
    const double share = part_rate(parts_[part_of_[a.item]]) * weight_[a.item];
    const double in_row = std::min(share, std::chrono::duration<double>(Clock::now() - a.start).count());
    work -= in_row;
    longest = std::max(longest, share - in_row);
  }
  return std::max({0.0, work / workers_, longest});
}

std::string ReportProgress::part_line(const Part& p) const {
  return fmt::format("{}: {}/{} rows, {} elapsed, ~{} left", part_name(p.kind), p.done, p.rows, short_duration(elapsed()),
                     short_duration(seconds_left()));
}

void ReportProgress::draw() {
  const Part* p = part_at_work();
  if (!p) return;
  std::string labels;
  std::size_t in_part = 0;  // rows of p at work
  for (const AtWork& a : at_work_) {
    labels += (labels.empty() ? "" : " | ") + a.label;
    in_part += &parts_[part_of_[a.item]] == p;
  }
  std::string line = fmt::format("[{}/{}] {} {}/{}, {} elapsed, ~{} left: {}", done_ + at_work_.size(), part_of_.size(),
                                 part_name(p->kind), p->done + in_part, p->rows, short_duration(elapsed()),
                                 short_duration(seconds_left()), labels);
  const auto width = static_cast<std::size_t>(terminal_columns() - 1);
  if (line.size() > width) line.resize(width);
  fmt::print(stderr, "\r{}\x1b[K", line);
  std::fflush(stderr);
  drawn_ = true;
}

void ReportProgress::begin(std::size_t k, const std::string& label) {
  const std::lock_guard<std::mutex> lock(mutex_);
  if (k >= part_of_.size()) return;
  at_work_.push_back({k, label, Clock::now()});
  if (style_ == ProgressStyle::Terminal) draw();
}

void ReportProgress::end(std::size_t k) {
  const std::lock_guard<std::mutex> lock(mutex_);
  const auto it = std::find_if(at_work_.begin(), at_work_.end(), [k](const AtWork& a) { return a.item == k; });
  if (it == at_work_.end()) return;
  Part& p = parts_[part_of_[k]];
  p.seconds += std::chrono::duration<double>(Clock::now() - it->start).count();
  at_work_.erase(it);
  ++p.done;
  p.done_weight += weight_[k];
  ++done_;
  if (style_ == ProgressStyle::Lines && p.done == p.rows) {
    fmt::print(stderr, "{}: {}/{} rows in {}, {} elapsed{}\n", part_name(p.kind), p.done, p.rows,
               short_duration(p.seconds) + (workers_ > 1 ? " of work" : ""), short_duration(elapsed()),
               done_ < part_of_.size() ? fmt::format(", ~{} left", short_duration(seconds_left())) : std::string());
    std::fflush(stderr);
    last_line_ = Clock::now();
  }
}

void ReportProgress::hold(const std::function<void()>& f) {
  const std::lock_guard<std::mutex> lock(mutex_);
  f();
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
