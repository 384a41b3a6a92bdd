// Why std::cout is sent to stderr for the whole process: CGAL's modular gcd
// (CGAL/Polynomial/modular_gcd_utcf_*.h, reached through the oracle's root isolation in `pge
// check`, `fuzz` and `report`) prints "UNLUCKY PRIME !!" to std::cout whenever a prime it tried
// turns out unlucky, and nothing in CGAL turns that off; piped JSON broke on it, `--quiet` or not.
// Swapping std::cout's buffer once at start-up catches that and any other library's chatter on
// every path, costs nothing per call (wrapping each CGAL call would), and leaves C's stdout alone:
// pge prints with fmt::print, which writes there. pge_stdout() is for pge's own iostream output.
#include "stdout.hpp"

#include <iostream>
#include <ostream>

namespace pge::cli {
namespace {

// std::cout's own buffer before the swap: with the default sync_with_stdio(true) it writes
// straight into C's stdout, so this output and fmt::print's stay in order.
std::streambuf* real_stdout_buffer = nullptr;

}  // namespace

void send_library_stdout_to_stderr() {
  if (real_stdout_buffer == nullptr) real_stdout_buffer = std::cout.rdbuf(std::cerr.rdbuf());
}

std::ostream& pge_stdout() {
  static std::ostream out(real_stdout_buffer != nullptr ? real_stdout_buffer : std::cout.rdbuf());
  return out;
}

OutputFile::OutputFile(const std::string& path) : to_stdout_(names_stdout(path)) {
  if (!to_stdout_) file_.open(path);
}

bool OutputFile::is_open() const { return to_stdout_ || file_.is_open(); }

std::ostream& OutputFile::stream() { return to_stdout_ ? pge_stdout() : file_; }

bool OutputFile::close() {
  if (to_stdout_) return static_cast<bool>(pge_stdout().flush());
  file_.close();
  return static_cast<bool>(file_);
}

}  // namespace pge::cli
