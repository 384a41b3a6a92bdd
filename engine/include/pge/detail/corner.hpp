// The corner rule (docs/events.md, "Corners"), shared by the translating contacts
// (engine/src/contact_polygon.hpp) and the turning ones (predict_rotating.hpp): where on an edge a
// vertex lies, the cone of displacements that make two bodies overlap at a vertex meeting a
// vertex, whether a relative motion enters it, and the corner's normal. Directions here are world
// directions: a turning body's interior directions are its edges turned to the contact's angle.
#pragma once

#include "pge/constants.hpp"
#include "pge/vec2.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>

namespace pge {

// A cone of directions by its two bounding rays: `cw` is the clockwise-most, `ccw` the
// counter-clockwise-most; the cone is at most a half-plane.
template <class T> struct Cone {
  Vec2<T> cw, ccw;
};

// The overlap cone of a vertex of P touching Q where Q's interior directions are q0, q1 and P's
// at its vertex p0, p1: the displacements of P relative to Q that make the bodies overlap,
// spanned by q0, q1, -p0 and -p1. (It is the interior angle of the Minkowski difference of the
// two bodies there, at most a half-plane while the bodies do not overlap.) Nothing when it has
// no interior (two collinear segments end to end).
template <class T>
std::optional<Cone<T>> overlap_cone_of(const Vec2<T>& q0, const Vec2<T>& q1, const Vec2<T>& p0, const Vec2<T>& p1) {
  const std::array<Vec2<T>, 4> g{q0, q1, -p0, -p1};
  // Any positive combination of the generators lies strictly inside the cone when it has an
  // interior: a reference direction from which the two bounding rays are told apart.
  const Vec2<T> r = g[0] + g[1] + g[2] + g[3];
  std::optional<Vec2<T>> cw, ccw;
  for (const Vec2<T>& gi : g) {
    if (cross(gi, r) > T(0)) {
      if (!cw || cross(*cw, gi) < T(0)) cw = gi;
    } else if (cross(r, gi) > T(0)) {
      if (!ccw || cross(*ccw, gi) > T(0)) ccw = gi;
    }
  }
  if (!cw || !ccw) return std::nullopt;
  return Cone<T>{*cw, *ccw};
}

// Whether a point leaving the cone's apex with velocity u and acceleration a goes strictly
// inside it: u inside; or u along a bounding ray and a turning it inwards; or u zero, or along
// the boundary line of a half-plane cone, and a inside. A bounding ray that turns (its body's
// interior direction, at w_cw or w_ccw rad/s) moves with it: the second derivative of the point's
// side of the ray r(t) is cross(r, a) + 2 w cross(perp(r), u) (r' = w perp(r); cross(r'', d)
// vanishes at the apex). A diamond's edge sliding exactly along a segment's end (u along the ray)
// while it turns onto it enters by that term alone (docs/rotation.md, E6). With w = 0, the
// translating rule.
template <class T>
bool enters_cone(const Cone<T>& cone, const Vec2<T>& u, const Vec2<T>& a, const T& w_cw = T(0), const T& w_ccw = T(0)) {
  const T right_of_cw = cross(cone.cw, u);
  const T left_of_ccw = cross(u, cone.ccw);
  // Curving to the left of cw, to the right of ccw (second derivatives of the two sides).
  const auto into_cw = [&] {
    return (w_cw == T(0) ? cross(cone.cw, a) : cross(cone.cw, a) + T(2) * w_cw * cross(perp(cone.cw), u)) > T(0);
  };
  const auto into_ccw = [&] {
    return (w_ccw == T(0) ? cross(a, cone.ccw) : cross(a, cone.ccw) + T(2) * w_ccw * cross(u, perp(cone.ccw))) > T(0);
  };
  if (u.x == T(0) && u.y == T(0)) return into_cw() && into_ccw();
  // Along both bounding rays: the cone is a half-plane (a vertex lying on a segment or on a flat
  // face) and u slides along its boundary line; a turns it inwards or not (box-slide.json).
  if (right_of_cw == T(0) && left_of_ccw == T(0)) return into_cw() && into_ccw();
  if (right_of_cw > T(0) && left_of_ccw > T(0)) return true;
  if (right_of_cw == T(0) && left_of_ccw > T(0)) return into_cw();
  if (left_of_ccw == T(0) && right_of_cw > T(0)) return into_ccw();
  return false;
}

// The normal of a corner contact, from Q towards P: the bisector of the cone's two outward
// normals (the normal cone of the Minkowski difference at that vertex). An impulse along any
// normal in that cone separates the bodies; the bisector is the one that depends only on the
// geometry, not on which of the corner's feature pairs a rounded root time found first. For
// parallel edges meeting end to end the two normals coincide with the edges' common normal.
// Every direction of the cone has a negative dot product with it, so a relative velocity with a
// positive one (after the impulse) leaves the cone.
template <class T> Vec2<T> corner_normal(const Cone<T>& cone) {
  using std::sqrt;
  const Vec2<T> n_cw{cone.cw.y, -cone.cw.x};
  const Vec2<T> n_ccw = perp(cone.ccw);
  return n_cw * (T(1) / sqrt(dot(n_cw, n_cw))) + n_ccw * (T(1) / sqrt(dot(n_ccw, n_ccw)));
}

// Where on edge e a vertex at d (relative to the edge's start) moving at u lies.
enum class EdgeSpot : std::uint8_t { Off, Start, Interior, End };

// `scale` is the size of the coordinates the contact was computed from (their rounding), `len`
// the edge's length.
template <class T>
EdgeSpot locate_on_edge(const Vec2<T>& d, const Vec2<T>& u, const Vec2<T>& e, const T& len, const T& scale) {
  using std::abs;
  const T along = dot(d, e);  // |e| times the distance from the start, along the edge
  const T ee = dot(e, e);
  // The corner slack (constants.hpp) in the same units, widened where the root's rounding in
  // time moves the contact point along the edge: by the tangential over the normal speed.
  T slack = T(kCornerSlackUlps) * std::numeric_limits<T>::epsilon() * scale * len;
  const T normal_speed = abs(cross(u, e));
  if (normal_speed > T(0)) slack = slack * (T(1) + abs(dot(u, e)) / normal_speed);
  slack = std::min(slack, ee / T(2));
  if (along < -slack || along > ee + slack) return EdgeSpot::Off;
  if (along <= slack) return EdgeSpot::Start;
  if (along >= ee - slack) return EdgeSpot::End;
  return EdgeSpot::Interior;
}

}  // namespace pge
