// The exact referee (DESIGN.md, "The oracle"). From an engine state it finds the exact next
// event: which pairs touch first, on which features, and when (an algebraic time that refines
// to any width), or none before the horizon. Given the engine's events one by one it judges each
// (agree, time error, tie, misorder, miss, phantom) and measures exact conservation.
#pragma once

#include "pge/event.hpp"
#include "pge/oracle_constants.hpp"
#include "pge/oracle_exact.hpp"
#include "pge/oracle_state.hpp"
#include "pge/oracle_time.hpp"

#include <cstdint>
#include <memory>
#include <optional>
#include <string_view>
#include <vector>

namespace pge::oracle {

// Features in contact, named as the engine names them (event.hpp) for the pair (a, b), a < b.
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

// The exact next event from a state: none before the horizon when `time` is empty.
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
enum class Verdict : std::uint8_t { Agree, Tie, TimeError, Misorder, Miss, Phantom };
inline constexpr int kVerdictCount = 6;
std::string_view verdict_name(Verdict v);  // "agree", "tie", "time_error", ...
inline bool is_failure(Verdict v) { return v == Verdict::Miss || v == Verdict::Phantom; }

// Energy and momentum across one collision, exactly, from the engine's velocities before and
// after (CollisionInfo) and its positions at the contact time (the exact paths before and after).
struct Conservation {
  bool both_moving = false;  // momentum is conserved only between two moving bodies
  bool elastic = false;      // pair restitution 1: kinetic + potential energy is conserved
  Dyadic energy_change;      // (kinetic + potential) after minus before
  ExactVec momentum_change;  // sum of m (v_after - v_before) over the moving bodies
  double kinetic_before = 0;   // the pair's kinetic energy before (scale of relative figures)
  double momentum_scale = 0;   // sum of m |v_before| (scale of relative figures)
};

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
};

struct EndJudgement {
  bool miss = false;  // a contact the engine never processed, before the horizon
  NextEvent next;
};

// A contact the engine passed over before a body's motion changed without a collision
// (Referee::take_motion): the body whose motion changed, when, and the exact contacts before it.
struct MotionMiss {
  BodyIndex body = kNoBody;
  Dyadic at;
  NextEvent next;  // the earliest contact the engine did not process (next.time before `at`)
};

struct RefereeOptions {
  bool filter = true;  // the certified filters; off: every pair is solved exactly
  long agree_ulps = kAgreeUlps;
  // With `filter`: the spatial filter (src/spatial_filter.hpp) picks the pairs that get the
  // interval test, O(1) per event; off, every pair gets it (O(N) per event; tests compare).
  bool spatial = true;
};

struct RefereeStats {
  std::uint64_t events = 0;
  std::uint64_t pairs_examined = 0;  // pairs that might touch first, over all searches
  std::uint64_t pairs_filtered = 0;  // of those, ruled out by the interval filter alone
  std::uint64_t pairs_exact = 0;     // pairs that needed exact arithmetic (the engine's own included)
  std::uint64_t features_exact = 0;  // feature pairs solved exactly
  double seconds = 0;                // wall time inside judge / judge_end / next_event
  // Contacts the engine passed over before a motion change that was not a collision (a body
  // sliding off a face, set_velocity): misses found by take_motion.
  std::uint64_t misses_between_events = 0;
};

// Follows one engine run from its initial state. Every change of the engine's state must reach
// it: collisions through judge() (each on_collision callback, impulse or not), other changes of
// a body's motion (World::on_motion_change) through take_motion().
class Referee {
 public:
  explicit Referee(ExactState state, RefereeOptions options = {});
  ~Referee();
  Referee(Referee&&) noexcept;
  Referee& operator=(Referee&&) noexcept;

  // Judges the engine's event against the current state, then takes the event's outcome: bodies
  // a and b continue on the given motions (what the engine holds after the event) and the
  // state's time becomes the event's time.
  Judgement judge(const ExactEvent& e, const ExactMotion& a_after, const ExactMotion& b_after);
  // At the end of a run that reached its horizon: any contact left before it is a miss.
  EndJudgement judge_end();
  // Body i continues on `motion` from `time` on (not a collision: a body sliding off the end of
  // a face it rested on, or a velocity set by a timer). A contact exactly before `time` that the
  // engine did not process is a miss: returned, and counted in stats().misses_between_events.
  EndJudgement take_motion(BodyIndex i, const ExactMotion& motion, const Dyadic& time);
  // The exact next event from the current state.
  NextEvent next_event();

  const ExactState& state() const;
  const RefereeStats& stats() const;
  // Every miss take_motion found, in the order found (stats().misses_between_events of them).
  const std::vector<MotionMiss>& motion_misses() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// The exact next event of a state.
NextEvent next_event(const ExactState& state, const RefereeOptions& options = {});

// Has `referee` judge every collision of `world` from now on (installs the world's collision
// callback): on_judged(info, event, judgement) is called after each judgement. The referee must
// have been made from the world's state before its first step, and must outlive the run.
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
