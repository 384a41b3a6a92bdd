// The referee for any engine (pge/judge.hpp): a stepping engine of ten lines writes a steps trace,
// and the referee gives each contact a verdict. Links pge::oracle and pge::io.
//
// Expected output, by hand: a ball of radius 0.25 m starts at x = 0 at 1 m/s towards a thin wall
// at x = 1.0625 (no gravity). It touches the wall when its centre reaches 1.0625 - 0.25 = 0.8125,
// at exactly t = 0.8125 s (every number is a double exactly). The engine moves the ball, then
// reports a contact and reverses the ball where a step ends with the ball overlapping the wall.
//   dt = 0.125 s, 12 steps to 1.5 s: the contact falls in step 6 (from 0), 0.75 to 0.875 s; that
//   step ends with the centre at 0.875, 0.1875 m from the wall, overlapping: reported in the step
//   where it happens, on time. Speed is kept: no energy drift.
//   dt = 1.5 s, one step: it ends with the centre at 1.5, 0.4375 m past the wall, more than a
//   radius: no overlap, no report. The ball passed through: missed (tunnelling), the gate fails
//   and failure_text gives that contact's line.
#include "pge/judge.hpp"
#include "pge/scene_io.hpp"
#include "pge/trace.hpp"

#include <cmath>
#include <cstdio>
#include <string>

namespace {

constexpr const char* kScene = R"({
  "format": "pge-scene/1", "name": "ball-and-wall",
  "bodies": [
    {"id": "ball", "circle": {"radius": 0.25}, "position": [0, 0], "velocity": [1, 0], "mass": 1},
    {"id": "wall", "segment": {"a": [1.0625, -1], "b": [1.0625, 1]}, "fixed": true}
  ],
  "run": {"until": 1.5}
})";

// A stepping engine: x += v dt; a step that ends overlapping the wall reports it and reverses v.
pge::Trace run_my_engine(double dt, double until) {
  pge::Trace trace;
  trace.mode = pge::TraceMode::Steps;
  trace.bodies = {"ball"};
  double x = 0, v = 1;
  for (int k = 1; k * dt <= until; ++k) {
    x += v * dt;
    pge::TraceStep step;
    if (std::abs(x - 1.0625) <= 0.25) {
      step.contacts.push_back({"ball", "wall"});
      v = -v;
    }
    step.t = k * dt;
    step.bodies.push_back({{x, 0}, {v, 0}});
    trace.steps.push_back(step);
  }
  return trace;
}

}  // namespace

int main() {
  const pge::Scene scene = pge::parse_scene(kScene, "ball-and-wall.json").scene;
  for (const double dt : {0.125, 1.5}) {
    // Throws pge::TraceError if the trace does not fit the scene.
    const pge::oracle::TraceJudgement j = pge::oracle::judge_trace(scene, run_my_engine(dt, scene.run.until));
    const pge::oracle::StepSummary& s = j.steps.summary;
    std::printf("dt = %g s, steps %zu, exact contacts %zu: %zu on time, %zu late, %zu missed, %zu phantom; "
                "energy drift %g\n",
                dt, s.steps, s.contacts, s.on_time, s.late, s.missed, s.phantom, s.largest_energy_drift);
    for (const pge::oracle::StepContact& c : j.steps.contacts) {
      std::printf("  %s\n", pge::oracle::contact_text(c).c_str());
    }
    // What a test prints when the gate fails (EXPECT_FALSE(j.failed()) << failure_text(j)).
    std::printf("  gate: %s\n", j.failed() ? ("fails:\n    " + pge::oracle::failure_text(j)).c_str() : "passes");
  }
}
