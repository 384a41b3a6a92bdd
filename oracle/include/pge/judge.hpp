// The referee for any engine: judges a trace (pge/trace.hpp) of a run of a scene against the
// exact oracle. This header, pge/trace.hpp and pge/trace_io.hpp are the API other engines'
// tests link (targets pge_oracle and pge_io).
//
// Events mode (an event-driven engine): every collision is judged as `pge check` judges PGE's
// (pge/oracle.hpp: agree, tie, time error, misorder, miss, phantom), with exact conservation;
// the trace's pre-collision states and post-collision velocities are the motions the referee
// follows from one collision to the next (a rotating body's too: TraceCollision::turn_a/b and
// wa_after/wb_after give its angle and spin, and its reference point plus its turned pivot offset
// its pivot, so PGE's own trace of a run gets pge check's verdicts).
//
// Steps mode (a stepping engine): from each step's start state (the previous step's end state,
// each moving body on the scene's closed-form path p + v tau + a tau^2 / 2 with the scene's
// constant acceleration) the referee finds the exact first contact of every pair that is apart
// at the step's start, and gives each contact a verdict:
//   on time:  the engine reported the pair in the step where the contact exactly happens;
//   late k:   the engine first reported it k steps later, the pair overlapping at every step
//             start in between, never deeper than the overlap bound;
//   missed:   never reported while the pair was in contact: it was apart again at a later step
//             start (pass-through: tunnelling), or overlapped past the bound
//             (JudgeOptions::overlap_bound) before a report, or the trace ended first;
//   phantom:  reported in a step through which the pair stays apart: apart at the step's start
//             and end, and no exact contact on the closed-form paths in between;
//   undecided: a pair with a rotating body whose contact in the step the referee cannot decide
//             (a tangency, a contact at an edge's very end: UndecidedTime), reported or not;
//             counted apart, neither agreement nor failure.
// A rotating body (the scene's `angular_velocity` or `angle`, pge-scene/2) is followed the same
// way: from the step's start state, with the angle and angular velocity the trace gives at the
// previous step's end (TraceStep::turns), its angle theta + omega (t - t_start) and its pivot
// (the centre of mass) on the closed-form path above, the contacts found by the certified
// rotating search (oracle/README.md, "Rotation"). A trace's position of a rotating body is its
// reference point; the pivot is that plus the turned pivot offset, rounded to double.
// A pair found overlapping at a step's end that was apart at its start without an exact contact
// on the start-state paths (a body's path changed inside the step, by another contact) counts as
// a contact in that step too, without an exact time ("off path"). Reports of a pair overlapping
// at the step's start are continuing contacts, not verdicts. Plus, per step, the deepest overlap
// of any pair and the energy and momentum drift, exactly from the trace's numbers (rounded
// once, to double, at the end).
//
// Usage (a stepping engine's test):
//
//   #include "pge/judge.hpp"      // pge::oracle::judge_trace
//   #include "pge/scene_io.hpp"   // pge::read_scene_file
//   #include "pge/trace_io.hpp"   // pge::read_trace_file, pge::write_trace
//
//   const pge::Scene scene = pge::read_scene_file("bullet.json").scene;
//   pge::Trace trace;                        // or pge::read_trace_file("run.jsonl")
//   trace.mode = pge::TraceMode::Steps;
//   trace.bodies = {"bullet"};               // the scene's moving bodies
//   for (each step of my engine)             // end time, states, reported pairs
//     trace.steps.push_back({t, {{position, velocity}}, {{"bullet", "wall"}}});
//   const pge::oracle::TraceJudgement j = pge::oracle::judge_trace(scene, trace);
//   EXPECT_FALSE(j.failed()) << pge::oracle::failure_text(j);
//   EXPECT_EQ(j.steps.summary.missed, 0u);
//
// judge_trace throws pge::TraceError (one line naming the line or step and the field) for a
// trace that does not fit the scene: an unknown body, a fixed body's state, a moving body left
// out, times not increasing, NaN or infinite numbers, a first state that is not the scene's.
//
// Units are the scene's: times in seconds, lengths in metres, masses in kilograms, energies in
// joules (any consistent set works; the referee never converts). A whole program that judges a
// stepping engine, with its output: docs/api.md, "pge/judge.hpp" (docs/examples/judge.cpp).
#pragma once

