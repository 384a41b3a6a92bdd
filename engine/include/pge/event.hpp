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

// The pair of features in contact, for the pair (a, b) with a the lower body index.
// Feature indices:
//   circle:  its only feature is 0.
//   segment: vertices 0 (a) and 1 (b); edge 0 runs from vertex 0 to vertex 1. A segment is
//            two-sided: it can be touched from either side of its line.
//   polygon: vertex k is the k-th vertex of the scene (counter-clockwise); edge k runs from
//            vertex k to vertex k + 1 (mod n). Polygon edges are one-sided: touched from outside,
//            along the outward normal (e.y, -e.x) of the edge vector e.
// The kind says which body contributes which feature:
//   CircleEdge / CircleVertex: one body is a circle (feature 0), the other contributes the edge
//     or vertex; which is which follows from the shapes.
//   VertexEdge: a's vertex feature_a against b's edge feature_b; EdgeVertex: a's edge
//     feature_a against b's vertex feature_b.
enum class ContactKind : std::uint8_t {
  CircleCircle = 0,  // centre distance equals the radius sum
  CircleEdge = 1,    // a circle against the interior of an edge (projection in [0, 1])
  CircleVertex = 2,  // a circle against a vertex (a circle of radius 0)
  VertexEdge = 3,    // a's vertex against b's edge interior (a point crossing a line)
  EdgeVertex = 4,    // a's edge interior against b's vertex
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
  // Angular velocities (rad/s, counter-clockwise) before and after: 0 for a body that does not
  // rotate; a fixed body's constant spin (docs/rotation.md).
  T wa_before{}, wb_before{}, wa_after{}, wb_after{};
  bool at_start_overlap = false;  // collided by the overlap rule
  // VertexEdge / EdgeVertex only: the vertex met the edge at one of its ends, a vertex against a
  // vertex (corner on corner, or parallel edges meeting end to end). `normal` is then the
  // corner normal (docs/events.md), not the edge's.
  bool corner = false;
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
