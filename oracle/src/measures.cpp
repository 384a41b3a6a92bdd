// Exact measurements of one engine event: conservation across it, and the gap of its features.
#include "features.hpp"
#include "judging.hpp"
#include "rotating.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace pge::oracle::detail {
namespace {

ExactVec position_at(const ExactMotion& m, const Dyadic& t) {
  const Dyadic d = t - m.t0;
  const Dyadic h = (d * d).scaled(-1);
  return {m.p0.x + m.v0.x * d + m.acc.x * h, m.p0.y + m.v0.y * d + m.acc.y * h};
}

Dyadic dot(const ExactVec& a, const ExactVec& b) { return a.x * b.x + a.y * b.y; }
Dyadic cross(const ExactVec& a, const ExactVec& b) { return a.x * b.y - a.y * b.x; }

// Kinetic energy m v.v / 2 plus the potential of the body's constant acceleration field,
// -m field.p, at time t on the given motion (a resting body's path has another acceleration
// than its field). `vv` is v.v.
Dyadic energy(const Dyadic& mass, const Dyadic& vv, const ExactVec& field, const ExactMotion& m, const Dyadic& t) {
  const Dyadic kinetic = vv.scaled(-1);
  if (field.x.is_zero() && field.y.is_zero()) return mass * kinetic;  // no potential: exactly the same sum
  return mass * (kinetic - dot(field, position_at(m, t)));
}

double length(const ExactVec& v) { return std::sqrt(dot(v, v).to_double()); }
double length_of(const Dyadic& vv) { return std::sqrt(vv.to_double()); }  // |v| from v.v

// The largest distance of a point of the body from its reference point (a rotating body's pivot).
double reach_of(const ExactBody& b) {
  double r = b.radius.to_double();
  for (const ExactVec& v : b.local) r = std::max(r, length(v));
  return r;
}

}  // namespace

Conservation measure_conservation(const ExactBody& a, const ExactBody& b, const ExactEvent& e,
                                  const ExactMotion& a_after, const ExactMotion& b_after) {
  Conservation c;
  c.both_moving = !a.fixed && !b.fixed;
  c.elastic = a.restitution == Dyadic(1) && b.restitution == Dyadic(1);
  const auto turns_not = [](const ExactBody& x) { return x.shape != ShapeKind::Circle && !x.rotates; };
  c.angular = c.both_moving && (a.rotates || b.rotates) && !turns_not(a) && !turns_not(b);
  const struct {
    const ExactBody& body;
    const ExactVec &before, &after;
    const Dyadic &w_before, &w_after;
    const ExactMotion& motion_after;
  } sides[2] = {{a, e.va_before, e.va_after, e.wa_before, e.wa_after, a_after},
                {b, e.vb_before, e.vb_after, e.wb_before, e.wb_after, b_after}};
  for (const auto& s : sides) {
    if (s.body.fixed) continue;
    const Dyadic vv_before = dot(s.before, s.before), vv_after = dot(s.after, s.after);
    c.energy_change += energy(s.body.mass, vv_after, s.body.field_acc, s.motion_after, e.time) -
                       energy(s.body.mass, vv_before, s.body.field_acc, s.body.motion, e.time);
    if (s.body.rotates) {
      // I omega^2 / 2 (the pivot is the centre of mass: the linear terms above are its own).
      c.energy_change += s.body.inertia * (s.w_after * s.w_after - s.w_before * s.w_before).scaled(-1);
      c.kinetic_before += (s.body.inertia * s.w_before * s.w_before).to_double() / 2;
    }
    if (c.angular) {
      const ExactVec p_before = position_at(s.body.motion, e.time), p_after = position_at(s.motion_after, e.time);
      c.angular_momentum_change += s.body.inertia * (s.w_after - s.w_before) +
                                   s.body.mass * (cross(p_after, s.after) - cross(p_before, s.before));
      // What rounding the impulse in doubles leaves in the change, body by body: each new spin
      // and velocity rounded (I |w'| and m |p| |v'|), the spin's and the momentum's change rounded
      // (I |dw|, m |p| |dv|), the two lever arms meeting at one point only within rounding of
      // the bodies' coordinates (m (|p| + reach) |dv|), the position rebased (m |p| |v'|):
      // I (|w| + |w'|) + m (|p| + reach) (|v| + |v'|), with |dw| <= |w| + |w'| and likewise dv.
      // (|I w| + m |p x v| alone is no scale: 0 for a body moving along a line through the
      // origin and barely turning, where the roundings are not.)
      c.angular_scale += s.body.inertia.to_double() * (std::abs(s.w_before.to_double()) + std::abs(s.w_after.to_double())) +
                         s.body.mass.to_double() * (length(p_before) + reach_of(s.body)) *
                             (length_of(vv_before) + length_of(vv_after));
    }
    c.momentum_change.x += s.body.mass * (s.after.x - s.before.x);
    c.momentum_change.y += s.body.mass * (s.after.y - s.before.y);
    c.kinetic_before += (s.body.mass * vv_before).to_double() / 2;
    c.momentum_scale += s.body.mass.to_double() * length_of(vv_before);
  }
  return c;
}

GapMeasure measure_gap(Frame& fr, FeatureCache& features, BodyIndex a, BodyIndex b, const FeaturePair& id,
                       const Dyadic& tau) {
  if (rotating_pair(fr, a, b)) return rotating_gap(fr, a, b, id, tau);
  for (const Feature& ft : features.of(fr, a, b)) {
    if (!(ft.id == id)) continue;
    const ContactPolys<Dyadic>& c = exact_contact_polys(ft, fr);
    const BodyModel<Dyadic>& pb = fr.exact_body(ft.point.body);
    const Dyadic f = evaluate(c.f, tau);
    if (!ft.to_edge) {
      // |D|^2 - R^2 = (|D| - R)(|D| + R): the difference is exact, the sum is not cancelling.
      // f is |D|^2 - R^2 exactly (point_point, with this R), so |D|^2 is f + R^2 exactly.
      const Dyadic reach = (ft.point.vertex < 0 ? pb.radius : Dyadic()) +
                           (ft.other.vertex < 0 ? fr.exact_body(ft.other.body).radius : Dyadic());
      const double r = reach.to_double();
      return {f.to_double() / (std::sqrt((f + reach * reach).to_double()) + r), r};
    }
    const double len = std::sqrt(c.length2.to_double());
    const double s = evaluate(c.side, tau).to_double();
    if (ft.point.vertex >= 0) return {f.to_double() / len, 0.0};  // f = sigma s
    const double r = pb.radius.to_double();
    if (ft.one_sided && s <= 0) return {s / len - r, r};  // behind the line: no cancellation
    // s^2 - r^2 e.e = (|s| - r|e|)(|s| + r|e|), and the distance is (|s| - r|e|) / |e|.
    return {f.to_double() / (len * (std::abs(s) + r * len)), r};
  }
  return {std::numeric_limits<double>::quiet_NaN(), 0.0};
}

}  // namespace pge::oracle::detail
