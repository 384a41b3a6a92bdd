// The accuracy report's data: one row per scene x configuration (solver x scalar), what the run
// measured, and the report's metadata (machine, build, commit). Written as JSON (the format the
// gate reads, "pge-report/1") and CSV; shards of one sweep merge into one result.
#pragma once

#include <cstdint>
#include <iosfwd>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace pge::report {

// Results that are missing, unreadable or inconsistent (the gate fails closed on these).
struct ReportError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

inline constexpr const char* kFormat = "pge-report/1";

// The relative time error |t_engine - t_exact| / t_exact of judged events, bucketed by binary
// exponent for the error CDFs: bucket 0 holds 0 (exact), bucket k >= 1 holds
// [2^(k - 1 + kRelMinExp), 2^(k + kRelMinExp)), the first and last buckets also what lies beyond.
// Relative error, not ulps, so that float and quad sit on one axis.
inline constexpr int kRelMinExp = -130;
inline constexpr int kRelBuckets = 142;  // up to 2^11
int rel_bucket(double relative_error);
double rel_bucket_upper(int bucket);  // the largest error a bucket holds (0 for bucket 0)

// What a row measures.
enum class RowKind : std::uint8_t {
  Accuracy,  // a fixture or random scene: judged by the exact oracle, and timed without it
  Scaling,   // the elastic gas at a body count: timed only (events per second against N)
  Drift,     // a long gas run: relative energy drift sampled along it
  Peer,      // a pge compare scene run by PGE or a peer (Box2D, Chipmunk): solver = engine,
             // scalar = setting; energy drift, penetration, tunnelling, final-state error
};
const char* row_kind_name(RowKind k);
RowKind parse_row_kind(const std::string& name);  // throws ReportError

struct Row {
  RowKind kind = RowKind::Accuracy;
  std::string family, scene, solver, scalar;
  std::string scene_hash;  // FNV-1a of the scene's canonical text (16 hex digits; empty: not recorded)
  std::uint64_t bodies = 0;
  std::uint64_t events = 0;       // contact events of the timed run (collisions and grazes)
  std::uint64_t predictions = 0;  // pair predictions of the timed run
  std::string stop;               // why the timed run stopped (until, max_events, event-storm)
  std::string error;              // non-empty: the run could not be made (why); nothing else is valid
  bool elastic = true;            // every body's restitution is 1: energy is conserved exactly

  // Accuracy (kind Accuracy): the judged run's verdicts and errors against the oracle.
  std::uint64_t judged_events = 0;  // events with an exact time to compare with
  std::uint64_t misses = 0, phantoms = 0, misorders = 0;
  double ulps_median = 0, ulps_p99 = 0, ulps_max = 0;  // |time error| in ulps of the engine's scalar
  double rel_p99 = 0, rel_max = 0;                     // relative time error
  std::vector<std::uint64_t> rel_hist;                 // kRelBuckets counts (empty: none judged)
  double energy_drift = 0;    // (E_end - E_start) / |E_start| over the run, signed
  double momentum_drift = 0;  // |P_end - P_start| / |P_start|
  double overlap = 0;         // the deepest contact overlap, as a fraction of the contact distance
                              // (Peer rows: the largest penetration over the smaller body's size)
  std::uint64_t tunnelled = 0;  // moving bodies that passed through a fixed body (accuracy rows: in
                                // the judged run, World::tunnels(); peer rows: as pge compare counts)
  double final_error = 0;       // Peer rows: RMS final-position error against PGE certified / extent

  // Speed: the timed runs (the engine alone, no oracle, no trace).
  unsigned repeats = 0;
  double wall_seconds = 0;      // median over the repeats
  double wall_min_seconds = 0;  // fastest repeat
  double events_per_second = 0;
  double ns_per_prediction = 0;
  // The judged run's engine time stood for the timed runs: a run of a minute or more is measured
  // once, inside its judged run (the oracle's own time taken out), not run again alone.
  bool timed_in_judged_run = false;

  // What measuring the row cost in all (its judged run, a peer scene's reference, every timed
  // run): wall seconds and the CPU seconds of the thread that measured it. Not compared by the
  // gate; they show where a sweep's time goes, and the progress estimate learns from them.
  double cost_seconds = 0, cost_cpu_seconds = 0;

