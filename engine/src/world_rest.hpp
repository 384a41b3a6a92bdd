// World<T>::Impl, part of world_impl.hpp. Resting contact (DESIGN.md): the faces that hold a body,
// its path without their normal components, and when it leaves them.
#pragma once

#include "world_impl.hpp"

namespace pge {

template <class T> inline auto World<T>::Impl::rest_speed(const Body& m, BodyIndex f, const T& acc_normal) const -> T {
  using std::abs;
  using std::sqrt;
  const T ulps = T(kRestHeightUlps) * std::numeric_limits<T>::epsilon();
  if (std::min(m.restitution, bodies[f].restitution) < T(1))
    return sqrt(T(2) * abs(acc_normal) * ulps * m.shape.coordinate_scale(kinematics(m, now).p));
  return ulps * sqrt(dot(m.v0, m.v0));
}

template <class T>
inline auto World<T>::Impl::face_of(BodyIndex f, const Vec2<T>& n, const Vec2<T>& point) const
    -> std::optional<Support> {
  const BodyShape<T>& shape = bodies[f].shape;
  if (!shape.is_outline()) return std::nullopt;  // curved: resting on it is not a straight path
  std::optional<Support> best;
  T best_cos{};
  for (std::size_t k = 0; k < shape.edges.size(); ++k) {
    const T len = shape.edge_length[k];
    if (!(len > T(0))) continue;
    // Divided, not multiplied by 1 / len: an axis-aligned edge's direction is then exactly a
    // unit axis, so the resting body's projected acceleration has no normal part at all (with
    // the reciprocal, a floor of length 7.98828125 gave (-0.9999999999999999, 0), and a ball
    // resting on it sank by 4e-16 in 4 s: found by the tile-joint motif).
    const Vec2<T> u{shape.edges[k].x / len, shape.edges[k].y / len};
    const Vec2<T> out{u.y, -u.x};  // outward for counter-clockwise outlines; a segment has both sides
    const T c = dot(out, n);
    if (!(c >= T(1) - T(kRestNormalTolerance))) continue;
    const T s = dot(point - shape.world[k], u);
    const T slack = T(kRestNormalTolerance) * len;
    if (s < -slack || s > len + slack) continue;
    if (best && !(c > best_cos)) continue;
    best_cos = c;
    best = Support{f, out, shape.world[k], u, len, T(0), T(0)};
  }
  return best;
}

template <class T> inline auto World<T>::Impl::contact_span(const Body& m, Support& s) const -> void {
  if (!m.shape.is_outline()) return;
  std::vector<Vec2<T>> turned;
  if (m.rotates) {
    const T angle = angle_at(m, now);
    for (const Vec2<T>& v : spin_of(m).vertices) turned.push_back(rotated(angle, v));
  }
  const std::vector<Vec2<T>>& points = m.rotates ? turned : m.shape.local;
  T low = std::numeric_limits<T>::infinity();
  for (const Vec2<T>& v : points) low = std::min(low, dot(v, s.n));
  const T tol = T(kRestVertexTolerance) * m.shape.size;
  bool first = true;
  for (const Vec2<T>& v : points) {
    if (dot(v, s.n) > low + tol) continue;
    const T along = dot(v, s.u);
    s.s_lo = first ? along : std::min(s.s_lo, along);
    s.s_hi = first ? along : std::max(s.s_hi, along);
    first = false;
  }
}

template <class T> inline auto World<T>::Impl::leave_time(const Body& m, const Support& s) const -> std::optional<T> {
  const Kinematics<T> k = kinematics(m, now);
  const T c0 = dot(k.p - s.origin, s.u), c1 = dot(k.v, s.u), c2 = dot(k.a, s.u) / T(2);
  std::optional<T> out;
  // Off the start: s + s_hi falls below 0. Off the end: length - (s + s_lo) falls below 0.
  const Poly<T> polys[2] = {Poly<T>{{c0 + s.s_hi, c1, c2, T(0), T(0)}, 2},
                            Poly<T>{{s.length - s.s_lo - c0, -c1, -c2, T(0), T(0)}, 2}};
  for (int end = 0; end < 2; ++end) {
    const Poly<T>& p = polys[end];
    if (never_decreasing(p) && p.c[0] >= T(0)) continue;
    const RootOutcome<T> r = earliest_downward_root(solver, p, T(0), horizon - now);
    if (r.status != RootStatus::Root) continue;
    // The first time the body is past the end as the engine rounds its position: exactly at
    // the end it still touches the face's edge with no normal speed, a contact at the very
    // instant it leaves, predicted again after every such graze.
    T t = now + r.t;
    auto past = [&](const T& at) {
      const T along = dot(kinematics(m, at).p - s.origin, s.u);
      return end == 0 ? along + s.s_hi < T(0) : along + s.s_lo > s.length;
    };
    for (int step = 0; step < kLeaveSteps && !past(t); ++step) t = boost::math::float_next(t);
    if (!out || t < *out) out = t;
  }
  return out;
}

template <class T> inline auto World<T>::Impl::resolve_supports(Body& m) -> void {
  const Vec2<T> a = m.field_acc;
  auto project = [](const Vec2<T>& x, const Vec2<T>& n) { return x - n * dot(x, n); };
  int keep_mask = 0;
  Vec2<T> acc = a;
  if (m.supports == 1) {
    if (dot(a, m.support[0].n) < T(0)) {
      keep_mask = 1;
      acc = project(a, m.support[0].n);
    }
  } else if (m.supports == 2) {
    const Vec2<T> n0 = m.support[0].n, n1 = m.support[1].n;
    const Vec2<T> a0 = project(a, n0), a1 = project(a, n1);
    if (dot(a, n0) >= T(0) && dot(a, n1) >= T(0)) {
      keep_mask = 0;
    } else if (dot(a, n0) < T(0) && dot(a0, n1) >= T(0)) {
      keep_mask = 1;
      acc = a0;
    } else if (dot(a, n1) < T(0) && dot(a1, n0) >= T(0)) {
      keep_mask = 2;
      acc = a1;
    } else {
      keep_mask = 3;  // pressed into both faces: held still
      acc = Vec2<T>{};
    }
  }
  int kept = 0;
  for (int k = 0; k < m.supports; ++k)
    if (keep_mask & (1 << k)) m.support[static_cast<std::size_t>(kept++)] = m.support[static_cast<std::size_t>(k)];
  m.supports = static_cast<std::uint8_t>(kept);
  m.acc = acc;
  if (kept == 2) {
    m.v0 = Vec2<T>{};
  } else if (kept == 1) {
    const Vec2<T> n = m.support[0].n;
    const Vec2<T> v = m.v0;
    m.v0 = project(v, n);
    // A tilted face's unit normal is rounded, and so are the projections: their normal
    // components are rounding, up to a few ulps of |a| and |v|, and over time would carry the
    // body into the face, where no contact is predicted (found by fuzz_engine under an
    // acceleration of 9e9: fixtures/regressions/rest-on-a-tilted-face-drifts-in.json). Both
    // are lifted off the face by kRestLiftUlps ulps of the unprojected magnitudes, more than
    // that rounding: the body can then only drift off the face by as much, a gap, never an
    // overlap. An axis-aligned face projects exactly and is left alone.
    if (n.x != T(0) && n.y != T(0)) {
      using std::sqrt;
      const T lift = T(kRestLiftUlps) * std::numeric_limits<T>::epsilon();
      m.acc += n * (lift * sqrt(dot(a, a)));
      m.v0 += n * (lift * sqrt(dot(v, v)));
    }
  }
}

template <class T>
inline auto World<T>::Impl::update_rest(BodyIndex mi, BodyIndex partner, const Vec2<T>& normal_to_m,
    const Vec2<T>& point)
    -> void {
  Body& m = bodies[mi];
  int kept = 0;
  for (int k = 0; k < m.supports; ++k) {
    const Support& s = m.support[static_cast<std::size_t>(k)];
    using std::abs;
    // Hit by another moving body: the face keeps holding it only if the hit left its normal
    // speed exactly zero; removing any normal speed there would change the two bodies'
    // momentum inside their own collision (found by fuzz_engine,
    // fixtures/regressions/rest-snap-in-a-two-body-collision.json). A normal speed left is
    // the face's own contact to settle, at once, as a contact with the face.
    const T w = dot(m.v0, s.n);
    const bool keep = bodies[partner].fixed ? abs(w) <= rest_speed(m, s.body, dot(m.field_acc, s.n)) : w == T(0);
    if (keep) m.support[static_cast<std::size_t>(kept++)] = s;
  }
  m.supports = static_cast<std::uint8_t>(kept);
  if (bodies[partner].fixed && !bodies[partner].rotates && !m.rests_on(partner) && m.supports < 2) {
    using std::sqrt;
    const T len = sqrt(dot(normal_to_m, normal_to_m));
    if (len > T(0)) {
      if (std::optional<Support> f = face_of(partner, normal_to_m * (T(1) / len), point)) {
        const T pressing = dot(m.acc, f->n);  // the path's: a face already held counts
        contact_span(m, *f);
        // Not at a face's end on the way off it (just slid off it, say): that is a graze of
        // the face's end vertex, not a rest.
        const std::optional<T> off = pressing < T(0) ? leave_time(m, *f) : std::nullopt;
        if (pressing < T(0) && dot(m.v0, f->n) <= rest_speed(m, partner, pressing) && !(off && *off <= now)) {
          m.support[static_cast<std::size_t>(m.supports++)] = *f;
          ++counts.rests;
        }
      }
    }
  }
  resolve_supports(m);  // with no face left: the field's acceleration again
}

template <class T> inline auto World<T>::Impl::continues_support(const Body& m, const Body& j) const -> bool {
  if (m.supports == 0 || !j.fixed || j.rotates || !j.shape.is_outline()) return false;
  const BodyShape<T>& shape = j.shape;
  for (int k = 0; k < m.supports; ++k) {
    const Support& f = m.support[static_cast<std::size_t>(k)];
    const auto on_line = [&](const Vec2<T>& x) { return pge::cross(x - f.origin, f.u) == T(0); };
    for (std::size_t e = 0; e < shape.edges.size(); ++e)
      if (dot(shape.edges[e], f.u) > T(0) && on_line(shape.world[e]) && on_line(shape.world[(e + 1) % shape.world.size()]))
        return true;
  }
  return false;
}

template <class T>
inline auto World<T>::Impl::continuing_face(BodyIndex mi, const Support& old) -> std::optional<Support> {
  using std::abs;
  const Body& m = bodies[mi];
  const Vec2<T> p = kinematics(m, now).p;
  const bool off_end = dot(p - old.origin, old.u) + old.s_lo > old.length;
  const Vec2<T> end = off_end ? old.origin + old.u * old.length : old.origin;
  const T tolerance = T(kRestHeightUlps) * std::numeric_limits<T>::epsilon() * m.shape.coordinate_scale(p);
  std::optional<Support> next;
  for_candidates(mi, [&](BodyIndex j) {
    if (next || j == old.body || !bodies[j].fixed) return;
    const std::optional<Support> f = face_of(j, old.n, end);
    if (f && abs(dot(end - f->origin, f->n)) <= tolerance) next = f;
  });
  if (next) contact_span(m, *next);
  return next;
}

template <class T> inline auto World<T>::Impl::leave(const Scheduled<T>& s, BodyIndex owner) -> void {
  Body& m = bodies[owner];
  rebase(m, now);
  const std::size_t k = s.feature_a;
  if (k < static_cast<std::size_t>(m.supports) && m.support[k].body == s.partner) {
    const Support old = m.support[k];
    for (std::size_t j = k; j + 1 < static_cast<std::size_t>(m.supports); ++j) m.support[j] = m.support[j + 1];
    --m.supports;
    if (const std::optional<Support> next = continuing_face(owner, old); next && !m.rests_on(next->body)) {
      m.support[static_cast<std::size_t>(m.supports++)] = *next;
      ++counts.rests;
    }
  }
  resolve_supports(m);
  ++m.version;
  ++counts.leaves;
  reschedule(owner);
}

}  // namespace pge
