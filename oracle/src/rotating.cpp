// Certified contacts of rotating bodies (rotating.hpp). The referee's own functions, from the
// stored paths: a rotating body's vertex k is c(tau) + R(theta + omega tau) r_k with c its pivot's
// quadratic path, every number the engine's double read exactly. They are evaluated with their
// first two derivatives (jets) in Arb's balls, which enclose sin and cos rigorously.
//
// A feature pair's earliest contact in [0, H] is the first root where its function f crosses
// from positive to negative with the contact point on the feature (the projection strictly
// inside the edge). The search bisects [0, H] left first. On an interval I with midpoint m and
// half-width h, f(I) is enclosed by f(m) + f'(m) [-h, h] + f''(I) [0, h^2] / 2 (met with the
// direct enclosure) and f'(I) by f'(m) + f''(I) [-h, h]: second-order tight, so an interval is
// dropped as soon as f > 0 on it, f' > 0 on it (a crossing there could only be upward), f < 0 on
// it away from tau = 0, or the point never projects onto the edge. Where f' < 0 on I, f has at
// most one root there, decided by the exact signs of f at I's ends (Arb at rising precision until
// the ball excludes zero; exact dyadic inputs), and the projection is decided at the root by
// narrowing it. An interval whose f and f' both hold zero below 2^-kRotatingTangencyBits is a
// tangency this search cannot resolve: UndecidedTime. Every dropped interval is dropped by a
// rigorous enclosure, so no contact is missed.
//
// Work is bounded: a near miss of depth d at a closest approach with curvature f'' is resolved
// once h^2 f'' / 2 < d, about log2(period / sqrt(d / f'')) levels per turn, so a body turning
// N times before its contact costs O(N log(1/d)) interval tests, never a step per turn of fixed
// size (the 1,000-turn near-miss test in tests/test_oracle_rotation.cpp).
#include "rotating.hpp"

