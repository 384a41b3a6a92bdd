// The oracle's own model of the bodies, in both number types, and the frame of one search:
// every path is written in tau = t - now, the time since the state's reference time.
#pragma once

#include "algebra.hpp"
#include "interval.hpp"
#include "pge/oracle_state.hpp"

#include <array>
#include <memory>
#include <optional>
#include <unordered_map>
#include <vector>

namespace pge::oracle::detail {

template <class N> struct BodyModel {
  ShapeKind shape = ShapeKind::Circle;
  bool fixed = false;
  N radius{};
  std::vector<V2<N>> local;  // moving bodies: vertex = reference point + local
  std::vector<V2<N>> world;  // fixed bodies: the engine's world vertices
  N t0{};
  V2<N> p0, v0, acc;
  std::array<BodyIndex, 2> supports{kNoBody, kNoBody};  // ExactMotion::supports
  // A rotating body (ExactBody::rotates). Its exact model keeps its outline about the pivot in
  // `local` and its angle's path here; its interval model, which only the spatial filter reads,
  // is the disc it sweeps as it turns (shape Circle, radius its reach about the pivot).
  bool rotates = false;
  N theta0{}, omega{};
  // The interval model of a rotating body: its outline about the pivot (what `local` held before
  // it became the disc), for the rotating pair filter's swept outlines (rotating.cpp).
  std::vector<V2<N>> turning_local;

  bool rests_on(BodyIndex j) const { return supports[0] == j || supports[1] == j; }
};

BodyModel<Dyadic> exact_model(const ExactBody& b);
BodyModel<Interval> interval_model(const ExactBody& b);
void set_motion(BodyModel<Dyadic>& m, const ExactMotion& motion);
void set_motion(BodyModel<Interval>& m, const ExactMotion& motion);

inline int vertex_count(const BodyModel<Dyadic>& b) {
  return static_cast<int>(b.fixed && !b.rotates ? b.world.size() : b.local.size());
}

// Vertex k in the body's own frame (local for moving bodies, world for fixed ones): differences
// of these are the body's constant edge vectors.
template <class N> const V2<N>& vertex_offset(const BodyModel<N>& b, int k) {
  return b.fixed ? b.world[static_cast<std::size_t>(k)] : b.local[static_cast<std::size_t>(k)];
}

template <class N> int next_vertex(const BodyModel<N>& b, int k) {
  const int n = static_cast<int>(b.fixed ? b.world.size() : b.local.size());
  return (k + 1) % n;
}

template <class N> V2<N> edge_vector(const BodyModel<N>& b, int k) {
  return vertex_offset(b, next_vertex(b, k)) - vertex_offset(b, k);
}

inline Dyadic halve(const Dyadic& x) { return x.scaled(-1); }
inline bool is_exact_zero(const Dyadic& x) { return x.is_zero(); }
inline bool is_exact_zero(const Interval& x) { return x.lo() == 0 && x.hi() == 0; }
inline Interval halve(const Interval& x) { return x * Interval(0.5); }

// The reference point's path: p(now + tau) = p0 + v0 (d + tau) + acc (d + tau)^2 / 2 with
// d = now - t0, expanded in tau. Fixed bodies stay at p0.
template <class N> PointPath<N> reference_path(const BodyModel<N>& b, const N& now) {
  if (b.fixed) return constant_path(b.p0);
  const N d = now - b.t0;
  PointPath<N> p;
  p.x.deg = p.y.deg = 2;
  if (is_exact_zero(b.acc.x) && is_exact_zero(b.acc.y)) {
    // No acceleration (a gas, a ball on a table): the same path without the terms that are 0.
    p.x.c[0] = b.p0.x + b.v0.x * d;
    p.y.c[0] = b.p0.y + b.v0.y * d;
    p.x.c[1] = b.v0.x;
    p.y.c[1] = b.v0.y;
    return p;  // c[2] = 0
  }
  const N h = halve(N(1));
  p.x.c[0] = b.p0.x + b.v0.x * d + b.acc.x * (d * d) * h;
  p.y.c[0] = b.p0.y + b.v0.y * d + b.acc.y * (d * d) * h;
  p.x.c[1] = b.v0.x + b.acc.x * d;
  p.y.c[1] = b.v0.y + b.acc.y * d;
  p.x.c[2] = b.acc.x * h;
  p.y.c[2] = b.acc.y * h;
  return p;
}

// A point of the body: its centre (vertex < 0) or a vertex.
template <class N> PointPath<N> point_path(const BodyModel<N>& b, const PointPath<N>& reference, int vertex) {
  if (vertex < 0) return reference;
  if (b.fixed) return constant_path(b.world[static_cast<std::size_t>(vertex)]);
  return shifted(reference, b.local[static_cast<std::size_t>(vertex)]);
}

// The models of every body, and the paths of one search (from `now`), computed on demand.
class Frame {
 public:
  Frame(const std::vector<BodyModel<Dyadic>>& exact, const std::vector<BodyModel<Interval>>& interval,
        const Dyadic& now);

