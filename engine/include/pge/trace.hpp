// A trace: what an engine did in a run of a scene, in doubles, independent of any file format
// (the file format "pge-trace/2" is read and written by pge/trace_io.hpp, and documented in
// docs/formats.md). The exact referee judges it (pge/judge.hpp). Two modes:
//   events: an event-driven engine's collisions, each with its time, the pair and the pair's
//           state just before it (PGE's own `pge run --trace` writes this mode);
//   steps:  a stepping engine's steps, each with its end time, every moving body's state at
//           that time and the contacts the engine reported during the step.
// Bodies are named by their scene ids, so that a trace can be written without knowing PGE's
// body order. Lines are 1-based line numbers in the file the trace was read from, 0 for a
// trace made in memory: errors name them.
#pragma once

#include "pge/vec2.hpp"

#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace pge {

enum class TraceMode : unsigned char { Events, Steps };

// A moving body's state at one time: position in metres, velocity in m/s (the scene's units).
struct TraceState {
  Vec2d position;
  Vec2d velocity;
};

// A body's turn at one time: angle in radians and angular velocity in rad/s (0, 0 for a body
// that does not turn).
struct TraceTurn {
  double angle = 0;
  double angular_velocity = 0;
};

// A pair of bodies the engine reported in contact (either order of ids).
struct TraceContact {
  std::string a, b;
};

// Steps mode: the step that ends at `t` (it starts where the previous step ended, the first at
// the scene's start, t = 0). `bodies` holds the state at `t` of every body Trace::bodies names,
// in that order; `contacts` the pairs the engine reported during the step, each once. In a scene
// with rotation `turns` holds each of those bodies' turn at `t`, in the same order (positions
// are then reference points, turned with the body, and velocities the centre of mass's);
// otherwise it is empty (the referee then reads every body as not turning). The referee follows
// a turning body between two steps at the recorded angular velocity (pge/judge.hpp).
struct TraceStep {
  double t = 0;
  std::vector<TraceState> bodies;
  std::vector<TraceContact> contacts;
  int line = 0;
  std::vector<TraceTurn> turns{};  // last, initialised: {t, bodies, contacts} still makes a step
};

// Events mode: one collision at `t` between bodies a and b (either order), their states just
// before it and their velocities just after it (positions do not jump).
struct TraceCollision {
  double t = 0;
  std::string a, b;
  TraceState before_a, before_b;
  Vec2d va_after, vb_after;
  int line = 0;
  // Optional: the features in contact, as PGE names them for (a, b) (event.hpp: "circle-edge",
  // [0, 2]); "" when the trace does not name them (then features and gap are not judged).
  std::string contact;
  unsigned feature_a = 0, feature_b = 0;
  // A pair with a rotating body (PGE writes these for it; needed when either body turns): each
  // body's turn just before (its angle, which does not jump, and angular velocity) and the
  // angular velocities just after, rad/s. `turning` says they were given.
  bool turning = false;
  TraceTurn turn_a{}, turn_b{};
  double wa_after = 0, wb_after = 0;
};

// How the run ended: at `t`; `reached_until` when it ran to its horizon, so that a contact left
// before `t` that the engine never processed is a miss.
struct TraceEnd {
  double t = 0;
  bool reached_until = true;
  int line = 0;
};

struct Trace {
  TraceMode mode = TraceMode::Steps;
  std::string engine;               // a label: "box2d 2.4 @ 60 Hz", "pge robust double"
  std::string scene;                // the scene's name, if the writer gave it ("" otherwise)
  // Steps mode: the ids of the bodies whose states each step lists, in that order: every moving
  // body of the scene, each once. Events mode: empty, or every body of the scene in scene order.
  std::vector<std::string> bodies;
  std::vector<TraceStep> steps;            // steps mode
  std::vector<TraceCollision> collisions;  // events mode
  std::optional<TraceEnd> end;
  std::string origin;  // the file it was read from, for messages ("" in memory)
  int header_line = 0;
};

// A bad trace. what() is one line naming what is known of the file, line and field:
//   run.jsonl:7: field "bodies[1][2]": NaN is not a JSON number
class TraceError : public std::runtime_error {
 public:
  TraceError(const std::string& origin, int line, std::string field, std::string reason)
      : std::runtime_error(message(origin, line, field, reason)), line_(line), field_(std::move(field)),
        reason_(std::move(reason)) {}
  int line() const { return line_; }
  const std::string& field() const { return field_; }
  const std::string& reason() const { return reason_; }

 private:
  static std::string message(const std::string& origin, int line, const std::string& field, const std::string& reason) {
    std::string m = origin.empty() ? std::string("trace") : origin;
    if (line > 0) m += ":" + std::to_string(line);
    m += ": ";
    if (!field.empty()) m += "field \"" + field + "\": ";
    return m + reason;
  }
  int line_ = 0;
  std::string field_;
  std::string reason_;
};

}  // namespace pge
