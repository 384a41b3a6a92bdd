// `pge report --jobs N`: the report's items measured by N worker processes forked from the
// report once it has planned them. A worker is a copy of the report process: it holds the same
// scenes and plan, and measures an item by the same code as `--jobs 1`, one at a time, so a row
// is the same whichever worker measures it. Processes rather than threads: nothing in the engine,
// the oracle or the peers (Box2D, Chipmunk) has to be thread-safe for it, and a worker that
// crashes costs the row it was measuring, not the others.
#pragma once

#include "pge/report_data.hpp"

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace pge::cli {

struct WorkerTasks {
  // In a worker: measures item k.
  std::function<report::Row(std::size_t k)> measure;
  // In the report: the row of item k when its worker died measuring it (why: how it died).
  std::function<report::Row(std::size_t k, const std::string& why)> failed;
  // In the report: item k went to a worker; its row came back (in the order rows finish).
  std::function<void(std::size_t k)> begin;
  std::function<void(std::size_t k, report::Row row)> done;
  // Runs its argument (which forks) at a moment no other thread of the report prints: a worker
  // must not inherit a stdio lock that another thread held.
  std::function<void(const std::function<void()>&)> fork_guard;
};

// Measures every item of `order` (handed out in this order, the next to the first worker free)
// with `jobs` workers. A worker that dies (a signal, an exit) costs its item, whose row is
// tasks.failed's, and is replaced while items are left; if no worker can be made, the report
// measures the rest itself. Returns how many workers died.
std::size_t measure_in_workers(const std::vector<std::size_t>& order, unsigned jobs, const WorkerTasks& tasks);

}  // namespace pge::cli