  const BodyModel<Dyadic>& exact_body(BodyIndex i) const { return exact_[i]; }
  const BodyModel<Interval>& interval_body(BodyIndex i) const { return interval_[i]; }
  std::size_t size() const { return exact_.size(); }
  const Dyadic& now() const { return now_; }
  const Interval& now_interval() const { return now_interval_; }

  const PointPath<Dyadic>& reference(BodyIndex i, const Dyadic*);
  const PointPath<Interval>& reference(BodyIndex i, const Interval*);
  template <class N> const BodyModel<N>& body(BodyIndex i) const;
  // What the rotating search derives of body i from this frame's now (rotating.cpp's own type,
  // erased here): made once per frame, shared by every pair the body is in.
  std::shared_ptr<const void>& rotating_slot(BodyIndex i) { return rotating_[i]; }
  // The same for the rotating pair filter's swept outline of body i over one window.
  std::shared_ptr<const void>& sweep_slot(BodyIndex i) { return sweeps_[i]; }
  // The exact contact functions of one feature pair (features.hpp's exact_contact_polys), made
  // once per frame: the gap measure and the engine pair's search both need them.
  std::shared_ptr<const void>& polys_slot(const void* feature) { return polys_[feature]; }

 private:
  const std::vector<BodyModel<Dyadic>>& exact_;
  const std::vector<BodyModel<Interval>>& interval_;
  Dyadic now_;
  Interval now_interval_;
  // Only the bodies a search looks at (a few, with the spatial filter): a map, not a vector of
  // every body, so that making a frame costs nothing per body.
  std::unordered_map<BodyIndex, PointPath<Dyadic>> exact_paths_;
  std::unordered_map<BodyIndex, PointPath<Interval>> interval_paths_;
  std::unordered_map<BodyIndex, std::shared_ptr<const void>> rotating_;
  std::unordered_map<BodyIndex, std::shared_ptr<const void>> sweeps_;
  std::unordered_map<const void*, std::shared_ptr<const void>> polys_;
};

template <> inline const BodyModel<Dyadic>& Frame::body<Dyadic>(BodyIndex i) const { return exact_[i]; }
template <> inline const BodyModel<Interval>& Frame::body<Interval>(BodyIndex i) const { return interval_[i]; }

template <class N> const PointPath<N>& reference_of(Frame& f, BodyIndex i) {
  return f.reference(i, static_cast<const N*>(nullptr));
}

template <class N> PointPath<N> point_of(Frame& f, BodyIndex body, int vertex) {
  return point_path(f.body<N>(body), reference_of<N>(f, body), vertex);
}

// The same without a copy where the point is the reference point itself (a centre): the frame's
// path, or else the vertex's path made in `store`.
template <class N>
const PointPath<N>& point_ref(Frame& f, BodyIndex body, int vertex, std::optional<PointPath<N>>& store) {
  if (vertex < 0) return reference_of<N>(f, body);
  return store.emplace(point_of<N>(f, body, vertex));
}

}  // namespace pge::oracle::detail