#include "ball.hpp"
#include "roots.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace pge::oracle::detail {
namespace {

// A function's value and its first two derivatives in tau, enclosed: in Arb's balls (Ball), or
// in the oracle's double intervals (Interval, src/interval.hpp: outward rounding), the quick
// first test of an interval, about twenty times cheaper, which decides most of them.
template <class N> struct JetT {
  N v, d, dd;
};
using Jet = JetT<Ball>;

template <class N> JetT<N> constant(const N& c) { return {c, N(), N()}; }
template <class N> JetT<N> operator+(const JetT<N>& a, const JetT<N>& b) { return {a.v + b.v, a.d + b.d, a.dd + b.dd}; }
template <class N> JetT<N> operator-(const JetT<N>& a, const JetT<N>& b) { return {a.v - b.v, a.d - b.d, a.dd - b.dd}; }
template <class N> JetT<N> operator*(const JetT<N>& a, const JetT<N>& b) {
  const N dd = a.d * b.d;
  return {a.v * b.v, a.d * b.v + a.v * b.d, a.dd * b.v + (dd + dd) + a.v * b.dd};
}
template <class N> JetT<N> negate(const JetT<N>& a) { return {-a.v, -a.d, -a.dd}; }

template <class N> struct VJT {
  JetT<N> x, y;
};
using VJ = VJT<Ball>;
template <class N> VJT<N> operator-(const VJT<N>& a, const VJT<N>& b) { return {a.x - b.x, a.y - b.y}; }
template <class N> JetT<N> cross(const VJT<N>& a, const VJT<N>& b) { return a.x * b.y - a.y * b.x; }
template <class N> JetT<N> dot(const VJT<N>& a, const VJT<N>& b) { return a.x * b.x + a.y * b.y; }

// One body's kinematics from the search's now (tau = 0), exact.
struct Kin {
  ShapeKind shape = ShapeKind::Circle;
  bool rotates = false;
  bool fixed_outline = false;  // a fixed polygon or segment that does not turn
  Ball radius;            // circles
  Ball c[3][2];           // centre (pivot, reference point): c0 + c1 tau + c2 tau^2, x and y
  std::vector<std::array<Ball, 2>> verts;  // about the centre (rotating: at angle 0)
  Ball theta, omega;      // angle at tau = 0 and its rate
  Dyadic reach2;          // the largest squared distance of a point of the shape from the centre
  // The same numbers enclosed in double intervals, for the quick test.
  Interval radius_i, c_i[3][2], omega_i;
  std::vector<std::array<Interval, 2>> verts_i;
  // Edge k (vertex k to the next): |e|^2 exactly, as a ball, and |e|^2 and |e| enclosed.
  std::vector<Dyadic> len2;
  std::vector<Ball> len2_b;
  std::vector<Interval> len2_i, elen_i;
};

int edge_count(const Kin& k) {
  if (k.shape == ShapeKind::Segment) return 1;
  return static_cast<int>(k.verts.size());
}

struct Feat {
  FeaturePair id;
  int pb = 0, pv = -1;  // the point: body (0 = a, 1 = b) and vertex (-1: a circle's centre)
  bool to_edge = false;
  int eb = 0, ek = 0;   // the edge from vertex ek of body eb to the next, or (point to point) its vertex ek
  int sigma = 1;        // the side of the edge measured from (+1: along (e.y, -e.x))
};

struct PairKin {
  std::shared_ptr<const Kin> kins[2];
  std::vector<Feat> feats;
  const Kin& kin(int i) const { return *kins[i]; }
};

Kin make_kin(Frame& fr, BodyIndex i) {
  const BodyModel<Dyadic>& m = fr.exact_body(i);
  Kin k;
  k.shape = m.shape;
  k.rotates = m.rotates;
  k.fixed_outline = m.fixed && !m.rotates && m.shape != ShapeKind::Circle;
  k.radius = Ball(m.radius);
  const PointPath<Dyadic>& p = reference_of<Dyadic>(fr, i);
  for (int j = 0; j < 3; ++j) {
    k.c[j][0] = j <= p.x.deg ? Ball(p.x.c[j]) : Ball();
    k.c[j][1] = j <= p.y.deg ? Ball(p.y.c[j]) : Ball();
  }
  // A fixed outline that does not turn is, against a turning body, its position plus its local
  // vertices, the exact sum (the engine's rotating predictor, World::Impl::rotating_shape, builds
  // it so; its rounded world vertices serve the translating pairs, which never meet this code).
  const std::vector<V2<Dyadic>>& vs = m.local;
  Dyadic r2 = m.radius * m.radius;
  for (const V2<Dyadic>& v : vs) {
    k.verts.push_back({Ball(v.x), Ball(v.y)});
    r2 = std::max(r2, v.x * v.x + v.y * v.y);
  }
  k.reach2 = r2;
  k.theta = Ball(m.theta0 + m.omega * (fr.now() - m.t0));
  k.omega = Ball(m.omega);
  k.radius_i = Interval::enclose(m.radius);
  k.omega_i = Interval::enclose(m.omega);
  for (int j = 0; j < 3; ++j) {
    k.c_i[j][0] = j <= p.x.deg ? Interval::enclose(p.x.c[j]) : Interval();
    k.c_i[j][1] = j <= p.y.deg ? Interval::enclose(p.y.c[j]) : Interval();
  }
  for (const V2<Dyadic>& v : vs) k.verts_i.push_back({Interval::enclose(v.x), Interval::enclose(v.y)});
  for (std::size_t e = 0; e < vs.size(); ++e) {
    const V2<Dyadic>& from = vs[e];
    const V2<Dyadic>& to = vs[(e + 1) % vs.size()];
    const Dyadic dx = to.x - from.x, dy = to.y - from.y;
    k.len2.push_back(dx * dx + dy * dy);
    k.len2_b.emplace_back(k.len2.back());
    const Interval l2 = Interval::enclose(k.len2.back());
    k.len2_i.push_back(l2);
    k.elen_i.push_back(Interval(next_down(std::sqrt(l2.lo())), sqrt_up(l2.hi())));
  }
  return k;
}

// Body i's kinematics from the frame's now, made once per frame (Frame::rotating_slot).
std::shared_ptr<const Kin> kin_of(Frame& fr, BodyIndex i) {
  std::shared_ptr<const void>& slot = fr.rotating_slot(i);
  if (!slot) slot = std::make_shared<const Kin>(make_kin(fr, i));
  return std::static_pointer_cast<const Kin>(slot);
}

std::vector<Feat> features_of(const PairKin& pk) {
  std::vector<Feat> out;
  const auto sigmas = [](const Kin& k) { return k.shape == ShapeKind::Segment ? std::vector<int>{1, -1} : std::vector<int>{1}; };
  const auto index = [](int k) { return static_cast<std::uint16_t>(k); };
  for (int x = 0; x < 2; ++x) {
    const int y = 1 - x;
    const Kin& kx = pk.kin(x);
    const Kin& ky = pk.kin(y);
    if (ky.shape == ShapeKind::Circle) continue;  // from the circle's side (two circles never turn)
    // The circle's centre (-1) or every vertex, against every edge of the other body.
    std::vector<int> points;
    if (kx.shape == ShapeKind::Circle) points.push_back(-1);
    for (int v = 0; kx.shape != ShapeKind::Circle && v < static_cast<int>(kx.verts.size()); ++v) points.push_back(v);
    for (int v : points)
      for (int l = 0; l < edge_count(ky); ++l)
        for (int s : sigmas(ky)) {
          Feat f;
          if (v < 0)
            f.id = x == 0 ? FeaturePair{ContactKind::CircleEdge, 0, index(l)} : FeaturePair{ContactKind::CircleEdge, index(l), 0};
          else
            f.id = x == 0 ? FeaturePair{ContactKind::VertexEdge, index(v), index(l)}
                          : FeaturePair{ContactKind::EdgeVertex, index(l), index(v)};
          f.pb = x;
          f.pv = v;
          f.to_edge = true;
          f.eb = y;
          f.ek = l;
          f.sigma = s;
          out.push_back(f);
        }
    if (kx.shape != ShapeKind::Circle) continue;
    for (int v = 0; v < static_cast<int>(ky.verts.size()); ++v) {  // the circle against every vertex
      Feat f;
      f.id = x == 0 ? FeaturePair{ContactKind::CircleVertex, 0, index(v)} : FeaturePair{ContactKind::CircleVertex, index(v), 0};
      f.pb = x;
      f.eb = y;
      f.ek = v;
      out.push_back(f);
    }
  }
  return out;
}

std::shared_ptr<PairKin> pair_kin(Frame& fr, BodyIndex a, BodyIndex b) {
  auto pk = std::make_shared<PairKin>();
  pk->kins[0] = kin_of(fr, a);
  pk->kins[1] = kin_of(fr, b);
  pk->feats = features_of(*pk);
  return pk;
}

Ball ball_meet(const Ball& a, const Ball& b) { return meet(a, b); }  // the friend, out of Num's scope

// A Kin's numbers and the operations the jets need, in either number type.
template <class N> struct Num;
template <> struct Num<Ball> {
  static const Ball& radius(const Kin& k) { return k.radius; }
  static const Ball& c(const Kin& k, int j, int i) { return k.c[j][i]; }
  static const std::array<Ball, 2>& vert(const Kin& k, int v) { return k.verts[static_cast<std::size_t>(v)]; }
  static const Ball& omega(const Kin& k) { return k.omega; }
  static const Ball& len2(const Kin& k, int e) { return k.len2_b[static_cast<std::size_t>(e)]; }
  static Ball elen(const Kin& k, int e) { return sqrt(len2(k, e)); }
  static void sin_cos_at(const Kin& k, const Ball& T, Ball& s, Ball& c) { sin_cos(s, c, k.theta + k.omega * T); }
  static Ball exact(const Dyadic& x) { return Ball(x); }
  static Ball root(const Ball& x) { return sqrt(x); }
  static bool positive(const Ball& x) { return x.positive(); }
  static bool negative(const Ball& x) { return x.negative(); }
  static Ball meet(const Ball& a, const Ball& b) { return ball_meet(a, b); }
};
template <> struct Num<Interval> {
  static const Interval& radius(const Kin& k) { return k.radius_i; }
  static const Interval& c(const Kin& k, int j, int i) { return k.c_i[j][i]; }
  static const std::array<Interval, 2>& vert(const Kin& k, int v) { return k.verts_i[static_cast<std::size_t>(v)]; }
  static const Interval& omega(const Kin& k) { return k.omega_i; }
  static const Interval& len2(const Kin& k, int e) { return k.len2_i[static_cast<std::size_t>(e)]; }
  static const Interval& elen(const Kin& k, int e) { return k.elen_i[static_cast<std::size_t>(e)]; }
  // sin and cos of the angle over T from Arb (rigorous), rounded outward to doubles.
  static void sin_cos_at(const Kin& k, const Interval& T, Interval& s, Interval& c) {
    const Precision guard(64);
    Ball sb, cb;
    sin_cos(sb, cb, k.theta + k.omega * Ball::hull(Dyadic::from(T.lo()), Dyadic::from(T.hi())));
    s = to_interval(sb);
    c = to_interval(cb);
  }
  static Interval to_interval(const Ball& b) {
    arf_t lo, hi;
    arf_init(lo);
    arf_init(hi);
    arb_get_lbound_arf(lo, b.get(), 64);
    arb_get_ubound_arf(hi, b.get(), 64);
    const Interval r(arf_get_d(lo, ARF_RND_FLOOR), arf_get_d(hi, ARF_RND_CEIL));
    arf_clear(lo);
    arf_clear(hi);
    return r;
  }
  static Interval exact(const Dyadic& x) { return Interval::enclose(x); }
  static Interval root(const Interval& x) {  // x >= 0
    const double lo = x.lo() > 0 ? next_down(std::sqrt(x.lo())) : 0.0;
    return Interval(std::max(lo, 0.0), sqrt_up(x.hi()));
  }
  static bool positive(const Interval& x) { return x.certainly_positive(); }
  static bool negative(const Interval& x) { return x.certainly_negative(); }
  static Interval meet(const Interval& a, const Interval& b) {
    const double lo = std::max(a.lo(), b.lo()), hi = std::min(a.hi(), b.hi());
    return lo <= hi ? Interval(lo, hi) : a;  // disjoint only if one were no enclosure
  }
};

// A body's points at tau = T (a point or an interval), as jets.
template <class N> class PoseT {
 public:
  using M = Num<N>;
  PoseT(const Kin& k, const N& T) : k_(k) {
    const N T2 = T * T;
    for (int i = 0; i < 2; ++i) {
      JetT<N>& j = i == 0 ? centre_.x : centre_.y;
      const N c2T = M::c(k, 2, i) * T;
      j.v = M::c(k, 0, i) + M::c(k, 1, i) * T + M::c(k, 2, i) * T2;
      j.d = M::c(k, 1, i) + (c2T + c2T);
      j.dd = M::c(k, 2, i) + M::c(k, 2, i);
    }
    if (k.rotates) {
      M::sin_cos_at(k, T, s_, c_);
      w2_ = M::omega(k) * M::omega(k);
    }
  }

  const VJT<N>& centre() const { return centre_; }

  // Vertex v's position alone (no derivatives): the cheap first test of an interval.
  std::array<N, 2> position(int v) const {
    const auto& r = M::vert(k_, v);
    if (!k_.rotates) return {centre_.x.v + r[0], centre_.y.v + r[1]};
    return {centre_.x.v + (c_ * r[0] - s_ * r[1]), centre_.y.v + (s_ * r[0] + c_ * r[1])};
  }

  VJT<N> vertex(int v) const {
    const auto& r = M::vert(k_, v);
    if (!k_.rotates) return {centre_.x + constant(r[0]), centre_.y + constant(r[1])};
    const N rx = c_ * r[0] - s_ * r[1];
    const N ry = s_ * r[0] + c_ * r[1];
    const N& w = M::omega(k_);
    return {{centre_.x.v + rx, centre_.x.d - w * ry, centre_.x.dd - w2_ * rx},
            {centre_.y.v + ry, centre_.y.d + w * rx, centre_.y.dd - w2_ * ry}};
  }

 private:
  const Kin& k_;
  VJT<N> centre_;
  N s_, c_, w2_;
};
using Pose = PoseT<Ball>;

// A feature's contact function f and projection u = (P - A).e, as jets.
template <class N> struct ValuesT {
  JetT<N> f, u;
};
using Values = ValuesT<Ball>;

template <class N> class PosedT {
 public:
  using M = Num<N>;
  PosedT(const PairKin& pk, const N& T) : pk_(pk), p_{PoseT<N>(pk.kin(0), T), PoseT<N>(pk.kin(1), T)} {
    for (int i = 0; i < 2; ++i) {
      verts_[i].resize(pk.kin(i).verts.size());
      positions_[i].resize(pk.kin(i).verts.size());
    }
  }

  ValuesT<N> values(const Feat& ft) {
    ValuesT<N> out;
    const VJT<N> p = ft.pv < 0 ? p_[ft.pb].centre() : vertex(ft.pb, ft.pv);
    const Kin& eb = pk_.kin(ft.eb);
    const N& r = M::radius(pk_.kin(ft.pb));
    if (!ft.to_edge) {
      const VJT<N> d = vertex(ft.eb, ft.ek) - p;
      out.f = dot(d, d) - constant(N(r * r));
      return out;
    }
    const int n = static_cast<int>(eb.verts.size());
    const VJT<N>& A = vertex(ft.eb, ft.ek);
    const VJT<N> e = vertex(ft.eb, (ft.ek + 1) % n) - A;
    const VJT<N> d = p - A;
    const JetT<N> s = cross(d, e);
    out.f = ft.sigma > 0 ? s : negate(s);
    if (ft.pv < 0) out.f = out.f - constant(N(r * M::elen(eb, ft.ek)));
    out.u = dot(d, e);
    return out;
  }

  // Whether the feature's function is certainly positive, or its point certainly off the edge,
  // over the whole of T, from positions alone (no derivatives): most features of a pair are
  // dropped so, and the jets are made only for the rest.
  bool apart_by_values(const Feat& ft) {
    const std::array<N, 2> p =
        ft.pv < 0 ? std::array<N, 2>{p_[ft.pb].centre().x.v, p_[ft.pb].centre().y.v} : position(ft.pb, ft.pv);
    const N& r = M::radius(pk_.kin(ft.pb));
    if (!ft.to_edge) {
      const std::array<N, 2>& q = position(ft.eb, ft.ek);
      const N dx = q[0] - p[0], dy = q[1] - p[1];
      return M::positive(dx * dx + dy * dy - r * r);
    }
    const int n = static_cast<int>(pk_.kin(ft.eb).verts.size());
    const std::array<N, 2>& A = position(ft.eb, ft.ek);
    const std::array<N, 2>& B = position(ft.eb, (ft.ek + 1) % n);
    const N ex = B[0] - A[0], ey = B[1] - A[1], dx = p[0] - A[0], dy = p[1] - A[1];
    N f = dx * ey - dy * ex;
    if (ft.sigma < 0) f = -f;
    if (ft.pv < 0) f = f - r * M::elen(pk_.kin(ft.eb), ft.ek);
    if (M::positive(f)) return true;
    const N u = dx * ex + dy * ey;
    return M::negative(u) || M::positive(u - M::len2(pk_.kin(ft.eb), ft.ek));
  }

  const VJT<N>& vertex(int body, int v) {
    auto& slot = verts_[body][static_cast<std::size_t>(v)];
    if (!slot) slot = p_[body].vertex(v);
    return *slot;
  }
  const std::array<N, 2>& position(int body, int v) {
    auto& slot = positions_[body][static_cast<std::size_t>(v)];
    if (!slot) slot = p_[body].position(v);
    return *slot;
  }
  const PoseT<N>& pose(int body) const { return p_[body]; }

 private:
  const PairKin& pk_;
  PoseT<N> p_[2];
  std::vector<std::optional<VJT<N>>> verts_[2];
  std::vector<std::optional<std::array<N, 2>>> positions_[2];
};
using Posed = PosedT<Ball>;

std::string undecided_text(const Feat& ft, const char* what) {
  return std::string("rotating contact undecided: ") + what + " (" + std::string(contact_kind_name(ft.id.contact)) + " " +
         std::to_string(ft.id.feature_a) + "/" + std::to_string(ft.id.feature_b) + ")";
}

enum class Of { F, DF, DDF, U };  // f, f', f'', or the projection u - shift

// The sign of f (f', f'', u - shift) at an exact point, at rising precision.
int sign_at_point(const PairKin& pk, const Feat& ft, const Ball& T_exact_or_tight, Of what = Of::F,
                  const Dyadic& shift = Dyadic()) {
  for (slong prec = 96; prec <= kRotatingMaxPrecision; prec *= 2) {
    const Precision guard(prec);
    Posed ps(pk, T_exact_or_tight);
    const Values v = ps.values(ft);
    const int s = what == Of::U     ? (v.u.v - Ball(shift)).sign()
                  : what == Of::DF  ? v.f.d.sign()
                  : what == Of::DDF ? v.f.dd.sign()
                                    : v.f.v.sign();
    if (s != 2) return s;
  }
  throw UndecidedTime(undecided_text(ft, "a sign at the precision cap"));
}

Dyadic half(const Dyadic& x) { return x.scaled(-1); }

// A simple downward root of a feature's contact function: f(lo) > 0 > f(hi), or a point.
class RotatingRoot final : public TranscendentalRoot {
 public:
  RotatingRoot(std::shared_ptr<const PairKin> pk, int feat, Dyadic lo, Dyadic hi)
      : pk_(std::move(pk)), feat_(feat), lo_(std::move(lo)), hi_(std::move(hi)) {}

