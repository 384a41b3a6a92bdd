// A certified enclosure of one real root of an integer polynomial, the fast path in front of
// CGAL (roots_cgal.cpp). Every claim it makes rests on exact signs of the polynomial at dyadic
// points, never on floating point: floating point only proposes where to look (Newton steps
// with a double quotient), exact evaluation decides.
//
// The invariant: lo < root < hi, p(lo) and p(hi) non-zero with opposite signs, and p has no
// other root in (lo, hi) (the interval it was made from isolated the root, and it only ever
// shrinks to sub-intervals with a sign change, which hold that root). Or a point: the root is
// the dyadic number lo == hi itself. Comparing with x inside (lo, hi) is one exact evaluation
// of p at x: zero means the root is x; otherwise the sign tells the side, since p keeps the
// sign of p(lo) on (lo, root) and the other sign on (root, hi) (the only root there, of odd
// multiplicity: the sign changes across it).
#pragma once

#include "pge/oracle_exact.hpp"

#include <optional>
#include <utility>
#include <vector>

namespace pge::oracle::detail {

// c[0] + c[1] x + c[2] x^2 + ..., no leading zero; empty is the zero polynomial.
using IntPoly = std::vector<mpz_class>;

// The exact sign of p at x.
int sign_at(const IntPoly& p, const Dyadic& x);

class RootEnclosure {
 public:
  // The root x itself.
  static RootEnclosure point(const Dyadic& x);
  // The root of p in (lo, hi), an isolating interval (the caller's promise: p has no other root
  // there). Checked: p(lo) and p(hi) must be non-zero with opposite signs, else nothing.
  static std::optional<RootEnclosure> isolated(IntPoly p, const Dyadic& lo, const Dyadic& hi);

  bool is_point() const { return point_; }
  const Dyadic& lo() const { return lo_; }
  const Dyadic& hi() const { return hi_; }
  const IntPoly& polynomial() const { return p_; }

  // The sign of (root - x), exact; an x inside the enclosure becomes one of its ends.
  int compare(const Dyadic& x);
  int compare(const mpq_class& x);
  // Shrinks the enclosure until hi - lo <= 2^-bits (or it is a point).
  void narrow(long bits);
  // One Newton step from x (a point near the root, inside the enclosure or not) with a quotient
  // good to `bits` bits, and probes at 2^-bits of the step's size on either side of where it
  // lands: with x near a simple root the enclosure shrinks to about 2^-bits of |x - root| in
  // four exact evaluations. Probes that miss the root only shrink it less; never wrong.
  void newton_from(const Dyadic& x, long bits);
  // The sign of q at the root, if interval evaluation over the enclosure (narrowed a few times)
  // decides it; nothing when q may vanish at the root (then only an exact gcd can tell).
  std::optional<int> sign_of(const IntPoly& q);

 private:
  RootEnclosure() = default;
  // Evaluates p at z strictly inside (lo, hi) and moves an end to z (or makes the root z).
  void probe(const Dyadic& z);
  // p(x) / p'(x) in double (a proposal, not a bound), x inside the enclosure; probes x.
  std::optional<double> newton_quotient(const Dyadic& x);
  Dyadic midpoint() const { return (lo_ + hi_).scaled(-1); }

  IntPoly p_, dp_;
  Dyadic lo_, hi_;
  int sign_lo_ = 0;  // the sign of p(lo)
  bool point_ = false;
};

// The sign of (a - b) if their enclosures separate after a few narrowings; nothing if they still
// overlap (the roots may be equal: only an exact gcd can tell).
std::optional<int> compare(RootEnclosure& a, RootEnclosure& b);

// The two real roots of a quadratic p (degree 2) with a positive discriminant, ascending, each
// in an isolating enclosure proved by four exact signs; nothing when the discriminant is not
// positive, a root is 0, or the roots are too close to isolate at 2^-40 relative width.
std::optional<std::pair<RootEnclosure, RootEnclosure>> quadratic_roots(const IntPoly& p);

}  // namespace pge::oracle::detail
