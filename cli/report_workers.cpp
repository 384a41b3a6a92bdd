#include "report_workers.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <optional>
#include <stdexcept>
#include <utility>
#include <poll.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

namespace pge::cli {
namespace {

// The protocol, a line each way: the report writes an item's index ("17\n"); the worker answers
// with the index and the row ("17 {...json...}\n") and waits for the next. End of input: no more.

bool write_all(int fd, const std::string& text) {
  std::size_t at = 0;
  while (at < text.size()) {
    const ssize_t n = write(fd, text.data() + at, text.size() - at);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    at += static_cast<std::size_t>(n);
  }
  return true;
}

// Takes the first complete line out of buffer (without its newline).
std::optional<std::string> take_line(std::string& buffer) {
  const std::size_t end = buffer.find('\n');
  if (end == std::string::npos) return std::nullopt;
  std::string line = buffer.substr(0, end);
  buffer.erase(0, end + 1);
  return line;
}

[[noreturn]] void worker_main(int in, int out, const WorkerTasks& tasks) {
  std::string buffer;
  char chunk[256];
  for (;;) {
    while (const std::optional<std::string> line = take_line(buffer)) {
      const std::size_t k = std::stoul(*line);
      const std::string answer = fmt::format("{} {}\n", k, report::row_to_json_line(tasks.measure(k)));
      if (!write_all(out, answer)) _exit(1);
    }
    const ssize_t n = read(in, chunk, sizeof chunk);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) _exit(n == 0 ? 0 : 1);  // no destructors, no atexit, no flushing the report's stdio
    buffer.append(chunk, static_cast<std::size_t>(n));
  }
}

struct Worker {
  pid_t pid = -1;
  int to = -1, from = -1;  // the report's ends: items to it, rows from it
  std::string buffer;      // what came from it, not yet a whole line
  std::optional<std::size_t> item;
};

std::string how_it_ended(int status) {
  if (WIFSIGNALED(status)) return fmt::format("killed by signal {} ({})", WTERMSIG(status), strsignal(WTERMSIG(status)));
  if (WIFEXITED(status)) return fmt::format("exited with {}", WEXITSTATUS(status));
  return "ended";
}

class Pool {
 public:
  Pool(const std::vector<std::size_t>& order, const WorkerTasks& tasks) : order_(order), tasks_(tasks) {}

  std::size_t run(unsigned jobs) {
    workers_.reserve(jobs);  // spawn() and the poll loop hold references into it
    for (unsigned j = 0; j < jobs && next_ < order_.size(); ++j) {
      workers_.emplace_back();
      if (!spawn(workers_.back())) {
        workers_.pop_back();
        break;
      }
      hand_out(workers_.back());
    }
    while (alive() > 0) wait_for_rows();
    if (next_ < order_.size()) {  // not one worker could be made: measure here
      fmt::print(stderr, "pge report: no worker process could be started ({}); measuring the rest here\n",
                 std::strerror(spawn_errno_));
      for (; next_ < order_.size(); ++next_) {
        tasks_.begin(order_[next_]);
        tasks_.done(order_[next_], tasks_.measure(order_[next_]));
      }
    }
    return deaths_;
  }

 private:
  std::size_t alive() const {
    return static_cast<std::size_t>(std::count_if(workers_.begin(), workers_.end(), [](const Worker& w) { return w.pid > 0; }));
  }

  bool spawn(Worker& w) {
    int down[2], up[2];
    if (pipe(down) != 0) {
      spawn_errno_ = errno;
      return false;
    }
    if (pipe(up) != 0) {
      spawn_errno_ = errno;
      close(down[0]);
      close(down[1]);
      return false;
    }
    const pid_t report = getpid();
    pid_t pid = -1;
    tasks_.fork_guard([&] {
      pid = fork();
      if (pid < 0) spawn_errno_ = errno;
    });
    if (pid == 0) {
      // The worker keeps its own two ends only: another worker's input must see its end when the
      // report closes it.
      for (const Worker& other : workers_)
        if (&other != &w && other.pid > 0) {
          close(other.to);
          close(other.from);
        }
      close(down[1]);
      close(up[0]);
      std::signal(SIGPIPE, SIG_DFL);
      // A report that is killed takes its workers with it (they would run out their rows).
      prctl(PR_SET_PDEATHSIG, SIGKILL);
      if (getppid() != report) _exit(1);
      worker_main(down[0], up[1], tasks_);
    }
    close(down[0]);
    close(up[1]);
    if (pid < 0) {
      close(down[1]);
      close(up[0]);
      return false;
    }
    w = Worker{pid, down[1], up[0], {}, std::nullopt};
    return true;
  }