  const Feat& feature() const { return pk_->feats[static_cast<std::size_t>(feat_)]; }
  const PairKin& pair() const { return *pk_; }

  int compare(const Dyadic& x) const override {
    if (lo_ == hi_) return detail_compare(lo_, x);
    if (x <= lo_) return 1;
    if (x >= hi_) return -1;
    const int s = sign_at_point(*pk_, feature(), Ball(x));
    if (s == 0) {
      lo_ = hi_ = x;
      return 0;
    }
    (s > 0 ? lo_ : hi_) = x;
    return s > 0 ? 1 : -1;
  }

  int compare(const mpq_class& x) const override {
    const mpz_class& den = x.get_den();
    if (mpz_popcount(den.get_mpz_t()) == 1)
      return compare(Dyadic(x.get_num(), -static_cast<long>(mpz_scan1(den.get_mpz_t(), 0))));
    for (long bits = 64; bits <= kRotatingMaxPrecision; bits *= 2) {
      if (x <= lo_.to_mpq()) return lo_ == hi_ ? (lo_.to_mpq() == x ? 0 : 1) : 1;
      if (x >= hi_.to_mpq()) return lo_ == hi_ ? (hi_.to_mpq() == x ? 0 : -1) : -1;
      narrow(bits);
    }
    // Inside an enclosure narrower than 2^-4096: the sign of f at the rational itself.
    for (slong prec = 96; prec <= kRotatingMaxPrecision; prec *= 2) {
      const Precision guard(prec);
      Posed ps(*pk_, Ball::rational(x));
      const int s = ps.values(feature()).f.v.sign();
      if (s == 1 || s == -1) return s;
    }
    throw UndecidedTime(undecided_text(feature(), "a time against a decimal boundary"));
  }