  // Drift (kind Drift): (contact events so far, relative energy drift) along the run.
  std::vector<std::pair<double, double>> series;

  // The key a row is matched by across reports (kind/family/scene/solver/scalar).
  std::string key() const;
  // The scene part of it (kind/family/scene): the rows of one scene in one sweep.
  std::string scene_key() const;
  std::string config() const { return solver + "/" + scalar; }
};

struct Meta {
  std::string format = kFormat;
  std::string created;       // UTC, ISO 8601
  std::string commit;        // git HEAD of the source tree ("unknown" outside a checkout)
  bool dirty = false;        // the tree had uncommitted changes
  std::string compiler, build_type;
  bool validate = false, sanitize = false;  // PGE_VALIDATE / sanitizer builds (slower)
  std::string cpu, os;
  unsigned cores = 0;
  bool quick = false;
  std::uint64_t seed = 1;  // of the random scenes
  unsigned shard = 0, shards = 1;
  std::vector<unsigned> shards_merged;  // after a merge: every shard index that went in
  std::string injected;                 // a deliberate regression (pge report --inject-regression)
  // A fixed CPU workload timed in the same process (median of repeats, seconds): the gate
  // compares speed as wall time / calibration, so that a slower or busier machine does not look
  // like a slower engine.
  double calibration_seconds = 0;
  std::uint64_t items = 0;  // work items of the whole sweep (every shard)
  // Worker processes that measured rows at once (pge report --jobs): with more than 1, a row's
  // timed runs ran beside another worker's work, on another core.
  unsigned jobs = 1;
};

struct Results {
  Meta meta;
  std::vector<Row> rows;
};

// JSON ("pge-report/1"); read_results throws ReportError naming the file and what is wrong.
std::string to_json_text(const Results& r);
Results from_json_text(const std::string& text, const std::string& origin);
Results read_results(const std::string& path);
void write_results(const std::string& path, const Results& r);  // throws ReportError
// A whole file as text; throws ReportError ("cannot read PATH").
std::string read_text_file(const std::string& path);
// Writes text beside `path` and renames it there, so that a crash never leaves half a file;
// throws ReportError.
void write_text_file_atomically(const std::string& path, const std::string& text);
// One row as one line of JSON (no newline) and back, exactly (pge report --jobs: a worker process
// hands its rows to the parent this way); row_from_json_line throws ReportError.
std::string row_to_json_line(const Row& row);
Row row_from_json_line(const std::string& line);
// CSV, one row per scene x configuration, a header line first; the histogram and the series stay
// in the JSON.
void write_csv(std::ostream& out, const Results& r);

// Joins the shards of one sweep: same commit, options and shard count, each shard once, no row
// twice. Throws ReportError otherwise; a missing shard is an error unless allow_partial.
Results merge(const std::vector<Results>& parts, bool allow_partial);

// The q-quantile of a relative-error histogram, as its bucket's upper bound (never an
// underestimate); 0 for an empty one.
double hist_quantile(const std::vector<std::uint64_t>& hist, double q);

// One configuration over every accuracy row: what the speed-against-error chart plots.
struct ConfigSummary {
  std::string solver, scalar;
  std::uint64_t scenes = 0, failed_runs = 0, events = 0, judged_events = 0;
  std::uint64_t misses = 0, phantoms = 0, misorders = 0;
  std::vector<std::uint64_t> rel_hist;
  double rel_p99 = 0, rel_max = 0;  // relative time error: p99 from the merged histogram, exact max
  double ulps_max = 0;              // the largest |time error| in ulps of a scene
  double worst_energy_drift = 0;    // the largest |energy drift| of an elastic scene
  double worst_momentum_drift = 0;  // the largest momentum drift of a scene
  double wall_seconds = 0;          // the sum of the scenes' median wall times
  double events_per_second = 0;     // events / wall_seconds
  double ns_per_prediction = 0;     // over all its scenes
  bool pareto = false;              // no other configuration is both faster and more accurate
};
std::vector<ConfigSummary> summarize(const Results& r);

// A configuration's place in the fixed order of the report (fast, robust, certified x float,
// double, long-double, quad); unknown names sort last.
int config_order(const std::string& solver, const std::string& scalar);

}  // namespace pge::report
