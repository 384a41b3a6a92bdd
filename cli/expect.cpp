#include "expect.hpp"

#include "check_report.hpp"

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <map>
#include <string_view>
#include <tuple>

namespace pge::cli {
namespace {

using Json = nlohmann::json;

// Counts may be written as integral floats (1e6); below 2^64 they convert exactly.
constexpr double kCountLimit = 18446744073709551616.0;

// Cut as the scene reader cuts (pge::excerpt).
std::string describe(const Json& value) {
  return excerpt(value.dump(-1, ' ', false, Json::error_handler_t::replace));
}

std::string quoted_list(std::initializer_list<std::string_view> names) {
  std::string out;
  for (std::string_view name : names) out += fmt::format("{}\"{}\"", out.empty() ? "" : ", ", name);
  return out;
}

class ExpectParser {
 public:
  explicit ExpectParser(const LoadedScene& loaded) : loaded_(loaded) {
    for (std::size_t i = 0; i < loaded.scene.bodies.size(); ++i)
      ids_.emplace(loaded.scene.bodies[i].id, static_cast<BodyIndex>(i));
  }

  Expect parse() const {
    Expect e;
    if (loaded_.expect_json.empty()) return e;
    e.present = true;
    // The reader has already checked the syntax, duplicate keys and number ranges.
    const Json root = Json::parse(loaded_.expect_json);
    const std::string at = "expect";
    object(root, at);
    allow_keys(root, at,
               {"note", "solvers", "stop", "events", "oracle", "max_time_error_ulps", "energy", "momentum",
                "max_overlap", "final", "collisions", "never_collide", "at_rest"});
    if (root.contains("note")) string(root["note"], at + ".note");
    if (root.contains("solvers")) e.solvers = solvers(root["solvers"], at + ".solvers");
    if (root.contains("stop")) e.stop = stop(root["stop"], at + ".stop");
    if (root.contains("events")) events(root["events"], at + ".events", e);
    if (root.contains("oracle")) e.oracle = boolean(root["oracle"], at + ".oracle");
    if (root.contains("max_time_error_ulps")) {
      const std::string path = at + ".max_time_error_ulps";
      // Asked for explicitly, it must be measured: without the oracle it would pass unseen.
      if (!e.oracle) fail(path, "needs the oracle, but the block says \"oracle\": false");
      // Clamped as the oracle clamps its ulps (2^62).
      e.max_time_error_ulps =
          static_cast<long long>(std::min<std::uint64_t>(count(root["max_time_error_ulps"], path), 1ull << 62));
    }
    if (root.contains("energy")) {
      const std::string path = at + ".energy";
      const Json& energy = root["energy"];
      object(energy, path);
      allow_keys(energy, path, {"max_relative_drift", "max_relative_gain"});
      if (energy.empty()) fail(path, "must hold \"max_relative_drift\" or \"max_relative_gain\"");
      if (energy.contains("max_relative_drift"))
        e.energy_drift = non_negative(energy["max_relative_drift"], path + ".max_relative_drift");
      if (energy.contains("max_relative_gain"))
        e.energy_gain = number(energy["max_relative_gain"], path + ".max_relative_gain");
    }
    if (root.contains("momentum")) {
      const std::string path = at + ".momentum";
      const Json& momentum = root["momentum"];
      object(momentum, path);
      allow_keys(momentum, path, {"max_relative_drift"});
      e.momentum_drift = non_negative(required(momentum, path, "max_relative_drift"), path + ".max_relative_drift");
    }
    if (root.contains("max_overlap")) e.max_overlap = non_negative(root["max_overlap"], at + ".max_overlap");
    if (root.contains("final")) finals(root["final"], at + ".final", e);
    if (root.contains("collisions")) collisions(root["collisions"], at + ".collisions", e);
    if (root.contains("never_collide")) never_collide(root["never_collide"], at + ".never_collide", e);
    if (root.contains("at_rest")) at_rest(root["at_rest"], at + ".at_rest", e);
    return e;
  }

 private:
  [[noreturn]] void fail(const std::string& field, const std::string& reason) const {
    throw SceneError(SceneErrorPlace{loaded_.path, 0, 0, -1, "", field}, reason);
  }