  void narrow(long bits) const override {
    const Dyadic target = Dyadic(1).scaled(-bits);
    while (lo_ != hi_ && hi_ - lo_ > target) {
      const Dyadic width = hi_ - lo_;
      const Dyadic m = half(lo_ + hi_);
      // Newton from the midpoint, then a point on the root's other side as far again as the
      // next Newton step: quadratic convergence, each step confirmed by exact signs.
      const Dyadic x = newton(m, bits);
      compare(x);
      if (lo_ != hi_) {
        const Dyadic y = newton(x, bits);
        const Dyadic z = x + (y - x).scaled(1);
        if (lo_ < z && z < hi_) compare(z);
      }
      if (lo_ != hi_ && hi_ - lo_ > half(width)) compare(half(lo_ + hi_));
    }
  }

  Dyadic lo() const override { return lo_; }
  Dyadic hi() const override { return hi_; }

 private:
  static int detail_compare(const Dyadic& a, const Dyadic& b) { return a < b ? -1 : (b < a ? 1 : 0); }

  // x - f(x) / f'(x), kept inside (lo, hi); the midpoint if the step fails.
  Dyadic newton(const Dyadic& x, long bits) const {
    const Precision guard(std::min<slong>(bits + 64, kRotatingMaxPrecision));
    Posed ps(*pk_, Ball(x));
    const Values v = ps.values(feature());
    if (v.f.d.sign() == 2 || v.f.d.exact_zero()) return half(lo_ + hi_);
    const Dyadic step = (v.f.v / v.f.d).mid();
    const Dyadic y = x - step;
    if (!(lo_ < y && y < hi_)) return half(lo_ + hi_);
    return y;
  }

