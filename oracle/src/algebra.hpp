// Vectors and polynomials (degree <= 4) over a number type N: Dyadic for the exact path,
// Interval for the filter. One body of formulas, two number types, so that the filter bounds
// exactly the function the exact path decides on.
#pragma once

#include <array>
#include <stdexcept>
#include <utility>

namespace pge::oracle {
class Dyadic;
}

namespace pge::oracle::detail {

class Interval;
// Whether x is exactly zero (model.hpp defines them).
inline bool is_exact_zero(const Dyadic& x);
inline bool is_exact_zero(const Interval& x);

template <class N> struct V2 {
  N x{}, y{};
};
template <class N> V2<N> operator+(const V2<N>& a, const V2<N>& b) { return {a.x + b.x, a.y + b.y}; }
template <class N> V2<N> operator-(const V2<N>& a, const V2<N>& b) { return {a.x - b.x, a.y - b.y}; }
template <class N> V2<N> operator*(const V2<N>& a, const N& s) { return {a.x * s, a.y * s}; }
template <class N> N dot(const V2<N>& a, const V2<N>& b) { return a.x * b.x + a.y * b.y; }
template <class N> N cross(const V2<N>& a, const V2<N>& b) { return a.x * b.y - a.y * b.x; }

inline constexpr int kMaxDegree = 4;  // contact functions of translating bodies

// p(x) = c[0] + c[1] x + ... + c[deg] x^deg (c[deg] may be zero).
template <class N> struct Poly {
  std::array<N, kMaxDegree + 1> c{};
  int deg = 0;

  static Poly constant(const N& v) {
    Poly p;
    p.c[0] = v;
    return p;
  }
};

template <class N> Poly<N> operator+(const Poly<N>& a, const Poly<N>& b) {
  Poly<N> r;
  r.deg = a.deg > b.deg ? a.deg : b.deg;
  for (int k = 0; k <= r.deg; ++k) r.c[k] = (k <= a.deg ? a.c[k] : N{}) + (k <= b.deg ? b.c[k] : N{});
  return r;
}

// Each coefficient written once, not copied first: Dyadic's are big numbers, and every copy is
// an allocation (the same values; an Interval coefficient past one operand's degree is that
// operand's own, not its sum with a zero, which would widen it by an ulp).
template <class N> Poly<N> operator-(const Poly<N>& a) {
  Poly<N> r;
  r.deg = a.deg;
  for (int k = 0; k <= r.deg; ++k) r.c[k] = -a.c[k];
  return r;
}

template <class N> Poly<N> operator-(const Poly<N>& a, const Poly<N>& b) {
  Poly<N> r;
  r.deg = a.deg > b.deg ? a.deg : b.deg;
  for (int k = 0; k <= r.deg; ++k)
    r.c[k] = k > b.deg ? a.c[k] : (k > a.deg ? -b.c[k] : a.c[k] - b.c[k]);  // a - b is a + (-b), exactly
  return r;
}

template <class N> Poly<N> operator*(const Poly<N>& a, const N& s) {
  Poly<N> r;
  r.deg = a.deg;
  for (int k = 0; k <= r.deg; ++k) r.c[k] = a.c[k] * s;
  return r;
}

// acc + term into acc, skipping a sum with an exact zero: the same value for Dyadic, without a
// copy; for Interval the exact sum itself, where the interval sum would widen it by an ulp
// (interval.hpp widens every rounded bound), so an enclosure as rigorous and a little tighter.
template <class N> void accumulate(N& acc, N&& term) {
  if (is_exact_zero(term)) return;
  if (is_exact_zero(acc)) acc = std::move(term);
  else acc = acc + term;
}

template <class N> Poly<N> operator*(const Poly<N>& a, const Poly<N>& b) {
  if (a.deg + b.deg > kMaxDegree) throw std::logic_error("oracle polynomial degree above 4");
  Poly<N> r;
  r.deg = a.deg + b.deg;
  for (int i = 0; i <= a.deg; ++i)
    for (int j = 0; j <= b.deg; ++j) accumulate(r.c[i + j], a.c[i] * b.c[j]);
  return r;
}

template <class N> Poly<N> derivative(const Poly<N>& p) {
  Poly<N> d;
  d.deg = p.deg > 0 ? p.deg - 1 : 0;
  for (int k = 1; k <= p.deg; ++k) d.c[k - 1] = p.c[k] * N(k);
  return d;
}

template <class N> N evaluate(const Poly<N>& p, const N& x) {
  N r = p.c[p.deg];
  for (int k = p.deg - 1; k >= 0; --k) r = r * x + p.c[k];
  return r;
}

// A point moving with constant acceleration: x(tau), y(tau) of degree <= 2.
template <class N> struct PointPath {
  Poly<N> x, y;
};

template <class N> PointPath<N> operator-(const PointPath<N>& a, const PointPath<N>& b) { return {a.x - b.x, a.y - b.y}; }

template <class N> PointPath<N> constant_path(const V2<N>& p) { return {Poly<N>::constant(p.x), Poly<N>::constant(p.y)}; }

template <class N> PointPath<N> shifted(const PointPath<N>& a, const V2<N>& offset) {
  PointPath<N> r;
  r.x.deg = a.x.deg;
  r.y.deg = a.y.deg;
  r.x.c[0] = a.x.c[0] + offset.x;
  r.y.c[0] = a.y.c[0] + offset.y;
  for (int k = 1; k <= a.x.deg; ++k) r.x.c[k] = a.x.c[k];
  for (int k = 1; k <= a.y.deg; ++k) r.y.c[k] = a.y.c[k];
  return r;
}

}  // namespace pge::oracle::detail
