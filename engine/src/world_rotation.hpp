// World<T>::Impl, part of world_impl.hpp. Rotation (docs/rotation.md): the bodies that turn,
// their pairs' contacts predicted by the rotating predictor (detail/predict_rotating.hpp) and
// answered with the impulse with lever arms (detail/rigid.hpp).
//
// Boundaries. Every pair of which one body turns goes through this file: prediction
// (predict_rotating), the impulse test at the horizon (rotating_approaching) and the collision
// (collide_rotating). The translate-only subsystems never see such a pair: the exact refinement
// skips its contacts (they are scheduled refined, the predictor's time standing), a rotating
// body rests on a fixed face only while it does not turn (landed face on face, omega exactly 0)
// and no body rests on a rotating one, and the overlap measures read the turned vertices
// (separation_at). A scene without a rotating body runs none of this.
#pragma once

#include "world_impl.hpp"

namespace pge {

template <class T> inline auto World<T>::Impl::setup_spin(std::size_t i, Body& b, const BodyDesc& d) -> void {
  using std::sqrt;
  Spin& r = spins[i];
  b.rotates = true;
  r.theta0 = T(d.angle);
  r.omega = T(d.angular_velocity);
  const std::vector<Vec2<T>>& local = b.shape.local;
  if (!d.fixed) {
    const detail::TurningMass<T> m = detail::turning_mass(local, T(d.mass), d.inertia > 0 ? T(d.inertia) : T(0));
    r.pivot = m.pivot;
    r.inertia = m.inertia;
    r.inv_inertia = T(1) / r.inertia;
  }
  T reach{};
  for (const Vec2<T>& v : local) {
    r.vertices.push_back(v - r.pivot);
    reach = std::max(reach, T(sqrt(dot(r.vertices.back(), r.vertices.back()))));
  }
  b.shape.reach = reach;
  // The path is the pivot's: the scene's position is the reference point at the scene's angle.
  b.p0 = b.p0 + rotated(r.theta0, r.pivot);
}

template <class T> inline auto World<T>::Impl::rotating_shape(const Body& b) const -> detail::RotatingShape<T> {
  detail::RotatingShape<T> s;
  if (!b.fixed) {
    s.path.t0 = b.t0;
    s.path.v0 = b.v0;
    s.path.a = b.acc;
  }
  s.path.p0 = b.p0;
  if (b.rotates) {
    const Spin& r = spin_of(b);
    s.path.theta0 = r.theta0;
    s.path.omega = r.omega;
    s.vertices = r.vertices;
  } else if (b.shape.is_outline()) {
    s.vertices = b.shape.local;  // a fixed outline's too: about its position, as the scene gives it
  }
  if (b.shape.kind == ShapeKind::Circle) s.radius = b.shape.radius;
  // The reach was rounded (a square root): widened by a few ulps so that it bounds every point.
  s.reach = b.shape.reach * (T(1) + T(8) * std::numeric_limits<T>::epsilon());
  return s;
}

// The pair's memo first. A pair is predicted again without either body's motion changing
// when the other body of an event, or a resume entry, reschedules a body: every partner of the
// body is predicted again, and on the spinning gas about half of the rotating searches were
// such repeats (a contact already found, or a window already searched clear). The memo holds
// the last search's answer while both bodies keep their versions (every motion change bumps
// one: collide, rest, leave, set_velocity): its contact, still ahead, is the pair's first
// contact whatever the caller's limit (a search with a smaller limit would stop short of it and
// be of no use to the caller either way); a window searched clear up to past what is asked is
// answered as a resume entry at its end; one searched clear up to a time short of what is asked
// is searched on from there, as the resume entry at that time would have it (the search starts
// anew at that time, its overlap rule with it). Anything else is searched from `now`.
template <class T>
inline auto World<T>::Impl::predict_rotating(BodyIndex lo, BodyIndex hi, const T& limit)
    -> std::optional<PredictedContact<T>> {
  const T wanted = std::min(limit, horizon);
  if (wanted < now) return std::nullopt;
  std::vector<RotatingMemo>& memos = spins[lo].memos;
  const std::uint64_t v_lo = bodies[lo].version, v_hi = bodies[hi].version;
  const auto memo = std::find_if(memos.begin(), memos.end(), [&](const RotatingMemo& m) { return m.partner == hi; });
  if (memo != memos.end() && memo->version_lo == v_lo && memo->version_hi == v_hi) {
    if (memo->result && !memo->result->resume && memo->result->time >= now) return memo->result;
    if (!(memo->result && !memo->result->resume) && wanted < memo->clear) {
      if (!(memo->clear < horizon)) return std::nullopt;
      PredictedContact<T> out{memo->clear, ContactKind::VertexEdge, 0, 0, false};
      out.rotating = true;
      out.resume = true;
      return out;
    }
  }
  T from = now;
  if (memo != memos.end() && memo->version_lo == v_lo && memo->version_hi == v_hi && memo->clear > now)
    from = memo->clear;  // no contact before it, and none found at it (else answered above)
  T clear = from;
  std::optional<PredictedContact<T>> out = search_rotating(lo, hi, limit, from, clear);
  // Stale memos (either body moved since) go before this one is kept: at most one per partner
  // met since the lower body's last change.
  std::erase_if(memos, [&](const RotatingMemo& m) {
    return m.partner == hi || m.version_lo != v_lo || m.version_hi != bodies[m.partner].version;
  });
  memos.push_back({hi, v_lo, v_hi, clear, out});
  return out;
}

template <class T>
inline auto World<T>::Impl::search_rotating(BodyIndex lo, BodyIndex hi, const T& limit, const T& from, T& clear)
    -> std::optional<PredictedContact<T>> {
  using std::abs;
  using std::sqrt;
  const detail::RotatingShape<T> sa = rotating_shape(bodies[lo]), sb = rotating_shape(bodies[hi]);
  const T wanted = std::min(limit, horizon);
  // The window: at most the time in which the pair's points can close by kRotatingWindowReaches
  // times their reaches' sum at their present speeds (the centres' relative speed plus each
  // spin times its reach). A search costs in proportion to its window (a box per near miss or
  // turn), and the first predictions of a run, with no best event to stop at, would otherwise
  // search to the horizon; past the window the pair is predicted again (a resume entry).
  // A pair whose bounding circles cannot meet before `wanted` (one search of a polynomial over
  // all of it) has no contact to predict there: without this a fast pair moving apart was
  // predicted again every span / speed, an ulp of the clock per resume entry at 1e16 m/s
  // (fixtures/regressions/rotation/box-at-1e16-mps-moving-apart-reaches-its-horizon.json).
  // (Measuring the window from where they meet instead of from `from` cut the predictions on the
  // spinning gas from 25.4 to 17.2 per event but made it slower, 960-980 events/s against 1,185:
  // longer windows cost the feature searches more than the resume entries they save.)
  const auto meet = detail::bounding_circles_meet(sa, sb, from, wanted, detail::RotatingOptions{}.max_boxes);
  if (meet && meet->status == RootStatus::None) {
    clear = wanted;
    return std::nullopt;
  }
  const Kinematics<T> ka = kinematics(bodies[lo], from), kb = kinematics(bodies[hi], from);
  const Vec2<T> dv = kb.v - ka.v;
  const T speed = sqrt(dot(dv, dv)) + abs(sa.path.omega) * sa.reach + abs(sb.path.omega) * sb.reach;
  const double reaches = solver == SolverKind::Fast ? kFastRotatingWindowReaches : kRotatingWindowReaches;
  const T span = T(reaches) * (sa.reach + sb.reach);
  T end = speed > T(0) && span / speed < wanted - from ? from + span / speed : wanted;
  if (!(end > from)) end = std::min(wanted, detail::interval_next_up(from));  // progress, however late the clock
  detail::RotatingOptions options;
  options.correctly_rounded = solver == SolverKind::Certified;
  // A contact at `from` whose points do not approach, or a corner passed, is searched past: it
  // would have no impulse and be found again at once (RotatingPairPredictor::set_contact_test;
  // fixtures/regressions/rotation/turning-boxes-meet-face-on-face-with-corners-aligned.json).
  const auto test = [&](const detail::RotatingContact<T>& contact) { return rotating_contact_test(lo, hi, contact); };
  const detail::RotatingContact<T> c = [&] {
    if (solver == SolverKind::Fast) return detail::predict_rotating_pair_fast(sa, sb, from, end);
    detail::RotatingPairPredictor<T> predictor(sa, sb, StartRule::OverlapCollides, options);
    predictor.set_contact_test(test);
    predictor.set_bounding_circles(meet);  // asked over [from, wanted], wanted >= end
    return predictor.earliest(from, end);
  }();
  if (c.rounding_undecided) ++counts.undecided_roundings;
  PredictedContact<T> out{c.t, ContactKind::VertexEdge, 0, 0, c.at_start_overlap};
  out.rotating = true;
  if (c.status == RootStatus::None) {
    clear = end;  // searched through end: nothing touches before it
    if (!(end < wanted)) return std::nullopt;
    out.time = end;
    out.resume = true;
    return out;
  }
  if (c.status == RootStatus::Undecided) {
    clear = c.t;
    // Progress every time: a search that stopped where it started resumes an ulp later.
    out.resume = true;
    if (!(out.time > from)) out.time = detail::interval_next_up(from);
    if (out.time > horizon) return std::nullopt;
    return out;
  }
  clear = c.t;
  if (c.t > horizon) return std::nullopt;
  out.at_start = c.at_start;
  const PredictedContact<T> features = contact_of(c);
  out.contact = features.contact;
  out.feature_a = features.feature_a;
  out.feature_b = features.feature_b;
  return out;
}

template <class T>
inline auto World<T>::Impl::contact_of(const detail::RotatingContact<T>& c) -> PredictedContact<T> {
  PredictedContact<T> out{c.t, ContactKind::VertexEdge, 0, 0, c.at_start_overlap};
  const auto index = [](std::size_t k) { return static_cast<std::uint16_t>(k); };
  switch (c.feature) {
    case detail::RotatingFeature::VertexEdge:
      out.contact = c.point_on_a ? ContactKind::VertexEdge : ContactKind::EdgeVertex;
      out.feature_a = index(c.point_on_a ? c.point : c.edge);
      out.feature_b = index(c.point_on_a ? c.edge : c.point);
      break;
    case detail::RotatingFeature::CircleEdge:
    case detail::RotatingFeature::CircleVertex:
      // The circle is the point side; its feature is 0, the other's the edge (or vertex) index.
      out.contact = c.feature == detail::RotatingFeature::CircleEdge ? ContactKind::CircleEdge : ContactKind::CircleVertex;
      out.feature_a = index(c.point_on_a ? 0 : c.edge);
      out.feature_b = index(c.point_on_a ? c.edge : 0);
      break;
  }
  return out;
}

template <class T>
inline auto World<T>::Impl::rotating_record(const Scheduled<T>& s, const T& t) const -> detail::RotatingContact<T> {
  detail::RotatingContact<T> c;
  c.status = RootStatus::Root;
  c.t = t;
  c.at_start = s.at_start && t == s.time;
  switch (s.contact) {
    case ContactKind::VertexEdge:
    case ContactKind::EdgeVertex:
      c.feature = detail::RotatingFeature::VertexEdge;
      c.point_on_a = s.contact == ContactKind::VertexEdge;
      c.point = c.point_on_a ? s.feature_a : s.feature_b;
      c.edge = c.point_on_a ? s.feature_b : s.feature_a;
      break;
    default:
      c.feature = s.contact == ContactKind::CircleEdge ? detail::RotatingFeature::CircleEdge
                                                        : detail::RotatingFeature::CircleVertex;
      c.point_on_a = bodies[s.lo].shape.kind == ShapeKind::Circle;
      c.edge = c.point_on_a ? s.feature_b : s.feature_a;
      break;
  }
  return c;
}

template <class T>
inline auto World<T>::Impl::rotating_geometry(const Scheduled<T>& s, const T& t) const -> detail::RotatingGeometry<T> {
  return detail::rotating_contact_geometry(rotating_shape(bodies[s.lo]), rotating_shape(bodies[s.hi]), rotating_record(s, t),
                                           solver != SolverKind::Fast);
}

// Whether the contact's point certainly approaches its edge (or a circle the edge) at `now` by
// the exact stored paths (detail::gap_rate_sign); false for a circle against a vertex.
template <class T> inline auto World<T>::Impl::approaches_after(const Scheduled<T>& s) const -> bool {
  const detail::RotatingContact<T> c = rotating_record(s, now);
  if (c.feature == detail::RotatingFeature::CircleVertex) return false;
  const detail::RotatingShape<T> sa = rotating_shape(bodies[s.lo]), sb = rotating_shape(bodies[s.hi]);
  return detail::gap_rate_sign(c.point_on_a ? sa : sb, c.point_on_a ? sb : sa, c, now) < 0;
}

template <class T> inline auto World<T>::Impl::rotating_approaching(const Scheduled<T>& s) const -> bool {
  return rotating_contact_test(s.lo, s.hi, rotating_record(s, s.time)) == detail::ContactTest::Collides;
}

template <class T>
inline auto World<T>::Impl::rotating_contact_test(BodyIndex lo, BodyIndex hi, const detail::RotatingContact<T>& c) const
    -> detail::ContactTest {
  const Body& a = bodies[lo];
  const Body& b = bodies[hi];
  const Kinematics<T> ka = kinematics(a, c.t), kb = kinematics(b, c.t);
  const detail::RotatingGeometry<T> g =
      detail::rotating_contact_geometry(rotating_shape(a), rotating_shape(b), c, solver != SolverKind::Fast);
  const T wa = a.rotates ? spin_of(a).omega : T(0), wb = b.rotates ? spin_of(b).omega : T(0);
  const Vec2<T> ua = ka.v + perp(g.arm_a) * wa, ub = kb.v + perp(g.arm_b) * wb;
  if (!g.enters) return detail::ContactTest::PassesCorner;
  return dot(ub - ua, g.normal) < T(0) && dot(g.normal, g.normal) > T(0) ? detail::ContactTest::Collides
                                                                         : detail::ContactTest::Touches;
}

template <class T> inline auto World<T>::Impl::collide_rotating(const Scheduled<T>& s) -> void {
  using std::sqrt;
  Body& a = bodies[s.lo];
  Body& b = bodies[s.hi];
  rebase(a, now);
  rebase(b, now);
  const Kinematics<T> ka = kinematics(a, now), kb = kinematics(b, now);
  const detail::RotatingGeometry<T> g = rotating_geometry(s, now);

  CollisionInfo<T> info = collision_info(s, ka, kb);
  info.point = g.point;
  info.corner = g.corner;
  const auto spin = [&](const Body& x) { return x.rotates ? spin_of(x).omega : T(0); };
  const auto inv_inertia = [&](const Body& x) { return x.rotates ? spin_of(x).inv_inertia : T(0); };
  info.wa_before = spin(a);
  info.wb_before = spin(b);

  // An axis-aligned normal is the exact unit vector along its axis, as in collide(): a box
  // landing flat then bounces with v.y' = e u exactly.
  Vec2<T> n = g.normal;
  if (n.y == T(0) && n.x != T(0)) n = Vec2<T>{n.x > T(0) ? T(1) : T(-1), T(0)};
  if (n.x == T(0) && n.y != T(0)) n = Vec2<T>{T(0), n.y > T(0) ? T(1) : T(-1)};
  const T n_len = sqrt(dot(n, n));
  // A fixed body's spin moves its surface (a turnstile), and nothing moves it: 1/m = 1/I = 0.
  detail::RigidState<T> ra{ka.v, spin(a), a.inv_mass, inv_inertia(a)};
  detail::RigidState<T> rb{kb.v, spin(b), b.inv_mass, inv_inertia(b)};
  const T e = std::min(a.restitution, b.restitution);
  // A corner whose relative motion does not enter the overlap cone passes or leaves: no impulse.
  const detail::RigidState<T> ra_before = ra, rb_before = rb;
  detail::Impulse<T> j;
  if (g.enters) j = detail::apply_rigid_impulse_with_arms(ra, g.arm_a, rb, g.arm_b, n, e);
  info.normal = n_len > T(0) ? n * (T(1) / n_len) : n;
  info.approach_speed = n_len > T(0) ? -j.v_n / n_len : T(0);
  if (j.applied) {
    const auto store = [&] {
      if (!a.fixed) {
        a.v0 = ra.v;
        if (a.rotates) spin_of(a).omega = ra.w;
      }
      if (!b.fixed) {
        b.v0 = rb.v;
        if (b.rotates) spin_of(b).omega = rb.w;
      }
    };
    store();
    // The stored velocities are the impulse's roundings: where the struck point's exact normal
    // velocity after them still approaches (restitution 0 leaves it zero up to rounding; E7 in
    // docs/rotation.md), the pair touches and approaches at this instant, a contact the exact
    // paths have and the search from here would pass (its start test is in rounding). The
    // impulse grows by an ulp, then 4, 16, ... until the exact paths certainly do not approach
    // there, or within rounding of zero (a face held flat: no change).
    if (solver != SolverKind::Fast && !g.corner && !g.face_on_face) {
      T bump = j.j * std::numeric_limits<T>::epsilon();
      for (int k = 0; k < kMaxImpulseLifts && approaches_after(s); ++k, bump = bump * T(4)) {
        ra = ra_before;
        rb = rb_before;
        j.j = j.j + bump;
        detail::apply_impulse(ra, g.arm_a, rb, g.arm_b, n, j.j);
        store();
        ++counts.impulse_lifts;
      }
    }
    info.impulse = j.j * n_len;
    ++counts.collisions;
    if (s.at_start_overlap) ++counts.overlap_starts;
  } else {
    ++counts.grazes;
  }
  // Resting contact (world_rest.hpp): a body that does not turn, or a rotating one that landed
  // face on face and does not turn (omega exactly 0: the impulse at the stretch's middle adds no
  // spin to a body that had none), may rest on a fixed face; faces a body now leaves stop holding
  // it; a body that turns rests on nothing (a corner holding a box up would take a torque that
  // resting contact does not model), and nothing rests on a rotating body (update_rest asks only
  // non-rotating faces).
  for (const auto& [i, partner, to_i] : {std::tuple{s.lo, s.hi, -g.normal}, std::tuple{s.hi, s.lo, g.normal}}) {
    Body& x = bodies[i];
    if (x.fixed) continue;
    if (!x.rotates || (spin_of(x).omega == T(0) && (g.face_on_face || x.supports > 0))) {
      update_rest(i, partner, to_i, g.point);
    } else if (x.supports > 0) {
      x.supports = 0;
      resolve_supports(x);
    }
  }
  info.va_after = a.v0;
  info.vb_after = b.v0;
  info.wa_after = spin(a);
  info.wb_after = spin(b);
  const Separation<T> sep = separation_at(a, b, now);
  info.gap = sep.gap;
  finish_collision(s, info, measure_overlap(-sep.gap, sep.contact_distance, rotating_rounding_scale(a, b, now), s.lo, s.hi));
}

template <class T> inline auto World<T>::Impl::world_vertex(const Body& b, std::size_t k, const T& t) const -> Vec2<T> {
  const Vec2<T> p = kinematics(b, t).p;
  if (b.rotates) return p + rotated(angle_at(b, t), spin_of(b).vertices[k]);
  return b.shape.vertex(p, k);
}

template <class T> inline auto World<T>::Impl::separation_at(const Body& a, const Body& b, const T& t) const -> Separation<T> {
  if (!a.rotates && !b.rotates) return pge::separation(a.shape, kinematics(a, t).p, b.shape, kinematics(b, t).p);
  const auto vertices_of = [&](const Body& x) { return [&x, &t, this](std::size_t k) { return world_vertex(x, k, t); }; };
  if (a.shape.is_outline() && b.shape.is_outline())
    return {outline_separation<T>(vertices_of(a), a.shape.vertex_count(), vertices_of(b), b.shape.vertex_count()),
            std::min(a.shape.size, b.shape.size)};
  const Body& circle = a.shape.is_outline() ? b : a;
  const Body& other = a.shape.is_outline() ? a : b;
  return {point_outline_distance(kinematics(circle, t).p, vertices_of(other), other.shape.vertex_count()) - circle.shape.radius,
          circle.shape.radius};
}

template <class T> inline auto World<T>::Impl::rotating_rounding_scale(const Body& a, const Body& b, const T& t) const -> T {
  using std::abs;
  using std::sqrt;
  const Kinematics<T> ka = kinematics(a, t), kb = kinematics(b, t);
  const auto scale = [](const Body& x, const Vec2<T>& p) {
    return x.rotates ? max_abs(p) + x.shape.reach : x.shape.coordinate_scale(p);
  };
  const Vec2<T> dv = kb.v - ka.v;
  return std::max(scale(a, ka.p), scale(b, kb.p)) + sqrt(dot(dv, dv)) * abs(t);
}

}  // namespace pge