  std::shared_ptr<const PairKin> pk_;
  int feat_;
  mutable Dyadic lo_, hi_;
};

// Whether two bodies are certainly apart over an interval T (poses at T and at its midpoint,
// H = T - m, H2 = [0, h^2 / 2]): the discs they sweep as they turn stay apart, or, where one is a
// fixed outline that does not turn (a wall, a floor: its disc would hold everything near it),
// the other's disc stays beyond the line of one of its edges (a segment's either side).
template <class N>
bool apart_over(const Kin& ka, const Kin& kb, const PoseT<N>& at, const PoseT<N>& am, const PoseT<N>& bt,
                const PoseT<N>& bm, const N& H, const N& H2) {
  using M = Num<N>;
  const auto certainly_positive = [&](const JetT<N>& gt, const JetT<N>& gm) {
    return M::positive(M::meet(gm.v + gm.d * H + gt.dd * H2, gt.v));
  };
  if (ka.fixed_outline != kb.fixed_outline) {
    const bool a_fixed = ka.fixed_outline;
    const Kin& wall = a_fixed ? ka : kb;
    const Kin& other = a_fixed ? kb : ka;
    const VJT<N>& ct = (a_fixed ? bt : at).centre();
    const VJT<N>& cm = (a_fixed ? bm : am).centre();
    const VJT<N>& w = (a_fixed ? at : bt).centre();  // constant: the outline's position
    const N reach = M::root(M::exact(other.reach2));
    const int n = static_cast<int>(wall.verts.size());
    const int edges = wall.shape == ShapeKind::Segment ? 1 : n;
    for (int k = 0; k < edges; ++k) {
      const auto& p = M::vert(wall, k);
      const auto& q = M::vert(wall, (k + 1) % n);
      const N ex = q[0] - p[0], ey = q[1] - p[1];
      const VJT<N> A{constant(N(w.x.v + p[0])), constant(N(w.y.v + p[1]))};
      const VJT<N> e{constant(ex), constant(ey)};
      const JetT<N> rl = constant(N(reach * M::root(ex * ex + ey * ey)));
      const JetT<N> st = cross(ct - A, e), sm = cross(cm - A, e);
      if (certainly_positive(st - rl, sm - rl)) return true;
      if (wall.shape == ShapeKind::Segment && certainly_positive(negate(st) - rl, negate(sm) - rl)) return true;
    }
    return false;
  }
  const VJT<N> dt = bt.centre() - at.centre(), dm = bm.centre() - am.centre();
  const N reach = M::root(M::exact(ka.reach2)) + M::root(M::exact(kb.reach2));
  const JetT<N> r2 = constant(N(reach * reach));
  return certainly_positive(dot(dt, dt) - r2, dot(dm, dm) - r2);
}

// A body's shape over a search window tau in [0, tau_hi], in double intervals from the
// frame's interval models (no exact kinematics: most pairs are decided here): each vertex (a
// circle: its centre) enclosed over the whole window, the angle's sin and cos by Arb. What the
// pair filter's separating-axis test reads; made once per body and window (Frame::sweep_slot).
struct Sweep {
  Dyadic tau_hi;
  ShapeKind shape = ShapeKind::Circle;
  Interval radius;
  std::vector<std::array<Interval, 2>> points;
};

Sweep make_sweep(Frame& fr, BodyIndex i, const Dyadic& tau_hi) {
  const BodyModel<Interval>& m = fr.interval_body(i);
  Sweep s{tau_hi, fr.exact_body(i).shape, m.radius, {}};
  const Interval T(0.0, Interval::enclose(tau_hi).hi());
  const PointPath<Interval>& c = reference_of<Interval>(fr, i);
  const Interval cx = evaluate(c.x, T), cy = evaluate(c.y, T);
  if (s.shape == ShapeKind::Circle) {
    s.points.push_back({cx, cy});
    return s;
  }
  if (!m.rotates) {  // translating, or a fixed outline: its position plus its local vertices
    for (const V2<Interval>& r : m.local) s.points.push_back({cx + r.x, cy + r.y});
    return s;
  }
  // The angle theta0 + omega (now + tau - t0) over the window, then sin and cos over it.
  const Interval angle = m.theta0 + m.omega * ((fr.now_interval() - m.t0) + T);
  Interval sn(-1.0, 1.0), cs(-1.0, 1.0);
  if (std::isfinite(angle.lo()) && std::isfinite(angle.hi())) {
    const Precision guard(64);
    Ball a, sb, cb;
    arf_t lo, hi;
    arf_init(lo);
    arf_init(hi);
    arf_set_d(lo, angle.lo());
    arf_set_d(hi, angle.hi());
    arb_set_interval_arf(a.get(), lo, hi, 64);
    arf_clear(lo);
    arf_clear(hi);
    sin_cos(sb, cb, a);
    sn = Num<Interval>::to_interval(sb);
    cs = Num<Interval>::to_interval(cb);
  }
  for (const V2<Interval>& r : m.turning_local)
    s.points.push_back({cx + (cs * r.x - sn * r.y), cy + (sn * r.x + cs * r.y)});
  return s;
}

const Sweep& sweep_of(Frame& fr, BodyIndex i, const Dyadic& tau_hi) {
  std::shared_ptr<const void>& slot = fr.sweep_slot(i);
  if (!slot || static_cast<const Sweep*>(slot.get())->tau_hi != tau_hi)
    slot = std::make_shared<const Sweep>(make_sweep(fr, i, tau_hi));
  return *static_cast<const Sweep*>(slot.get());
}

// Whether b's shape lies beyond a's along the axis n = (nx, ny) (any exact doubles) all through
// the window: the least n.q over b's points (less its radius |n| for a circle) above the
// largest n.p over a's (plus its radius |n|), each bound rounded outward. Convex shapes, so
// their points' projections span theirs.
bool beyond_along(const Sweep& a, const Sweep& b, double nx, double ny) {
  const Interval X(nx), Y(ny);
  double top = -std::numeric_limits<double>::infinity(), bottom = std::numeric_limits<double>::infinity();
  for (const auto& p : a.points) top = std::max(top, (X * p[0] + Y * p[1]).hi());
  for (const auto& q : b.points) bottom = std::min(bottom, (X * q[0] + Y * q[1]).lo());
  const Interval norm(0.0, sqrt_up((square(X) + square(Y)).hi()));
  if (a.shape == ShapeKind::Circle) top = (Interval(top) + a.radius * norm).hi();
  if (b.shape == ShapeKind::Circle) bottom = (Interval(bottom) - b.radius * norm).lo();
  return bottom > top;
}

double mid(const Interval& x) { return 0.5 * x.lo() + 0.5 * x.hi(); }

// Whether the two shapes are certainly apart all through the window (the pair filter in front of
// the discs of apart_over, which overlap in a dense gas of turning polygons): a separating axis,
// chosen in plain doubles from the points' midpoints (any axis is sound: the proof is
// beyond_along's outward rounding), among every edge's normal of either outline both ways and,
// for a circle, the directions from its centre to the other's points. Apart shapes have no
// contact: every contact the search reports has a point on the other's feature (f = 0 there),
// or the two overlapping at tau = 0 (the overlap rule).
bool apart_through(const Sweep& sa, const Sweep& sb) {
  const Sweep* sweeps[2] = {&sa, &sb};
  std::vector<std::array<double, 2>> points[2];
  for (int i = 0; i < 2; ++i)
    for (const auto& p : sweeps[i]->points) points[i].push_back({mid(p[0]), mid(p[1])});
  std::vector<std::array<double, 2>> axes;
  for (int i = 0; i < 2; ++i) {
    const std::vector<std::array<double, 2>>& ps = points[i];
    if (sweeps[i]->shape == ShapeKind::Circle) {
      for (const auto& q : points[1 - i]) {
        axes.push_back({q[0] - ps[0][0], q[1] - ps[0][1]});
        axes.push_back({ps[0][0] - q[0], ps[0][1] - q[1]});
      }
      continue;
    }
    const std::size_t n = ps.size(), edges = sweeps[i]->shape == ShapeKind::Segment ? 1 : n;
    for (std::size_t k = 0; k < edges; ++k) {
      const auto& p = ps[k];
      const auto& q = ps[(k + 1) % n];
      axes.push_back({q[1] - p[1], p[0] - q[0]});
      axes.push_back({p[1] - q[1], q[0] - p[0]});
    }
  }
  // The axis of widest separation in doubles (a guess), then proven.
  double best = 0;
  std::array<double, 2> axis{0, 0};
  for (const auto& n : axes) {
    const double len = std::hypot(n[0], n[1]);
    if (!(len > 0) || !std::isfinite(len)) continue;
    double top = -std::numeric_limits<double>::infinity(), bottom = std::numeric_limits<double>::infinity();
    for (const auto& p : points[0]) top = std::max(top, n[0] * p[0] + n[1] * p[1]);
    for (const auto& q : points[1]) bottom = std::min(bottom, n[0] * q[0] + n[1] * q[1]);
    double gap = (bottom - top) / len;
    if (sa.shape == ShapeKind::Circle) gap -= sa.radius.hi();
    if (sb.shape == ShapeKind::Circle) gap -= sb.radius.hi();
    if (gap > best) best = gap, axis = n;
  }
  return best > 0 && beyond_along(sa, sb, axis[0], axis[1]);
}

// The search of one pair over [0, H], left first (see the top of this file).
class PairSearch {
 public:
  PairSearch(std::shared_ptr<const PairKin> pk, SearchCounters& n) : pk_(std::move(pk)), n_(n) {}

  std::optional<PairResult> run(const Dyadic& H) {
    std::vector<int> live(pk_->feats.size());
    for (std::size_t i = 0; i < live.size(); ++i) live[i] = static_cast<int>(i);
    n_.features_exact += live.size();
    if (H.sign() <= 0) {
      visit_start(live);
    } else {
      visit(Dyadic(), H, live);
    }
    if (!best_) return std::nullopt;
    return best_->result;
  }

 private:
  struct Best {
    std::shared_ptr<const RotatingRoot> root;
    PairResult result;
  };

  // H = 0: only a contact at tau = 0 (touching or overlapping and approaching).
  void visit_start(const std::vector<int>& live) {
    for (int i : live) {
      const Feat& ft = pk_->feats[static_cast<std::size_t>(i)];
      const int s = sign_at_point(*pk_, ft, Ball());
      if (s > 0) continue;
      const Precision guard(256);
      Posed ps(*pk_, Ball());
      if (!ps.values(ft).f.d.negative()) continue;
      if (s < 0 && !overlap_applies(ft)) continue;
      if (ft.to_edge && !on_edge_at_start(ft)) continue;
      offer(std::make_shared<RotatingRoot>(pk_, i, Dyadic(), Dyadic()), i, s < 0);
    }
  }

  static long prec_for(const Dyadic& width) {
    const long bits = -(static_cast<long>(mpz_sizeinbase(width.mantissa().get_mpz_t(), 2)) + width.exponent());
    return std::clamp<long>(80 + std::max(0L, bits), 80, 512);
  }

