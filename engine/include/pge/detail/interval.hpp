// Rigorous interval arithmetic in a floating-point type B (float, double, long double, Quad), and
// enclosures of sin and cos with proven error terms: what the rotating contact solver
// (roots_rotating.hpp) evaluates its contact functions in, so that a sign it relies on is a sign
// of the exact function of the stored paths.
//
// Rounding. Each bound is rounded to nearest (B's arithmetic, never a change of the FPU mode) and
// moved one representable value outward only when its exact rounding error points inward
// (Rounding below): the result is what directed rounding gives. This needs IEEE arithmetic without
// contraction or extended evaluation (the build's -ffp-contract=off, SSE2); Quad's software
// arithmetic rounds correctly too. Exact results, zeros among them, stay unwidened: widening
// exact zeros would fill the enclosures with subnormals, which x86 handles in slow microcode.
// NaN bounds widen to the whole line.
//
// sin and cos. x is reduced to r = x - k pi/2 with |r| <~ pi/4, pi/2 split in three parts so that
// k P1 and k P2 are exact for |k| < 2^(p - p/2 - 1) (Cody and Waite, "Software Manual for the
// Elementary Functions", 1980, ch. 8) and the last part an enclosure; then r = a + d with a the
// nearest multiple of 1/32 (d = r - a exact, |d| <= 1/64), sin r = sin a cos d + cos a sin d and
// cos r = cos a cos d - sin a sin d from tabulated enclosures of sin a and cos a (computed in 332
// bits) and Taylor polynomials in d^2 with enclosures of the reciprocal factorials and the
// Lagrange remainder |d|^(n+1) / (n+1)! added as an interval: four and four terms in double
// where |r| <= 0.8 would need eleven and eleven (the table is Tang's idea for exp and log:
// "Table-driven implementation of the exponential function in IEEE floating-point arithmetic",
// ACM TOMS 15, 1989). Over a wide interval the range is the hull of the two
// end values and of +-1 at every extremum k pi/2 it may contain (decided from the reductions of
// the ends, conservatively: a doubtful extremum is included).
#pragma once

#include "pge/scalar.hpp"

#include <boost/math/constants/constants.hpp>
#include <boost/multiprecision/cpp_bin_float.hpp>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <type_traits>
#include <vector>

