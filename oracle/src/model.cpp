#include "model.hpp"

namespace pge::oracle::detail {
namespace {

V2<Dyadic> exact_vec(const ExactVec& v) { return {v.x, v.y}; }
V2<Interval> interval_vec(const ExactVec& v) { return {Interval::enclose(v.x), Interval::enclose(v.y)}; }

template <class N, class Convert> BodyModel<N> model_of(const ExactBody& b, Convert convert) {
  BodyModel<N> m;
  m.shape = b.shape;
  m.fixed = b.fixed;
  m.rotates = b.rotates;
  for (const ExactVec& v : b.local) m.local.push_back(convert(v));
  for (const ExactVec& v : b.world) m.world.push_back(convert(v));
  return m;
}

}  // namespace

Interval Interval::enclose(const Dyadic& x) {
  const double d = x.to_double();  // the nearest double: within half an ulp of x
  if (!std::isfinite(d)) return whole();
  // x is a double exactly when its odd mantissa has at most 53 bits, on the subnormals' grid
  // (exponent >= -1074) and below the overflow: to_double converted it exactly then.
  const long bits = static_cast<long>(mpz_sizeinbase(x.mantissa().get_mpz_t(), 2));
  if (bits <= 53 && x.exponent() >= -1074 && bits - 1 + x.exponent() <= 1023) return Interval(d);
  return {next_down(d), next_up(d)};
}

BodyModel<Dyadic> exact_model(const ExactBody& b) {
  BodyModel<Dyadic> m = model_of<Dyadic>(b, exact_vec);
  m.radius = b.radius;
  set_motion(m, b.motion);
  return m;
}

BodyModel<Interval> interval_model(const ExactBody& b) {
  BodyModel<Interval> m = model_of<Interval>(b, interval_vec);
  m.radius = Interval::enclose(b.radius);
  if (b.rotates) {
    // The disc the outline sweeps about its pivot: what the spatial filter needs of it.
    double reach = 0;
    for (const V2<Interval>& v : m.local) reach = std::max(reach, sqrt_up((square(v.x) + square(v.y)).hi()));
    m.shape = ShapeKind::Circle;
    m.radius = Interval(reach);
    m.turning_local = std::move(m.local);
    m.local.clear();
  }
  set_motion(m, b.motion);
  return m;
}

void set_motion(BodyModel<Dyadic>& m, const ExactMotion& motion) {
  m.t0 = motion.t0;
  m.p0 = exact_vec(motion.p0);
  m.v0 = exact_vec(motion.v0);
  m.acc = exact_vec(motion.acc);
  m.supports = motion.supports;
  m.theta0 = motion.theta0;
  m.omega = motion.omega;
}

void set_motion(BodyModel<Interval>& m, const ExactMotion& motion) {
  m.t0 = Interval::enclose(motion.t0);
  m.p0 = interval_vec(motion.p0);
  m.v0 = interval_vec(motion.v0);
  m.acc = interval_vec(motion.acc);
  m.supports = motion.supports;
  m.theta0 = Interval::enclose(motion.theta0);
  m.omega = Interval::enclose(motion.omega);
}

Frame::Frame(const std::vector<BodyModel<Dyadic>>& exact, const std::vector<BodyModel<Interval>>& interval,
             const Dyadic& now)
    : exact_(exact),
      interval_(interval),
      now_(now),
      now_interval_(Interval::enclose(now)) {}

const PointPath<Dyadic>& Frame::reference(BodyIndex i, const Dyadic*) {
  auto it = exact_paths_.find(i);
  if (it == exact_paths_.end()) it = exact_paths_.emplace(i, reference_path(exact_[i], now_)).first;
  return it->second;
}

const PointPath<Interval>& Frame::reference(BodyIndex i, const Interval*) {
  auto it = interval_paths_.find(i);
  if (it == interval_paths_.end()) it = interval_paths_.emplace(i, reference_path(interval_[i], now_interval_)).first;
  return it->second;
}

}  // namespace pge::oracle::detail
