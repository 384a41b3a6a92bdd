// A scene's `expect` block (fixtures/README.md, "Expectations"): what must hold when `pge check`
// runs the scene, and how one run measures up to it.
#pragma once

#include "pge/event.hpp"
#include "pge/roots.hpp"
#include "pge/scene_io.hpp"
#include "pge/vec2.hpp"

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace pge::cli {

struct SceneCheck;

struct ExpectedFinal {
  BodyIndex body = kNoBody;
  std::optional<Vec2d> position, velocity;
  std::optional<double> angle, angular_velocity;  // rad, rad/s (World::snapshot)
  double tolerance = 0;  // absolute, per component
};

struct ExpectedCollision {
  BodyIndex a = kNoBody, b = kNoBody;
  double time = 0, tolerance = 0;
};

struct ExpectedRest {
  std::vector<BodyIndex> bodies;
  double by = 0;
  double tolerance = 0;  // largest speed at the end
};

struct Expect {
  bool present = false;  // the scene has an expect block; absent, nothing below is checked
  std::vector<SolverKind> solvers{SolverKind::Robust, SolverKind::Certified};
  StopReason stop = StopReason::ReachedUntil;
  std::optional<std::uint64_t> events_min, events_max;
  bool oracle = true;
  long long max_time_error_ulps = 0;  // checked only with the oracle
  std::optional<double> energy_drift, energy_gain, momentum_drift, max_overlap;
  std::vector<ExpectedFinal> finals;
  std::vector<ExpectedCollision> collisions;
  std::vector<std::pair<BodyIndex, BodyIndex>> never_collide;
  std::optional<ExpectedRest> at_rest;

  bool lists(SolverKind solver) const;
};

// The scene's expect block, or an Expect with present = false if it has none. Throws SceneError
// naming the file and the key (field "expect.final[0].body") for an unknown key, a value of the
// wrong type or range, or a body id the scene does not have.
Expect parse_expect(const LoadedScene& loaded);

// Follows a run's contact events for the expectations about pairs and times, without storing
// the events (a long run may have millions).
class ExpectTracker {
 public:
  ExpectTracker(const Expect& expect, std::size_t bodies);
  void observe(double time, BodyIndex a, BodyIndex b);

  // Per expected collision: the pair's event time nearest the expected one, if it had any.
  const std::vector<std::optional<double>>& nearest() const { return nearest_; }
  // Per never_collide pair: its first contact event, if any.
  const std::vector<std::optional<double>>& first_contact() const { return first_contact_; }
  // Per body: its last contact event, if any.
  const std::vector<std::optional<double>>& last_contact() const { return last_contact_; }

 private:
  const Expect& expect_;
  std::vector<std::optional<double>> nearest_, first_contact_, last_contact_;
};

// How far a run is held to the expect block.
enum class Enforcement : std::uint8_t {
  None,      // no expect block: the run is judged as `pge check` always did (miss, phantom, storm)
  Full,      // the scene's own run with a listed solver: every expectation is enforced
  Verdicts,  // a run the block does not describe (--until, --max-events, --scalar): judged as
             // without a block, except that a storm the block expects is no failure
  Contrast,  // a solver the block does not list: reported, never a failure
};

struct ExpectFailure {
  std::string key;   // where in the block, e.g. "final[0].velocity"
  std::string text;  // "expected ..., measured ..."
};

struct ExpectOutcome {
  Enforcement enforcement = Enforcement::None;
  std::string why;         // for Verdicts and Contrast: why the block is not (fully) enforced
  bool storm_expected = false;  // the block says "stop": "event-storm"
  bool evaluated = false;  // the expectations were measured (Full, or Contrast on the scene's run)
  std::size_t checked = 0;
  std::vector<ExpectFailure> failures;
};

// Measures the run `c` (oracle verdicts, energy, momentum, final states; tracker: the events)
// against every expectation of the block.
void evaluate(const Expect& expect, const Scene& scene, const ExpectTracker& tracker, const SceneCheck& c,
              ExpectOutcome& outcome);

}  // namespace pge::cli
