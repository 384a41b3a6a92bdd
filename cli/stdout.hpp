// Standard output belongs to pge's own output: summaries, tables, JSON and traces piped on.
// What libraries print to std::cout goes to stderr instead (see stdout.cpp for why).
#pragma once

#include <fstream>
#include <iosfwd>
#include <string>

namespace pge::cli {

// From now on std::cout writes to stderr; pge_stdout() keeps the real standard output. main
// calls it first, before any library runs; calling it again changes nothing.
void send_library_stdout_to_stderr();

// The real standard output, in step with fmt::print (both write through C's stdout).
std::ostream& pge_stdout();

// An output file named on the command line: `-` is standard output (pge_stdout()), where the
// caller prints nothing else, so that what is written there is the whole stream (a JSON
// document a program reads).
class OutputFile {
 public:
  explicit OutputFile(const std::string& path);
  static bool names_stdout(const std::string& path) { return path == "-"; }
  bool is_open() const;  // always for standard output
  std::ostream& stream();
  // Flushes (and closes a file): whether everything was written.
  bool close();

 private:
  bool to_stdout_;
  std::ofstream file_;
};

}  // namespace pge::cli