  // The next item to w, or the end of its input when none is left.
  void hand_out(Worker& w) {
    if (next_ >= order_.size()) {
      if (w.to >= 0) close(w.to);
      w.to = -1;
      return;
    }
    const std::size_t k = order_[next_++];
    w.item = k;
    tasks_.begin(k);
    // A write to a worker that has died fails (SIGPIPE is ignored meanwhile); its end of output
    // follows and says how it ended.
    write_all(w.to, fmt::format("{}\n", k));
  }

  void wait_for_rows() {
    std::vector<pollfd> fds;
    std::vector<Worker*> of;
    for (Worker& w : workers_)
      if (w.pid > 0) {
        fds.push_back({w.from, POLLIN, 0});
        of.push_back(&w);
      }
    if (poll(fds.data(), fds.size(), -1) < 0) {
      if (errno == EINTR) return;
      throw std::runtime_error(fmt::format("pge report: waiting for the workers: {}", std::strerror(errno)));
    }
    for (std::size_t i = 0; i < fds.size(); ++i)
      if (fds[i].revents != 0) read_from(*of[i]);
  }

  void read_from(Worker& w) {
    char chunk[65536];
    const ssize_t n = read(w.from, chunk, sizeof chunk);
    if (n < 0 && errno == EINTR) return;
    if (n <= 0) {
      ended(w);
      return;
    }
    w.buffer.append(chunk, static_cast<std::size_t>(n));
    while (const std::optional<std::string> line = take_line(w.buffer)) {
      const std::size_t space = line->find(' ');
      const std::size_t k = w.item.value_or(0);
      report::Row row;
      try {
        if (!w.item || space == std::string::npos || std::stoul(line->substr(0, space)) != k)
          throw report::ReportError("a row for another item");
        row = report::row_from_json_line(line->substr(space + 1));
      } catch (const std::exception& e) {
        row = tasks_.failed(k, fmt::format("the worker's answer was unreadable: {}", e.what()));
      }
      w.item.reset();
      tasks_.done(k, std::move(row));
      hand_out(w);
    }
  }

  void ended(Worker& w) {
    close(w.from);
    if (w.to >= 0) close(w.to);
    int status = 0;
    while (waitpid(w.pid, &status, 0) < 0 && errno == EINTR) {
    }
    const std::optional<std::size_t> item = w.item;
    w = Worker{};
    if (!item && WIFEXITED(status) && WEXITSTATUS(status) == 0) return;  // done, as asked
    ++deaths_;
    // The item it held, if any, is its only loss; a replacement takes the items left.
    if (item) tasks_.done(*item, tasks_.failed(*item, "the worker process measuring it " + how_it_ended(status)));
    if (next_ < order_.size() && spawn(w)) hand_out(w);
  }

  const std::vector<std::size_t>& order_;
  const WorkerTasks& tasks_;
  std::vector<Worker> workers_;
  std::size_t next_ = 0, deaths_ = 0;
  int spawn_errno_ = 0;
};

}  // namespace

std::size_t measure_in_workers(const std::vector<std::size_t>& order, unsigned jobs, const WorkerTasks& tasks) {
  // A worker that dies must not take the report with it through a write to its pipe.
  struct sigaction ignore {}, old {};
  ignore.sa_handler = SIG_IGN;
  sigaction(SIGPIPE, &ignore, &old);
  Pool pool(order, tasks);
  std::size_t deaths = 0;
  try {
    deaths = pool.run(std::max(1u, jobs));
  } catch (...) {
    sigaction(SIGPIPE, &old, nullptr);
    throw;
  }
  sigaction(SIGPIPE, &old, nullptr);
  return deaths;
}

}  // namespace pge::cli
