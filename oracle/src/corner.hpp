// Corners. A vertex v of body A that meets an edge of body B exactly at the edge's end meets
// B's vertex w there, and the contact point is on both bodies' boundaries at once. The bodies
// begin to overlap just after (a collision) only if no line through the corner separates them
// then; near the corner they are cones, so the candidate separating lines are the edges at w
// (against v) and the edges at v (against w), each usable only where its vertex is extreme
// towards it, i.e. exactly the feature pairs of the pair list at that corner. So the contact
// collides iff every one of them goes negative just after the contact time (exact signs of the
// derivatives at the algebraic root). Otherwise it is a graze at a corner: a box sliding exactly
// level onto another's top, or a corner passing exactly by a corner, does not collide.
#pragma once

#include "features.hpp"
#include "roots.hpp"

namespace pge::oracle::detail {

// `vertex_edge` touches its edge's end `end` (0: the edge's first vertex, 1: its second) at tau
// = r. Whether the two bodies begin to overlap there.
bool corner_enters(Frame& frame, FeatureCache& features, const Feature& vertex_edge, int end, const RealRoot& r);

}  // namespace pge::oracle::detail
