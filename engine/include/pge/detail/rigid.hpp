// Rigid-body quantities of rotating bodies (issue "Rotation", items 2 and 5): the mass properties
// of a polygon lamina and of a thin rod, and the collision impulse with lever arms.
//
// Mass properties. A uniform polygon of mass m with vertices p_k (counter-clockwise) has area
// A = 1/2 sum c_k, c_k = p_k x p_(k+1), centroid G = sum (p_k + p_(k+1)) c_k / (6 A), and second
// moment about a point O in its plane J_O = sum c_k (p_k.p_k + p_k.p_(k+1) + p_(k+1).p_(k+1)) / 12
// with the p_k taken relative to O (the triangle fan from O, each triangle's polar moment
// integrated in closed form). The moment of inertia about the centroid is m J_G / A; it is computed
// with the vertices shifted to the centroid first, so that a polygon far from its reference point
// does not lose its inertia to cancellation (the parallel-axis form m J_O / A - m |G - O|^2 would).
// A segment is a thin rod of length L: m L^2 / 12 about its midpoint.
//
// Impulse. With contact point P, lever arms r_a = P - c_a and r_b = P - c_b, normal n from a to b
// (any length), contact velocities u = v + w x r (w x r = (-w r.y, w r.x)) and
// v_n = (u_b - u_a) . n < 0 (approaching), the impulse along n is
//   j = -(1 + e) v_n / (n.n (1/m_a + 1/m_b) + (r_a x n)^2 / I_a + (r_b x n)^2 / I_b),
// applied as v_a -= j n / m_a, w_a -= j (r_a x n) / I_a, v_b += j n / m_b, w_b += j (r_b x n) / I_b.
// A fixed body has 1/m = 0 and a body that does not rotate 1/I = 0; with both 1/I zero every
// angular term is an exact zero and the impulse is bit for bit the translating engine's
// j = -(1 + e) v_n / (n.n (1/m_a + 1/m_b)).
#pragma once

#include "pge/vec2.hpp"

#include <cstddef>
#include <vector>

namespace pge::detail {

template <class T> struct MassProperties {
  T area{};      // signed: positive for counter-clockwise vertices
  Vec2<T> centroid;
  T inertia_per_mass{};  // about the centroid; times the mass gives the moment of inertia
};

template <class T> MassProperties<T> polygon_mass_properties(const std::vector<Vec2<T>>& p) {
  MassProperties<T> out;
  const std::size_t n = p.size();
  if (n < 3) return out;
  // Relative to the first vertex: the centroid's sums then cancel no large coordinates.
  T twice_area{};
  Vec2<T> moment;  // sum (q_k + q_(k+1)) c_k
  for (std::size_t k = 1; k + 1 < n; ++k) {
    const Vec2<T> q1 = p[k] - p[0], q2 = p[k + 1] - p[0];
    const T c = cross(q1, q2);
    twice_area += c;
    moment = moment + (q1 + q2) * c;
  }
  out.area = twice_area / T(2);
  if (!(twice_area != T(0))) return out;
  out.centroid = p[0] + moment * (T(1) / (T(3) * twice_area));
  T j12{};  // 12 J_G
  for (std::size_t k = 0; k < n; ++k) {
    const Vec2<T> a = p[k] - out.centroid, b = p[(k + 1) % n] - out.centroid;
    j12 += cross(a, b) * (dot(a, a) + dot(a, b) + dot(b, b));
  }
  // J_G / A = (j12 / 12) / (twice_area / 2) = j12 / (6 twice_area).
  out.inertia_per_mass = j12 / (T(6) * twice_area);
  return out;
}

template <class T> T rod_inertia_per_mass(const Vec2<T>& a, const Vec2<T>& b) {
  const Vec2<T> d = b - a;
  return dot(d, d) / T(12);
}

// Where a moving body that turns turns, and its moment of inertia there: an outline of two
// vertices (a segment) about its midpoint as a thin rod, of three or more (a polygon) about its
// area centroid as a uniform lamina; a given inertia (> 0) replaces the computed one. The
// engine (World's setup_spin) and the peers (peers::rigid_frame) both take it from here.
template <class T> struct TurningMass {
  Vec2<T> pivot;
  T inertia{};
};
template <class T>
TurningMass<T> turning_mass(const std::vector<Vec2<T>>& outline, const T& mass, const T& given_inertia) {
  TurningMass<T> out;
  T per_mass{};
  if (outline.size() == 2) {
    out.pivot = (outline[0] + outline[1]) * T(0.5);
    per_mass = rod_inertia_per_mass(outline[0], outline[1]);
  } else {
    const MassProperties<T> mp = polygon_mass_properties(outline);
    out.pivot = mp.centroid;
    per_mass = mp.inertia_per_mass;
  }
  out.inertia = given_inertia > T(0) ? given_inertia : mass * per_mass;
  return out;
}

template <class T> struct RigidState {
  Vec2<T> v;
  T w{};            // angular velocity, counter-clockwise positive
  T inv_mass{};     // 0: fixed
  T inv_inertia{};  // 0: fixed, or does not rotate
};

template <class T> struct Impulse {
  T j{};        // along n (n's own length: the impulse vector is j n)
  T v_n{};      // (u_b - u_a) . n before
  bool applied = false;
};

// The impulse j n at the lever arms ra and rb: a loses it, b gains it.
template <class T>
void apply_impulse(RigidState<T>& a, const Vec2<T>& ra, RigidState<T>& b, const Vec2<T>& rb, const Vec2<T>& n, const T& j) {
  const T ran = cross(ra, n), rbn = cross(rb, n);
  a.v -= n * (j * a.inv_mass);
  b.v += n * (j * b.inv_mass);
  a.w -= ran * j * a.inv_inertia;
  b.w += rbn * j * b.inv_inertia;
}

// The same with the lever arms ra = P - ca and rb = P - cb given (a caller that knows them more
// precisely than the difference of world coordinates: detail::RotatingGeometry).
template <class T>
Impulse<T> apply_rigid_impulse_with_arms(RigidState<T>& a, const Vec2<T>& ra, RigidState<T>& b, const Vec2<T>& rb,
                                         const Vec2<T>& n, const T& e) {
  const Vec2<T> ua = a.v + perp(ra) * a.w, ub = b.v + perp(rb) * b.w;
  Impulse<T> out;
  out.v_n = dot(ub - ua, n);
  const T ran = cross(ra, n), rbn = cross(rb, n);
  const T k = dot(n, n) * (a.inv_mass + b.inv_mass) + ran * ran * a.inv_inertia + rbn * rbn * b.inv_inertia;
  if (!(out.v_n < T(0)) || !(k > T(0))) return out;
  out.j = -(T(1) + e) * out.v_n / k;
  out.applied = true;
  apply_impulse(a, ra, b, rb, n, out.j);
  return out;
}

// The impulse of a contact at P between a (centre ca) and b (centre cb) along n (from a to b),
// restitution e; a and b are updated in place when the pair approaches.
template <class T>
Impulse<T> apply_rigid_impulse(RigidState<T>& a, const Vec2<T>& ca, RigidState<T>& b, const Vec2<T>& cb,
                               const Vec2<T>& P, const Vec2<T>& n, const T& e) {
  return apply_rigid_impulse_with_arms(a, P - ca, b, P - cb, n, e);
}

}  // namespace pge::detail
