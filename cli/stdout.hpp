// Standard output belongs to pge's own output: summaries, tables, JSON and traces piped on.
// What libraries print to std::cout goes to stderr instead (see stdout.cpp for why).
#pragma once

#include <iosfwd>

namespace pge::cli {

// From now on std::cout writes to stderr; pge_stdout() keeps the real standard output. main
// calls it first, before any library runs; calling it again changes nothing.
void send_library_stdout_to_stderr();

// The real standard output, in step with fmt::print (both write through C's stdout).
std::ostream& pge_stdout();

}  // namespace pge::cli
