// What `pge check` records per event and how it summarises a scene (text and JSON).
#pragma once

#include "expect.hpp"

#include "pge/oracle.hpp"
#include "pge/scene.hpp"
#include "pge/world.hpp"

#include <array>
#include <cstdint>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

namespace pge::cli {

// One judged engine event, reduced to what the summary and the JSON need.
struct EventRecord {
  std::uint64_t index = 0;  // 0-based, in engine order
  double time = 0;          // the engine's time (rounded to double for extended scalars)
  BodyIndex a = kNoBody, b = kNoBody;
  oracle::FeaturePair features;
  bool impulse = false;  // false: the engine found the contact not approaching (no impulse)
  bool overlap_rule = false;
  oracle::Verdict verdict = oracle::Verdict::Agree;
  bool has_exact_time = false;
  // The pair's exact contact time, 20 decimals, truncated: written where something prints it (a
  // failure's line, the JSON's events; make_record's `decimals`), else empty.
  std::string exact_time;
  long long ulps = 0;
  double relative_error = 0;
  bool features_match = false;
  std::vector<std::pair<BodyIndex, BodyIndex>> earliest;  // pairs at the exact first contact (verdicts but Agree)
  bool elastic = false, both_moving = false;
  double energy_change = 0, energy_relative = 0;
  double momentum_change = 0, momentum_relative = 0;
  double gap = 0, contact_distance = 0;
  bool rotating = false;  // a pair with a rotating body: its time bound is the rotating one
};

// Two bodies as "\"a\"-\"b\"" ("?" for an index the scene does not have).
std::string pair_text(const Scene& s, BodyIndex a, BodyIndex b);

// The record of a judged event. `decimals`: the exact time in decimals for every event (the
// JSON's); without it only a failure's, which its line prints. (Writing 30,000 of them cost
// `pge check` on a 200-ball gas about a tenth of its time beside the referee's.)
EventRecord make_record(std::uint64_t index, double time, const oracle::ExactEvent& e, const oracle::Judgement& j,
                        bool decimals);

struct SceneCheck {
  std::string path, name, scalar, solver, stop;
  // The solver's promised bound on an event's time error in ulps (promised_time_error_ulps);
  // nothing for fast, which promises none.
  std::optional<long long> time_bound_ulps;
  std::optional<long long> rotating_time_bound_ulps;  // pairs with a rotating body (promised_rotating_time_error_ulps)
  StopReason stop_reason = StopReason::ReachedUntil;
  BodyIndex storm_a = kNoBody, storm_b = kNoBody;  // an event storm's two bodies
  std::size_t bodies = 0;
  double time = 0, horizon = 0;
  bool judged = true;  // false: the engine ran without the oracle (the expect block's "oracle": false)
  std::vector<EventRecord> events;  // the judged events (none when not judged)
  std::uint64_t contact_events = 0;  // collisions and zero-impulse contacts, judged or not
  // Measured by the engine before the first step and at the end: kinetic + potential energy,
  // momentum of the moving bodies, and every body's state at the end.
  double energy_start = 0, energy_end = 0;
  Vec2d momentum_start, momentum_end;
  std::vector<BodySnapshot<double>> final_states;
  // The engine's largest overlap at a contact as a fraction of the contact distance
  // (World::largest_contact_overlap: the contact deepest in rounding units).
  double largest_contact_overlap = 0;
  // The bodies that passed through a fixed body (World::tunnels(), pge/tunnel.hpp).
  std::vector<Tunnel> tunnels;
  ExpectOutcome expect;
  bool end_checked = false;  // the run reached its horizon and the oracle looked for leftovers
  oracle::EndJudgement end;
  oracle::RefereeStats oracle;
  std::vector<oracle::MotionMiss> motion_misses;  // contacts passed over before a slide off a face
  double engine_seconds = 0;     // of the run's wall time, what the oracle did not take
  std::uint64_t predictions = 0;  // the engine's pair predictions (World::counts())
  bool filter = true;
};

// Counts of each verdict, the end check's miss included.
std::array<std::uint64_t, oracle::kVerdictCount> verdict_counts(const SceneCheck& c);
bool has_failure(const SceneCheck& c);
// The largest |time error| in ulps over the judged events (0 when none has an exact time).
long long largest_abs_ulps(const SceneCheck& c);
// (E_end - E_start) / |E_start|, signed; 0 when both are 0, infinite when only E_start is 0.
double energy_relative_change(const SceneCheck& c);
// |P_end - P_start| / |P_start|, with the same conventions.
double momentum_relative_drift(const SceneCheck& c);

// The judged events whose time is further from the exact time than the solver promises (0
// when it promises nothing).
std::uint64_t past_time_bound(const SceneCheck& c);

// Why the run fails (for a contrast run: would fail), as short reasons ("collisions[0]",
// "stop (event-storm)", "2 miss", "1 tunnelled"); empty when it passes.
std::vector<std::string> failure_reasons(const SceneCheck& c);

void print_summary(const SceneCheck& c, const Scene& scene);
// The scene's summary and every event's verdict as one JSON object, events streamed one per
// line (a long run's events never sit in memory as JSON).
void write_json(std::ostream& out, const SceneCheck& c, const Scene& scene);

// `pge check --table`: one row per scene, a cell per solver (fast, robust, certified).
struct TableCell {
  std::string events, ulps, drift;
  std::string result;  // pass, FAIL: reason, n/a (contrast: ...), error: ...; empty: not run
};
struct TableRow {
  std::string family, scene;
  std::array<TableCell, 3> cells;  // indexed by SolverKind
};
TableCell table_cell(const SceneCheck& c);
void write_table(std::ostream& out, const std::vector<TableRow>& rows);

}  // namespace pge::cli
