// What `pge check` records per event and how it summarises a scene (text and JSON).
#pragma once

#include "pge/oracle.hpp"
#include "pge/scene.hpp"

#include <array>
#include <cstdint>
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
  std::string exact_time;  // the pair's exact contact time, 20 decimals, truncated
  long long ulps = 0;
  double relative_error = 0;
  bool features_match = false;
  std::vector<std::pair<BodyIndex, BodyIndex>> earliest;  // pairs at the exact first contact
  bool elastic = false, both_moving = false;
  double energy_change = 0, energy_relative = 0;
  double momentum_change = 0, momentum_relative = 0;
  double gap = 0, contact_distance = 0;
};

EventRecord make_record(std::uint64_t index, double time, const oracle::ExactEvent& e, const oracle::Judgement& j);

struct SceneCheck {
  std::string path, name, scalar, solver, stop;
  std::size_t bodies = 0;
  double time = 0, horizon = 0;
  std::vector<EventRecord> events;
  bool end_checked = false;  // the run reached its horizon and the oracle looked for leftovers
  oracle::EndJudgement end;
  oracle::RefereeStats oracle;
  double engine_seconds = 0;
  bool filter = true;
};

// Counts of each verdict, the end check's miss included.
std::array<std::uint64_t, oracle::kVerdictCount> verdict_counts(const SceneCheck& c);
bool has_failure(const SceneCheck& c);

void print_summary(const SceneCheck& c, const Scene& scene);
// The scene's summary and every event's verdict as one JSON object, events streamed one per
// line (a long run's events never sit in memory as JSON).
void write_json(std::ostream& out, const SceneCheck& c, const Scene& scene);

}  // namespace pge::cli
