// Exact real roots of integer polynomials: the oracle's only contact with CGAL, kept behind
// this interface so that one translation unit (roots_cgal.cpp) pays CGAL's compile time.
#pragma once

#include "pge/oracle_exact.hpp"
#include "root_enclosure.hpp"

#include <memory>
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
// A hint, never a change of value: narrows r's enclosure to about 2^-bits of |x - r| by one
// Newton step from x, a point near r (see RootEnclosure::newton_from).
void refine_near(const RealRoot& r, const Dyadic& x, long bits);
// Whether r is known to be rational with the value `value` (a root made by root_at, or a
// root whose isolating interval collapsed to a point).
bool rational_value(const RealRoot& r, mpq_class& value);

}  // namespace pge::oracle::detail
