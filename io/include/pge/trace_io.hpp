// Reading and writing traces (JSON Lines, format "pge-trace/2", see docs/formats.md): what an
// engine did in a run, for the referee (pge/judge.hpp). The structs are in pge/trace.hpp. Times
// are in seconds, positions in metres, velocities in m/s: the scene's units, never converted.
//
//   std::ifstream in("run.jsonl");
//   const pge::Trace trace = pge::read_trace(in, "run.jsonl");  // throws pge::TraceError
//   std::ofstream out("copy.jsonl");
//   pge::write_trace(out, trace);
//
// A whole program (a trace made in memory, written, read back, and a bad one's error) with its
// output: docs/api.md, "pge/trace_io.hpp" (docs/examples/trace_io.cpp). Link pge::io.
#pragma once

#include "pge/trace.hpp"

#include <iosfwd>
#include <string>

namespace pge {

// Parses a whole trace. Throws TraceError, one line naming the origin, the line and the field,
// for malformed JSON, a missing or unknown key, a wrong type, NaN or a number past a double, an
// unknown format or mode, a line of the other mode, or times that decrease (steps: that do not
// increase). Whether the bodies and states fit a scene is checked by the referee. `origin` names
// the stream in messages and becomes Trace::origin; each step and collision keeps its 1-based
// line number. Reads `in` to its end; TraceError "read error" if the stream fails.
Trace read_trace(std::istream& in, const std::string& origin);
// The same from a file (origin: the path); TraceError (line 0) if it cannot be opened.
Trace read_trace_file(const std::string& path);

// Writes `trace` as pge-trace/2, every double in shortest round-trip form: read_trace gives it
// back (lines aside). Throws std::invalid_argument for a name or id that is not UTF-8. It does
// not check the trace against any scene, nor that times increase: read_trace and the referee do.
// The stream's own errors are left in its state (check `out` after the call).
void write_trace(std::ostream& out, const Trace& trace);

}  // namespace pge
