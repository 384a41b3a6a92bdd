// Reading "pge-trace/2" traces (JSON Lines, docs/formats.md): each line is parsed on its own,
// and every error names the line and the field within it.
#include "json_path.hpp"
#include "json_text.hpp"
#include "pge/scene_io.hpp"
#include "pge/trace_io.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <istream>
#include <set>

namespace pge {
namespace {

using Json = nlohmann::json;

constexpr std::string_view kFormat = "pge-trace/2";
// A line nests at most this deep: a step line needs 4 (the line, "bodies", a state, nothing
// deeper); far below what would make nlohmann's recursion or a message's path a problem.
constexpr int kMaxDepth = 16;

// One line of the trace: its text, its number, and errors that name the field in it.
class Line {
 public:
  Line(std::string_view text, int number, const std::string& origin) : text_(text), number_(number), origin_(origin) {}

  int number() const { return number_; }

  [[noreturn]] void fail(const JsonPath& path, const std::string& reason) const {
    throw TraceError(origin_, number_, dotted(path), reason);
  }
  [[noreturn]] void fail_at(std::size_t offset, const std::string& reason) const {
    fail(walk_json(text_, offset, [](const JsonToken&, const JsonPath&) { return true; }), reason);
  }

  Json parse() const {
    if (const std::size_t deep = nesting_too_deep(text_, kMaxDepth); deep != std::string_view::npos)
      fail_at(deep, fmt::format("nested more than {} levels deep", kMaxDepth));
    Json root;
    bool overflow = false;
    try {
      root = Json::parse(text_.begin(), text_.end());
    } catch (const Json::parse_error& error) {
      const std::size_t offset = std::min<std::size_t>(error.byte > 0 ? error.byte - 1 : 0, text_.size());
      if (is_nan_or_infinity(word_at(text_, offset)))
        fail_at(offset, fmt::format("{} is not a JSON number; NaN and infinities are not allowed", word_at(text_, offset)));
      fail_at(offset, syntax_reason(error));
    } catch (const Json::out_of_range&) {
      overflow = true;  // located by token_problem
    }
    if (const auto problem = token_problem(text_)) fail_at(problem->offset, problem->reason);
    if (overflow) fail({}, "a number is out of range for a double");
    if (!root.is_object()) fail({}, "a line must be an object {...}, got " + describe(root));
    return root;
  }

  void keys(const Json& object, const JsonPath& path, std::initializer_list<std::string_view> required,
            std::initializer_list<std::string_view> optional) const {
    for (const std::string_view key : required)
      if (!object.contains(key)) fail(path + std::string(key), "missing");
    for (const auto& item : object.items()) {
      // Not a structured binding: clang before 16 cannot capture one in a lambda.
      const std::string& key = item.key();
      const auto known = [&key](std::initializer_list<std::string_view> names) {
        return std::find(names.begin(), names.end(), key) != names.end();
      };
      if (!known(required) && !known(optional)) fail(path + key, "unknown key");
    }
  }

  double number(const Json& value, const JsonPath& path) const {
    if (!value.is_number()) fail(path, "must be a number, got " + describe(value));
    return value.get<double>();
  }
  Vec2d vec2(const Json& value, const JsonPath& path) const {
    if (!value.is_array() || value.size() != 2) fail(path, "must be an array [x, y] of 2 numbers, got " + describe(value));
    return {number(value[0], path + 0), number(value[1], path + 1)};
  }
  TraceTurn turn(const Json& value, const JsonPath& path) const {
    if (!value.is_array() || value.size() != 2)
      fail(path, "must be a turn [angle, angular velocity] of 2 numbers, got " + describe(value));
    return {number(value[0], path + 0), number(value[1], path + 1)};
  }
  TraceState state(const Json& value, const JsonPath& path) const {
    if (!value.is_array() || value.size() != 4)
      fail(path, "must be a state [x, y, vx, vy] of 4 numbers, got " + describe(value));
    return {{number(value[0], path + 0), number(value[1], path + 1)},
            {number(value[2], path + 2), number(value[3], path + 3)}};
  }
  std::string string(const Json& value, const JsonPath& path) const {
    if (!value.is_string()) fail(path, "must be a string, got " + describe(value));
    return value.get<std::string>();
  }
  const Json& array(const Json& value, const JsonPath& path) const {
    if (!value.is_array()) fail(path, "must be an array [...], got " + describe(value));
    return value;
  }

 private:
  std::string_view text_;
  int number_;
  const std::string& origin_;
};

JsonPath key(const char* k) { return JsonPath{} + std::string(k); }

class TraceReader {
 public:
  explicit TraceReader(const std::string& origin) { trace_.origin = origin; }

