#include "pge/oracle_time.hpp"

#include "roots.hpp"

#include <stdexcept>

namespace pge::oracle {
namespace {

long bit_length(const mpz_class& m) { return static_cast<long>(mpz_sizeinbase(m.get_mpz_t(), 2)); }

// Of two adjacent representable numbers, the one with the even significand (even ordinal).
Dyadic even_of(const Dyadic& a, const Dyadic& b, const TimeFormat& f) {
  return mpz_even_p(format_ordinal(a, f).get_mpz_t()) ? a : b;
}

}  // namespace

ExactTime::ExactTime(Dyadic base, std::shared_ptr<const detail::RealRoot> offset)
    : base_(std::move(base)), offset_(std::move(offset)) {}

ExactTime ExactTime::at(const Dyadic& t) { return ExactTime(t, detail::root_at(Dyadic())); }

std::pair<mpq_class, mpq_class> ExactTime::bracket(long bits) const {
  auto [lo, hi] = detail::bracket(*offset_, bits);
  const mpq_class b = base_.to_mpq();
  return {lo + b, hi + b};
}

int ExactTime::compare(const Dyadic& t) const { return detail::compare(*offset_, t - base_); }

int ExactTime::compare(const ExactTime& o) const {
  if (base_ != o.base_) throw std::logic_error("ExactTime::compare: times from different searches");
  return detail::compare(*offset_, *o.offset_);
}

Dyadic ExactTime::round_to(const TimeFormat& f) const {
  // A first approximation fine enough to fix the binade (relative error below 2^-8), or the
  // subnormal range if the time is that small.
  long bits = 64;
  long binade = f.min_exponent - 1;
  const long enough_for_subnormals = f.digits - f.min_exponent + 8;
  for (;;) {
    const Dyadic a = grid_floor(bracket(bits).first, bits);
    if (!a.is_zero() && bit_length(a.mantissa()) - 1 + a.exponent() >= 8 - bits) {
      binade = std::max(binade, bit_length(a.mantissa()) - 1 + a.exponent() - 1);
      break;
    }
    if (bits > enough_for_subnormals) break;
    bits *= 4;
  }
  if (compare(Dyadic()) == 0) return Dyadic();
  // Within a quarter quantum of the time, then walk to the representable number whose rounding
  // cell (between the midpoints to its neighbours) holds the exact time.
  const long quantum = std::max(binade, static_cast<long>(f.min_exponent) - 1) - f.digits + 1;
  const long fine = 2 - quantum;
  Dyadic c = round_to_format(grid_floor(bracket(fine).first, fine), f);
  for (;;) {
    const Dyadic below = format_step(c, -1, f), above = format_step(c, 1, f);
    const int lo = compare((below + c).scaled(-1));
    if (lo < 0) { c = below; continue; }
    if (lo == 0) return even_of(below, c, f);
    const int hi = compare((c + above).scaled(-1));
    if (hi > 0) { c = above; continue; }
    if (hi == 0) return even_of(c, above, f);
    return c;
  }
}

double ExactTime::to_double() const { return round_to(TimeFormat::of<double>()).to_double(); }

std::string ExactTime::decimal(int digits) const {
  mpz_class scale = 1;
  for (int k = 0; k < digits; ++k) scale *= 10;
  // 10^d < 2^(3.33 d): this many bits more than separates consecutive multiples of 10^-d.
  const long bits = 4L * digits + 8;
  mpz_class n_lo, n_hi;
  if (const auto b = detail::dyadic_bracket(*offset_, bits)) {
    // The same bracket in dyadic numbers: floor(m 2^e 10^d) without rationals.
    const auto scaled_floor = [&](mpz_class& n, const Dyadic& x) {
      n = x.mantissa() * scale;
      if (x.exponent() >= 0) mpz_mul_2exp(n.get_mpz_t(), n.get_mpz_t(), static_cast<mp_bitcnt_t>(x.exponent()));
      else mpz_fdiv_q_2exp(n.get_mpz_t(), n.get_mpz_t(), static_cast<mp_bitcnt_t>(-x.exponent()));
    };
    scaled_floor(n_lo, b->first + base_);
    scaled_floor(n_hi, b->second + base_);
  } else {
    const auto [lo, hi] = bracket(bits);
    const mpq_class lo_s = lo * scale, hi_s = hi * scale;
    mpz_fdiv_q(n_lo.get_mpz_t(), lo_s.get_num_mpz_t(), lo_s.get_den_mpz_t());
    mpz_fdiv_q(n_hi.get_mpz_t(), hi_s.get_num_mpz_t(), hi_s.get_den_mpz_t());
  }
  mpz_class n = n_lo;
  if (n_hi != n_lo) {
    // The bracket straddles k / 10^d (k = n_lo + 1): decide exactly which side the time is on.
    const mpq_class boundary(mpz_class(n_lo + 1), scale);
    n = detail::compare(*offset_, mpq_class(boundary - base_.to_mpq())) >= 0 ? mpz_class(n_lo + 1) : n_lo;
  }
  const mpz_class whole = n / scale, frac = n % scale;
  std::string f = frac.get_str();
  if (static_cast<int>(f.size()) < digits) f.insert(0, static_cast<std::size_t>(digits) - f.size(), '0');
  return whole.get_str() + (digits > 0 ? "." + f : "");
}

}  // namespace pge::oracle