  void object(const Json& value, const std::string& path) const {
    if (!value.is_object()) fail(path, "must be an object {...}, got " + describe(value));
  }
  void array(const Json& value, const std::string& path) const {
    if (!value.is_array()) fail(path, "must be an array [...], got " + describe(value));
  }
  void allow_keys(const Json& object, const std::string& path, std::initializer_list<std::string_view> known) const {
    for (const auto& [key, value] : object.items())
      if (std::find(known.begin(), known.end(), key) == known.end())
        fail(path + "." + key, fmt::format("unknown key \"{}\"; known keys are {}", excerpt(key), quoted_list(known)));
  }
  const Json& required(const Json& object, const std::string& path, const char* key) const {
    if (!object.contains(key)) fail(path + "." + key, "missing; it is required");
    return object[key];
  }

  std::string string(const Json& value, const std::string& path) const {
    if (!value.is_string()) fail(path, "must be a string, got " + describe(value));
    return value.get<std::string>();
  }
  bool boolean(const Json& value, const std::string& path) const {
    if (!value.is_boolean()) fail(path, "must be true or false, got " + describe(value));
    return value.get<bool>();
  }
  // Parsed JSON numbers are finite: the reader has rejected NaN, infinities and overflow.
  double number(const Json& value, const std::string& path) const {
    if (!value.is_number()) fail(path, "must be a number, got " + describe(value));
    return value.get<double>();
  }
  double non_negative(const Json& value, const std::string& path) const {
    const double x = number(value, path);
    if (!(x >= 0)) fail(path, "must be a number >= 0, got " + describe(value));
    return x;
  }
  std::uint64_t count(const Json& value, const std::string& path) const {
    if (value.is_number_unsigned()) return value.get<std::uint64_t>();
    const double x = value.is_number() ? value.get<double>() : -1;
    if (!(x >= 0 && x < kCountLimit && std::floor(x) == x))
      fail(path, "must be an integer >= 0, got " + describe(value));
    return static_cast<std::uint64_t>(x);
  }
  Vec2d vector(const Json& value, const std::string& path) const {
    if (!value.is_array() || value.size() != 2 || !value[0].is_number() || !value[1].is_number())
      fail(path, "must be an array [x, y] of 2 numbers, got " + describe(value));
    return {value[0].get<double>(), value[1].get<double>()};
  }
  BodyIndex body(const Json& value, const std::string& path) const {
    const std::string id = string(value, path);
    const auto it = ids_.find(id);
    if (it == ids_.end()) fail(path, fmt::format("no body {} in the scene", describe(value)));
    return it->second;
  }
  std::pair<BodyIndex, BodyIndex> pair(const Json& value, const std::string& path) const {
    if (!value.is_array() || value.size() != 2)
      fail(path, "must be an array [id, id] of 2 body ids, got " + describe(value));
    const BodyIndex a = body(value[0], path + "[0]"), b = body(value[1], path + "[1]");
    if (a == b) fail(path, "names the same body twice: " + describe(value));
    return {std::min(a, b), std::max(a, b)};
  }

  std::vector<SolverKind> solvers(const Json& value, const std::string& path) const {
    array(value, path);
    if (value.empty()) fail(path, "must list at least one solver");
    std::vector<SolverKind> out;
    for (std::size_t k = 0; k < value.size(); ++k) {
      const std::string where = fmt::format("{}[{}]", path, k);
      SolverKind kind{};
      if (!parse_solver_kind(string(value[k], where), kind))
        fail(where, "must be \"fast\", \"robust\" or \"certified\", got " + describe(value[k]));
      out.push_back(kind);
    }
    return out;
  }

  StopReason stop(const Json& value, const std::string& path) const {
    const std::string name = string(value, path);
    for (StopReason r : {StopReason::ReachedUntil, StopReason::MaxEvents, StopReason::EventStorm})
      if (name == stop_reason_name(r)) return r;
    fail(path, "must be \"reached-until\", \"max-events\" or \"event-storm\", got " + describe(value));
  }

