#include "features.hpp"

#include "pge/constants.hpp"

#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>

namespace pge::oracle::detail {
namespace {

// Feature indices are 16-bit (FeaturePair); scenes hold at most kMaxPolygonVertices vertices per
// polygon (validate_scene), so every index fits, and one that did not would be a bug, not a wrap.
static_assert(kMaxPolygonVertices - 1 <= std::numeric_limits<std::uint16_t>::max(),
              "every vertex and edge index of a polygon must fit a 16-bit feature index");
std::uint16_t feature_index(int k) {
  if (k < 0 || static_cast<std::size_t>(k) >= kMaxPolygonVertices)
    throw std::logic_error("oracle: feature index " + std::to_string(k) + " outside [0, kMaxPolygonVertices)");
  return static_cast<std::uint16_t>(k);
}

using Body = BodyModel<Dyadic>;

int edge_count(const Body& b) {
  if (b.shape == ShapeKind::Segment) return 1;  // edge 0: vertex 0 to vertex 1, both sides
  return vertex_count(b);
}

FeaturePair named(ContactKind kind, int a_feature, int b_feature) {
  return {kind, feature_index(a_feature), feature_index(b_feature)};
}

// The side of the edge line (direction e) that body x lies on, seen from its vertex v: +1 along
// the normal (e.y, -e.x), -1 against it, 0 if x is a segment parallel to e; nothing if the line
// through v parallel to e cuts through x (v is not extreme towards the edge).
std::optional<int> body_side(const Body& x, int v, const V2<Dyadic>& e) {
  const int n = vertex_count(x);
  const int neighbours[2] = {(v + n - 1) % n, (v + 1) % n};
  bool above = false, below = false;
  for (int nb : neighbours) {
    const int s = cross(vertex_offset(x, nb) - vertex_offset(x, v), e).sign();
    above = above || s > 0;
    below = below || s < 0;
  }
  if (above && below) return std::nullopt;
  return above ? 1 : (below ? -1 : 0);
}

void circle_features(const Frame& fr, BodyIndex circle, BodyIndex other, std::vector<Feature>& out) {
  const Body& x = fr.exact_body(other);
  const bool circle_is_a = circle < other;
  auto id = [&](ContactKind kind, int k) {
    return circle_is_a ? named(kind, 0, k) : named(kind, k, 0);
  };
  for (int k = 0; k < edge_count(x); ++k) {
    Feature f;
    f.id = id(ContactKind::CircleEdge, k);
    f.point = {circle, -1};
    f.to_edge = true;
    f.edge_body = other;
    f.edge = k;
    f.one_sided = x.shape == ShapeKind::Polygon;
    out.push_back(f);
  }
  for (int k = 0; k < vertex_count(x); ++k) {
    Feature f;
    f.id = id(ContactKind::CircleVertex, k);
    f.point = {circle, -1};
    f.other = {other, k};
    out.push_back(f);
  }
}

// Vertices of body `vb` against the edges of body `eb` (both segments or polygons).
void vertex_edge_features(const Frame& fr, BodyIndex vb, BodyIndex eb, std::vector<Feature>& out) {
  const Body& x = fr.exact_body(vb);
  const Body& y = fr.exact_body(eb);
  const bool one_sided = y.shape == ShapeKind::Polygon;
  for (int k = 0; k < edge_count(y); ++k) {
    const V2<Dyadic> e = edge_vector(y, k);
    for (int v = 0; v < vertex_count(x); ++v) {
      const std::optional<int> side = body_side(x, v, e);
      if (!side) continue;
      if (one_sided && *side < 0) continue;  // x lies behind the edge's outward side from v
      Feature f;
      f.id = vb < eb ? named(ContactKind::VertexEdge, v, k) : named(ContactKind::EdgeVertex, k, v);
      f.point = {vb, v};
      f.to_edge = true;
      f.edge_body = eb;
      f.edge = k;
      f.one_sided = one_sided;
      f.sigma = one_sided ? 1 : *side;
      out.push_back(f);
    }
  }
}

}  // namespace

std::vector<Feature> pair_features(const Frame& fr, BodyIndex a, BodyIndex b) {
  std::vector<Feature> out;
  const Body& x = fr.exact_body(a);
  const Body& y = fr.exact_body(b);
  if (x.fixed && y.fixed) return out;
  const bool x_circle = x.shape == ShapeKind::Circle, y_circle = y.shape == ShapeKind::Circle;
  if (x_circle && y_circle) {
    Feature f;
    f.id = {ContactKind::CircleCircle, 0, 0};
    f.point = {a, -1};
    f.other = {b, -1};
    out.push_back(f);
  } else if (x_circle) {
    circle_features(fr, a, b, out);
  } else if (y_circle) {
    circle_features(fr, b, a, out);
  } else {
    vertex_edge_features(fr, a, b, out);
    vertex_edge_features(fr, b, a, out);
  }
  return out;
}

const std::vector<Feature>& FeatureCache::of(const Frame& frame, BodyIndex a, BodyIndex b) {
  const std::uint64_t key = (std::uint64_t{a} << 32) | b;
  auto it = lists_.find(key);
  if (it == lists_.end()) it = lists_.emplace(key, pair_features(frame, a, b)).first;
  return it->second;
}

}  // namespace pge::oracle::detail