#include "pge/oracle.hpp"
#include "pge/oracle_state.hpp"
#include "pge/scene.hpp"
#include "pge/trace.hpp"

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace pge::oracle {

// How the referee judges a trace. The defaults are what `pge judge` uses.
struct JudgeOptions {
  // Steps mode: a pair overlapping deeper than this fraction of its contact distance (radius
  // sum; a circle's radius against a wall or polygon; the smaller size of two polygons or
  // segments, a size being the larger side of the bounding box: World::largest_overlap's
  // measure) before the engine reports it is missed. Dimensionless. 0.5: half a radius of a
  // ball sunk into a wall unreported is no late report but a miss.
  double overlap_bound = 0.5;
  RefereeOptions referee;  // events mode: the referee's filters and agreement in ulps
};

// A steps-mode contact's verdict (the rules are in this file's opening comment). Missed and
// Phantom fail a trace (StepJudgement::failed); OnTime, Late and Undecided do not.
enum class StepVerdict : unsigned char { OnTime, Late, Missed, Phantom, Undecided };
// The verdict's name in `pge judge --json`: "on_time", "late", "missed", "phantom", "undecided"
// ("?" for a value outside the enum). Never throws.
std::string_view step_verdict_name(StepVerdict v);

// Why a contact was missed: None (not missed), PassThrough (apart again at a later step start
// without a report: tunnelling), Overlap (deeper than JudgeOptions::overlap_bound before a
// report), Unreported (the trace ended before a report).
enum class MissKind : unsigned char { None, PassThrough, Overlap, Unreported };
// "", "pass_through", "overlap", "unreported" ("?" outside the enum). Never throws.
std::string_view miss_kind_name(MissKind k);

// One contact of a steps-mode trace (or one phantom report). Times in seconds, depths in the
// scene's length unit.
struct StepContact {
  std::string a, b;          // scene ids, in scene order
  std::size_t step = 0;      // 0-based index into Trace::steps: where it exactly happens (phantom: reported)
  std::optional<double> exact_time;  // the exact contact time, rounded to double; none off path and for phantoms
  bool off_path = false;     // found overlapping at the step's end, no exact contact on the start-state paths
  StepVerdict verdict = StepVerdict::OnTime;
  std::size_t late_steps = 0;              // Late: steps between the contact's step and the report
  std::optional<std::size_t> reported_step;  // the step whose contacts name it (none: missed)
  MissKind miss = MissKind::None;
  // The deepest overlap of the pair (length units) at the step ends from the contact to its
  // report or miss, and as a fraction of the pair's contact distance.
  double depth = 0;
  double relative_depth = 0;
  std::string undecided_reason;  // Undecided: what could not be decided (UndecidedTime)
};

// The counts and extremes of a steps-mode judgement (what `pge judge` prints). Energies are
// kinetic plus the potential of the scene's constant field (m g y for gravity g pointing down
// y), in joules; drifts are relative, dimensionless.
struct StepSummary {
  std::size_t steps = 0;     // Trace::steps.size()
  std::size_t contacts = 0;  // exact contacts (on time + late + missed)
  std::size_t on_time = 0, late = 0, missed = 0, phantom = 0;
  std::size_t undecided = 0;           // not among the contacts: neither agreement nor failure
  std::size_t tunnelled = 0;           // of the missed: pass-through
  std::size_t continuing_reports = 0;  // reports of a pair overlapping or touching at the step's start
  // Reports of a pair apart at the step's start, one of whose moving bodies has an exact contact
  // in the same step: its path changed inside the step, past which the referee's paths from the
  // step's start do not follow it, so the report is judged neither a contact nor a phantom.
  std::size_t unfollowed_reports = 0;
  std::size_t largest_late_steps = 0;
  double largest_depth = 0;            // deepest overlap at any step end, length units
  double largest_relative_depth = 0;   // as a fraction of the contact distance
  double largest_energy_drift = 0;     // max over steps of |E_k - E_start| / |E_start| (inf from 0)
  double largest_momentum_drift = 0;   // max over steps of |P_k - P_start| / |P_start|
  double energy_start = 0, energy_end = 0;  // kinetic + potential of the constant field
};

// What judge_steps finds: every contact and phantom report, per-step measures, the summary.
struct StepJudgement {
  std::vector<StepContact> contacts;  // by step, then pair
  std::vector<double> depth;          // per step: the deepest overlap at its end (0: none), length units
  std::vector<double> energy_drift;   // per step: (E_k - E_start) / |E_start|
  StepSummary summary;
  // True when a contact was missed or a report was a phantom: what fails a gate.
  bool failed() const { return summary.missed > 0 || summary.phantom > 0; }
};

// One collision of an events-mode trace and its judgement (pge/oracle.hpp).
struct EventVerdict {
  std::size_t index = 0;  // into Trace::collisions
  std::string a, b;       // scene ids, in scene order
  double t = 0;           // the trace's collision time, seconds
  ExactEvent event;  // the collision as the referee read it (body indices in scene order)
  Judgement judgement;
};

// What judge_events finds: a verdict per collision, their counts, exact conservation.
struct EventJudgement {
  std::vector<EventVerdict> events;  // one per Trace::collisions entry, in trace order
  std::optional<EndJudgement> end;  // when the trace's end record says it reached its horizon
  std::size_t counts[kVerdictCount] = {};  // per Verdict
  double largest_energy_change = 0;        // |change| / kinetic energy before, over elastic collisions
  double largest_momentum_change = 0;      // |change| / momentum scale, over two-moving-body collisions
  // Kinetic + potential energy and momentum of the moving bodies at the scene's start and at the
  // trace's end (its end record, else its last collision), on the motions the trace gave.
  double energy_start = 0, energy_end = 0;
  Vec2d momentum_start, momentum_end;
  RefereeStats stats;
  // True when a collision is a miss or a phantom, or a contact is left before the end: what
  // fails a gate (as `pge check`).
  bool failed() const {
    return counts[static_cast<int>(Verdict::Miss)] > 0 || counts[static_cast<int>(Verdict::Phantom)] > 0 ||
           (end && end->miss);
  }
};

// judge_trace's result: the judgement of the trace's mode (the other member stays empty).
struct TraceJudgement {
  TraceMode mode = TraceMode::Steps;
  StepJudgement steps;    // steps mode
  EventJudgement events;  // events mode
  bool failed() const { return mode == TraceMode::Steps ? steps.failed() : events.failed(); }
};

// Judges `trace` as a run of `scene` (the scene as PGE reads it: fixed bodies' vertices at
// position + vertex rounded to double). Throws pge::TraceError for a trace that does not fit the
// scene, std::invalid_argument for an invalid scene, UnsupportedScene for one PGE does not model.
// Preconditions: none beyond a Trace as read_trace makes it or as filled in memory (the mode
// decides which judgement runs); everything a trace can get wrong is reported by TraceError.
TraceJudgement judge_trace(const Scene& scene, const Trace& trace, const JudgeOptions& options = {});
// judge_trace for one mode; throws TraceError (field "mode") for a trace of the other mode.
StepJudgement judge_steps(const Scene& scene, const Trace& trace, const JudgeOptions& options = {});
EventJudgement judge_events(const Scene& scene, const Trace& trace, const JudgeOptions& options = {});

// One line per failure ("contact bullet-wall in step 12 (exact t = 0.19662): missed (pass-through:
// tunnelling)"), "" when nothing failed: what a test prints when it fails.
std::string failure_text(const TraceJudgement& j);
// One contact's line, whatever its verdict: `contact "ball"-"wall" in step 6 (exact t = 0.8125):
// on time` (the exact time rounded to double, printed with up to 17 significant digits, seconds).
std::string contact_text(const StepContact& c);

}  // namespace pge::oracle