  void line(std::string_view text, int number) {
    if (text.find_first_not_of(" \t\r") == std::string_view::npos) return;  // blank lines are allowed
    const Line l(text, number, trace_.origin);
    const Json j = l.parse();
    if (!seen_header_) return header(l, j);
    if (trace_.end) l.fail({}, fmt::format("nothing may follow the end record (line {})", trace_.end->line));
    if (!j.contains("event")) l.fail(key("event"), "missing");
    const std::string event = l.string(j["event"], key("event"));
    if (event == "end") return end(l, j);
    if (trace_.mode == TraceMode::Steps) {
      if (event != "step") l.fail(key("event"), fmt::format("must be \"step\" or \"end\" in a steps trace, got \"{}\"", excerpt(event)));
      return step(l, j);
    }
    if (event == "collision") return collision(l, j);
    if (event == "frame") return frame(l, j);
    l.fail(key("event"), fmt::format("must be \"collision\", \"frame\" or \"end\" in an events trace, got \"{}\"", excerpt(event)));
  }

  Trace finish() {
    if (!seen_header_) throw TraceError(trace_.origin, 0, "", "no header line (the file is empty)");
    return std::move(trace_);
  }

 private:
  void header(const Line& l, const Json& j) {
    if (!j.contains("format")) l.fail(key("format"), fmt::format("missing: the first line must be the header, with \"format\": \"{}\"", kFormat));
    const std::string format = l.string(j["format"], key("format"));
    if (format == "pge-trace/1")
      l.fail(key("format"), "pge-trace/1 (before issue 28) has no pre-collision states and cannot be judged; write the "
                            "trace again with this version (pge run --trace writes pge-trace/2)");
    if (format != kFormat) l.fail(key("format"), fmt::format("must be \"{}\", got \"{}\"", kFormat, excerpt(format)));
    l.keys(j, {}, {"format", "mode"}, {"engine", "scene", "bodies", "scalar", "solver", "until"});
    const std::string mode = l.string(j["mode"], key("mode"));
    if (mode == "events") trace_.mode = TraceMode::Events;
    else if (mode == "steps") trace_.mode = TraceMode::Steps;
    else l.fail(key("mode"), fmt::format("must be \"events\" or \"steps\", got \"{}\"", excerpt(mode)));
    if (j.contains("engine")) trace_.engine = l.string(j["engine"], key("engine"));
    if (j.contains("scene")) trace_.scene = l.string(j["scene"], key("scene"));
    for (const char* k : {"scalar", "solver"})
      if (j.contains(k)) l.string(j[k], key(k));
    if (j.contains("until")) l.number(j["until"], key("until"));
    if (j.contains("bodies")) {
      const Json& ids = l.array(j["bodies"], key("bodies"));
      std::set<std::string> seen;
      for (std::size_t i = 0; i < ids.size(); ++i) {
        const JsonPath at = key("bodies") + static_cast<int>(i);
        std::string id = l.string(ids[i], at);
        if (!seen.insert(id).second) l.fail(at, fmt::format("body \"{}\" is listed twice", excerpt(id)));
        trace_.bodies.push_back(std::move(id));
      }
    } else if (trace_.mode == TraceMode::Steps) {
      l.fail(key("bodies"), "missing: a steps trace lists the ids of the bodies whose states each step gives");
    }
    trace_.header_line = l.number();
    seen_header_ = true;
  }

  // Times: finite (the reader already refuses NaN and infinities), not before the last.
  double time(const Line& l, const Json& j, bool strictly_after) {
    const double t = l.number(j["t"], key("t"));
    if (t < 0) l.fail(key("t"), fmt::format("must be >= 0, got {}", t));
    if (t < last_t_ || (strictly_after && t == last_t_ && last_line_ > 0))
      l.fail(key("t"), fmt::format("{} is {} the time of line {} ({}): times must {}", t, t == last_t_ ? "equal to" : "before",
                                   last_line_, last_t_, strictly_after ? "increase from step to step" : "not decrease"));
    last_t_ = t;
    last_line_ = l.number();
    return t;
  }

  void step(const Line& l, const Json& j) {
    l.keys(j, {}, {"event", "t", "bodies"}, {"turns", "contacts"});
    TraceStep s;
    s.line = l.number();
    s.t = time(l, j, true);
    const Json& states = l.array(j["bodies"], key("bodies"));
    if (states.size() != trace_.bodies.size())
      l.fail(key("bodies"), fmt::format("has {} states, the header lists {} bodies", states.size(), trace_.bodies.size()));
    for (std::size_t i = 0; i < states.size(); ++i) s.bodies.push_back(l.state(states[i], key("bodies") + static_cast<int>(i)));
    if (j.contains("turns")) {  // [angle, angular velocity] of each body the header lists
      const Json& turns = l.array(j["turns"], key("turns"));
      if (turns.size() != trace_.bodies.size())
        l.fail(key("turns"), fmt::format("has {} turns, the header lists {} bodies", turns.size(), trace_.bodies.size()));
      for (std::size_t i = 0; i < turns.size(); ++i) s.turns.push_back(l.turn(turns[i], key("turns") + static_cast<int>(i)));
    }
    if (j.contains("contacts")) {
      const Json& contacts = l.array(j["contacts"], key("contacts"));
      for (std::size_t i = 0; i < contacts.size(); ++i) {
        const JsonPath at = key("contacts") + static_cast<int>(i);
        if (!contacts[i].is_array() || contacts[i].size() != 2)
          l.fail(at, "must be a pair [id, id] of body ids, got " + describe(contacts[i]));
        s.contacts.push_back({l.string(contacts[i][0], at + 0), l.string(contacts[i][1], at + 1)});
      }
    }
    trace_.steps.push_back(std::move(s));
  }

