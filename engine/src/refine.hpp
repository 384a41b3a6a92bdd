// Correctly rounded event times for the robust and certified solvers. A prediction solves the
// contact polynomial built in T from the bodies' rounded states at `now`; its root is exact for
// that polynomial, but the polynomial is not the exact contact function of the paths the bodies
// really follow. Before such an event is processed its time is therefore re-derived from
// those paths: each moving body follows p(t) = p0 + v0 (t - t0) + acc (t - t0)^2 / 2 with its
// stored values read as exact numbers (the state the exact oracle reads, oracle/), and the
// event's feature pair has an exact contact function whose sign is decided in dyadic rationals.
// Walking T values outwards from the predicted time and bisecting finds the two adjacent T
// values around the crossing; the sign at their midpoint picks the nearer one (ties to even).
// The contact functions are the oracle's (squared forms, so no square root is ever taken):
//   circle-circle  |d|^2 - (ra + rb)^2
//   circle-edge    side^2 - r^2 |e|^2, side = cross(centre - edge start, e); a polygon's edge
//                  is one-sided (side <= 0 is behind it: negative), a segment's two-sided
//   circle-vertex  |centre - vertex|^2 - r^2
//   vertex-edge    cross(vertex - edge start, e)
// Costs a few signs per processed event (not per prediction), nearly all decided by a
// floating-point filter (filtered_contact_sign) before any exact arithmetic.
#pragma once

#include "body_shape.hpp"
#include "contact_common.hpp"
#include "event_heap.hpp"

#include "pge/roots.hpp"
#include "pge/vec2.hpp"

#include <cmath>
#include <limits>
#include <optional>
#include <vector>

namespace pge {
namespace refine {

using detail::exact::Dyadic;

// A dyadic rational with the arithmetic Vec2, dot and cross need.
struct Exact {
  Dyadic d;
  Exact() = default;
  Exact(int v) { d.m = v; detail::exact::normalize(d); }  // NOLINT: Vec2's members start as {0}
  explicit Exact(Dyadic v) : d(std::move(v)) { detail::exact::normalize(d); }
  template <class T> static Exact of(const T& x) { return Exact(detail::exact::to_dyadic(x)); }