  void visit(const Dyadic& a, const Dyadic& b, const std::vector<int>& live) {
    if (best_ && best_->root->hi() <= a) return;
    const Dyadic width = b - a;
    const Precision guard(prec_for(width));
    const Dyadic m = half(a + b), h = half(width);
    // The quick pass in double intervals: the pair apart, or a feature dropped by its values or
    // by the same Taylor forms as below. Only what it leaves is taken to Arb's balls.
    const Interval Ti = hull(Interval::enclose(a), Interval::enclose(b)), Mi = Interval::enclose(m);
    const Interval Hi = Ti - Mi, H2i = square(Hi) * Interval(0.5);
    PosedT<Interval> qt(*pk_, Ti), qm(*pk_, Mi);
    if (apart_over(pk_->kin(0), pk_->kin(1), qt.pose(0), qm.pose(0), qt.pose(1), qm.pose(1), Hi, H2i)) return;
    // Intervals wide enough for doubles decide in doubles; tiny ones (or the start's, which
    // needs exact signs at tau = 0) go on to Arb's balls.
    Dyadic scale = b.abs();
    if (scale < Dyadic(1)) scale = Dyadic(1);
    const bool tiny = a.is_zero() || width <= scale * Dyadic(1).scaled(-kQuickBits);
    const Interval hi_h = Interval::enclose(h);
    std::vector<int> slow, keep;
    for (int i : live) {
      const Feat& ft = pk_->feats[static_cast<std::size_t>(i)];
      if (qt.apart_by_values(ft)) continue;
      const ValuesT<Interval> it = qt.values(ft), im = qm.values(ft);
      using MI = Num<Interval>;
      const Interval F = MI::meet(im.f.v + im.f.d * Hi + it.f.dd * H2i, it.f.v);
      if (F.certainly_positive() || (F.certainly_negative() && !a.is_zero())) continue;
      // Below zero all through [0, b]: no crossing, only the overlap rule at tau = 0, which a
      // certainly shallower axis rules out (overlap_applies; most of a dense gas's near pairs).
      if (F.certainly_negative() && shallower_axis_at_start(ft)) continue;
      const Interval D = MI::meet(im.f.d + it.f.dd * Hi, it.f.d);
      if (D.certainly_positive()) continue;
      if (ft.to_edge) {
        const Interval U = MI::meet(im.u.v + it.u.d * Hi, it.u.v);
        if (U.certainly_negative() || (U - Num<Interval>::len2(pk_->kin(ft.eb), ft.ek)).certainly_positive()) continue;
      }
      if (tiny) {
        slow.push_back(i);
      } else if (!settle(i, a, b, im, it, D, hi_h, H2i)) {
        keep.push_back(i);
      }
    }
    if (!slow.empty()) {
      const Ball T = Ball::hull(a, b), M(m), H = Ball::hull(-h, h), H2 = Ball::hull(Dyadic(), half(h * h));
      Posed pt(*pk_, T), pm(*pk_, M);
      for (int i : slow) {
        const Feat& ft = pk_->feats[static_cast<std::size_t>(i)];
        if (pt.apart_by_values(ft)) continue;
        const Values vt = pt.values(ft), vm = pm.values(ft);
        // Exactly zero over I (a vertex sliding along an edge's line, both at rest in angle): no
        // crossing (oracle/README.md).
        if (vt.f.v.exact_zero()) continue;
        const Ball F = meet(vm.f.v + vm.f.d * H + vt.f.dd * H2, vt.f.v);
        if (F.positive()) continue;
        const Ball D = meet(vm.f.d + vt.f.dd * H, vt.f.d);
        if (D.positive()) continue;
        if (F.negative()) {  // below zero throughout: no downward crossing here, only the start's overlap
          if (!a.is_zero() || vt.f.d.exact_zero()) continue;
          const int d0 = sign_at_point(*pk_, ft, Ball(), Of::DF);
          if (d0 > 0 || (d0 == 0 && sign_at_point(*pk_, ft, Ball(), Of::DDF) >= 0)) continue;  // not approaching
        }
        if (ft.to_edge) {
          const Ball U = meet(vm.u.v + vt.u.d * H, vt.u.v);
          if (U.negative() || (U - Num<Ball>::len2(pk_->kin(ft.eb), ft.ek)).positive()) continue;
        }
        if (!settle(i, a, b, vm, vt, D, Ball(h), H2)) keep.push_back(i);
      }
    }
    if (keep.empty()) return;
    if (width <= scale * Dyadic(1).scaled(-kRotatingTangencyBits))
      throw UndecidedTime(undecided_text(pk_->feats[static_cast<std::size_t>(keep.front())], "a tangency"));
    visit(a, m, keep);
    visit(m, b, keep);
  }

  // f decreasing on [a, b] (f' < 0 but perhaps at an end): at most one root there. A root at a
  // dyadic end is a downward crossing only where f' < 0; where f' = 0 too it is a tangency: at
  // tau = 0 a contact if f'' < 0 (approaching at second order), elsewhere a graze.
  // A feature still live on [a, b] whose f' enclosure D is not positive: settled (true) if f'
  // < 0 there (resolve), or if f'' has one sign and the exact signs of f' at the ends show f
  // increasing (dropped) or decreasing (resolve): an end where f' is exactly zero (a tangency at
  // a dyadic time, as in a graze placed on purpose) is decided so, where enclosures never could.
  template <class N>
  bool settle(int i, const Dyadic& a, const Dyadic& b, const ValuesT<N>& vm, const ValuesT<N>& vt, const N& D,
              const N& h, const N& H2) {
    using M = Num<N>;
    if (M::negative(D)) {
      resolve(i, a, b, vm, vt, h, H2);
      return true;
    }
    const int curvature = M::positive(vt.f.dd) ? 1 : (M::negative(vt.f.dd) ? -1 : 0);
    if (curvature == 0) return false;
    const Feat& ft = pk_->feats[static_cast<std::size_t>(i)];
    const int da = sign_at_point(*pk_, ft, Ball(a), Of::DF), db = sign_at_point(*pk_, ft, Ball(b), Of::DF);
    if ((curvature > 0 && da >= 0) || (curvature < 0 && db >= 0)) return true;  // f' > 0 inside: increasing
    if ((curvature > 0 && db <= 0) || (curvature < 0 && da <= 0)) {            // f' < 0 but at an end
      resolve(i, a, b, vm, vt, h, H2);
      return true;
    }
    return false;
  }

  // vm, vt: the jets at the midpoint and over [a, b]; f at an end is first tried from the Taylor
  // form there, f(m) +- f'(m) h + f''(I) [0, h^2 / 2], and taken at the point only if that holds 0.
  template <class N>
  void resolve(int i, const Dyadic& a, const Dyadic& b, const ValuesT<N>& vm, const ValuesT<N>& vt, const N& h,
               const N& H2) {
    using M = Num<N>;
    const Feat& ft = pk_->feats[static_cast<std::size_t>(i)];
    const auto end_sign = [&](const Dyadic& x, int side) {
      const N step = vm.f.d * h;
      const N f = vm.f.v + (side > 0 ? step : -step) + vt.f.dd * H2;
      if (M::positive(f)) return 1;
      if (M::negative(f)) return -1;
      return sign_at_point(*pk_, ft, Ball(x));
    };
    const int sb = end_sign(b, 1);
    if (sb > 0) return;
    const int sa = end_sign(a, -1);
    bool overlap = false;
    if (sa < 0) {
      if (!a.is_zero() || !overlap_applies(ft)) return;
      overlap = true;
    }
    const auto crossing_at = [&](const Dyadic& x) {
      const int d = sign_at_point(*pk_, ft, Ball(x), Of::DF);
      if (d < 0) return true;
      if (x.is_zero() && d == 0 && sign_at_point(*pk_, ft, Ball(x), Of::DDF) < 0) return true;
      if (!graze_ || x < *graze_) graze_ = x;  // touching zero and turning back: a graze
      return false;
    };
    std::shared_ptr<const RotatingRoot> root;
    if (sa < 0) {
      root = std::make_shared<RotatingRoot>(pk_, i, a, a);
    } else if (sa == 0) {
      if (!crossing_at(a)) return;
      root = std::make_shared<RotatingRoot>(pk_, i, a, a);
    } else if (sb == 0) {
      if (!crossing_at(b)) return;
      root = std::make_shared<RotatingRoot>(pk_, i, b, b);
    } else {
      root = std::make_shared<RotatingRoot>(pk_, i, a, b);
    }
    if (ft.to_edge && !on_edge_at(*root)) return;
    if (ft.pv >= 0 && !extreme_at(*root)) return;
    offer(root, i, overlap);
  }

