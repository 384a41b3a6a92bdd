// Scalar types the engine is instantiated for, and the few traits it needs of them.
#pragma once

#include <boost/multiprecision/cpp_bin_float.hpp>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string_view>
#include <type_traits>

namespace pge {

// IEEE-754 binary128 semantics (113-bit significand), in software, header-only.
// Slow, but exact to its precision and available without libquadmath.
using Quad = boost::multiprecision::cpp_bin_float_quad;

enum class ScalarKind { Float, Double, LongDouble, QuadPrecision };

template <class T> struct ScalarTraits;
template <> struct ScalarTraits<float> {
  static constexpr ScalarKind kind = ScalarKind::Float;
  static constexpr std::string_view name = "float";
};
template <> struct ScalarTraits<double> {
  static constexpr ScalarKind kind = ScalarKind::Double;
  static constexpr std::string_view name = "double";
};
template <> struct ScalarTraits<long double> {
  static constexpr ScalarKind kind = ScalarKind::LongDouble;
  static constexpr std::string_view name = "long double";
};
template <> struct ScalarTraits<Quad> {
  static constexpr ScalarKind kind = ScalarKind::QuadPrecision;
  static constexpr std::string_view name = "quad";
};

std::string_view scalar_name(ScalarKind kind);
// Parses "float", "double", "long-double" (or "long double"), "quad"; false if unknown.
bool parse_scalar_kind(std::string_view text, ScalarKind& out);

// Calls f(std::type_identity<T>{}) for the type T of `kind` (float, double, long double, Quad)
// and returns what it returns: the one switch from a scalar named at run time (a command-line
// option, a report setting) to the template instantiated for it.
template <class F> auto with_scalar(ScalarKind kind, F&& f) {
  switch (kind) {
    case ScalarKind::Float: return f(std::type_identity<float>{});
    case ScalarKind::Double: return f(std::type_identity<double>{});
    case ScalarKind::LongDouble: return f(std::type_identity<long double>{});
    case ScalarKind::QuadPrecision: return f(std::type_identity<Quad>{});
  }
  throw std::logic_error("unknown scalar kind");
}

// Conversion to double for output; exact for float and double, rounded otherwise.
template <class T> double to_double(const T& x) { return static_cast<double>(x); }

}  // namespace pge