  friend Exact operator+(const Exact& a, const Exact& b) {
    detail::exact::Int ma, mb;
    Dyadic r;
    r.e = detail::exact::align(a.d, b.d, ma, mb);
    r.m = ma + mb;
    return Exact(std::move(r));
  }
  friend Exact operator-(const Exact& a) {
    Dyadic r = a.d;
    r.m = -r.m;
    return Exact(std::move(r));
  }
  friend Exact operator-(const Exact& a, const Exact& b) { return a + (-b); }
  friend Exact operator*(const Exact& a, const Exact& b) {
    Dyadic r;
    r.m = a.d.m * b.d.m;
    r.e = a.d.e + b.d.e;
    return Exact(std::move(r));
  }
  Exact half() const {
    Dyadic r = d;
    r.e -= 1;
    return Exact(std::move(r));
  }
  int sign() const { return detail::exact::sign_of_int(d.m); }
};

using ExactVec = Vec2<Exact>;

template <class T> ExactVec exact_vec(const Vec2<T>& v) { return {Exact::of(v.x), Exact::of(v.y)}; }

// One body's path and shape as stored: p(t) = p0 + v0 (t - t0) + acc (t - t0)^2 / 2, read as
// exact numbers (a fixed body stays at p0).
template <class T> struct Path {
  const BodyShape<T>* shape = nullptr;
  bool fixed = false;
  T t0{};
  Vec2<T> p0, v0, acc;
};

// One body as the exact contact functions read it.
template <class T> struct ExactBody {
  const BodyShape<T>* shape = nullptr;
  bool fixed = false;
  Exact t0;
  ExactVec p0, v0, half_acc;

  ExactVec position(const Exact& t) const {
    if (fixed) return p0;
    const Exact tau = t - t0;
    return p0 + (v0 + half_acc * tau) * tau;
  }
  // Vertex k: a fixed body's rounded world vertex, a moving body's exact p(t) + local[k].
  ExactVec vertex(const ExactVec& p, std::size_t k) const {
    return shape->fixed ? exact_vec(shape->world[k]) : p + exact_vec(shape->local[k]);
  }
  // Edge k's vector (vertex k+1 - vertex k) in the body's own frame: constant in time.
  ExactVec edge(std::size_t k) const {
    const auto& v = shape->fixed ? shape->world : shape->local;
    return exact_vec(v[(k + 1) % v.size()]) - exact_vec(v[k]);
  }
};

template <class T> ExactBody<T> exact_body(const Path<T>& x) {
  ExactBody<T> b;
  b.shape = x.shape;
  b.fixed = x.fixed;
  b.p0 = exact_vec(x.p0);
  if (!x.fixed) {
    b.t0 = Exact::of(x.t0);
    b.v0 = exact_vec(x.v0);
    b.half_acc = {Exact::of(x.acc.x).half(), Exact::of(x.acc.y).half()};
  }
  return b;
}

// The contact function of the scheduled feature pair, its sign (negative: overlapping, zero:
// touching), in any arithmetic: a View gives each body's kind and radius, its points (its
// centre, its vertex k) and edge vectors in the arithmetic's numbers, and the difference of two
// points; sign_of gives a number's sign, or nothing if the arithmetic cannot decide it. The
// exact evaluation (ExactView, dyadic rationals) and the filter (FilterView below, floating
// point with an error bound) are both this function.
template <class View, class T>
std::optional<int> feature_sign(const View& a, const View& b, const Scheduled<T>& s) {
  switch (s.contact) {
    case ContactKind::CircleCircle: {
      const auto d = View::difference(b.centre(), a.centre());
      const auto rr = a.radius() + b.radius();
      return sign_of(dot(d, d) - rr * rr);
    }
    case ContactKind::CircleEdge:
    case ContactKind::CircleVertex: {
      const bool a_circle = a.kind() == ShapeKind::Circle;
      const View& c = a_circle ? a : b;
      const View& o = a_circle ? b : a;
      const std::size_t k = a_circle ? s.feature_b : s.feature_a;
      const auto r = c.radius();
      const auto q = View::difference(c.centre(), o.vertex(k));
      if (s.contact == ContactKind::CircleVertex) return sign_of(dot(q, q) - r * r);
      const auto e = o.edge(k);
      const auto side = cross(q, e);
      if (o.kind() == ShapeKind::Polygon) {  // one-sided: side <= 0 is behind the edge
        const std::optional<int> front = sign_of(side);
        if (!front) return std::nullopt;
        if (*front <= 0) return -1;
      }
      return sign_of(side * side - r * r * dot(e, e));
    }
    case ContactKind::VertexEdge:
    case ContactKind::EdgeVertex: {
      const bool a_vertex = s.contact == ContactKind::VertexEdge;
      const View& vb = a_vertex ? a : b;
      const View& eb = a_vertex ? b : a;
      const std::size_t k = a_vertex ? s.feature_a : s.feature_b;  // vertex
      const std::size_t j = a_vertex ? s.feature_b : s.feature_a;  // internal edge
      return sign_of(cross(View::difference(vb.vertex(k), eb.vertex(j)), eb.edge(j)));
    }
  }
  return 1;
}

inline std::optional<int> sign_of(const Exact& x) { return x.sign(); }

// An exact body at time t: its points are exact positions.
template <class T> class ExactView {
 public:
  ExactView(const ExactBody<T>& b, const Exact& t) : b_(b), p_(b.position(t)) {}
  ShapeKind kind() const { return b_.shape->kind; }
  Exact radius() const { return Exact::of(b_.shape->radius); }
  const ExactVec& centre() const { return p_; }
  ExactVec vertex(std::size_t k) const { return b_.vertex(p_, k); }
  ExactVec edge(std::size_t k) const { return b_.edge(k); }
  static ExactVec difference(const ExactVec& y, const ExactVec& x) { return y - x; }

 private:
  const ExactBody<T>& b_;
  ExactVec p_;
};

// Sign of the exact contact function of the scheduled feature pair at time t.
template <class T>
int contact_sign(const ExactBody<T>& a, const ExactBody<T>& b, const Scheduled<T>& s, const Exact& t) {
  return *feature_sign(ExactView<T>(a, t), ExactView<T>(b, t), s);
}

// --- A floating-point filter in front of contact_sign.
// Most signs the refinement asks for are far from zero in floating point: the walk probes T
// values an ulp or more from the crossing, where the contact function is larger than the
// rounding of a careful evaluation. The filter evaluates the same function (feature_sign, with
// a FilterView) with a running bound on its error and answers only when the bound decides the
// sign; otherwise the exact evaluation answers (the filtered-then-exact pattern of CGAL's
// filtered predicates and Shewchuk's adaptive orientation tests). Two things make it decide
// often:
//   - positions are never formed: the difference of the two features' points is built as
//     (base_b - base_a) + (offset_b - offset_a) + (motion_b - motion_a), where a base is a
//     stored p0 or fixed vertex, an offset a polygon's local vertex and a motion
//     v0 tau + acc tau^2 / 2, so that the rounding is relative to the distance between the
//     bodies, not to their distance from the origin (a large box decides as often as a small
//     one);
//   - the time is passed as t + dt with both T values (dt = half the gap between two adjacent
//     T values, for the walk's final midpoint), so that tau = (t - t0) + dt is rounded
//     relative to tau.
// The filter runs in a wider type than T: double for float, long double for double (x87's
// 64-bit significand on x86-64: 11 bits more, which leaves about 1 sign in 1,000 undecided in
// the hard cases of tests/test_refine_filter.cpp and 1 in 1,700 on a 1,000-disc gas; in double
// itself 40% of the gas's signs stayed undecided, since the walk's signs sit within an ulp or
// two of the clock from the crossing). Long double and quad have no wider hardware type; in
// their own precision the filter decided 2% of those signs (same test), so they go to the exact
// evaluation directly (kFilterPays).

template <class T> struct FilterScalar { using type = T; };
template <> struct FilterScalar<float> { using type = double; };
template <> struct FilterScalar<double> { using type = long double; };
template <class T>
inline constexpr bool kFilterPays = std::numeric_limits<typename FilterScalar<T>::type>::digits > std::numeric_limits<T>::digits;

// Whether E's arithmetic really carries the digits numeric_limits says: x87's precision control
// can be set to 53 bits (some libraries do), and then a long double bound would be too small.
// Checked once at run time; if not, the filter stays off (the exact signs answer everything).
template <class E> bool arithmetic_has_its_digits() {
  static const bool ok = [] {
    volatile E one = E(1);  // volatile: computed by the processor as configured, not folded
    volatile E tiny = std::numeric_limits<E>::epsilon();
    const E sum = one + tiny;
    return sum != one;
  }();
  return ok;
}

// A computed value v and a bound e on its distance from the exact value of the expression.
// Every operation's rounding is bounded by epsilon |result| (twice the unit roundoff of
// round-to-nearest, so directed rounding is covered too); that holds for sums always and for
// products whose result is a normal number, so a product of non-zero factors that comes out
// below tiny() (near underflow) marks the value lost (undecided) instead: adding an absolute
// term per product would fill the bounds with subnormal numbers, which cost a hundred cycles
// per operation on x86. The bound's own rounding (a relative (1 + u)^k for an expression of k
// operations) is covered by the factor 2 in decided_sign, and the smallest normal number
// there covers subnormal bounds. A NaN or infinity anywhere leaves the comparison false:
// undecided.
template <class E> struct Bounded {
  E v{0};
  E e{0};
  bool lost = false;
  Bounded() = default;
  Bounded(int x) : v(x) {}  // NOLINT: Vec2's members start as {0}
  static Bounded of(const E& x) {
    Bounded b;
    b.v = x;
    return b;
  }
  static E eps() { return std::numeric_limits<E>::epsilon(); }
  static E tiny() { return std::numeric_limits<E>::min() / std::numeric_limits<E>::epsilon(); }
  friend Bounded operator+(const Bounded& a, const Bounded& b) {
    using std::abs;
    Bounded r;
    r.v = a.v + b.v;
    r.e = a.e + b.e + eps() * abs(r.v);
    r.lost = a.lost || b.lost;
    return r;
  }
  friend Bounded operator-(const Bounded& a, const Bounded& b) {
    using std::abs;
    Bounded r;
    r.v = a.v - b.v;
    r.e = a.e + b.e + eps() * abs(r.v);
    r.lost = a.lost || b.lost;
    return r;
  }
  friend Bounded operator-(const Bounded& a) {
    Bounded r = a;
    r.v = -a.v;
    return r;
  }
  friend Bounded operator*(const Bounded& a, const Bounded& b) {
    using std::abs;
    Bounded r;
    r.v = a.v * b.v;
    r.e = abs(a.v) * b.e + abs(b.v) * a.e + a.e * b.e + eps() * abs(r.v);
    r.lost = a.lost || b.lost || (abs(r.v) < tiny() && a.v != E(0) && b.v != E(0));
    return r;
  }
  // The exact value's sign if the bound decides it.
  std::optional<int> decided_sign() const {
    if (lost) return std::nullopt;
    const E margin = E(2) * e + std::numeric_limits<E>::min();
    if (v > margin) return 1;
    if (-v > margin) return -1;
    return std::nullopt;
  }
};

template <class E> std::optional<int> sign_of(const Bounded<E>& x) { return x.decided_sign(); }

// A body at the time t + dt for the filter: a point is kept as base + offset + motion (a stored
// p0 or fixed vertex, a polygon's local vertex, and v0 tau + acc tau^2 / 2 if the body moves),
// and the difference of two points subtracts bases first, then offsets, then motions.
template <class T> class FilterView {
 public:
  using E = typename FilterScalar<T>::type;
  using B = Bounded<E>;
  using V = Vec2<B>;
  struct Point {
    Vec2<T> base, offset;
    const V* motion;  // nullptr: the point does not move
  };
  FilterView(const Path<T>& x, const T& t, const T& dt) : x_(x) {
    if (x.fixed) return;
    const B tau = (num(t) - num(x.t0)) + num(dt);
    const V half_acc = vec(x.acc) * B::of(E(0.5));
    motion_ = (vec(x.v0) + half_acc * tau) * tau;
  }
  ShapeKind kind() const { return x_.shape->kind; }
  B radius() const { return num(x_.shape->radius); }
  Point centre() const { return {x_.p0, {}, x_.fixed ? nullptr : &motion_}; }
  Point vertex(std::size_t k) const {
    if (x_.shape->fixed) return {x_.shape->world[k], {}, nullptr};
    return {x_.p0, x_.shape->local[k], x_.fixed ? nullptr : &motion_};
  }
  V edge(std::size_t k) const {
    const auto& v = x_.shape->fixed ? x_.shape->world : x_.shape->local;
    return vec(v[(k + 1) % v.size()]) - vec(v[k]);
  }
  static V difference(const Point& y, const Point& x) {
    V d = vec(y.base) - vec(x.base);
    if (!(y.offset == Vec2<T>{} && x.offset == Vec2<T>{})) d = d + (vec(y.offset) - vec(x.offset));
    if (y.motion) d = d + *y.motion;
    if (x.motion) d = d - *x.motion;
    return d;
  }

 private:
  static B num(const T& v) { return B::of(E(v)); }
  static V vec(const Vec2<T>& v) { return {num(v.x), num(v.y)}; }
  const Path<T>& x_;
  V motion_;
};

// The sign of contact_sign's function at the time t + dt (exactly, as real numbers), or nothing
// if rounding could change it.
template <class T>
std::optional<int> filtered_contact_sign(const Path<T>& a, const Path<T>& b, const Scheduled<T>& s, const T& t,
                                         const T& dt) {
  return feature_sign(FilterView<T>(a, t, dt), FilterView<T>(b, t, dt), s);
}

// --- The same filter for two circles, expanded once about a time.
// The walk asks a few signs at T values within a few ulps of one another. For two circles the
// contact function is a polynomial in delta = t - at about any time `at`:
//   d(at + delta) = D0 + D1 delta + D2 delta^2   (D0 = d(at), D1 = d'(at), D2 = d''/2 = dacc / 2)
//   f = |d|^2 - (ra + rb)^2 = c0 + c1 delta + ... + c4 delta^4
// an identity of real numbers, so its value at any delta is the contact function's. The
// coefficients are computed once, in Bounded arithmetic (their error bounds rigorous as above),
// from the same like-terms-first differences as FilterView; each sign is then a Horner
// evaluation at delta = (t - at) + dt, also in Bounded arithmetic: about 10 operations where
// FilterView takes about 40. The bound on D0 is FilterView's bound on d (the same operations
// at `at`), and delta is small where the walk asks (t within a few ulps of `at`), so this
// filter decides the signs FilterView decides (tests/test_refine_filter.cpp compares them).
// Bodies without acceleration (the gas) leave D2, c3 and c4 exactly zero: the polynomial is a
// quadratic and Horner starts at c2.
template <class T> class CirclePairFilter {
 public:
  using E = typename FilterScalar<T>::type;
  using B = Bounded<E>;
  using V = Vec2<B>;
  CirclePairFilter(const Path<T>& a, const Path<T>& b, const T& at) : at_(E(at)) {
    const auto still = [](const Path<T>& x) { return x.fixed || x.acc == Vec2<T>{}; };
    if (still(a) && still(b)) {
      // Neither body accelerates (the gas): the same operations as below, in straight-line code
      // (no Motion records: x87 values kept in registers, not stored and loaded again).
      const auto displacement = [&](const Path<T>& x) {
        if (x.fixed) return V{};
        const B tau = difference(at_, E(x.t0));
        return V{exact_times(E(x.v0.x), tau), exact_times(E(x.v0.y), tau)};
      };
      const auto velocity = [](const Path<T>& x) { return x.fixed ? Vec2<E>{} : Vec2<E>{E(x.v0.x), E(x.v0.y)}; };
      const Vec2<E> va = velocity(a), vb = velocity(b);
      const V d0 = V{difference(b.p0.x, a.p0.x), difference(b.p0.y, a.p0.y)} + (displacement(b) - displacement(a));
      const B rr = B::of(E(a.shape->radius)) + B::of(E(b.shape->radius));
      const V d1{difference(vb.x, va.x), difference(vb.y, va.y)};
      c_[0] = dot(d0, d0) - rr * rr;
      c_[1] = twice(dot(d0, d1));
      c_[2] = dot(d1, d1);
      degree_ = 2;
      return;
    }
    const Motion ma = motion(a), mb = motion(b);
    const V d0 = V{difference(b.p0.x, a.p0.x), difference(b.p0.y, a.p0.y)} + (mb.displacement - ma.displacement);
    const B rr = B::of(E(a.shape->radius)) + B::of(E(b.shape->radius));
    c_[0] = dot(d0, d0) - rr * rr;
    if (!ma.accelerates && !mb.accelerates) {
      // d1 = v0b - v0a (a fixed body's velocity is zero): one rounding of exact values.
      const V d1{difference(mb.v0.x, ma.v0.x), difference(mb.v0.y, ma.v0.y)};
      c_[1] = twice(dot(d0, d1));
      c_[2] = dot(d1, d1);
      degree_ = 2;
      return;
    }
    const V d1 = velocity(b, mb) - velocity(a, ma);
    const V d2 = half_acc(mb) - half_acc(ma);
    c_[1] = twice(dot(d0, d1));
    c_[2] = dot(d1, d1) + twice(dot(d0, d2));
    c_[3] = twice(dot(d1, d2));
    c_[4] = dot(d2, d2);
    degree_ = 4;
  }
  // The sign of the contact function at t + dt (exactly), or nothing if rounding could change it.
  std::optional<int> sign(const T& t, const T& dt) const {
    B delta = difference(E(t), at_);
    if (dt != T(0)) delta = delta + B::of(E(dt));
    B f = c_[degree_];
    for (int k = degree_ - 1; k >= 0; --k) f = f * delta + c_[k];
    return f.decided_sign();
  }
  // What correctly_rounded_crossing(at, now, sign) returns, where this expansion (about `at`, the
  // predicted time) proves it without the walk: two signs instead of the walk's three or more.
  // The guess g is the T nearest at + delta, delta = -c0 / c1 (a Newton step: delta is a few
  // ulps). It is the walk's answer when the function is certainly positive at the midpoint below
  // g and negative at the midpoint above (one crossing between them: the walk's bracket closes
  // on g and its midpoint rule keeps g), and certainly decreasing over every time the walk could
  // probe from `at` (its steps double from about an ulp, so they overshoot the crossing by at
  // most about its distance from `at`: 4 |g - at| plus 16 ulps on each side covers them; the
  // slope c1 + 2 c2 delta rises with delta, c2 = |d1|^2 >= 0, so its sign at the right end
  // decides). Only without acceleration (a quadratic); nothing where any of it is not proven,
  // and the walk runs.
  std::optional<T> rounded_crossing(const T& now) const {
    using std::abs;
    if (degree_ != 2 || !(c_[1].v < E(0))) return std::nullopt;
    const T at = T(at_);
    const T g = T(at_ - c_[0].v / c_[1].v);
    if (!(g > now) || !(at > now)) return std::nullopt;
    const T below = boost::math::float_prior(g), above = boost::math::float_next(g);
    if (!(below > now)) return std::nullopt;
    const T half_below = (g - below) / T(2), half_above = (above - g) / T(2);
    if (!(half_below + half_below == g - below) || !(half_above + half_above == above - g)) return std::nullopt;
    const T unit = std::max(abs(at) * std::numeric_limits<T>::epsilon(), above - below);
    const T distance = abs(g - at);
    if (!(distance <= T(1048576) * unit)) return std::nullopt;
    const T right = std::max(at, above) + (T(4) * distance + T(16) * unit);
    const B slope = c_[1] + twice(c_[2] * difference(E(right), at_));
    if (slope.decided_sign() != std::optional<int>(-1)) return std::nullopt;
    if (sign(below, half_below) != std::optional<int>(1)) return std::nullopt;
    if (sign(g, half_above) != std::optional<int>(-1)) return std::nullopt;
    return g;
  }

 private:
  // One body's terms at `at`: its displacement since t0 and the exact values it came from (all
  // zero for a fixed body).
  struct Motion {
    V displacement;
    B tau;
    Vec2<E> v0, acc;
    bool accelerates = false;
  };
  Motion motion(const Path<T>& x) const {
    Motion m;
    if (x.fixed) return m;
    m.tau = difference(at_, E(x.t0));
    m.v0 = {E(x.v0.x), E(x.v0.y)};
    m.acc = {E(x.acc.x), E(x.acc.y)};
    m.accelerates = !(x.acc == Vec2<T>{});
    if (!m.accelerates) {
      m.displacement = {exact_times(m.v0.x, m.tau), exact_times(m.v0.y, m.tau)};
      return m;
    }
    const V v0{B::of(m.v0.x), B::of(m.v0.y)};
    m.displacement = (v0 + half_acc(m) * m.tau) * m.tau;  // FilterView's motion
    return m;
  }
  static V velocity(const Path<T>& x, const Motion& m) {  // v0 + acc tau
    if (x.fixed) return {};
    return V{B::of(m.v0.x), B::of(m.v0.y)} + V{exact_times(m.acc.x, m.tau), exact_times(m.acc.y, m.tau)};
  }
  static V half_acc(const Motion& m) { return {B::of(m.acc.x / E(2)), B::of(m.acc.y / E(2))}; }  // exact
  // Bounded's operations with an operand known exact (its bound zero), the zero terms left out.
  static B difference(const E& x, const E& y) {
    using std::abs;
    B r;
    r.v = x - y;
    r.e = B::eps() * abs(r.v);
    return r;
  }
  static B exact_times(const E& x, const B& y) {
    using std::abs;
    B r;
    r.v = x * y.v;
    r.e = abs(x) * y.e + B::eps() * abs(r.v);
    r.lost = y.lost || (abs(r.v) < B::tiny() && x != E(0) && y.v != E(0));
    return r;
  }
  static B twice(B x) {  // exact in binary floating point
    x.v = x.v * E(2);
    x.e = x.e * E(2);
    return x;
  }
  E at_;
  B c_[5];
  int degree_ = 2;
};

// Signs the filter decided, and signs evaluated exactly, on this thread (read by tests).
inline thread_local std::uint64_t filtered_signs = 0;
inline thread_local std::uint64_t exact_signs = 0;

// The sign of a scheduled contact's function, filtered first; the exact bodies are built on
// the first sign the filter cannot decide.
template <class T> class ContactSigner {
 public:
  ContactSigner(const Path<T>& a, const Path<T>& b, const Scheduled<T>& s) : a_(a), b_(b), s_(s) {}
  // At t + dt.
  int operator()(const T& t, const T& dt = T(0)) {
    if constexpr (kFilterPays<T>) {
      if (arithmetic_has_its_digits<typename FilterScalar<T>::type>()) {
        if (s_.contact == ContactKind::CircleCircle) {  // the expansion first, then FilterView
          if (!circles_) circles_.emplace(a_, b_, t);
          if (const std::optional<int> f = circles_->sign(t, dt)) {
            ++filtered_signs;
            return *f;
          }
        }
        if (const std::optional<int> f = filtered_contact_sign(a_, b_, s_, t, dt)) {
          ++filtered_signs;
          return *f;
        }
      }
    }
    return exact(dt == T(0) ? Exact::of(t) : Exact::of(t) + Exact::of(dt));
  }
  // correctly_rounded_crossing(predicted, now, *this) without its walk, where the circle pair's
  // expansion proves the answer (CirclePairFilter::rounded_crossing); nothing otherwise.
  std::optional<T> rounded_crossing(const T& predicted, const T& now) {
    if constexpr (kFilterPays<T>) {
      if (s_.contact == ContactKind::CircleCircle && arithmetic_has_its_digits<typename FilterScalar<T>::type>()) {
        if (!circles_) circles_.emplace(a_, b_, predicted);
        if (std::optional<T> t = circles_->rounded_crossing(now)) {
          filtered_signs += 2;
          return t;
        }
      }
    }
    return std::nullopt;
  }
  int exact(const Exact& t) {
    ++exact_signs;
    if (!ea_) {
      ea_ = exact_body(a_);
      eb_ = exact_body(b_);
    }
    return contact_sign(*ea_, *eb_, s_, t);
  }

 private:
  const Path<T>& a_;
  const Path<T>& b_;
  const Scheduled<T>& s_;
  std::optional<ExactBody<T>> ea_, eb_;
  std::optional<CirclePairFilter<T>> circles_;  // expanded about the first time asked
};

// --- Near-grazes of two circles, decided exactly (robust and certified).
// The contact polynomial built from rounded states decides a pair that passes within rounding
// of touching by its rounding: a path one ulp inside the radius sum can come out as a graze (a
// missed collision) and one ulp outside as a hit (a phantom). When the rounded polynomial's
// closest approach in the window is that close to zero, the pair is predicted again from the
// exact polynomial of the exact paths (the oracle's), isolated with the exact solver.

// Relative closeness below which a closest approach counts as a near-graze: far above the
// rounding of the polynomial (a few hundred ulps of its scale), far below any real miss.
// 2^-36 leaves double 2^16 ulps for the rounding, but lies below float's own (2^-23), where a
// graze within rounding would be the rounding's call again (issue 23's audit): so it is
// 2^-36 or kNearGrazeUlps ulps of T, whichever is larger. float: 2^-15; double, long double and
// quad: 2^-36.
inline constexpr double kNearGrazeRelative = 0x1p-36;
inline constexpr double kNearGrazeUlps = 256;
template <class T> T near_graze_relative() {
  return std::max(T(kNearGrazeRelative), T(kNearGrazeUlps) * std::numeric_limits<T>::epsilon());
}

// Whether the rounded function p = |d + dv t + da t^2 / 2|^2 - r^2 comes within rounding of
// zero at a local minimum in (0, horizon], or starts within rounding of zero while approaching
// or receding by less than near_graze_relative of its relative speed (p'(0) = 2 d.dv against
// 2 |d| |dv|): a touching pair whose approach is the rounding's call. That includes the ever smaller
// residues a cascade of hand-overs leaves (relative speeds of 1e-16, 1e-32, ...), which the
// robust solver's degree reduction would drop as negligible. `scale` is the pair's coordinate
// magnitude.
template <class T>
bool near_graze(const Poly<T>& p, const Vec2<T>& d, const Vec2<T>& dv, const Vec2<T>& da, const T& r, const T& scale,
                const T& horizon) {
  using std::abs;
  using std::sqrt;
  // The square of the pair's length scale at t (|d| + r + |dv| t + |da| t^2 / 2 + scale), bounded
  // by Cauchy-Schwarz without square roots: this runs on every prediction of two circles.
  const auto reach2 = [&](const T& t) {
    const T rs = r + scale;
    return T(4) * (dot(d, d) + rs * rs + dot(dv, dv) * (t * t) + dot(da, da) * (t * t * t * t / T(4)));
  };
  const T relative = near_graze_relative<T>();
  const auto close = [&](const T& t) { return abs(p(t)) <= relative * reach2(t); };
  if (abs(p.c[0]) <= relative * reach2(T(0)) && p.c[1] <= T(2) * relative * sqrt(dot(d, d) * dot(dv, dv)))
    return true;
  if (p.degree == 2) {
    if (!(p.c[2] > T(0)) || !(p.c[1] < T(0))) return false;
    const T t = -p.c[1] / (T(2) * p.c[2]);
    return t <= horizon && close(t);
  }
  // Local minima of p: where p' crosses zero going up, that is where -p' crosses going down.
  Poly<T> falling = p.derivative();
  for (int k = 0; k <= falling.degree; ++k) falling.c[k] = -falling.c[k];
  bool found = false;
  robust_visit_downward_roots(falling, T(0), horizon, StartRule::CrossingsOnly, [&](const T& t, bool) {
    found = close(t);
    return found;
  });
  return found;
}

// --- The exact paths as polynomials in tau = t - now (the line graze below, and the exact
// contact polynomials of the refinement's re-decisions further down).

// A point's exact path in tau = t - now: c[0] + c[1] tau + c[2] tau^2, with D = now - t0:
// c0 = p(now), c1 = v0 + acc D, c2 = acc / 2 (a fixed body's points stay put).
template <class T> void exact_point_path(const ExactBody<T>& x, const Exact& now, ExactVec c[3]) {
  c[0] = x.position(now);
  c[1] = ExactVec{};
  c[2] = ExactVec{};
  if (x.fixed) return;
  const Exact dt = now - x.t0;
  c[1] = x.v0 + x.half_acc * dt + x.half_acc * dt;
  c[2] = x.half_acc;
}

// The same for vertex k of a body.
template <class T> void exact_vertex_path(const ExactBody<T>& x, std::size_t k, const Exact& now, ExactVec c[3]) {
  exact_point_path(x, now, c);
  c[0] = x.vertex(c[0], k);
}

// The exact paths of a scheduled line contact's point (a circle's centre, or the vertex) and of
// its edge's start in tau = t - now, and the edge's vector; false for a pair of no line contact.
template <class T>
bool line_contact_paths(const ExactBody<T>& a, const ExactBody<T>& b, const Scheduled<T>& s, const Exact& now,
                        ExactVec (&p)[3], ExactVec (&start)[3], ExactVec& e) {
  if (s.contact == ContactKind::CircleEdge) {
    const bool a_circle = a.shape->kind == ShapeKind::Circle;
    const std::size_t k = a_circle ? s.feature_b : s.feature_a;
    exact_point_path(a_circle ? a : b, now, p);
    exact_vertex_path(a_circle ? b : a, k, now, start);
    e = (a_circle ? b : a).edge(k);
    return true;
  }
  if (s.contact != ContactKind::VertexEdge && s.contact != ContactKind::EdgeVertex) return false;
  const bool a_vertex = s.contact == ContactKind::VertexEdge;
  const std::size_t k = a_vertex ? s.feature_a : s.feature_b;  // vertex
  const std::size_t j = a_vertex ? s.feature_b : s.feature_a;  // edge
  exact_vertex_path(a_vertex ? a : b, k, now, p);
  exact_vertex_path(a_vertex ? b : a, j, now, start);
  e = (a_vertex ? b : a).edge(j);
  return true;
}

// The line function of a scheduled line contact (CircleEdge, VertexEdge or EdgeVertex) in
// tau = t - now, sigma[0] + sigma[1] tau + sigma[2] tau^2: cross(centre - edge start, e) for a
// circle against edge e, cross(vertex - edge start, e) for a vertex against it (positive in
// front of a polygon's edge).
template <class T>
void exact_line_poly(const ExactBody<T>& a, const ExactBody<T>& b, const Scheduled<T>& s, const Exact& now,
                     Exact sigma[3]) {
  ExactVec p[3], start[3];
  ExactVec e;
  line_contact_paths(a, b, s, now, p, start, e);
  for (int i = 0; i < 3; ++i) sigma[i] = cross(p[i] - start[i], e);
}

// Where a scheduled line contact's point (a circle's centre or a vertex, against an edge) lies
// at the exact crossing of its contact function that [lo, hi] brackets (exact times, now <= lo
// < hi, the function positive at lo and not at hi; refine::correctly_rounded_crossing's T
// value and its neighbours): strictly inside the edge, strictly before its start, strictly past
// its end, or Unknown (an end itself, which is the corner rule's, a bracket that does not hold,
// or not decided within kPlaceBisections; EdgePlace, contact_common.hpp). The oracle counts a line contact only where its
// point lies on the closed edge; beyond an end, the end vertex's feature pairs meet instead.
// The point's projection on the edge, dot(point - start, e), is a quadratic in tau = t - now;
// an interval on which it is monotone (its slope of one sign at both ends) and on one side of
// 0 and of e.e at both ends decides; otherwise the bracket is halved at its exact midpoint,
// keeping the crossing (the contact function's exact sign there).
inline constexpr int kPlaceBisections = 160;

template <class T>
EdgePlace exact_place_at_crossing(const ExactBody<T>& a, const ExactBody<T>& b, const Scheduled<T>& s,
                                  const Exact& now, Exact lo, Exact hi) {
  ExactVec p[3], start[3];
  ExactVec e;
  if (!line_contact_paths(a, b, s, now, p, start, e)) return EdgePlace::Unknown;
  const std::optional<detail::exact::IntPoly> poly = exact_feature_poly(a, b, s, now);
  if (!poly) return EdgePlace::Unknown;
  const auto contact = [&](const Exact& t) { return detail::exact::sign_at(*poly, (t - now).d); };
  if (!(contact(lo) > 0 && contact(hi) <= 0)) return EdgePlace::Unknown;
  Exact q[3];
  for (int i = 0; i < 3; ++i) q[i] = dot(p[i] - start[i], e);
  const Exact length2 = dot(e, e);
  const auto along = [&](const Exact& t) {
    const Exact tau = t - now;
    return q[0] + (q[1] + q[2] * tau) * tau;
  };
  const auto slope = [&](const Exact& t) { return (q[1] + Exact(2) * q[2] * (t - now)).sign(); };
  const auto place = [&](const Exact& x) {  // of one projection value, strictly
    if (x.sign() < 0) return EdgePlace::Before;
    if ((x - length2).sign() > 0) return EdgePlace::After;
    return x.sign() > 0 && (x - length2).sign() < 0 ? EdgePlace::On : EdgePlace::Unknown;
  };
  for (int k = 0; k <= kPlaceBisections; ++k) {
    if (contact(hi) == 0) return place(along(hi));  // the crossing is hi itself
    const EdgePlace at_lo = place(along(lo));
    if (at_lo != EdgePlace::Unknown && at_lo == place(along(hi)) && (q[2].sign() == 0 || slope(lo) == slope(hi)))
      return at_lo;
    const Exact mid((lo + hi).half());
    (contact(mid) > 0 ? lo : hi) = mid;
  }
  return EdgePlace::Unknown;
}

// --- The separating-axis overlap rule at now, decided exactly (robust and certified).
// The pairs of two outlines (polygons or segments) that realise their least penetration at
// now, from the stored paths: every edge of each body is an axis, its value the least of
// cross(vertex - edge start, e) over the other body's vertices (negative: that vertex lies
// behind the edge's line), and the pair meets only where no axis value is positive. The least
// penetration is the axis whose value over |e| is largest (compared squared: no square root),
// and its pairs are its deepest vertices. Only an exact overlap is decided here: nothing (the
// rounded rule decides, as before) when an axis separates or the pair only touches (the largest
// value zero), since a rounded function overlapping there finds the pair's next contact only
// through the overlap rules (a box bounced off a ramp with its vertex exactly on the line and
// an ulp inside it in long double: the rounded function never came back above zero, and the
// turning-overlap rule caught its return; fixtures/regressions/box-placed-on-an-incline.json);
// nothing either when more pairs tie than OverlapPairs holds.
template <class T>
std::optional<OverlapPairs> exact_overlap_pairs(const ExactBody<T>& a, const ExactBody<T>& b, const Exact& now) {
  const auto vertices = [&](const ExactBody<T>& x) {
    const ExactVec p = x.position(now);
    std::vector<ExactVec> v;
    v.reserve(x.shape->vertex_count());
    for (std::size_t k = 0; k < x.shape->vertex_count(); ++k) v.push_back(x.vertex(p, k));
    return v;
  };
  const std::vector<ExactVec> at[2] = {vertices(a), vertices(b)};
  struct Axis {
    int side;  // 0: an edge of b against a's vertices (OverlapPairs' sides)
    std::size_t j;
    Exact value, length2;
  };
  std::vector<Axis> axes;
  for (int side = 0; side < 2; ++side) {
    const ExactBody<T>& q = side == 0 ? b : a;
    const std::vector<ExactVec>& qv = at[side == 0 ? 1 : 0];
    const std::vector<ExactVec>& pv = at[side == 0 ? 0 : 1];
    for (std::size_t j = 0; j < qv.size(); ++j) {
      const ExactVec e = q.edge(j);
      Exact least = cross(pv[0] - qv[j], e);
      for (std::size_t k = 1; k < pv.size(); ++k) {
        const Exact c = cross(pv[k] - qv[j], e);
        if ((c - least).sign() < 0) least = c;
      }
      if (least.sign() > 0) return std::nullopt;
      axes.push_back(Axis{side, j, least, dot(e, e)});
    }
  }
  // x's separation value / |e| against y's: > 0 when x's is larger (x less deep), both <= 0.
  const auto compare = [](const Axis& x, const Axis& y) {
    return (y.value * y.value * x.length2 - x.value * x.value * y.length2).sign();
  };
  std::size_t best = 0;
  for (std::size_t i = 1; i < axes.size(); ++i)
    if (compare(axes[i], axes[best]) > 0) best = i;
  if (axes[best].value.sign() == 0) return std::nullopt;
  OverlapPairs out;
  for (const Axis& x : axes) {
    if (compare(x, axes[best]) != 0) continue;
    const ExactBody<T>& q = x.side == 0 ? b : a;
    const std::vector<ExactVec>& qv = at[x.side == 0 ? 1 : 0];
    const std::vector<ExactVec>& pv = at[x.side == 0 ? 0 : 1];
    const ExactVec e = q.edge(x.j);
    for (std::size_t k = 0; k < pv.size(); ++k)
      if ((cross(pv[k] - qv[x.j], e) - x.value).sign() == 0 && !out.add(x.side, k, x.j)) return std::nullopt;
  }
  return out;
}

// --- Near-grazes of line contacts, decided exactly (robust and certified).
// A circle or a vertex against an edge meets it where a distance to the edge's line, quadratic
// in time for translating bodies, reaches the radius (or zero). At a double root (a ball touching
// a ceiling at the apex of its bounce) the rounded quadratic crosses or not by its rounding:
// contact_common.hpp's near_line_graze finds such a minimum, and the exact paths decide it here.

// Whether the scheduled line contact (CircleEdge, VertexEdge or EdgeVertex), apart at `now` and
// approaching with its distance function convex, crosses before that function's minimum: its
// line function sigma(tau) = s0 + s1 tau + s2 tau^2 (tau = t - now, exact_line_poly) taken on
// the side the pair is on, the minimum s0 - s1^2 / (4 s2) against the radius times |e|
// (squared: no square root) or against zero. Exactly at the radius is a graze: Misses.
// Undecided where the test does not apply (touching or overlapping at now, not approaching,
// concave, or behind a polygon's edge): the rounded prediction stands there.
template <class T>
GrazeVerdict exact_line_graze(const ExactBody<T>& a, const ExactBody<T>& b, const Scheduled<T>& s, const Exact& now) {
  Exact sigma[3];
  exact_line_poly(a, b, s, now, sigma);
  Exact f0 = sigma[0], s1 = sigma[1], s2 = sigma[2];
  const bool circle = s.contact == ContactKind::CircleEdge;
  const ExactBody<T>& outline = !circle ? (s.contact == ContactKind::VertexEdge ? b : a)
                                        : (a.shape->kind == ShapeKind::Circle ? b : a);
  const int side = f0.sign();
  if (side == 0 || (side < 0 && !(circle && outline.shape->kind == ShapeKind::Segment))) return GrazeVerdict::Undecided;
  if (side < 0) {
    f0 = -f0;
    s1 = -s1;
    s2 = -s2;
  }
  if (!(s2.sign() > 0 && s1.sign() < 0)) return GrazeVerdict::Undecided;
  const Exact low = Exact(4) * s2 * f0 - s1 * s1;  // 4 s2 times the minimum of sigma
  if (!circle) return low.sign() < 0 ? GrazeVerdict::Crosses : GrazeVerdict::Misses;
  const bool a_circle = a.shape->kind == ShapeKind::Circle;
  const Exact r = Exact::of((a_circle ? a : b).shape->radius);
  const ExactVec e = outline.edge(a_circle ? s.feature_b : s.feature_a);
  const Exact ee = dot(e, e);
  if (!((f0 * f0 - r * r * ee).sign() > 0)) return GrazeVerdict::Undecided;  // touching or overlapping now
  if (low.sign() < 0) return GrazeVerdict::Crosses;
  const Exact reach = Exact(4) * s2 * r;  // 4 s2 times r, against 4 s2 times the minimum, squared
  return (low * low - reach * reach * ee).sign() < 0 ? GrazeVerdict::Crosses : GrazeVerdict::Misses;
}

// Exact coefficients f[0..4] as a polynomial in integers (every coefficient times
// 2^-(least exponent): a positive multiple, with the same roots and signs).
inline detail::exact::IntPoly integer_poly(const Exact (&f)[5]) {
  detail::exact::IntPoly out;
  long low = 0;
  bool any = false;
  for (const Exact& c : f)
    if (c.d.m != 0) {
      low = any ? std::min(low, c.d.e) : c.d.e;
      any = true;
    }
  for (int k = 0; k < 5; ++k)
    if (f[k].d.m != 0) out.c[k] = f[k].d.m << static_cast<unsigned>(f[k].d.e - low);
  out.degree = 4;
  while (out.degree > 0 && out.c[out.degree] == 0) --out.degree;
  return out;
}

// |d(tau)|^2 - rr^2 for the difference d of two point paths.
inline detail::exact::IntPoly exact_distance_poly(const ExactVec (&d)[3], const Exact& rr) {
  Exact f[5];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) f[i + j] = f[i + j] + dot(d[i], d[j]);
  f[0] = f[0] - rr * rr;
  return integer_poly(f);
}

// The exact contact polynomial of two circles in tau = t - now (a positive multiple of it, in
// integers): |pb(now + tau) - pa(now + tau)|^2 - (ra + rb)^2 from the exact paths.
template <class T>
detail::exact::IntPoly exact_circle_poly(const ExactBody<T>& a, const ExactBody<T>& b, const Exact& now) {
  ExactVec ca[3], cb[3], d[3];
  exact_point_path(a, now, ca);
  exact_point_path(b, now, cb);
  for (int k = 0; k < 3; ++k) d[k] = cb[k] - ca[k];
  return exact_distance_poly(d, Exact::of(a.shape->radius) + Exact::of(b.shape->radius));
}

// The exact contact function of a scheduled pair other than two circles, as a polynomial in
// tau = t - now (a positive multiple of it, in integers) with contact_sign's sign wherever it
// applies: circle-vertex |q|^2 - r^2 (degree 4); vertex-edge the cross product (degree 2);
// circle-edge side^2 - r^2 |e|^2 (degree 4), which is contact_sign's function while the centre
// stays on the side of the edge's line it is on at now (a segment is two-sided, so there
// always; a polygon's edge only in front: nothing if the centre is on or behind its line at now,
// where contact_sign is -1 and no polynomial is).
template <class T>
std::optional<detail::exact::IntPoly> exact_feature_poly(const ExactBody<T>& a, const ExactBody<T>& b,
                                                         const Scheduled<T>& s, const Exact& now) {
  switch (s.contact) {
    case ContactKind::CircleCircle: return exact_circle_poly(a, b, now);
    case ContactKind::CircleEdge:
    case ContactKind::CircleVertex: {
      const bool a_circle = a.shape->kind == ShapeKind::Circle;
      const ExactBody<T>& c = a_circle ? a : b;
      const ExactBody<T>& o = a_circle ? b : a;
      const std::size_t k = a_circle ? s.feature_b : s.feature_a;
      const Exact r = Exact::of(c.shape->radius);
      if (s.contact == ContactKind::CircleVertex) {
        ExactVec pc[3], pv[3], q[3];
        exact_point_path(c, now, pc);
        exact_vertex_path(o, k, now, pv);
        for (int i = 0; i < 3; ++i) q[i] = pc[i] - pv[i];
        return exact_distance_poly(q, r);
      }
      const ExactVec e = o.edge(k);
      Exact side[3], f[5];
      exact_line_poly(a, b, s, now, side);
      if (o.shape->kind == ShapeKind::Polygon && side[0].sign() <= 0) return std::nullopt;
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) f[i + j] = f[i + j] + side[i] * side[j];
      f[0] = f[0] - r * r * dot(e, e);
      return integer_poly(f);
    }
    case ContactKind::VertexEdge:
    case ContactKind::EdgeVertex: {
      Exact f[5];
      exact_line_poly(a, b, s, now, f);
      return integer_poly(f);
    }
  }
  return std::nullopt;
}

