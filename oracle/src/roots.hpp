// Exact real roots of integer polynomials: the oracle's only contact with CGAL, kept behind
// this interface so that one translation unit (roots_cgal.cpp) pays CGAL's compile time.
#pragma once

#include "pge/oracle_exact.hpp"
#include "root_enclosure.hpp"

#include <cstdint>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

namespace pge::oracle::detail {

// An algebraic real number (a root of an integer polynomial with an isolating interval that
// refines on demand). Opaque: defined in roots_cgal.cpp.
class RealRoot;
using RootHandle = std::shared_ptr<const RealRoot>;

struct RootWithMultiplicity {
  RootHandle root;
  int multiplicity = 1;
};

// A simple root of a function that is not a polynomial: a contact function of a rotating body,
// which holds sin and cos of its angle (rotating.cpp). Known by lo < root < hi with the function
// of opposite non-zero signs at the ends (or a dyadic point, lo = hi), refined in place by exact
// sign decisions at dyadic points. A sign that cannot be decided within the precision cap throws
// UndecidedTime (pge/oracle_time.hpp).
class TranscendentalRoot {
 public:
  virtual ~TranscendentalRoot() = default;
  virtual int compare(const Dyadic& x) const = 0;  // sign of (root - x)
  virtual int compare(const mpq_class& x) const = 0;
  virtual void narrow(long bits) const = 0;  // until hi - lo <= 2^-bits
  virtual Dyadic lo() const = 0;
  virtual Dyadic hi() const = 0;
};
RootHandle transcendental_root(std::shared_ptr<const TranscendentalRoot> t);
const TranscendentalRoot* transcendental_of(const RealRoot& r);  // null for an algebraic root

// Two roots of which one (at least) is transcendental and which agree to this many bits below
// the point are taken as equal: they cannot be told apart by brackets (a true tie, such as the
// two mirror-image corners of a symmetric scene, never can), and 2^-256 s is far below every
// format's resolution. Counted (tied_within_cap()).
inline constexpr long kTranscendentalTieBits = 256;
std::uint64_t tied_within_cap();

// Every real root of p (not the zero polynomial), ascending, with its multiplicity.
std::vector<RootWithMultiplicity> real_roots(const IntPoly& p);
// The exact sign of p at r: -1, 0 or 1.
int sign_at(const IntPoly& p, const RealRoot& r);
int compare(const RealRoot& a, const RealRoot& b);
int compare(const RealRoot& a, const Dyadic& x);
int compare(const RealRoot& a, const mpq_class& x);
RootHandle root_at(const Dyadic& x);  // x itself, as an algebraic real
// Rationals lo <= r <= hi with hi - lo <= 2^-bits (refines r in place).
std::pair<mpq_class, mpq_class> bracket(const RealRoot& r, long bits);
// bracket(r, bits) as dyadic numbers, when r keeps an enclosure of its own (every root but one
// only CGAL holds): the same narrowing, the same ends, without rationals.
std::optional<std::pair<Dyadic, Dyadic>> dyadic_bracket(const RealRoot& r, long bits);
// A hint, never a change of value: narrows r's enclosure to about 2^-bits of |x - r| by one
// Newton step from x, a point near r (see RootEnclosure::newton_from).
void refine_near(const RealRoot& r, const Dyadic& x, long bits);
// Whether r is known to be rational with the value `value` (a root made by root_at, or a
// root whose isolating interval collapsed to a point).
bool rational_value(const RealRoot& r, mpq_class& value);

}  // namespace pge::oracle::detail