  // A vertex meets an edge only as its body's lowest point towards it: its neighbours not
  // certainly below it, measured from the feature's side (this is what keeps a two-sided
  // segment from being met from its far side by a body that already touches its near side).
  bool extreme_at(const RotatingRoot& r) const {
    const Feat& ft = r.feature();
    const Kin& kp = pk_->kin(ft.pb);
    const int n = static_cast<int>(kp.verts.size());
    const int neighbours[2] = {(ft.pv + n - 1) % n, (ft.pv + 1) % n};
    for (long bits = 32;; bits += 32) {
      bool all_above = true;
      {
        const Precision guard(std::min<slong>(bits + 96, kRotatingMaxPrecision));
        Posed ps(*pk_, r.lo() == r.hi() ? Ball(r.lo()) : Ball::hull(r.lo(), r.hi()));
        const VJ& v = ps.vertex(ft.pb, ft.pv);
        const VJ& A = ps.vertex(ft.eb, ft.ek);
        const VJ e = ps.vertex(ft.eb, (ft.ek + 1) % static_cast<int>(pk_->kin(ft.eb).verts.size())) - A;
        for (int nb : neighbours) {
          if (nb == ft.pv) continue;
          Ball q = cross(ps.vertex(ft.pb, nb) - v, e).v;
          if (ft.sigma < 0) q = -q;
          if (q.negative()) return false;
          if (!(q.positive() || q.exact_zero())) all_above = false;
        }
      }
      // Parallel to the edge within the cap: an edge lying on the edge, which touches.
      if (all_above || r.lo() == r.hi() || bits > kTranscendentalTieBits) return true;
      Dyadic span = r.hi() - r.lo();
      const long w = static_cast<long>(mpz_sizeinbase(span.mantissa().get_mpz_t(), 2)) + span.exponent();
      r.narrow(std::max(-w + 16, bits));
    }
  }

  // The projection strictly inside the edge at the root: narrowed until decided.
  bool on_edge_at(const RotatingRoot& r) const {
    const Feat& ft = r.feature();
    for (long bits = 32;; bits += 32) {
      if (r.lo() == r.hi()) {
        const int s0 = sign_at_point(*pk_, ft, Ball(r.lo()), Of::U);
        const int s1 = sign_at_point(*pk_, ft, Ball(r.lo()), Of::U, pk_->kin(ft.eb).len2[static_cast<std::size_t>(ft.ek)]);
        if (s0 == 0 || s1 == 0) throw UndecidedTime(undecided_text(ft, "a contact at an edge's end"));
        return s0 > 0 && s1 < 0;
      }
      {
        const Precision guard(std::min<slong>(bits + 96, kRotatingMaxPrecision));
        Posed ps(*pk_, Ball::hull(r.lo(), r.hi()));
        const Ball U = ps.values(ft).u.v;
        if (U.negative() || (U - Num<Ball>::len2(pk_->kin(ft.eb), ft.ek)).positive()) return false;
        if (U.positive() && (U - Num<Ball>::len2(pk_->kin(ft.eb), ft.ek)).negative()) return true;
      }
      if (bits > kTranscendentalTieBits) throw UndecidedTime(undecided_text(ft, "a contact at an edge's end"));
      Dyadic span = r.hi() - r.lo();
      long w = static_cast<long>(mpz_sizeinbase(span.mantissa().get_mpz_t(), 2)) + span.exponent();
      r.narrow(std::max(-w + 16, bits));
    }
  }

  bool on_edge_at_start(const Feat& ft) const {
    const int s0 = sign_at_point(*pk_, ft, Ball(), Of::U);
    const int s1 = sign_at_point(*pk_, ft, Ball(), Of::U, pk_->kin(ft.eb).len2[static_cast<std::size_t>(ft.ek)]);
    if (s0 == 0 || s1 == 0) throw UndecidedTime(undecided_text(ft, "a contact at an edge's end"));
    return s0 > 0 && s1 < 0;
  }

  // Overlapping at tau = 0 and approaching (the overlap rule, oracle/README.md): a vertex counts
  // against the edge of least penetration only, and only as its body's deepest vertex along it;
  // a circle against a one-sided edge only from outside the edge line.
  bool overlap_applies(const Feat& ft) const {
    if (!ft.to_edge) return true;
    const Precision guard(512);
    if (!start_pose_) {
      start_pose_.emplace(*pk_, Ball());
      start_distance_.resize(pk_->feats.size());
    }
    const Kin& ke = pk_->kin(ft.eb);
    // sigma cross / |e|, the signed distance of the point at tau = 0: each once per search.
    const auto distance = [&](const Feat& g) -> const Ball& {
      std::optional<Ball>& slot = start_distance_[static_cast<std::size_t>(&g - pk_->feats.data())];
      if (!slot) {
        Ball f = start_pose_->values(g).f.v;
        if (g.pv < 0) f = f + pk_->kin(g.pb).radius * Num<Ball>::elen(pk_->kin(g.eb), g.ek);
        slot = f / Num<Ball>::elen(pk_->kin(g.eb), g.ek);
      }
      return *slot;
    };
    const Ball& mine = distance(ft);
    if (ft.pv < 0) return !mine.negative();  // the centre not behind the line (on the side measured from)
    if (shallower_axis(ft, mine, distance)) return false;
    // Against a segment (no inside, two sides): the body must lie more on the side measured from
    // than behind the line, the least penetration: its highest vertex above the line at least as
    // far as this one, its deepest, is below it.
    bool shallow_side = false;
    for (const Feat& g : pk_->feats) {
      if (!g.to_edge || g.pb != ft.pb || g.eb != ft.eb || g.sigma != ft.sigma || g.pv < 0) continue;
      if (g.ek == ft.ek && !(distance(g) + mine).negative()) shallow_side = true;
      // A shallower edge of a polygon: the overlap is not along this one.
      if (ke.shape != ShapeKind::Segment && g.pv == ft.pv && g.ek != ft.ek && (distance(g) - mine).positive()) return false;
      if (g.ek == ft.ek && g.pv != ft.pv && (mine - distance(g)).positive()) return false;  // a deeper vertex
    }
    return ke.shape != ShapeKind::Segment || shallow_side;
  }

  // The separating-axis view of the translating rule (overlap_rule.hpp): every edge line of
  // either outline, from each side it is struck on, is an axis whose depth is the least signed
  // distance of the other outline's vertices from it. An axis other than the feature's own that
  // is certainly shallower than the vertex's depth behind its edge (a separating axis, depth
  // > 0, among them) says the overlap is not along this edge. Without it a segment touching
  // another end to side (a rod's end on a wall) leaves the wall's far end metres behind the
  // rod's line, projecting onto the rod, and that was taken for an overlap.
  template <class Distance>
  bool shallower_axis(const Feat& ft, const Ball& mine, const Distance& distance) const {
    const auto same_axis = [](const Feat& g, const Feat& h) { return g.eb == h.eb && g.ek == h.ek && g.sigma == h.sigma; };
    for (const Feat& axis : pk_->feats) {
      if (!axis.to_edge || axis.pv < 0 || same_axis(axis, ft)) continue;
      bool shallower = true;
      for (const Feat& g : pk_->feats)
        if (g.to_edge && g.pv >= 0 && same_axis(g, axis) && !(distance(g) - mine).positive()) shallower = false;
      if (shallower) return true;
    }
    return false;
  }