  void collision(const Line& l, const Json& j) {
    // PGE's own collision lines carry more (the contact, the normal, ...): known, not needed.
    l.keys(j, {}, {"event", "t", "a", "b", "before", "va", "vb"},
           {"contact", "features", "normal", "point", "approach_speed", "impulse", "gap", "overlap_rule", "turn", "wa",
            "wb"});
    TraceCollision c;
    c.line = l.number();
    c.t = time(l, j, false);
    c.a = l.string(j["a"], key("a"));
    c.b = l.string(j["b"], key("b"));
    const Json& before = l.array(j["before"], key("before"));
    if (before.size() != 2) l.fail(key("before"), "must hold 2 states [[x, y, vx, vy], [x, y, vx, vy]] (a, then b), got " + describe(before));
    c.before_a = l.state(before[0], key("before") + 0);
    c.before_b = l.state(before[1], key("before") + 1);
    c.va_after = l.vec2(j["va"], key("va"));
    c.vb_after = l.vec2(j["vb"], key("vb"));
    if (j.contains("contact")) c.contact = l.string(j["contact"], key("contact"));
    if (j.contains("features")) {
      const Json& f = j["features"];
      const auto index = [&l](const Json& x, const JsonPath& at) {
        if (!x.is_number_unsigned() || x.get<std::uint64_t>() > 65535) l.fail(at, "must be a feature index in [0, 65535], got " + describe(x));
        return x.get<unsigned>();
      };
      if (!f.is_array() || f.size() != 2) l.fail(key("features"), "must be a pair [i, j] of feature indices, got " + describe(f));
      c.feature_a = index(f[0], key("features") + 0);
      c.feature_b = index(f[1], key("features") + 1);
    }
    const int turns = static_cast<int>(j.contains("turn")) + static_cast<int>(j.contains("wa")) + static_cast<int>(j.contains("wb"));
    if (turns > 0 && turns < 3)
      l.fail(key(j.contains("turn") ? (j.contains("wa") ? "wb" : "wa") : "turn"),
             "missing: a collision of a turning pair gives \"turn\", \"wa\" and \"wb\" together");
    if (turns == 3) {
      const Json& turn = l.array(j["turn"], key("turn"));
      if (turn.size() != 2) l.fail(key("turn"), "must hold 2 turns [[angle, w], [angle, w]] (a, then b), got " + describe(turn));
      c.turning = true;
      c.turn_a = l.turn(turn[0], key("turn") + 0);
      c.turn_b = l.turn(turn[1], key("turn") + 1);
      c.wa_after = l.number(j["wa"], key("wa"));
      c.wb_after = l.number(j["wb"], key("wb"));
    }
    trace_.collisions.push_back(std::move(c));
  }

  // PGE's frame lines sample the state; the referee follows the collisions, so frames are only
  // read for their form and their times.
  void frame(const Line& l, const Json& j) {
    l.keys(j, {}, {"event", "t", "bodies"}, {"turns"});
    time(l, j, false);
    const Json& states = l.array(j["bodies"], key("bodies"));
    for (std::size_t i = 0; i < states.size(); ++i) l.state(states[i], key("bodies") + static_cast<int>(i));
  }

  void end(const Line& l, const Json& j) {
    l.keys(j, {}, {"event", "t"}, {"stop", "collisions", "state_hash"});
    TraceEnd e;
    e.line = l.number();
    e.t = time(l, j, false);
    if (j.contains("stop")) e.reached_until = l.string(j["stop"], key("stop")) == "reached-until";
    trace_.end = e;
  }

  Trace trace_;
  bool seen_header_ = false;
  double last_t_ = 0;
  int last_line_ = 0;
};

}  // namespace

Trace read_trace(std::istream& in, const std::string& origin) {
  TraceReader reader(origin);
  std::string text;
  int number = 0;
  while (std::getline(in, text)) reader.line(text, ++number);
  if (in.bad()) throw TraceError(origin, 0, "", "read error");
  return reader.finish();
}

Trace read_trace_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw TraceError(path, 0, "", fmt::format("cannot open: {}", std::strerror(errno)));
  return read_trace(in, path);
}

}  // namespace pge
