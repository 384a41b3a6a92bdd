// The exact referee (DESIGN.md, "The oracle"). From an engine state it finds the exact next
// event: which pairs touch first, on which features, and when (an algebraic time that refines
// to any width), or none before the horizon. Given the engine's events one by one it judges each
// (agree, time error, tie, misorder, miss, phantom) and measures exact conservation.
//
// The referee reads only state: an ExactState made from a World by exact_state()
// (pge/oracle_state.hpp), every double converted exactly to a dyadic rational. Times are in
// seconds, lengths in metres, masses in kilograms: the scene's units. Usage (PGE's own engine
// judged as `pge check` judges it):
//
//   pge::World<double> world(scene);
//   const pge::oracle::NextEvent first = pge::oracle::next_event(pge::oracle::exact_state(world));
//   if (first.time) std::puts(first.time->decimal(20).c_str());   // exact, truncated decimals
//
//   pge::oracle::Referee referee(pge::oracle::exact_state(world));  // before the first step
//   pge::oracle::follow(world, referee, [](const auto& info, const auto& event, const auto& j) {
//     if (pge::oracle::is_failure(j.verdict)) { /* a miss or a phantom */ }
//   });
//   world.run();
//   if (world.stop_reason() == pge::StopReason::ReachedUntil && referee.judge_end().miss) { /* ... */ }
//
// A whole program with its output: docs/api.md, "pge/oracle.hpp" (docs/examples/oracle.cpp).
// Other engines' runs are judged from a trace instead (pge/judge.hpp).
#pragma once