  void events(const Json& value, const std::string& path, Expect& e) const {
    object(value, path);
    allow_keys(value, path, {"min", "max"});
    if (value.empty()) fail(path, "must hold \"min\" or \"max\"");
    if (value.contains("min")) e.events_min = count(value["min"], path + ".min");
    if (value.contains("max")) e.events_max = count(value["max"], path + ".max");
    if (e.events_min && e.events_max && *e.events_min > *e.events_max)
      fail(path, fmt::format("min {} is above max {}", *e.events_min, *e.events_max));
  }

  void finals(const Json& value, const std::string& path, Expect& e) const {
    array(value, path);
    for (std::size_t k = 0; k < value.size(); ++k) {
      const std::string at = fmt::format("{}[{}]", path, k);
      const Json& item = value[k];
      object(item, at);
      allow_keys(item, at, {"body", "position", "velocity", "angle", "angular_velocity", "tolerance"});
      ExpectedFinal f;
      f.body = body(required(item, at, "body"), at + ".body");
      if (item.contains("position")) f.position = vector(item["position"], at + ".position");
      if (item.contains("velocity")) f.velocity = vector(item["velocity"], at + ".velocity");
      if (item.contains("angle")) f.angle = number(item["angle"], at + ".angle");
      if (item.contains("angular_velocity")) f.angular_velocity = number(item["angular_velocity"], at + ".angular_velocity");
      if (!f.position && !f.velocity && !f.angle && !f.angular_velocity)
        fail(at, "must hold \"position\", \"velocity\", \"angle\" or \"angular_velocity\"");
      if (item.contains("tolerance")) f.tolerance = non_negative(item["tolerance"], at + ".tolerance");
      e.finals.push_back(f);
    }
  }

  void collisions(const Json& value, const std::string& path, Expect& e) const {
    array(value, path);
    for (std::size_t k = 0; k < value.size(); ++k) {
      const std::string at = fmt::format("{}[{}]", path, k);
      const Json& item = value[k];
      object(item, at);
      allow_keys(item, at, {"pair", "time", "tolerance"});
      ExpectedCollision c;
      std::tie(c.a, c.b) = pair(required(item, at, "pair"), at + ".pair");
      c.time = number(required(item, at, "time"), at + ".time");
      if (item.contains("tolerance")) c.tolerance = non_negative(item["tolerance"], at + ".tolerance");
      e.collisions.push_back(c);
    }
  }

  void never_collide(const Json& value, const std::string& path, Expect& e) const {
    array(value, path);
    for (std::size_t k = 0; k < value.size(); ++k) e.never_collide.push_back(pair(value[k], fmt::format("{}[{}]", path, k)));
  }

  void at_rest(const Json& value, const std::string& path, Expect& e) const {
    object(value, path);
    allow_keys(value, path, {"bodies", "by", "tolerance"});
    ExpectedRest r;
    const Json& bodies = required(value, path, "bodies");
    array(bodies, path + ".bodies");
    if (bodies.empty()) fail(path + ".bodies", "must list at least one body");
    for (std::size_t k = 0; k < bodies.size(); ++k) r.bodies.push_back(body(bodies[k], fmt::format("{}.bodies[{}]", path, k)));
    r.by = number(required(value, path, "by"), path + ".by");
    if (value.contains("tolerance")) r.tolerance = non_negative(value["tolerance"], path + ".tolerance");
    e.at_rest = r;
  }

  const LoadedScene& loaded_;
  std::map<std::string, BodyIndex> ids_;
};

// --- evaluation -----------------------------------------------------------------------------

std::string vec_text(const Vec2d& v) { return fmt::format("({:.17g}, {:.17g})", v.x, v.y); }

bool within(const Vec2d& measured, const Vec2d& expected, double tolerance) {
  return std::abs(measured.x - expected.x) <= tolerance && std::abs(measured.y - expected.y) <= tolerance;
}

class Evaluation {
 public:
  Evaluation(const Scene& scene, ExpectOutcome& outcome) : scene_(scene), out_(outcome) {}

  // One expectation checked; when `holds` is false, `text` says what was expected and measured.
  template <class Text> void check(const std::string& key, bool holds, Text text) {
    ++out_.checked;
    if (!holds) out_.failures.push_back({key, text()});
  }
  std::string pair(BodyIndex a, BodyIndex b) const { return pair_text(scene_, a, b); }
  const std::string& id(BodyIndex i) const { return scene_.bodies[i].id; }

