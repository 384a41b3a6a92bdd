// When the overlap rule applies to a vertex against an edge.
//
// A one-sided distance to an edge line is negative for every point behind the line, near or
// far, so "f(now) < 0" alone would collide a vertex on the far side of a body with the body's
// near edge. The rule therefore follows the separating-axis view of two convex bodies: at
// `now` they overlap (or touch) when no edge normal of either separates them; the pair is in
// contact along the axis of least penetration (every axis tying for it), and the vertices
// deepest along that axis against its edge are the features the overlap rule may collide.
#pragma once

#include "features.hpp"

namespace pge::oracle::detail {

// Bodies are polygons or segments (a segment's edge gives the two axes +n and -n). Exact, at
// tau = 0 of the frame.
bool overlap_rule_applies(Frame& frame, const Feature& vertex_edge);

}  // namespace pge::oracle::detail
