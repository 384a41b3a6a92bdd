// Events mode of the trace referee (pge/judge.hpp): an event-driven engine's collisions, judged
// by the same Referee that judges PGE's own (pge check), following the motions the trace gives.
#include "judge_scene.hpp"

#include <fmt/core.h>

#include <optional>

#include <algorithm>
#include <array>
#include <cmath>
#include <tuple>
#include <utility>

namespace pge::oracle {

using namespace detail;

namespace {

// How far a pair's state just before a collision may be from the path the referee follows it on
// (the trace's previous collision of the body, or the scene's start), relative to
// max(1, |the value on the path|), in each component of position and velocity. Dimensionless. An
// event-driven engine holds the same closed-form path and differs from it by the rounding of its
// clock and its rebased positions, ulps of 1e-16; a difference past 1e-6 is a body moved without
// an event the trace shows (a teleport, a lost collision line), which no verdict can describe.
constexpr double kStateTolerance = 1e-6;

ExactVec position_at(const ExactMotion& m, const Dyadic& t) {
  const Dyadic d = t - m.t0;
  const Dyadic h = (d * d).scaled(-1);
  return {m.p0.x + m.v0.x * d + m.acc.x * h, m.p0.y + m.v0.y * d + m.acc.y * h};
}

ExactVec velocity_at(const ExactMotion& m, const Dyadic& t) {
  const Dyadic d = t - m.t0;
  return {m.v0.x + m.acc.x * d, m.v0.y + m.acc.y * d};
}

// A body's state as a trace gives it: x, y, vx, vy (the reference point, and the centre of
// mass's velocity), then its angle and angular velocity (0, 0 for a body that does not turn).
using StateArray = std::array<double, 6>;
// How a message names a component of it (the field names the position and velocity already).
constexpr const char* kStateNames[6] = {"", "", "", "", "angle ", "angular velocity "};

// The first component of `seen` further than kStateTolerance from `on_path` (-1: none).
int mismatch(const StateArray& seen, const StateArray& on_path) {
  for (int k = 0; k < 6; ++k)
    if (std::abs(seen[k] - on_path[k]) > kStateTolerance * std::max(1.0, std::abs(on_path[k]))) return k;
  return -1;
}

// Body i on its path at time t, as a trace gives it.
StateArray path_state(const SceneModel& m, const ExactBody& body, BodyIndex i, const Dyadic& t) {
  const Dyadic angle = angle_at(body.motion, t);
  const Vec2d p = reference_of(m, i, position_at(body.motion, t), angle);
  const ExactVec v = velocity_at(body.motion, t);
  return {p.x, p.y, v.x.to_double(), v.y.to_double(), angle.to_double(), body.motion.omega.to_double()};
}

// Energy and momentum of the moving bodies at time t on the state's motions.
std::pair<double, Vec2d> totals_at(const ExactState& s, const Dyadic& t) {
  Dyadic energy;
  ExactVec momentum;
  for (const ExactBody& b : s.bodies) {
    if (b.fixed) continue;
    const ExactVec v = velocity_at(b.motion, t);
    energy += body_energy(b, position_at(b.motion, t), v, b.motion.omega);
    momentum.x += b.mass * v.x;
    momentum.y += b.mass * v.y;
  }
  return {energy.to_double(), {momentum.x.to_double(), momentum.y.to_double()}};
}

struct Side {
  BodyIndex body;
  const TraceState* before;
  const Vec2d* after;
  const char* name;  // "a" or "b"
  int state_index;   // in "before"
  TraceTurn turn;    // before (0, 0 when the trace gives none)
  double w_after;
};

}  // namespace

EventJudgement judge_events(const Scene& scene, const Trace& trace, const JudgeOptions& options) {
  const TraceFailer failer(trace);
  if (trace.mode != TraceMode::Events) failer.fail(trace.header_line, "header", "mode", "judge_events needs an events trace");
  SceneModel model = scene_model(scene);
  if (!trace.bodies.empty() && trace.bodies != model.ids) {
    std::size_t k = 0;
    while (k < trace.bodies.size() && k < model.ids.size() && trace.bodies[k] == model.ids[k]) ++k;
    failer.fail(trace.header_line, "header", fmt::format("bodies[{}]", k),
                fmt::format("an events trace lists every body of the scene in scene order ({} bodies: \"{}\" first), or none",
                            model.ids.size(), model.ids.empty() ? "" : model.ids[0]));
  }
  // The engine ran to its own horizon: contacts before it count.
  if (trace.end && trace.end->reached_until && std::isfinite(trace.end->t)) {
    model.state.horizon = Dyadic::from(trace.end->t);
  }
  EventJudgement out;
  std::tie(out.energy_start, out.momentum_start) = totals_at(model.state, Dyadic());
  Referee referee(std::move(model.state), options.referee);
  double last_t = 0;
  for (std::size_t k = 0; k < trace.collisions.size(); ++k) {
    const TraceCollision& c = trace.collisions[k];
    const std::string element = fmt::format("collisions[{}]", k);
    failer.finite(c.t, c.line, element, "t");
    if (c.t < last_t) failer.fail(c.line, element, "t", fmt::format("{} is before the previous collision's time {}", c.t, last_t));
    last_t = c.t;
    Side sides[2] = {{failer.body(model, c.line, element, "a", c.a), &c.before_a, &c.va_after, "a", 0, c.turn_a, c.wa_after},
                     {failer.body(model, c.line, element, "b", c.b), &c.before_b, &c.vb_after, "b", 1, c.turn_b, c.wb_after}};
    if (sides[0].body == sides[1].body) failer.fail(c.line, element, "b", "a body cannot collide with itself");
    if (sides[0].body > sides[1].body) std::swap(sides[0], sides[1]);
    const ExactState& now = referee.state();
    if (now.bodies[sides[0].body].fixed && now.bodies[sides[1].body].fixed)
      failer.fail(c.line, element, "b", "two fixed bodies never collide");
    for (const Side& side : sides)
      if (now.bodies[side.body].rotates && !c.turning)
        failer.fail(c.line, element, "turn",
                    fmt::format("missing: body \"{}\" rotates, and a collision of a turning pair gives each body's "
                                "[angle, angular velocity] before and \"wa\", \"wb\" after",
                                model.ids[side.body]));
    const Dyadic t = Dyadic::from(c.t);
    ExactMotion after[2];
    for (int s = 0; s < 2; ++s) {
      const Side& side = sides[s];
      const std::string field = fmt::format("before[{}]", side.state_index);
      failer.finite(*side.before, c.line, element, field);
      failer.finite(side.after->x, c.line, element, fmt::format("v{}[0]", side.name));
      failer.finite(side.after->y, c.line, element, fmt::format("v{}[1]", side.name));
      const std::string turn_field = fmt::format("turn[{}]", side.state_index);
      failer.finite(side.turn.angle, c.line, element, turn_field + "[0]");
      failer.finite(side.turn.angular_velocity, c.line, element, turn_field + "[1]");
      failer.finite(side.w_after, c.line, element, fmt::format("w{}", side.name));
      const ExactBody& body = now.bodies[side.body];
      const StateArray on_path = path_state(model, body, side.body, t);
      const StateArray seen = {side.before->position.x, side.before->position.y, side.before->velocity.x,
                               side.before->velocity.y,  side.turn.angle,         side.turn.angular_velocity};
      if (const int bad = mismatch(seen, on_path); bad >= 0)
        failer.fail(c.line, element, bad < 4 ? fmt::format("{}[{}]", field, bad) : fmt::format("{}[{}]", turn_field, bad - 4),
                    fmt::format("body \"{}\" is not where the scene and the trace's earlier collisions put it: {}{} on "
                                "its path, {} in the trace{}",
                                model.ids[side.body], kStateNames[bad], on_path[bad], seen[bad],
                                body.fixed ? " (a fixed body never moves)" : ""));
      if (body.fixed && (side.after->x != 0 || side.after->y != 0))
        failer.fail(c.line, element, fmt::format("v{}", side.name), fmt::format("body \"{}\" is fixed: it stays at rest", model.ids[side.body]));
      if (body.fixed && !(Dyadic::from(side.w_after) == body.motion.omega))
        failer.fail(c.line, element, fmt::format("w{}", side.name),
                    fmt::format("body \"{}\" is fixed: it keeps its angular velocity {}", model.ids[side.body], body.motion.omega.to_double()));
      // A rotating body goes on from its recorded angle (which does not jump) and pivot, at its
      // angular velocity after.
      after[s] = body.fixed ? body.motion
                            : ExactMotion{t,
                                          pivot_of(model, side.body, side.before->position, side.turn.angle),
                                          ExactVec::from(*side.after),
                                          body.motion.acc,
                                          {kNoBody, kNoBody},
                                          body.rotates ? Dyadic::from(side.turn.angle) : Dyadic(),
                                          body.rotates ? Dyadic::from(side.w_after) : Dyadic()};
    }
    ExactEvent e;
    e.time = t;
    e.a = sides[0].body;
    e.b = sides[1].body;
    e.va_before = ExactVec::from(sides[0].before->velocity);
    e.vb_before = ExactVec::from(sides[1].before->velocity);
    e.va_after = ExactVec::from(*sides[0].after);
    e.vb_after = ExactVec::from(*sides[1].after);
    e.wa_before = Dyadic::from(sides[0].turn.angular_velocity);
    e.wb_before = Dyadic::from(sides[1].turn.angular_velocity);
    e.wa_after = Dyadic::from(sides[0].w_after);
    e.wb_after = Dyadic::from(sides[1].w_after);
    e.impulse = !(sides[0].before->velocity == *sides[0].after && sides[1].before->velocity == *sides[1].after &&
                  sides[0].turn.angular_velocity == sides[0].w_after && sides[1].turn.angular_velocity == sides[1].w_after);
    if (!c.contact.empty()) {
      std::optional<ContactKind> kind;
      for (const ContactKind kind_k : {ContactKind::CircleCircle, ContactKind::CircleEdge, ContactKind::CircleVertex,
                                  ContactKind::VertexEdge, ContactKind::EdgeVertex})
        if (contact_kind_name(kind_k) == c.contact) kind = kind_k;
      if (!kind) failer.fail(c.line, element, "contact", fmt::format("unknown contact kind \"{}\"", c.contact.substr(0, 80)));
      e.contact = *kind;
      e.feature_a = static_cast<std::uint16_t>(c.feature_a);
      e.feature_b = static_cast<std::uint16_t>(c.feature_b);
      if (sides[0].state_index == 1) {  // named for (b, a): as the referee names it for (a, b)
        std::swap(e.feature_a, e.feature_b);
        if (e.contact == ContactKind::VertexEdge) e.contact = ContactKind::EdgeVertex;
        else if (e.contact == ContactKind::EdgeVertex) e.contact = ContactKind::VertexEdge;
      }
    }
    // Without named features the verdict is the same, features and gap are then not judged; but
    // for a rotating pair's event at an exact graze, which is undecided only where the gap of
    // the engine's features shows it within rounding of the tangency (oracle/README.md,
    // "Rotation"), and otherwise a phantom.
    EventVerdict verdict{k, model.ids[e.a], model.ids[e.b], c.t, e, referee.judge(e, after[0], after[1])};
    ++out.counts[static_cast<int>(verdict.judgement.verdict)];
    const Conservation& cons = verdict.judgement.conservation;
    if (cons.elastic && e.impulse && cons.kinetic_before > 0)
      out.largest_energy_change = std::max(out.largest_energy_change, std::abs(cons.energy_change.to_double()) / cons.kinetic_before);
    if (cons.both_moving && e.impulse && cons.momentum_scale > 0)
      out.largest_momentum_change =
          std::max(out.largest_momentum_change,
                   std::hypot(cons.momentum_change.x.to_double(), cons.momentum_change.y.to_double()) / cons.momentum_scale);
    out.events.push_back(std::move(verdict));
  }
  if (trace.end) {
    failer.finite(trace.end->t, trace.end->line, "end", "t");
    if (trace.end->t < last_t)
      failer.fail(trace.end->line, "end", "t", fmt::format("{} is before the last collision's time {}", trace.end->t, last_t));
    last_t = trace.end->t;
  }
  const auto [energy_end, momentum_end] = totals_at(referee.state(), Dyadic::from(last_t));
  out.energy_end = energy_end;
  out.momentum_end = momentum_end;
  if (trace.end && trace.end->reached_until) out.end = referee.judge_end();
  out.stats = referee.stats();
  return out;
}

}  // namespace pge::oracle
