#include "pge/hash.hpp"

#include <bit>
#include <cmath>

namespace pge {

void StateHasher::add_word(std::uint64_t w) {
  for (int i = 0; i < 8; ++i) {
    h_ ^= (w >> (8 * i)) & 0xffu;
    h_ *= 0x100000001b3ull;
  }
}

void StateHasher::add(float x) { add_word(std::bit_cast<std::uint32_t>(x)); }
void StateHasher::add(double x) { add_word(std::bit_cast<std::uint64_t>(x)); }

// Extended types carry padding bytes whose content is unspecified, so their value is taken
// apart into sign, exponent and significand bits with exact operations instead.
namespace {
template <class T> void add_decomposed(StateHasher& h, const T& x, int significand_bits) {
  using std::frexp;
  using std::isnan;
  using std::ldexp;
  using std::signbit;
  using std::floor;
  if (isnan(x)) { h.add_word(0x7ff8000000000001ull); return; }
  h.add_word(signbit(x) ? 1u : 0u);
  if (x == T(0)) { h.add_word(0); return; }
  if (x > std::numeric_limits<T>::max() || x < -std::numeric_limits<T>::max()) {
    h.add_word(0x7ff0000000000000ull);
    return;
  }
  int exponent = 0;
  T m = frexp(x < T(0) ? -x : x, &exponent);  // m in [0.5, 1): exact
  h.add_word(static_cast<std::uint64_t>(static_cast<std::int64_t>(exponent)));
  for (int taken = 0; taken < significand_bits; taken += 32) {
    m = ldexp(m, 32);  // exact: a power-of-two scaling
    const T whole = floor(m);
    h.add_word(static_cast<std::uint64_t>(whole));
    m -= whole;  // exact: removes the integer part
  }
}
}  // namespace

void StateHasher::add(long double x) { add_decomposed(*this, x, 64); }
void StateHasher::add(const Quad& x) { add_decomposed(*this, x, 113); }

}  // namespace pge