#include "pge/event.hpp"
#include "pge/oracle_constants.hpp"
#include "pge/oracle_exact.hpp"
#include "pge/oracle_state.hpp"
#include "pge/oracle_time.hpp"

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace pge::oracle {

// Features in contact, named as the engine names them (event.hpp) for the pair (a, b), a < b:
// the contact kind and each body's feature index (vertex or edge number; 0 for a circle).
struct FeaturePair {
  ContactKind contact = ContactKind::CircleCircle;
  std::uint16_t feature_a = 0;
  std::uint16_t feature_b = 0;
  bool operator==(const FeaturePair&) const = default;
};

// A pair touching at a contact time, with every feature pair that touches then.
struct PairContact {
  BodyIndex a = kNoBody, b = kNoBody;
  std::vector<FeaturePair> features;
  bool overlap_rule = false;  // found overlapping: approaching at the search's start, or turning back (contact.hpp)
};

// The exact next event from a state: none before the horizon when `time` is empty. Pairs are
// sorted by (a, b), each with a < b.
struct NextEvent {
  std::optional<ExactTime> time;
  std::vector<PairContact> pairs;  // every pair touching at `time` (more than one: a tie)
};

// Verdicts, from good to bad (see oracle/README.md for the exact rules).
//   Agree:     the engine's pair is the exact first contact, its time within kAgreeUlps.
//   Tie:       as Agree, and another pair touches at exactly the same time.
//   TimeError: the engine's pair is the exact first contact, its time off by more than kAgreeUlps.
//   Misorder:  the engine's pair touches within kAgreeUlps of the engine's time, but another pair
//              touches exactly earlier, also within kAgreeUlps of it: two near-simultaneous
//              contacts taken in the other order, a difference below the time's resolution.
//   Miss:      another pair touches exactly earlier than the engine's time, by more than
//              kAgreeUlps: the engine skipped it.
//   Phantom:   the engine's pair does not touch at the engine's time (its exact contact is more
//              than kAgreeUlps later, or never before the horizon) and nothing was skipped.
//   Undecided: a pair with a rotating body whose contact the referee could not decide within its
//              precision cap (a tangency, a contact at an edge's very end, a sign at the cap:
//              UndecidedTime); counted apart, neither agreement nor failure.
enum class Verdict : std::uint8_t { Agree, Tie, TimeError, Misorder, Miss, Phantom, Undecided };
inline constexpr int kVerdictCount = 7;
// The verdict's name as `pge check --json` writes it: "agree", "tie", "time_error", "misorder",
// "miss", "phantom", "undecided" ("?" outside the enum). Never throws.
std::string_view verdict_name(Verdict v);
// Miss and Phantom fail a run (`pge check` exits 1); the others do not.
inline bool is_failure(Verdict v) { return v == Verdict::Miss || v == Verdict::Phantom; }

// Energy and momentum across one collision, exactly, from the engine's velocities before and
// after (CollisionInfo) and its positions at the contact time (the exact paths before and after).
// Energies in joules (kg m^2 / s^2), momenta in kg m / s.
struct Conservation {
  bool both_moving = false;  // momentum is conserved only between two moving bodies
  bool elastic = false;      // pair restitution 1: kinetic + potential energy is conserved
  Dyadic energy_change;      // (kinetic + potential) after minus before
  ExactVec momentum_change;  // sum of m (v_after - v_before) over the moving bodies
  double kinetic_before = 0;   // the pair's kinetic energy before (scale of relative figures)
  double momentum_scale = 0;   // sum of m |v_before| (scale of relative figures)
  // With a rotating body: kinetic energy includes I omega^2 / 2 (exact: omega and I are the
  // engine's doubles, and the pivot, the centre of mass, moves on its polynomial path). Angular
  // momentum about the origin, I omega + m p x v summed over the moving bodies, is conserved when
  // both move and neither is an outline that does not turn (whose constraint absorbs torque):
  // then `angular` is set and the change is exact. Its scale is what rounding the impulse in
  // doubles can leave in it, summed over both bodies: I (|omega| + |omega'|) + m (|p| + reach)
  // (|v| + |v'|), before and after, the reach being the body's largest distance from its pivot.
  bool angular = false;
  Dyadic angular_momentum_change;
  double angular_scale = 0;
};

// The referee's judgement of one engine event (Referee::judge). Times are exact, seconds.
struct Judgement {
  Verdict verdict = Verdict::Agree;
  std::optional<ExactTime> pair_time;      // exact contact time of the engine's pair, if it touches
  std::vector<FeaturePair> pair_features;  // its features at that time
  bool features_match = false;             // the engine's features are among them
  std::optional<ExactTime> earliest_time;  // the exact first contact of any pair
  std::vector<PairContact> earliest;       // every pair touching then
  // Engine time minus the exact pair time rounded to the engine's format, in ulps of that format
  // (positive: the engine is late); only when pair_time is set. Clamped to +-2^62.
  long long ulps = 0;
  // |t_engine - t_exact| / t_exact (0 when both are 0), from a bracket of t_exact below 2^-64 of
  // the difference: accurate to the double it is reported in (truncated).
  double relative_error = 0;
  Conservation conservation;
  // Signed separation of the engine's features at the engine's time from the exact contact
  // function (negative: overlap), in length units, and the contact distance it compares with
  // (radius sum, or radius; 0 for a vertex against an edge). NaN if the engine's features are
  // not a feature pair the oracle knows.
  double gap = 0;
  double contact_distance = 0;
  std::string undecided_reason;  // Verdict::Undecided: what could not be decided (UndecidedTime)
};

// At the end of a run, or at a motion change (Referee::judge_end, Referee::take_motion).
struct EndJudgement {
  bool miss = false;  // a contact the engine never processed, before the horizon
  bool undecided = false;  // the search met a rotating contact it could not decide (no verdict)
  std::string undecided_reason;
  NextEvent next;     // the exact next contact the referee found (empty: none before the horizon)
};

// A contact the engine passed over before a body's motion changed without a collision
// (Referee::take_motion): the body whose motion changed, when, and the exact contacts before it.
struct MotionMiss {
  BodyIndex body = kNoBody;
  Dyadic at;
  NextEvent next;  // the earliest contact the engine did not process (next.time before `at`)
};

// How the referee searches; the defaults are `pge check`'s. Every setting gives the same
// verdicts (the filters only rule out pairs that certainly do not touch first); they change speed.
struct RefereeOptions {
  bool filter = true;  // the certified filters; off: every pair is solved exactly
  long agree_ulps = kAgreeUlps;  // ulps of the engine's scalar within which a time agrees (oracle_constants.hpp)
  // With `filter`: the spatial filter (src/spatial_filter.hpp) picks the pairs that get the
  // interval test, O(1) per event; off, every pair gets it (O(N) per event; tests compare).
  bool spatial = true;
};

// What the referee's work cost: counts since it was made, for reports.
struct RefereeStats {
  std::uint64_t events = 0;  // judge() calls
  std::uint64_t pairs_examined = 0;  // pairs that might touch first, over all searches
  std::uint64_t pairs_filtered = 0;  // of those, ruled out by the interval filter alone
  std::uint64_t pairs_exact = 0;     // pairs that needed exact arithmetic (the engine's own included)
  std::uint64_t features_exact = 0;  // feature pairs solved exactly
  double seconds = 0;                // wall time inside judge / judge_end / next_event
  // Contacts the engine passed over before a motion change that was not a collision (a body
  // sliding off a face, set_velocity): misses found by take_motion.
  std::uint64_t misses_between_events = 0;
  // Searches that met a rotating contact they could not decide within the precision cap
  // (UndecidedTime): judge() verdicts Undecided, and judge_end / take_motion without a verdict.
  std::uint64_t undecided = 0;
};

// Follows one engine run from its initial state. Every change of the engine's state must reach
// it: collisions through judge() (each on_collision callback, impulse or not), other changes of
// a body's motion (World::on_motion_change) through take_motion().
class Referee {
 public:
  // Precondition: `state` is the run's initial state (exact_state(world) before the first step).
  // Throws nothing for a state exact_state made (std::logic_error only for a referee bug).
  explicit Referee(ExactState state, RefereeOptions options = {});
  ~Referee();
  Referee(Referee&&) noexcept;
  Referee& operator=(Referee&&) noexcept;

  // Judges the engine's event against the current state, then takes the event's outcome: bodies
  // a and b continue on the given motions (what the engine holds after the event) and the
  // state's time becomes the event's time. Preconditions: events come in the order the engine
  // processed them (times not decreasing), and every motion change between them went through
  // take_motion. Throws std::invalid_argument when e.a >= e.b or a body index is out of range.
  Judgement judge(const ExactEvent& e, const ExactMotion& a_after, const ExactMotion& b_after);
  // At the end of a run that reached its horizon: any contact left before it is a miss. (A run
  // stopped early, by its collision budget or a storm, has no such promise: do not call it.)
  EndJudgement judge_end();
  // Body i continues on `motion` from `time` on (not a collision: a body sliding off the end of
  // a face it rested on, or a velocity set by a timer). A contact exactly before `time` that the
  // engine did not process is a miss: returned, and counted in stats().misses_between_events.
  // Throws std::invalid_argument for a body index out of range.
  EndJudgement take_motion(BodyIndex i, const ExactMotion& motion, const Dyadic& time);
  // The exact next event from the current state (state() is not changed). Throws UndecidedTime
  // when a rotating pair's contact cannot be decided within the precision cap.
  NextEvent next_event();

  const ExactState& state() const;    // the state as the referee follows it now
  const RefereeStats& stats() const;
  // Every miss take_motion found, in the order found (stats().misses_between_events of them).
  const std::vector<MotionMiss>& motion_misses() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// The exact next event of a state: the earliest approaching contact after state.now and not
// after state.horizon (DESIGN.md, "What an event is"), every pair touching then. Exact: the time
// refines to any width (ExactTime::bracket, decimal). Throws UndecidedTime for a rotating contact
// it cannot decide within the precision cap, nothing else for a state exact_state made
// (std::logic_error only for a referee bug).
NextEvent next_event(const ExactState& state, const RefereeOptions& options = {});

// Has `referee` judge every collision of `world` from now on (installs the world's collision
// callback): on_judged(info, event, judgement) is called after each judgement. The referee must
// have been made from the world's state before its first step, and must outlive the run. It
// replaces the world's collision and motion-change callbacks: install your own only through
// `on_judged`. Exceptions from the referee (none for a World's own events) pass out of step().
template <class T, class OnJudged> void follow(World<T>& world, Referee& referee, OnJudged on_judged) {
  world.on_collision([&world, &referee, on_judged](const CollisionInfo<T>& info) {
    const ExactEvent e = exact_event(info);
    const Judgement j = referee.judge(e, exact_motion(world.motion(info.a)), exact_motion(world.motion(info.b)));
    on_judged(info, e, j);
  });
  world.on_motion_change([&world, &referee](BodyIndex i, T time) {
    referee.take_motion(i, exact_motion(world.motion(i)), Dyadic::from(time));
  });
}

}  // namespace pge::oracle
