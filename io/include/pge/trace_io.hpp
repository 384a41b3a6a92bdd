// Reading and writing traces (JSON Lines, format "pge-trace/2", see docs/formats.md): what an
// engine did in a run, for the referee (pge/judge.hpp). The structs are in pge/trace.hpp.
//
//   std::ifstream in("run.jsonl");
//   const pge::Trace trace = pge::read_trace(in, "run.jsonl");  // throws pge::TraceError
//   std::ofstream out("copy.jsonl");
//   pge::write_trace(out, trace);
#pragma once

#include "pge/trace.hpp"

#include <iosfwd>
#include <string>

namespace pge {

// Parses a whole trace. Throws TraceError, one line naming the origin, the line and the field,
// for malformed JSON, a missing or unknown key, a wrong type, NaN or a number past a double, an
// unknown format or mode, a line of the other mode, or times that decrease (steps: that do not
// increase). Whether the bodies and states fit a scene is checked by the referee.
Trace read_trace(std::istream& in, const std::string& origin);
// The same from a file; TraceError if it cannot be opened.
Trace read_trace_file(const std::string& path);

// Writes `trace` as pge-trace/2, every double in shortest round-trip form: read_trace gives it
// back (lines aside). Throws std::invalid_argument for a name or id that is not UTF-8.
void write_trace(std::ostream& out, const Trace& trace);

}  // namespace pge
