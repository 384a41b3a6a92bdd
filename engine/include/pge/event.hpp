// What the engine reports: events, contacts, and why a run stopped.
#pragma once

#include "pge/vec2.hpp"

#include <cstdint>
#include <string_view>

namespace pge {

using BodyIndex = std::uint32_t;
inline constexpr BodyIndex kNoBody = 0xffffffffu;

// Event kinds, in the order simultaneous events are processed (DESIGN.md: by time, then kind,
// then the lower body id, then the higher).
enum class EventKind : std::uint8_t { Collision = 0, Timer = 1, Frame = 2 };

// The pair of features in contact. Feature indices: a segment's edge is 0, its endpoints are
// vertices 0 (a) and 1 (b); a circle's only feature is 0.
enum class ContactKind : std::uint8_t {
  CircleCircle = 0,  // centre distance equals the radius sum
  CircleEdge = 1,    // a circle against the interior of an edge (projection in [0, 1])
  CircleVertex = 2,  // a circle against a vertex (a circle of radius 0)
  VertexEdge = 3,    // a polygon vertex against an edge interior (polygons: later)
};

std::string_view event_kind_name(EventKind kind);
std::string_view contact_kind_name(ContactKind kind);

template <class T> struct CollisionInfo {
  T time{};
  BodyIndex a = kNoBody;      // the lower body index
  BodyIndex b = kNoBody;      // the higher body index
  ContactKind contact = ContactKind::CircleCircle;
  std::uint16_t feature_a = 0;
  std::uint16_t feature_b = 0;
  Vec2<T> normal;             // unit normal, from a towards b
  Vec2<T> point;              // the contact point
  T approach_speed{};         // -(v_b - v_a) . normal before the impulse (> 0: approaching)
  T impulse{};                // magnitude along `normal` (0 when not approaching)
  T gap{};                    // signed separation at the contact (negative: overlap)
  Vec2<T> va_before, vb_before, va_after, vb_after;
  bool at_start_overlap = false;  // collided by the overlap rule
};

enum class StopReason : std::uint8_t {
  ReachedUntil,   // simulated time reached the run's horizon
  MaxEvents,      // the collision budget ran out
  EventStorm,     // a storm was detected (see StormInfo)
  Stopped,        // a callback asked to stop
};

std::string_view stop_reason_name(StopReason reason);

template <class T> struct StormInfo {
  T time{};
  BodyIndex a = kNoBody;
  BodyIndex b = kNoBody;
  std::uint64_t collisions = 0;  // collisions of body `a` inside the storm window
};

}  // namespace pge