 private:
  const Scene& scene_;
  ExpectOutcome& out_;
};

}  // namespace

bool Expect::lists(SolverKind solver) const {
  return std::find(solvers.begin(), solvers.end(), solver) != solvers.end();
}

Expect parse_expect(const LoadedScene& loaded) { return ExpectParser(loaded).parse(); }

ExpectTracker::ExpectTracker(const Expect& expect, std::size_t bodies)
    : expect_(expect),
      nearest_(expect.collisions.size()),
      first_contact_(expect.never_collide.size()),
      last_contact_(expect.at_rest ? bodies : 0) {}

void ExpectTracker::observe(double time, BodyIndex a, BodyIndex b) {
  const auto same = [a, b](BodyIndex x, BodyIndex y) { return (x == a && y == b) || (x == b && y == a); };
  for (std::size_t k = 0; k < nearest_.size(); ++k) {
    const ExpectedCollision& c = expect_.collisions[k];
    if (same(c.a, c.b) && (!nearest_[k] || std::abs(time - c.time) < std::abs(*nearest_[k] - c.time))) nearest_[k] = time;
  }
  for (std::size_t k = 0; k < first_contact_.size(); ++k)
    if (!first_contact_[k] && same(expect_.never_collide[k].first, expect_.never_collide[k].second)) first_contact_[k] = time;
  if (!last_contact_.empty()) {
    last_contact_[a] = time;
    last_contact_[b] = time;
  }
}

void evaluate(const Expect& e, const Scene& scene, const ExpectTracker& tracker, const SceneCheck& c, ExpectOutcome& out) {
  out.evaluated = true;
  Evaluation x(scene, out);
  x.check("stop", c.stop_reason == e.stop, [&] {
    return fmt::format("expected the run to stop on {}, measured {} at t = {:.17g}{}", stop_reason_name(e.stop), c.stop,
                       c.time, c.storm_a == kNoBody ? "" : " (bodies " + x.pair(c.storm_a, c.storm_b) + ")");
  });
  if (e.events_min || e.events_max) {
    const std::uint64_t lo = e.events_min.value_or(0);
    const std::uint64_t hi = e.events_max.value_or(std::numeric_limits<std::uint64_t>::max());
    x.check("events", c.contact_events >= lo && c.contact_events <= hi, [&] {
      const std::string range = !e.events_max ? fmt::format("at least {}", lo)
                                : lo == hi      ? fmt::format("exactly {}", lo)
                                                : fmt::format("{} to {}", lo, hi);
      return fmt::format("expected {} contact events, measured {}", range, c.contact_events);
    });
  }
  if (e.oracle) {
    const auto n = verdict_counts(c);
    const auto misses = n[static_cast<std::size_t>(oracle::Verdict::Miss)];
    const auto phantoms = n[static_cast<std::size_t>(oracle::Verdict::Phantom)];
    x.check("oracle", misses + phantoms == 0, [&] {
      return fmt::format("expected no miss and no phantom against the oracle, measured {} misses ({} of them at the end) "
                         "and {} phantoms",
                         misses, c.end.miss ? 1 : 0, phantoms);
    });
    const long long ulps = largest_abs_ulps(c);
    x.check("max_time_error_ulps", ulps <= e.max_time_error_ulps, [&] {
      return fmt::format("expected time errors of at most {} ulps, measured {} ulps", e.max_time_error_ulps, ulps);
    });
  }
  const double de = energy_relative_change(c);
  if (e.energy_drift)
    x.check("energy.max_relative_drift", std::abs(de) <= *e.energy_drift, [&] {
      return fmt::format("expected a relative energy drift of at most {:.3g}, measured {:.3g} ({:.17g} -> {:.17g})",
                         *e.energy_drift, std::abs(de), c.energy_start, c.energy_end);
    });
  if (e.energy_gain)
    x.check("energy.max_relative_gain", de <= *e.energy_gain, [&] {
      return fmt::format("expected a relative energy gain of at most {:.3g}, measured {:.3g} ({:.17g} -> {:.17g})",
                         *e.energy_gain, de, c.energy_start, c.energy_end);
    });
  if (e.momentum_drift) {
    const double dp = momentum_relative_drift(c);
    x.check("momentum.max_relative_drift", dp <= *e.momentum_drift, [&] {
      return fmt::format("expected a relative momentum drift of at most {:.3g}, measured {:.3g} ({} -> {})",
                         *e.momentum_drift, dp, vec_text(c.momentum_start), vec_text(c.momentum_end));
    });
  }
  if (e.max_overlap)
    x.check("max_overlap", c.largest_contact_overlap <= *e.max_overlap, [&] {
      return fmt::format("expected the largest overlap at a contact to be at most {:.3g} of the contact distance, "
                         "measured {:.3g}",
                         *e.max_overlap, c.largest_contact_overlap);
    });
  for (std::size_t k = 0; k < e.finals.size(); ++k) {
    const ExpectedFinal& f = e.finals[k];
    const BodySnapshot<double>& s = c.final_states[f.body];
    const auto check_final = [&](const char* what, const std::optional<Vec2d>& expected, const Vec2d& measured) {
      if (!expected) return;
      x.check(fmt::format("final[{}].{}", k, what), within(measured, *expected, f.tolerance), [&] {
        return fmt::format("expected body \"{}\" to end with {} {} (tolerance {:.3g}), measured {}", x.id(f.body), what,
                           vec_text(*expected), f.tolerance, vec_text(measured));
      });
    };
    check_final("position", f.position, s.position);
    check_final("velocity", f.velocity, s.velocity);
    const auto check_turn = [&](const char* what, const std::optional<double>& expected, double measured) {
      if (!expected) return;
      x.check(fmt::format("final[{}].{}", k, what), std::abs(measured - *expected) <= f.tolerance, [&] {
        return fmt::format("expected body \"{}\" to end with {} {} (tolerance {:.3g}), measured {}", x.id(f.body), what,
                           *expected, f.tolerance, measured);
      });
    };
    check_turn("angle", f.angle, s.angle);
    check_turn("angular_velocity", f.angular_velocity, s.angular_velocity);
  }
  for (std::size_t k = 0; k < e.collisions.size(); ++k) {
    const ExpectedCollision& ec = e.collisions[k];
    const std::optional<double>& t = tracker.nearest()[k];
    x.check(fmt::format("collisions[{}]", k), t && std::abs(*t - ec.time) <= ec.tolerance, [&] {
      return fmt::format("expected a contact event of {} at t = {:.17g} (tolerance {:.3g}), measured {}",
                         x.pair(ec.a, ec.b), ec.time, ec.tolerance,
                         t ? fmt::format("the nearest at t = {:.17g}", *t) : std::string("none of that pair"));
    });
  }
  for (std::size_t k = 0; k < e.never_collide.size(); ++k) {
    const auto [a, b] = e.never_collide[k];
    const std::optional<double>& t = tracker.first_contact()[k];
    x.check(fmt::format("never_collide[{}]", k), !t, [&] {
      return fmt::format("expected no contact event of {}, measured one at t = {:.17g}", x.pair(a, b), *t);
    });
  }
  if (e.at_rest) {
    for (std::size_t k = 0; k < e.at_rest->bodies.size(); ++k) {
      const BodyIndex i = e.at_rest->bodies[k];
      const std::optional<double>& last = tracker.last_contact()[i];
      const Vec2d v = c.final_states[i].velocity;
      const double speed = std::hypot(v.x, v.y);
      const bool quiet = !last || *last <= e.at_rest->by;
      x.check(fmt::format("at_rest.bodies[{}]", k), quiet && speed <= e.at_rest->tolerance, [&] {
        return fmt::format("expected body \"{}\" at rest by t = {:.17g} (no contact event after it, speed at most {:.3g} at "
                           "the end), measured {}speed {:.3g}",
                           x.id(i), e.at_rest->by, e.at_rest->tolerance,
                           quiet ? "" : fmt::format("a contact event at t = {:.17g} and ", *last), speed);
      });
    }
  }
}

}  // namespace pge::cli