  // shallower_axis for a vertex's feature at tau = 0, in double intervals (the vertices'
  // signed distances, each f / |e|, compared cross-multiplied by the edges' lengths): true only
  // where an axis is certainly shallower, so overlap_applies is false for the feature.
  bool shallower_axis_at_start(const Feat& ft) {
    if (!ft.to_edge || ft.pv < 0) return false;
    using MI = Num<Interval>;
    if (start_f_.empty()) {
      PosedT<Interval> ps(*pk_, Interval(0.0));
      start_f_.resize(pk_->feats.size());
      for (std::size_t g = 0; g < pk_->feats.size(); ++g)
        if (pk_->feats[g].to_edge && pk_->feats[g].pv >= 0) start_f_[g] = ps.values(pk_->feats[g]).f.v;
    }
    const auto index = [&](const Feat& g) { return static_cast<std::size_t>(&g - pk_->feats.data()); };
    const auto same_axis = [](const Feat& g, const Feat& h) { return g.eb == h.eb && g.ek == h.ek && g.sigma == h.sigma; };
    const Interval& mine = start_f_[index(ft)];
    const Interval& my_len = MI::elen(pk_->kin(ft.eb), ft.ek);
    for (const Feat& axis : pk_->feats) {
      if (!axis.to_edge || axis.pv < 0 || same_axis(axis, ft)) continue;
      const Interval scaled_mine = mine * MI::elen(pk_->kin(axis.eb), axis.ek);
      bool shallower = true;
      for (const Feat& g : pk_->feats)
        if (g.to_edge && g.pv >= 0 && same_axis(g, axis) && !(start_f_[index(g)] * my_len - scaled_mine).certainly_positive())
          shallower = false;
      if (shallower) return true;
    }
    return false;
  }

  void offer(const std::shared_ptr<const RotatingRoot>& root, int i, bool overlap) {
    const Feat& ft = pk_->feats[static_cast<std::size_t>(i)];
    RootHandle handle = transcendental_root(root);
    if (!best_) {
      best_ = Best{root, PairResult{handle, overlap, {ft.id}}};
      return;
    }
    const int c = compare(*handle, *best_->result.tau);
    if (c < 0) {
      best_ = Best{root, PairResult{handle, overlap, {ft.id}}};
    } else if (c == 0) {
      std::vector<FeaturePair>& fs = best_->result.features;
      if (std::find(fs.begin(), fs.end(), ft.id) == fs.end()) fs.push_back(ft.id);
      best_->result.overlap_rule = best_->result.overlap_rule || overlap;
    }
  }

  std::shared_ptr<const PairKin> pk_;
  SearchCounters& n_;
  mutable std::optional<Posed> start_pose_;  // overlap_applies: the pair at tau = 0, 512 bits
  mutable std::vector<std::optional<Ball>> start_distance_;
  std::vector<Interval> start_f_;  // shallower_axis_at_start: f at tau = 0 of the vertices' features
  std::optional<Best> best_;

 public:
  std::optional<Dyadic> graze_;  // the earliest exact tangency (f = f' = 0 at a dyadic time) met
};

}  // namespace

std::optional<PairResult> rotating_pair_contact(Frame& fr, BodyIndex a, BodyIndex b, const Dyadic& tau_hi,
                                                SearchCounters& n) {
  PairSearch search(pair_kin(fr, a, b), n);
  return search.run(tau_hi);
}

std::optional<Dyadic> rotating_graze(Frame& fr, BodyIndex a, BodyIndex b, const Dyadic& tau_hi) {
  SearchCounters n;
  PairSearch search(pair_kin(fr, a, b), n);
  search.run(tau_hi);
  return search.graze_;
}

bool rotating_may_touch(Frame& fr, BodyIndex a, BodyIndex b, const Dyadic& tau_hi) {
  if (tau_hi.sign() <= 0) return true;
  if (apart_through(sweep_of(fr, a, tau_hi), sweep_of(fr, b, tau_hi))) return false;
  const std::shared_ptr<const Kin> pa = kin_of(fr, a), pb = kin_of(fr, b);
  const Kin &ka = *pa, &kb = *pb;
  const Precision guard(80);
  const Dyadic h = half(tau_hi);
  const Ball T = Ball::hull(Dyadic(), tau_hi), M(h), H = Ball::hull(-h, h), H2 = Ball::hull(Dyadic(), half(h * h));
  const Pose at(ka, T), am(ka, M), bt(kb, T), bm(kb, M);
  return !apart_over(ka, kb, at, am, bt, bm, H, H2);
}

double rotating_pair_scale(Frame& fr, BodyIndex a, BodyIndex b, const Dyadic& tau) {
  const Precision guard(64);
  double scale = 0;
  for (BodyIndex i : {a, b}) {
    const std::shared_ptr<const Kin> k = kin_of(fr, i);
    const VJ c = Pose(*k, Ball(tau)).centre();
    const double reach = std::sqrt(k->reach2.to_double());
    scale = std::max(scale, std::max(std::abs(c.x.v.mid_double()), std::abs(c.y.v.mid_double())) + reach);
  }
  return scale;
}

GapMeasure rotating_gap(Frame& fr, BodyIndex a, BodyIndex b, const FeaturePair& id, const Dyadic& tau) {
  const std::shared_ptr<PairKin> pk = pair_kin(fr, a, b);
  const Precision guard(128);
  Posed ps(*pk, Ball(tau));
  std::optional<GapMeasure> out;
  bool out_facing = false;
  for (const Feat& ft : pk->feats) {
    if (!(ft.id == id)) continue;
    const Values v = ps.values(ft);
    const double r = ft.pv < 0 ? pk->kin(ft.pb).radius.mid_double() : 0.0;
    double gap = 0;
    // A segment's edge is measured from the side the point's body lies on (its centre): from the
    // other side every gap has the wrong sign.
    bool facing = true;
    if (ft.to_edge) {
      gap = (v.f.v / Num<Ball>::elen(pk->kin(ft.eb), ft.ek)).mid_double();
      const int n = static_cast<int>(pk->kin(ft.eb).verts.size());
      const VJ& A = ps.vertex(ft.eb, ft.ek);
      const Ball side = cross(ps.pose(ft.pb).centre() - A, ps.vertex(ft.eb, (ft.ek + 1) % n) - A).v;
      facing = ft.sigma > 0 ? side.positive() : side.negative();
    } else {
      const double d2 = (v.f.v + pk->kin(ft.pb).radius * pk->kin(ft.pb).radius).mid_double();
      gap = std::sqrt(std::max(d2, 0.0)) - r;
    }
    if (!out || (facing && !out_facing) || (facing == out_facing && std::abs(gap) < std::abs(out->gap))) {
      out = GapMeasure{gap, r};
      out_facing = facing;
    }
  }
  if (!out) return {std::numeric_limits<double>::quiet_NaN(), 0.0};
  return *out;
}

}  // namespace pge::oracle::detail
