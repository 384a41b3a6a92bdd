// Hashing the exact bits of scalars, for determinism checks.
#pragma once

#include "pge/scalar.hpp"

#include <cstdint>

namespace pge {

// FNV-1a over 64-bit words.
class StateHasher {
 public:
  void add_word(std::uint64_t w);
  void add(float x);
  void add(double x);
  void add(long double x);  // the 64-bit significand, sign and exponent: no padding bytes
  void add(const Quad& x);  // the 113-bit significand, sign and exponent
  std::uint64_t value() const { return h_; }

 private:
  std::uint64_t h_ = 0xcbf29ce484222325ull;
};

}  // namespace pge