// Doublings of the step before the walk gives up (the prediction is then kept as it is).
inline constexpr int kRefineMaxDoublings = 80;

// The T nearest the exact crossing (positive before, non-positive after) closest to
// `predicted`, not before `now`: `now` itself when the pair is already touching or overlapping
// then; nothing when no crossing is found near it (a touch the exact paths never make).
// `sign(t, dt)` is the contact function's sign at t + dt, `sign.exact(t)` at an exact time
// (ContactSigner).
template <class T, class Sign> std::optional<T> correctly_rounded_crossing(const T& predicted, const T& now, Sign& sign) {
  using std::abs;
  const auto at = [&](const T& t) { return sign(t); };
  const T unit = std::max(abs(predicted) * std::numeric_limits<T>::epsilon(), std::numeric_limits<T>::denorm_min());
  T lo = predicted, hi = predicted;
  T step = unit;
  if (at(predicted) > 0) {
    for (int k = 0;; ++k) {
      if (k > kRefineMaxDoublings) return std::nullopt;
      const T next = lo + step;
      step = step * T(2);
      if (!(next > lo)) continue;
      if (at(next) <= 0) {
        hi = next;
        break;
      }
      lo = next;
    }
  } else {
    for (int k = 0;; ++k) {
      // Already touching or overlapping at `now` (left so by the previous event's rounding):
      // the overlap rule's time.
      if (hi <= now) return now;
      if (k > kRefineMaxDoublings) return std::nullopt;
      T next = hi - step;
      step = step * T(2);
      if (next < now) next = now;
      if (!(next < hi)) continue;
      if (at(next) > 0) {
        lo = next;
        break;
      }
      hi = next;
    }
  }
  // Bisect to adjacent T values: at(lo) > 0 >= at(hi).
  for (;;) {
    const T mid = lo + (hi - lo) / T(2);
    if (!(mid > lo && mid < hi)) break;
    (at(mid) > 0 ? lo : hi) = mid;
  }
  // The sign at the exact midpoint lo + (hi - lo) / 2: hi - lo is exact for adjacent values
  // (Sterbenz), and so is its half unless it is the smallest subnormal.
  const T half = (hi - lo) / T(2);
  const auto exact_mid = [&] {
    return Exact(detail::exact::midpoint(detail::exact::to_dyadic(lo), detail::exact::to_dyadic(hi)));
  };
  const int s = half + half == hi - lo ? sign(lo, half) : sign.exact(exact_mid());
  if (s > 0) return hi;  // the crossing is past the midpoint
  if (s < 0) return std::max(lo, now);
  return std::max(detail::exact::round_to_scalar<T>(exact_mid().d), now);  // exactly halfway: ties to even
}

}  // namespace refine
}  // namespace pge
