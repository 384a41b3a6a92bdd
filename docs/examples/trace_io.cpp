// Traces (pge/trace.hpp, pge/trace_io.hpp): a stepping engine's two steps written as
// pge-trace/2 JSON Lines, read back, and the one-line error a bad trace gets. Links pge::io.
//
// Expected output, by hand: the text is a header line (format, mode, engine, scene, the bodies
// each step lists) and one line per step: its end time, each listed body's [x, y, vx, vy] and
// the pairs reported in the step, every double in shortest round-trip form ("0.1", and 0 as
// "0.0"). Read back, the trace has the same 2 steps, the second reporting ball-floor. In the bad
// trace the second step ends at 0.05 s, before the first (0.1 s): the error names line 3 (the
// header is line 1) and the field "t".
#include "pge/trace.hpp"
#include "pge/trace_io.hpp"

#include <cstdio>
#include <sstream>
#include <string>

int main() {
  pge::Trace trace;
  trace.mode = pge::TraceMode::Steps;
  trace.engine = "my engine, dt = 0.1 s";
  trace.scene = "drop";
  trace.bodies = {"ball"};  // every moving body of the scene, in the order each step lists them
  // Steps: end time (s), then position (m) and velocity (m/s) of each listed body, then contacts.
  trace.steps.push_back({0.1, {{{0, 5.05}, {0, -0.981}}}, {}});
  trace.steps.push_back({0.2, {{{0, 4.9}, {0, -1.962}}}, {{"ball", "floor"}}});

  std::ostringstream out;
  pge::write_trace(out, trace);
  std::printf("%s", out.str().c_str());

  std::istringstream in(out.str());
  const pge::Trace back = pge::read_trace(in, "run.jsonl");  // throws pge::TraceError
  std::printf("read back: %zu steps, step 2 reports %s-%s\n", back.steps.size(), back.steps[1].contacts[0].a.c_str(),
              back.steps[1].contacts[0].b.c_str());

  std::string bad = out.str();
  bad.replace(bad.find("\"t\":0.2"), 7, "\"t\":0.05");
  std::istringstream bad_in(bad);
  try {
    pge::read_trace(bad_in, "bad.jsonl");
  } catch (const pge::TraceError& e) {
    std::printf("error: %s\n", e.what());
  }
}
