// A 2D vector over any scalar type.
#pragma once

#include <cmath>

namespace pge {

template <class T> struct Vec2 {
  T x{0};
  T y{0};

  Vec2() = default;
  Vec2(T x_, T y_) : x(x_), y(y_) {}

  Vec2 operator+(const Vec2& o) const { return {x + o.x, y + o.y}; }
  Vec2 operator-(const Vec2& o) const { return {x - o.x, y - o.y}; }
  Vec2 operator-() const { return {-x, -y}; }
  Vec2 operator*(const T& s) const { return {x * s, y * s}; }
  Vec2& operator+=(const Vec2& o) { x += o.x; y += o.y; return *this; }
  Vec2& operator-=(const Vec2& o) { x -= o.x; y -= o.y; return *this; }
  bool operator==(const Vec2& o) const { return x == o.x && y == o.y; }
};

template <class T> T dot(const Vec2<T>& a, const Vec2<T>& b) { return a.x * b.x + a.y * b.y; }
template <class T> T cross(const Vec2<T>& a, const Vec2<T>& b) { return a.x * b.y - a.y * b.x; }
// The left-hand perpendicular: for a counter-clockwise edge it points outward on the right, so
// callers orient it explicitly.
template <class T> Vec2<T> perp(const Vec2<T>& a) { return {-a.y, a.x}; }

// v turned counter-clockwise by `angle` radians: a turning body's vertex about its pivot, the
// engine's, the checks' and the pictures' alike.
template <class T> Vec2<T> rotated(const T& angle, const Vec2<T>& v) {
  using std::cos;
  using std::sin;
  const T c = cos(angle), s = sin(angle);
  return {c * v.x - s * v.y, s * v.x + c * v.y};
}

template <class U, class T> Vec2<U> vec_cast(const Vec2<T>& v) {
  return {static_cast<U>(v.x), static_cast<U>(v.y)};
}

using Vec2d = Vec2<double>;

}  // namespace pge