namespace pge::detail {

template <class B> B interval_next_up(const B& x) {
  if (!(x < std::numeric_limits<B>::infinity())) return x;  // +inf or NaN
  if (x == B(0)) return std::numeric_limits<B>::denorm_min();
  if constexpr (std::is_same_v<B, double> || std::is_same_v<B, float>) {
    using U = std::conditional_t<std::is_same_v<B, double>, std::uint64_t, std::uint32_t>;
    const U bits = std::bit_cast<U>(x);
    return std::bit_cast<B>(x > B(0) ? U(bits + 1) : U(bits - 1));
  } else if constexpr (std::is_same_v<B, long double> && std::numeric_limits<long double>::digits == 64) {
    // x87 extended: an explicit 64-bit significand (integer bit set in normal numbers) and a
    // 15-bit biased exponent with the sign. A normal value steps by one in the significand,
    // carrying into the exponent; the rest (subnormals, the binades next to them) goes to libm,
    // whose nextafterl is ten times slower (a tenth of a rotating search's time).
    struct Parts {
      std::uint64_t significand;
      std::uint16_t sign_exponent;
    };
    Parts p{};
    std::memcpy(&p, &x, sizeof p);
    const unsigned exponent = p.sign_exponent & 0x7fffu;
    const bool negative = (p.sign_exponent & 0x8000u) != 0;
    constexpr std::uint64_t integer_bit = std::uint64_t{1} << 63;
    if (exponent > 1 && exponent < 0x7ffe && (p.significand & integer_bit) != 0) {
      if (!negative) {
        if (++p.significand == 0) {
          p.significand = integer_bit;
          ++p.sign_exponent;
        }
      } else if (p.significand-- == integer_bit) {
        p.significand = ~std::uint64_t{0};
        --p.sign_exponent;
      }
      long double r;
      std::memcpy(&r, &p, sizeof p);
      return r;
    }
    return std::nextafter(x, std::numeric_limits<B>::infinity());
  } else if constexpr (std::is_floating_point_v<B>) {
    return std::nextafter(x, std::numeric_limits<B>::infinity());
  } else {
    static_assert(std::is_same_v<B, Quad>, "intervals are over float, double, long double or Quad");
    return Quad(nextafterq(x.backend().value(), std::numeric_limits<Quad>::infinity().backend().value()));
  }
}
template <class B> B interval_next_down(const B& x) { return -interval_next_up<B>(-x); }

// Directed rounding emulated in round-to-nearest: the bound on the exact result of a + b, x * y
// or a / d from the rounded result r and the sign of its exact error (TwoSum, Knuth, TAOCP vol. 2,
// 4.2.2; the error of a product or quotient from one fused multiply-add, exact when no bound is
// near underflow). An exact result is not widened, so intervals stay as tight as with the FPU in
// directed modes. Past underflow or overflow the bounds widen by one ulp each way instead.
template <class B> struct Rounding {
  static constexpr bool builtin = std::is_floating_point_v<B>;
  // Below this the error terms may underflow; past max() / 2 the sums may overflow.
  static B tiny() { return std::numeric_limits<B>::min() / std::numeric_limits<B>::epsilon() * B(8); }
  static bool ordinary(const B& r) {
    const B m = r < B(0) ? B(-r) : r;
    return m > tiny() && m < std::numeric_limits<B>::max() / B(4);
  }
  // a + b - r, exact (TwoSum) where r = fl(a + b) is ordinary
  static B sum_error(const B& a, const B& b, const B& r) {
    const B bb = r - a;
    return (a - (r - bb)) + (b - bb);
  }
  // sign(a + b - r)
  static int sum_error_sign(const B& a, const B& b, const B& r) {
    const B e = sum_error(a, b, r);
    return (e > B(0)) - (e < B(0));
  }
  // sign(x y - r): one fused multiply-add for double (exact by IEEE 754: x y - r rounded once,
  // and its sign is the exact error's), Dekker's exact product (pge/scalar.hpp) for float and
  // long double, the significands' product in integers for Quad (pge/scalar.hpp).
  static int product_error_sign(const B& x, const B& y, const B& r) {
    if constexpr (std::is_same_v<B, double>) {
      const B e = std::fma(x, y, -r);
      return (e > B(0)) - (e < B(0));
    } else {
      return exact_product_minus_sign(x, y, r);
    }
  }
  // The same for an ordinary r (x and y finite and non-zero) where it comes cheaply, true then:
  // double's fused multiply-add needs no splitting whatever the factors' sizes, float's product
  // is exact in double, and two normal x87 long doubles are compared in integers (their 64-bit
  // significands' 128-bit product against the result's significand, shifted by the exponents).
  // False where the general path must decide (other types; long double factors that are not
  // normal numbers).
  static bool quick_product_error_sign(const B& x, const B& y, const B& r, int& sign) {
    if constexpr (std::is_same_v<B, double>) {
      sign = product_error_sign(x, y, r);
      return true;
    } else if constexpr (std::is_same_v<B, float>) {
      // x y is exact in double (24 + 24 bits), and a rounded difference has the exact one's sign.
      const double e = double(x) * double(y) - double(r);
      sign = (e > 0.0) - (e < 0.0);
      return true;
    } else if constexpr (x87_long_double) {
      struct Parts {
        std::uint64_t significand;
        std::uint16_t sign_exponent;
      };
      Parts px{}, py{}, pr{};
      std::memcpy(&px, &x, sizeof px);
      std::memcpy(&py, &y, sizeof py);
      std::memcpy(&pr, &r, sizeof pr);
      constexpr std::uint64_t integer_bit = std::uint64_t{1} << 63;
      const int ex = px.sign_exponent & 0x7fff, ey = py.sign_exponent & 0x7fff, er = pr.sign_exponent & 0x7fff;
      if ((px.significand & py.significand & integer_bit) == 0 || ex == 0 || ey == 0 || ex == 0x7fff || ey == 0x7fff)
        return false;
      // |x| = mx 2^(ex - 16446) for a normal x (bias 16383, 63 fraction bits), r (ordinary) too:
      // |x y| - |r| has the sign of the significands' 128-bit product against r's, scaled.
      constexpr int bias = 16446;
      const int magnitude = detail::compare_scaled(
          detail::U256{0, static_cast<U128>(px.significand) * py.significand}, ex + ey - 2 * bias,
          detail::U256{0, pr.significand}, er - bias);
      sign = (x < B(0)) != (y < B(0)) ? -magnitude : magnitude;
      return true;
    } else {
      static_assert(!quick_products);
      return false;
    }
  }
  static constexpr bool x87_long_double =
      std::is_same_v<B, long double> && std::numeric_limits<long double>::digits == 64;
  static constexpr bool quick_products = std::is_same_v<B, double> || std::is_same_v<B, float> || x87_long_double;
  // float and double: an ordinary r moved to the next value up (or down) when `step`, in
  // integers and without a branch on `step`: an error's sign is as good as random, so a branch on
  // it mispredicts about half the time, which cost more than the arithmetic (bench_scale
  // spinning_polygons/1000, the emulated roundings half its time: 1,380-1,560 -> 2,110-2,230
  // events/s). An ordinary value is normal, finite and far from both ends of the range, so one
  // step in its bits is the next value and stays ordinary. (The same in an x87 long double's
  // significand, carrying into its exponent, was slower than the branch: 2,040-2,100 events/s
  // with it, the value's round trip through memory costing more than the mispredictions saved.)
  static constexpr bool branch_free = std::is_same_v<B, double> || std::is_same_v<B, float>;
  using Bits = std::conditional_t<std::is_same_v<B, float>, std::uint32_t, std::uint64_t>;
  // Up moves a positive value away from 0 and a negative one towards it: +s on the bits, less
  // 2 s for a negative value (down the reverse).
  static B step_up_if(const B& r, bool step) {
    const Bits bits = std::bit_cast<Bits>(r), s = Bits(step), turn = Bits((s & (bits >> (8 * sizeof(Bits) - 1))) << 1);
    return std::bit_cast<B>(Bits(bits + s - turn));
  }
  static B step_down_if(const B& r, bool step) {
    const Bits bits = std::bit_cast<Bits>(r), s = Bits(step), turn = Bits((s & (bits >> (8 * sizeof(Bits) - 1))) << 1);
    return std::bit_cast<B>(Bits(bits - s + turn));
  }
  static B down_if(const B& r, bool step) {
    if constexpr (branch_free) return step_down_if(r, step);
    else return step ? interval_next_down(r) : r;
  }
  static B up_if(const B& r, bool step) {
    if constexpr (branch_free) return step_up_if(r, step);
    else return step ? interval_next_up(r) : r;
  }
  // Whether Dekker's splitting of x and y cannot overflow.
  static bool splittable(const B& x, const B& y) {
    const B limit = std::numeric_limits<B>::max() * std::numeric_limits<B>::epsilon() / B(8);
    return (x < B(0) ? B(-x) : x) < limit && (y < B(0) ? B(-y) : y) < limit;
  }
  // sign(a / d - r) for d > 0: the sign of a - r d
  static int quotient_error_sign(const B& a, const B& d, const B& r) { return -product_error_sign(r, d, a); }

  static B down(const B& r, int error_sign) {
    if (r == B(0) && error_sign == 0) return r;
    if (!ordinary(r)) return interval_next_down(r);
    return error_sign < 0 ? interval_next_down(r) : r;
  }
  static B up(const B& r, int error_sign) {
    if (r == B(0) && error_sign == 0) return r;
    if (!ordinary(r)) return interval_next_up(r);
    return error_sign > 0 ? interval_next_up(r) : r;
  }
  static B add_down(const B& a, const B& b) {
    const B r = a + b;
    if constexpr (branch_free) {
      if (ordinary(r)) return step_down_if(r, sum_error(a, b, r) < B(0));
    }
    return down(r, sum_error_sign(a, b, r));
  }
  static B add_up(const B& a, const B& b) {
    const B r = a + b;
    if constexpr (branch_free) {
      if (ordinary(r)) return step_up_if(r, sum_error(a, b, r) > B(0));
    }
    return up(r, sum_error_sign(a, b, r));
  }
  // An ordinary product (the common case) is stepped outward by its error's sign alone where
  // that comes cheaply (quick_product_error_sign); zeros, underflow, overflow and the rest take
  // the general path. The same bounds as the general path's wherever that one can split the
  // factors; past that (double factors beyond about 2^970) exact where it widened by an ulp.
  static B mul_down(const B& x, const B& y) {
    if constexpr (quick_products) {
      const B r = x * y;
      int e = 0;
      if (ordinary(r) && quick_product_error_sign(x, y, r, e)) return down_if(r, e < 0);
    }
    if (x == B(0) || y == B(0)) return B(0);
    const B r = x * y;
    return down(r, ordinary(r) && splittable(x, y) ? product_error_sign(x, y, r) : -1);
  }
  static B mul_up(const B& x, const B& y) {
    if constexpr (quick_products) {
      const B r = x * y;
      int e = 0;
      if (ordinary(r) && quick_product_error_sign(x, y, r, e)) return up_if(r, e > 0);
    }
    if (x == B(0) || y == B(0)) return B(0);
    const B r = x * y;
    return up(r, ordinary(r) && splittable(x, y) ? product_error_sign(x, y, r) : 1);
  }
  // A quotient's error sign is that of r d - a, exact only where a is ordinary too: below that
  // the difference can fall under the smallest subnormal and round to zero (2^-1026 divided by
  // 2^-106 (1 + 2^-52) in double), and the bound widens by a value instead.
  static B div_down(const B& a, const B& d) {
    if (a == B(0)) return B(0);
    const B r = a / d;
    return down(r, ordinary(r) && ordinary(a) && splittable(r, d) ? quotient_error_sign(a, d, r) : -1);
  }
  static B div_up(const B& a, const B& d) {
    if (a == B(0)) return B(0);
    const B r = a / d;
    return up(r, ordinary(r) && ordinary(a) && splittable(r, d) ? quotient_error_sign(a, d, r) : 1);
  }
};

template <class B> class Interval {
 public:
  Interval() : lo_(0), hi_(0) {}
  Interval(const B& v) : lo_(v), hi_(v) {}  // NOLINT: values of B are exact
  Interval(const B& lo, const B& hi) : lo_(lo), hi_(hi) {
    if (!(lo_ <= hi_)) *this = whole();  // NaN, or bounds crossed by an overflow
  }
  static Interval whole() {
    Interval r;
    r.lo_ = -std::numeric_limits<B>::infinity();
    r.hi_ = std::numeric_limits<B>::infinity();
    return r;
  }

  const B& lo() const { return lo_; }
  const B& hi() const { return hi_; }
  B mid() const { return lo_ / B(2) + hi_ / B(2); }
  B width() const { return hi_ - lo_; }
  B magnitude() const { return std::max(abs(lo_), abs(hi_)); }
  bool positive() const { return lo_ > B(0); }  // certainly > 0
  bool negative() const { return hi_ < B(0); }  // certainly < 0
  int sign() const { return positive() ? 1 : negative() ? -1 : 0; }  // certain sign; 0 if it may be 0
  bool contains(const B& x) const { return lo_ <= x && x <= hi_; }
  bool contains_zero() const { return contains(B(0)); }

  friend Interval operator-(const Interval& a) { return raw(-a.hi_, -a.lo_); }
  friend Interval operator+(const Interval& a, const Interval& b) {
    return raw(R::add_down(a.lo_, b.lo_), R::add_up(a.hi_, b.hi_));
  }
  friend Interval operator-(const Interval& a, const Interval& b) {
    return raw(R::add_down(a.lo_, -b.hi_), R::add_up(a.hi_, -b.lo_));
  }
  friend Interval operator*(const Interval& a, const Interval& b) {
    // By the signs of the factors (nine cases, two products each except when both straddle 0).
    const B &al = a.lo_, &ah = a.hi_, &bl = b.lo_, &bh = b.hi_;
    if (al >= B(0)) {
      if (bl >= B(0)) return raw(R::mul_down(al, bl), R::mul_up(ah, bh));
      if (bh <= B(0)) return raw(R::mul_down(ah, bl), R::mul_up(al, bh));
      return raw(R::mul_down(ah, bl), R::mul_up(ah, bh));
    }
    if (ah <= B(0)) {
      if (bl >= B(0)) return raw(R::mul_down(al, bh), R::mul_up(ah, bl));
      if (bh <= B(0)) return raw(R::mul_down(ah, bh), R::mul_up(al, bl));
      return raw(R::mul_down(al, bh), R::mul_up(al, bl));
    }
    if (bl >= B(0)) return raw(R::mul_down(al, bh), R::mul_up(ah, bh));
    if (bh <= B(0)) return raw(R::mul_down(ah, bl), R::mul_up(al, bl));
    return raw(std::min(R::mul_down(al, bh), R::mul_down(ah, bl)),
               std::max(R::mul_up(al, bl), R::mul_up(ah, bh)));
  }
  // a b + c with each bound widened one ulp outward, without the exact error terms: cheaper, and
  // as tight where the result is added to far larger terms (the tails of the Taylor series).
  friend Interval loose_mul_add(const Interval& a, const Interval& b, const Interval& c) {
    B lo = std::numeric_limits<B>::infinity(), hi = -lo;
    for (const B& x : {a.lo_, a.hi_}) {
      for (const B& y : {b.lo_, b.hi_}) {
        const B r = x * y;
        lo = std::min(lo, r);
        hi = std::max(hi, r);
      }
    }
    return raw(interval_next_down(interval_next_down(lo) + c.lo_),
               interval_next_up(interval_next_up(hi) + c.hi_));
  }
  // Division by a positive value of B.
  friend Interval operator/(const Interval& a, const B& d) {
    return raw(R::div_down(a.lo_, d), R::div_up(a.hi_, d));
  }
  Interval square() const {
    const B a = std::min(abs(lo_), abs(hi_)), b = std::max(abs(lo_), abs(hi_));
    if (lo_ >= B(0) || hi_ <= B(0)) return raw(R::mul_down(a, a), R::mul_up(b, b));
    return raw(B(0), R::mul_up(b, b));
  }
  // The square root of the non-negative part: each bound from B's sqrt, then stepped outward
  // until its square (rounded outward) is on the right side, so no claim about the library's
  // sqrt is needed.
  Interval sqrt() const {
    using std::sqrt;
    if (!(hi_ >= B(0))) return whole();
    const B l = lo_ > B(0) ? lo_ : B(0);
    B rl = sqrt(l), rh = sqrt(hi_);
    while (rl > B(0) && R::mul_up(rl, rl) > l) rl = interval_next_down(rl);
    while (R::mul_down(rh, rh) < hi_) rh = interval_next_up(rh);
    return raw(rl, rh);
  }
  friend Interval hull(const Interval& a, const Interval& b) {
    return raw(std::min(a.lo_, b.lo_), std::max(a.hi_, b.hi_));
  }
  // The common part, or `a` when they do not meet (both enclose one value: they always meet
  // unless a bound is wrong, and then the wider answer is the safe one).
  friend Interval intersect(const Interval& a, const Interval& b) {
    const B lo = std::max(a.lo_, b.lo_), hi = std::min(a.hi_, b.hi_);
    return lo <= hi ? raw(lo, hi) : a;
  }
  Interval clamp(const B& lo, const B& hi) const {
    return raw(std::max(lo_, lo), std::min(hi_, hi));
  }

 private:
  using R = Rounding<B>;
  static B abs(const B& x) { return x < B(0) ? B(-x) : x; }
  static Interval raw(const B& lo, const B& hi) {
    Interval r;
    r.lo_ = lo;
    r.hi_ = hi;
    if (!(r.lo_ <= r.hi_)) r = whole();
    return r;
  }
  B lo_, hi_;
};

// Enclosures of sin and cos over one interval of arguments.
template <class B> struct SinCos {
  Interval<B> sin, cos;
};

template <class B> class TrigTables {
 public:
  static const TrigTables& get() {
    static const TrigTables tables;
    return tables;
  }

  // The largest |x| reduced with k P1, k P2 exact; past it sin and cos are [-1, 1].
  B reduce_limit;
  B p1, p2;            // pi/2 = p1 + p2 + p3, p1 and p2 with half of B's digits
  Interval<B> p3;
  B two_over_pi;       // rounded: picks k, any k works (the reduction is exact whatever it is)
  Interval<B> two_pi;  // for "wider than a turn"
  // sin r = r (s[0] + s[1] r^2 + ... ) + E, cos r = c[0] + c[1] r^2 + ... + E, with the
  // coefficients' enclosures and the number of terms such that the remainder for |r| <= 0.8 is
  // below B's epsilon / 64.
  std::vector<Interval<B>> sin_coef, cos_coef;
  // For |r| <= reduced_max, the terms left out: r^(2n+3) / (2n+3)! and r^(2n+2) / (2n+2)!
  // (n + 1 terms kept) bound the rest of these alternating series with decreasing terms.
  B reduced_max;
  B sin_remainder, cos_remainder;
  // The table: sin and cos of j / kSteps for |j| <= table_half (covering |r| <= reduced_max), and
  // the series for |d| <= step_max (1 / (2 kSteps), rounded up) with their remainders.
  static constexpr int kSteps = 32;
  int table_half = 0;
  std::vector<Interval<B>> table_sin, table_cos;  // index j + table_half
  B step_max;
  std::vector<Interval<B>> step_sin_coef, step_cos_coef;
  B step_sin_remainder, step_cos_remainder;

 private:
  using High = boost::multiprecision::cpp_bin_float_100;  // 332 bits: far past Quad's 113

  static Interval<B> enclose(const High& v) {
    const B r = static_cast<B>(v);
    return Interval<B>(interval_next_down(r), interval_next_up(r));
  }
  // v truncated to `bits` significant bits (v > 0).
  static High truncate_bits(const High& v, int bits) {
    int e = 0;
    const High m = boost::multiprecision::frexp(v, &e);  // v = m 2^e, m in [0.5, 1)
    return boost::multiprecision::ldexp(boost::multiprecision::trunc(boost::multiprecision::ldexp(m, bits)),
                                        e - bits);
  }

  TrigTables() {
    const int digits = std::numeric_limits<B>::digits;
    const int half = digits / 2;
    const High half_pi = boost::math::constants::half_pi<High>();
    const High h1 = truncate_bits(half_pi, half);
    const High h2 = truncate_bits(half_pi - h1, half);
    p1 = static_cast<B>(h1);
    p2 = static_cast<B>(h2);
    p3 = enclose(half_pi - h1 - h2);
    // k P1 is exact while k has at most digits - half bits; x ~ k pi / 2.
    reduce_limit = static_cast<B>(boost::multiprecision::ldexp(High(1), digits - half - 2));
    two_over_pi = static_cast<B>(2 / boost::math::constants::pi<High>());
    two_pi = enclose(boost::math::constants::two_pi<High>());

    const High tiny = boost::multiprecision::ldexp(High(1), -digits - 6);
    const High r_max = High(0.8);  // > pi/4 + the reduction's error
    reduced_max = static_cast<B>(r_max);
    if (High(reduced_max) > r_max) reduced_max = interval_next_down(reduced_max);
    // sin: terms (-1)^n r^(2n+1) / (2n+1)!, cos: (-1)^n r^(2n) / (2n)!; each table stops when the
    // next term's bound at r_max is below tiny, and that bound is the remainder.
    const auto taylor = [&](int first_power, std::vector<Interval<B>>& coef, B& remainder, const High& r_top) {
      High fact = 1;  // (2n + first_power)!
      for (int n = 0;; ++n) {
        coef.push_back(enclose((n % 2 == 0 ? 1 : -1) / fact));
        const int power = 2 * n + first_power + 2;
        const High next = fact * (power - 1) * power;
        const High bound = boost::multiprecision::pow(r_top, power) / next;
        if (bound < tiny) {
          remainder = interval_next_up(static_cast<B>(bound));
          return;
        }
        fact = next;
      }
    };
    taylor(1, sin_coef, sin_remainder, r_max);
    taylor(0, cos_coef, cos_remainder, r_max);

    const High d_max = High(1) / (2 * kSteps) * (1 + boost::multiprecision::ldexp(High(1), -20));
    step_max = static_cast<B>(d_max);
    if (High(step_max) > d_max) step_max = interval_next_down(step_max);
    taylor(1, step_sin_coef, step_sin_remainder, d_max);
    taylor(0, step_cos_coef, step_cos_remainder, d_max);
    table_half = static_cast<int>(boost::multiprecision::ceil(r_max * kSteps)) + 1;
    for (int j = -table_half; j <= table_half; ++j) {
      const High a = High(j) / kSteps;
      table_sin.push_back(enclose(boost::multiprecision::sin(a)));
      table_cos.push_back(enclose(boost::multiprecision::cos(a)));
    }
  }
};

// The reduction of one value x: x = k pi/2 + r, r enclosed (|r| <= pi/4 + a few ulps).
template <class B> struct Reduced {
  long long k = 0;
  Interval<B> r;
  bool ok = true;  // false past TrigTables::reduce_limit (or not finite)
};

// The integer nearest x, as a value of B: how both reductions below pick their multiple (of
// pi/2, of the table's step); each is exact whichever integer it picks.
template <class B> B nearest_integer(const B& x) {
  if constexpr (std::is_floating_point_v<B>) {
    return std::nearbyint(x);
  } else {
    using boost::multiprecision::round;
    return B(round(x));
  }
}

template <class B> Reduced<B> reduce_half_pi(const B& x) {
  const TrigTables<B>& tab = TrigTables<B>::get();
  Reduced<B> out;
  if (!(x <= tab.reduce_limit && x >= -tab.reduce_limit)) {
    out.ok = false;
    return out;
  }
  const B kb = nearest_integer(B(x * tab.two_over_pi));
  out.k = static_cast<long long>(kb);
  if (out.k == 0) {
    out.r = Interval<B>(x);
    return out;
  }
  // x - k p1 and k p1, k p2 are exact (Sterbenz; p1, p2 carry half the digits).
  const Interval<B> kk(kb);
  out.r = (Interval<B>(x) - kk * Interval<B>(tab.p1)) - kk * Interval<B>(tab.p2) - kk * tab.p3;
  return out;
}

// sin x = x (s[0] + s[1] x^2 + ...) + E and cos x = c[0] + c[1] x^2 + ... + E by Horner in x^2,
// the last `exact` steps of each with directed rounding and the earlier ones with the cheaper
// one-ulp widening (loose_mul_add: rigorous too, as a rounding to nearest is never more than one
// step off, subnormal steps included; right where those terms are scaled down by x^2 enough
// that an ulp of theirs is far below one of the result), and each remainder E (a bound for the
// |x| the coefficients were chosen for) added as an interval.
template <class B>
SinCos<B> taylor_sin_cos(const Interval<B>& x, const std::vector<Interval<B>>& sin_coef,
                         const std::vector<Interval<B>>& cos_coef, const B& sin_remainder, const B& cos_remainder,
                         std::size_t exact) {
  const Interval<B> x2 = x.square();
  const auto horner = [&](const std::vector<Interval<B>>& coef) {
    Interval<B> v = coef.back();
    for (std::size_t i = coef.size() - 1; i-- > 0;) v = i >= exact ? loose_mul_add(v, x2, coef[i]) : v * x2 + coef[i];
    return v;
  };
  return {x * horner(sin_coef) + Interval<B>(-sin_remainder, sin_remainder),
          horner(cos_coef) + Interval<B>(-cos_remainder, cos_remainder)};
}

// sin and cos of the reduced argument r (|r| <= ~0.8), each with its remainder: by the table
// where r is narrow (a reduced point), by the series over all of |r| <= 0.8 otherwise.
template <class B> SinCos<B> sin_cos_reduced(const Interval<B>& r) {
  const TrigTables<B>& tab = TrigTables<B>::get();
  if (!(r.magnitude() <= tab.reduced_max)) return {Interval<B>(B(-1), B(1)), Interval<B>(B(-1), B(1))};
  {
    const B jb = nearest_integer(B(r.mid() * B(TrigTables<B>::kSteps)));
    const int j = static_cast<int>(jb);
    // a = j / kSteps exactly (a power of two); d = r - a, enclosed whether or not it is exact.
    const Interval<B> d = r - Interval<B>(jb / B(TrigTables<B>::kSteps));
    if (j >= -tab.table_half && j <= tab.table_half && d.magnitude() <= tab.step_max) {
      // The series' terms past the first are scaled by d^2 <= 2^-12 at least once more: one-ulp
      // widening for them.
      const SinCos<B> sc = taylor_sin_cos(d, tab.step_sin_coef, tab.step_cos_coef, tab.step_sin_remainder,
                                          tab.step_cos_remainder, 1);
      const Interval<B>& sd = sc.sin;
      const Interval<B>& cd = sc.cos;
      const auto k = static_cast<std::size_t>(j + tab.table_half);
      const Interval<B>& sa = tab.table_sin[k];
      const Interval<B>& ca = tab.table_cos[k];
      return {sa * cd + ca * sd, ca * cd - sa * sd};
    }
  }
  // Horner in r^2; the terms past the second are scaled by r^2 <= 0.64 at least twice, so they
  // take the cheaper one-ulp widening.
  return taylor_sin_cos(r, tab.sin_coef, tab.cos_coef, tab.sin_remainder, tab.cos_remainder, 2);
}

template <class B> SinCos<B> sin_cos_computed(const Interval<B>& x);

// The last few hundred enclosures of sin and cos, per thread, keyed by the argument's bits: a
// rotating pair's feature functions share their waves (the two angles and their difference), and
// a prediction asks them at the same times over and over (every feature's gap at the search's
// start, each search's first box): 42% of the sines a 1,000-polygon spinning gas asks in double
// are repeats, and the memo made it 13% faster (bench_scale spinning_polygons/1000, release
// build). sin_cos is a function of the argument's two bounds alone, so a hit returns exactly what
// the computation would: the same enclosures, the same events. Over the bounds' value bits (an
// x87 long double's 10 of its 16 bytes); Quad computes every time.
template <class B> class SinCosMemo {
 public:
  static constexpr bool enabled = std::is_same_v<B, float> || std::is_same_v<B, double> ||
                                  (std::is_same_v<B, long double> && std::numeric_limits<long double>::digits == 64);
  static SinCos<B> get(const Interval<B>& x) {
    const Key key = key_of(x);
    Entry& e = entries()[slot(key)];
    if (e.used && e.key == key) return {Interval<B>(e.sin_lo, e.sin_hi), Interval<B>(e.cos_lo, e.cos_hi)};
    const SinCos<B> v = sin_cos_computed(x);
    e = {key, true, v.sin.lo(), v.sin.hi(), v.cos.lo(), v.cos.hi()};
    return v;
  }

 private:
  static constexpr std::size_t kSlots = 256;
  static constexpr std::size_t kValueBytes = std::is_same_v<B, long double> ? 10 : sizeof(B);
  using Key = std::array<std::uint64_t, 3>;  // lo's first 8 bytes, hi's, then the rest of both
  struct Entry {
    Key key;
    bool used;
    B sin_lo, sin_hi, cos_lo, cos_hi;
  };
  static Key key_of(const Interval<B>& x) {
    Key k{};
    constexpr std::size_t head = kValueBytes < 8 ? kValueBytes : 8, tail = kValueBytes - head;
    std::memcpy(&k[0], &x.lo(), head);
    std::memcpy(&k[1], &x.hi(), head);
    if constexpr (tail > 0) {
      std::memcpy(&k[2], reinterpret_cast<const unsigned char*>(&x.lo()) + head, tail);
      std::memcpy(reinterpret_cast<unsigned char*>(&k[2]) + tail, reinterpret_cast<const unsigned char*>(&x.hi()) + head, tail);
    }
    return k;
  }
  static std::size_t slot(const Key& k) {
    std::uint64_t h = k[0] * 0x9E3779B97F4A7C15ull ^ (k[1] + 0x632BE59BD9B4E019ull + (k[0] << 6)) ^ k[2];
    h ^= h >> 29;
    h *= 0xBF58476D1CE4E5B9ull;
    return static_cast<std::size_t>(h >> 56) % kSlots;
  }
  static std::array<Entry, kSlots>& entries() {
    static thread_local std::array<Entry, kSlots> table{};
    return table;
  }
};

// sin(x), cos(x) for every x in X: each contains the exact range over X (through the memo above
// where B has one).
template <class B> SinCos<B> sin_cos(const Interval<B>& x) {
  if constexpr (SinCosMemo<B>::enabled) {
    return SinCosMemo<B>::get(x);
  } else {
    return sin_cos_computed(x);
  }
}
template <class B> SinCos<B> sin_cos_computed(const Interval<B>& x) {
  const TrigTables<B>& tab = TrigTables<B>::get();
  const Interval<B> unit(B(-1), B(1));
  SinCos<B> whole{unit, unit};
  if (!(x.width() < tab.two_pi.lo())) return whole;
  const Reduced<B> a = reduce_half_pi(x.lo()), b = reduce_half_pi(x.hi());
  if (!a.ok || !b.ok) return whole;
  // sin(k pi/2 + r) and cos(k pi/2 + r) from sin r and cos r, by k mod 4.
  auto at = [](const Reduced<B>& red) {
    const SinCos<B> sc = sin_cos_reduced(red.r);
    switch (((red.k % 4) + 4) % 4) {
      case 0: return SinCos<B>{sc.sin, sc.cos};
      case 1: return SinCos<B>{sc.cos, -sc.sin};
      case 2: return SinCos<B>{-sc.sin, -sc.cos};
      default: return SinCos<B>{-sc.cos, sc.sin};
    }
  };
  SinCos<B> out = at(a);
  if (x.hi() != x.lo()) {
    const SinCos<B> e = at(b);
    out.sin = hull(out.sin, e.sin);
    out.cos = hull(out.cos, e.cos);
    // The multiples k pi/2 that may lie in X (a doubtful one is kept): k_lo <= k <= k_hi.
    const long long k_lo = a.r.lo() > B(0) ? a.k + 1 : a.k;
    const long long k_hi = b.r.hi() < B(0) ? b.k - 1 : b.k;
    B s_lo = out.sin.lo(), s_hi = out.sin.hi(), c_lo = out.cos.lo(), c_hi = out.cos.hi();
    for (long long k = k_lo; k <= k_hi; ++k) {
      switch (((k % 4) + 4) % 4) {
        case 0: c_hi = B(1); break;
        case 1: s_hi = B(1); break;
        case 2: c_lo = B(-1); break;
        default: s_lo = B(-1); break;
      }
    }
    out.sin = Interval<B>(s_lo, s_hi);
    out.cos = Interval<B>(c_lo, c_hi);
  }
  out.sin = out.sin.clamp(B(-1), B(1));
  out.cos = out.cos.clamp(B(-1), B(1));
  return out;
}

}  // namespace pge::detail
