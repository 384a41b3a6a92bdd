#include "pge/event.hpp"
#include "pge/scalar.hpp"
#include "pge/scene.hpp"
#include "pge/world.hpp"

namespace pge {

std::string_view scalar_name(ScalarKind kind) {
  switch (kind) {
    case ScalarKind::Float: return "float";
    case ScalarKind::Double: return "double";
    case ScalarKind::LongDouble: return "long-double";
    case ScalarKind::QuadPrecision: return "quad";
  }
  return "?";
}

bool parse_scalar_kind(std::string_view text, ScalarKind& out) {
  if (text == "float") out = ScalarKind::Float;
  else if (text == "double") out = ScalarKind::Double;
  else if (text == "long-double" || text == "long double") out = ScalarKind::LongDouble;
  else if (text == "quad") out = ScalarKind::QuadPrecision;
  else return false;
  return true;
}

std::string_view solver_name(SolverKind kind) {
  switch (kind) {
    case SolverKind::Fast: return "fast";
    case SolverKind::Robust: return "robust";
    case SolverKind::Certified: return "certified";
  }
  return "?";
}

bool parse_solver_kind(std::string_view text, SolverKind& out) {
  if (text == "fast") out = SolverKind::Fast;
  else if (text == "robust") out = SolverKind::Robust;
  else if (text == "certified") out = SolverKind::Certified;
  else return false;
  return true;
}

std::string_view broad_phase_name(BroadPhase b) {
  switch (b) {
    case BroadPhase::Auto: return "auto";
    case BroadPhase::AllPairs: return "all-pairs";
    case BroadPhase::Grid: return "grid";
  }
  return "?";
}

bool parse_broad_phase(std::string_view text, BroadPhase& out) {
  if (text == "auto") out = BroadPhase::Auto;
  else if (text == "all-pairs") out = BroadPhase::AllPairs;
  else if (text == "grid") out = BroadPhase::Grid;
  else return false;
  return true;
}

std::string_view event_kind_name(EventKind kind) {
  switch (kind) {
    case EventKind::Collision: return "collision";
    case EventKind::Timer: return "timer";
    case EventKind::Frame: return "frame";
  }
  return "?";
}

std::string_view contact_kind_name(ContactKind kind) {
  switch (kind) {
    case ContactKind::CircleCircle: return "circle-circle";
    case ContactKind::CircleEdge: return "circle-edge";
    case ContactKind::CircleVertex: return "circle-vertex";
    case ContactKind::VertexEdge: return "vertex-edge";
    case ContactKind::EdgeVertex: return "edge-vertex";
  }
  return "?";
}

std::string_view stop_reason_name(StopReason reason) {
  switch (reason) {
    case StopReason::ReachedUntil: return "reached-until";
    case StopReason::MaxEvents: return "max-events";
    case StopReason::EventStorm: return "event-storm";
    case StopReason::Stopped: return "stopped";
  }
  return "?";
}

}  // namespace pge
