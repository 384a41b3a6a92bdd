// Scalar types the engine is instantiated for, and the few traits it needs of them.
#pragma once

#if defined(__STRICT_ANSI__)
#error "pge::Quad is GCC's __float128 (Boost.Multiprecision float128): compile in the GNU dialect (-std=gnu++20; CMake: CXX_EXTENSIONS ON, its default)"
#endif

#include <boost/multiprecision/cpp_bin_float.hpp>
#include <boost/multiprecision/float128.hpp>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string_view>
#include <type_traits>

namespace pge {

// IEEE-754 binary128 (113-bit significand): GCC's __float128, its arithmetic in libgcc's software
// floating point (+, -, *, / correctly rounded), its functions in libquadmath. Until 2026-12 it was
// Boost's cpp_bin_float_quad: six times slower, and not quite binary128 (Boost 1.74 rounds about
// one sum in 2,000 of far-apart magnitudes the wrong way, tests/test_quad.cpp), so a few quad
// runs changed with it. Three things below keep the rest as they were: the square root is
// correctly rounded (libquadmath's sqrtq is not: a quarter of random inputs come out one ulp
// off), sin, cos, acos and cbrt are the old type's own, and a wider binary number converts to
// Quad rounded once.
using Quad = boost::multiprecision::float128;
using QuadSoftware = boost::multiprecision::cpp_bin_float_quad;  // the old type: same format, no subnormals

namespace detail {

__extension__ using U128 = unsigned __int128;  // GCC's (and Clang's) 128-bit integer
// A 256-bit unsigned integer, hi 2^128 + lo: the exact product of two binary128 significands.
struct U256 {
  U128 hi = 0, lo = 0;
};
inline int bit_length(U128 x) {
  const auto top = static_cast<std::uint64_t>(x >> 64), bottom = static_cast<std::uint64_t>(x);
  if (top != 0) return 128 - __builtin_clzll(top);
  return bottom != 0 ? 64 - __builtin_clzll(bottom) : 0;
}
inline int bit_length(const U256& x) { return x.hi != 0 ? 128 + bit_length(x.hi) : bit_length(x.lo); }
inline U256 multiply(U128 a, U128 b) {
  using U = U128;
  const U a0 = static_cast<std::uint64_t>(a), a1 = a >> 64, b0 = static_cast<std::uint64_t>(b), b1 = b >> 64;
  const U low = a0 * b0, cross1 = a0 * b1, cross2 = a1 * b0;
  const U cross = cross1 + cross2;
  const U cross_carry = cross < cross1 ? U(1) << 64 : U(0);  // 2^128 of `cross`: 2^192 of the product
  U256 r;
  r.lo = low + (cross << 64);
  r.hi = a1 * b1 + (cross >> 64) + cross_carry + (r.lo < low ? 1 : 0);
  return r;
}
inline U256 shifted_left(const U256& x, int k) {  // 0 <= k < 256, no bit lost (the caller's bound)
  if (k == 0) return x;
  if (k >= 128) return {x.lo << (k - 128), 0};
  return {(x.hi << k) | (x.lo >> (128 - k)), x.lo << k};
}
inline int compare(const U256& x, const U256& y) {
  if (x.hi != y.hi) return x.hi < y.hi ? -1 : 1;
  return x.lo < y.lo ? -1 : (x.lo == y.lo ? 0 : 1);
}
// sign(p 2^pe - q 2^qe), exactly, for p, q of at most 255 bits: first by their top bits' places,
// then, in one binade, on one grid (the side with the larger exponent shifted left, to at most
// the other's length). The products of quad_product_minus_sign and of x87 long doubles
// (Rounding::quick_product_error_sign, pge/detail/interval.hpp) are decided here.
inline int compare_scaled(U256 p, int pe, U256 q, int qe) {
  const bool p_zero = p.hi == 0 && p.lo == 0, q_zero = q.hi == 0 && q.lo == 0;
  if (p_zero || q_zero) return p_zero == q_zero ? 0 : (p_zero ? -1 : 1);
  const int top_p = bit_length(p) + pe, top_q = bit_length(q) + qe;
  if (top_p != top_q) return top_p > top_q ? 1 : -1;
  if (pe > qe) p = shifted_left(p, pe - qe);
  if (qe > pe) q = shifted_left(q, qe - pe);
  return compare(p, q);
}

// sign(a b - c), exactly, for any finite binary128 values (GCC's __float128), in integers: each
// value is its significand times a power of two (subnormals too), and the two significands'
// product (at most 226 bits) is compared with the third's (compare_scaled). Not finite: nothing
// (the caller decides otherwise).
inline std::optional<int> quad_product_minus_sign(const __float128& a, const __float128& b, const __float128& c) {
  struct Parts {
    U128 significand;
    int exponent;  // |x| = significand 2^exponent
    bool negative;
  };
  const auto parts = [](const __float128& x, Parts& out) {
    U128 bits;
    static_assert(sizeof bits == sizeof x);
    std::memcpy(&bits, &x, sizeof bits);
    const auto biased = static_cast<int>((bits >> 112) & 0x7fff);
    if (biased == 0x7fff) return false;
    const U128 fraction = bits & ((static_cast<U128>(1) << 112) - 1);
    out.negative = (bits >> 127) != 0;
    out.significand = biased == 0 ? fraction : fraction | (static_cast<U128>(1) << 112);
    out.exponent = (biased == 0 ? 1 : biased) - 16383 - 112;
    return true;
  };
  Parts pa{}, pb{}, pc{};
  if (!parts(a, pa) || !parts(b, pb) || !parts(c, pc)) return std::nullopt;
  const int sab = pa.significand == 0 || pb.significand == 0 ? 0 : (pa.negative != pb.negative ? -1 : 1);
  const int sc = pc.significand == 0 ? 0 : (pc.negative ? -1 : 1);
  if (sab == 0) return -sc;
  if (sc == 0 || sab != sc) return sab;
  // Same signs: sab times the comparison of |a b| with |c|.
  return sab * compare_scaled(multiply(pa.significand, pb.significand), pa.exponent + pb.exponent,
                              U256{0, pc.significand}, pc.exponent);
}

// sign(a b - c), exactly. Quad: in integers (quad_product_minus_sign), for any finite values.
// Otherwise for a b within a factor of two of c (c = a b rounded, say) and far from overflow and
// underflow, in a binary type B without a fused multiply-add: Dekker's exact product (Dekker, "A
// floating-point technique for extending the available precision", Numer. Math. 18, 1971: a
// p-bit significand splits into halves with the constant 2^ceil(p/2) + 1), then p - c exact by
// Sterbenz's lemma. (For Quad the integers take 43 ns against Dekker's 345, with the product
// itself, in software: the correctly rounded square root below takes two such signs.)
template <class B> int exact_product_minus_sign(const B& a, const B& b, const B& c) {
  if constexpr (std::is_same_v<B, Quad>) {
    if (const std::optional<int> s = quad_product_minus_sign(a.backend().value(), b.backend().value(), c.backend().value()))
      return *s;
  }
  constexpr int half = (std::numeric_limits<B>::digits + 1) / 2;
  const B split = B(std::uint64_t{1} << half) + B(1);
  const auto halves = [&](const B& x, B& hi, B& lo) {
    const B s = split * x;
    hi = s - (s - x);
    lo = x - hi;
  };
  B ah, al, bh, bl;
  halves(a, ah, al);
  halves(b, bh, bl);
  const B p = a * b;
  const B err = (((ah * bh - p) + ah * bl) + al * bh) + al * bl;  // a b - p, exactly
  const B d = (p - c) + err;
  return (d > B(0)) - (d < B(0));
}

// The correctly rounded square root (to nearest). x = m 4^k with m in [1/2, 2) (exact); r =
// sqrtq(m) is within an ulp; r is the nearest to sqrt(m) exactly when r r- < m <= r r+ (r- and
// r+ the neighbours of r: Tuckerman's test, as the midpoints' squares differ from these products by
// less than the spacing of m's multiples of 2^-226 and are never m itself); otherwise step.
inline Quad quad_sqrt(const Quad& x) {
  if (!(x > 0) || !(x < std::numeric_limits<Quad>::infinity())) return Quad(sqrtq(x.backend().value()));
  int e = 0;
  Quad m = frexp(x, &e);  // x = m 2^e, m in [1/2, 1)
  if (e % 2 != 0) {
    m = ldexp(m, 1);
    --e;
  }
  Quad r(sqrtq(m.backend().value()));
  // r's neighbours: r is positive and normal (near 1), so they are its encoding plus or minus one.
  const auto step = [](const Quad& v, int by) {
    U128 bits;
    std::memcpy(&bits, &v.backend().value(), sizeof bits);
    bits = by > 0 ? bits + 1 : bits - 1;
    __float128 out;
    std::memcpy(&out, &bits, sizeof out);
    return Quad(out);
  };
  for (int k = 0; k < 4; ++k) {
    const Quad next = step(r, 1);
    if (exact_product_minus_sign(r, next, m) >= 0) break;
    r = next;
  }
  for (int k = 0; k < 4; ++k) {
    const Quad next = step(r, -1);
    if (exact_product_minus_sign(r, next, m) < 0) break;
    r = next;
  }
  return ldexp(r, e / 2);
}

// The old type's sin, cos, acos and cbrt (engine/src/quad.cpp), so that fast's cubic roots and a
// turning body's vertices stay what they were. libquadmath's are closer (about 3% of random
// arguments in [-10, 10] not correctly rounded, against 78%), a change of results of its own.
Quad quad_sin(const Quad& x);
Quad quad_cos(const Quad& x);
Quad quad_acos(const Quad& x);
Quad quad_cbrt(const Quad& x);

}  // namespace detail

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

// Found by argument-dependent lookup from every unqualified call on a Quad (`using std::sqrt;
// sqrt(x)`), and preferred to Boost's templates for float128 as exact matches that are not templates.
namespace boost::multiprecision {
inline float128 sqrt(const float128& x) { return pge::detail::quad_sqrt(x); }
inline float128 sin(const float128& x) { return pge::detail::quad_sin(x); }
inline float128 cos(const float128& x) { return pge::detail::quad_cos(x); }
inline float128 acos(const float128& x) { return pge::detail::quad_acos(x); }
inline float128 cbrt(const float128& x) { return pge::detail::quad_cbrt(x); }
}  // namespace boost::multiprecision

// A wider binary cpp_bin_float converted to Quad: Boost's generic conversion adds the value's
// 63-bit pieces one by one, rounding each time, and misses the nearest Quad in about one case in
// 4,000; converting to the old type first (cpp_bin_float rounds once, to nearest) and then to
// Quad (exact: 113 bits fit) gives the nearest. Found by argument-dependent lookup from Boost's
// converting constructor, and more specialized than its generic template.
namespace boost::multiprecision::backends {
template <unsigned Digits, digit_base_type Base, class Allocator, class Exponent, Exponent MinE, Exponent MaxE>
void generic_interconvert(float128_backend& to, const cpp_bin_float<Digits, Base, Allocator, Exponent, MinE, MaxE>& from,
                          const mpl::int_<number_kind_floating_point>& to_kind,
                          const mpl::int_<number_kind_floating_point>& from_kind) {
  using Wide = number<cpp_bin_float<Digits, Base, Allocator, Exponent, MinE, MaxE>, et_off>;
  const pge::QuadSoftware rounded{Wide(from)};
  boost::multiprecision::detail::generic_interconvert(to, rounded.backend(), to_kind, from_kind);
}
}  // namespace boost::multiprecision::backends
