// Writing "pge-trace/2" traces: one JSON object per line, doubles in shortest round-trip form.
#include "pge/trace_io.hpp"

#include <nlohmann/json.hpp>

#include <ostream>
#include <stdexcept>

namespace pge {
namespace {

// Keeps keys in the order written, so lines read as the format describes them.
using Json = nlohmann::ordered_json;

Json vec2(const Vec2d& v) { return Json::array({v.x, v.y}); }
Json state(const TraceState& s) { return Json::array({s.position.x, s.position.y, s.velocity.x, s.velocity.y}); }
Json turn(const TraceTurn& w) { return Json::array({w.angle, w.angular_velocity}); }

void put(std::ostream& out, const Json& line) {
  try {
    out << line.dump() << '\n';
  } catch (const Json::type_error& e) {
    throw std::invalid_argument(std::string("write_trace: a name or id is not UTF-8: ") + e.what());
  }
}

}  // namespace

void write_trace(std::ostream& out, const Trace& trace) {
  const bool steps = trace.mode == TraceMode::Steps;
  Json header = {{"format", "pge-trace/2"}, {"mode", steps ? "steps" : "events"}};
  if (!trace.engine.empty()) header["engine"] = trace.engine;
  if (!trace.scene.empty()) header["scene"] = trace.scene;
  if (steps || !trace.bodies.empty()) header["bodies"] = trace.bodies;
  put(out, header);
  for (const TraceStep& s : trace.steps) {
    Json states = Json::array();
    for (const TraceState& b : s.bodies) states.push_back(state(b));
    Json contacts = Json::array();
    for (const TraceContact& c : s.contacts) contacts.push_back(Json::array({c.a, c.b}));
    Json line = {{"event", "step"}, {"t", s.t}, {"bodies", std::move(states)}};
    if (!s.turns.empty()) {
      Json turns = Json::array();
      for (const TraceTurn& w : s.turns) turns.push_back(turn(w));
      line["turns"] = std::move(turns);
    }
    line["contacts"] = std::move(contacts);
    put(out, line);
  }
  for (const TraceCollision& c : trace.collisions) {
    Json line = {{"event", "collision"}, {"t", c.t}, {"a", c.a}, {"b", c.b}};
    if (!c.contact.empty()) {
      line["contact"] = c.contact;
      line["features"] = Json::array({c.feature_a, c.feature_b});
    }
    line["before"] = Json::array({state(c.before_a), state(c.before_b)});
    line["va"] = vec2(c.va_after);
    line["vb"] = vec2(c.vb_after);
    if (c.turning) {
      line["turn"] = Json::array({turn(c.turn_a), turn(c.turn_b)});
      line["wa"] = c.wa_after;
      line["wb"] = c.wb_after;
    }
    put(out, line);
  }
  if (trace.end)
    put(out, {{"event", "end"}, {"t", trace.end->t}, {"stop", trace.end->reached_until ? "reached-until" : "stopped"}});
}

}  // namespace pge
