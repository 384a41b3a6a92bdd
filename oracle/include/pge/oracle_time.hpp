// An exact event time: base + r, where base is the (dyadic) time the search started from and r
// is an algebraic real, the root of an exact contact polynomial, known by an isolating interval
// that refines to any width on demand.
#pragma once

#include "pge/oracle_exact.hpp"

#include <memory>
#include <stdexcept>
#include <string>
#include <utility>

namespace pge::oracle {

namespace detail {
class RealRoot;
}

// A question about a time of a rotating body's contact (a transcendental number) that the
// referee cannot decide within its precision cap: the sign of the contact function at a point
// stays unresolved at the highest precision tried (oracle/README.md, "Rotation"). A judgement
// that meets one is reported as undecided, never as agreement.
struct UndecidedTime : std::runtime_error {
  using std::runtime_error::runtime_error;
};

class ExactTime {
 public:
  ExactTime(Dyadic base, std::shared_ptr<const detail::RealRoot> offset);
  static ExactTime at(const Dyadic& t);  // a rational time

  const Dyadic& base() const { return base_; }
  // Rationals lo <= t <= hi with hi - lo <= 2^-bits.
  std::pair<mpq_class, mpq_class> bracket(long bits) const;
  int compare(const Dyadic& t) const;  // sign of (this - t), exact
  // Exact comparison of two times found from the same base (one event's search).
  // Throws std::logic_error for different bases.
  int compare(const ExactTime& o) const;
  bool operator==(const ExactTime& o) const { return compare(o) == 0; }
  bool operator<(const ExactTime& o) const { return compare(o) < 0; }

  // The representable number of format f nearest to this time (ties to even), exactly.
  Dyadic round_to(const TimeFormat& f) const;
  double to_double() const;  // nearest double
  // The first `digits` decimals after the point, truncated (not rounded), exactly:
  // "0.7071067811..." for digits = 10. Times are >= 0.
  std::string decimal(int digits) const;

  const std::shared_ptr<const detail::RealRoot>& offset() const { return offset_; }

 private:
  Dyadic base_;
  std::shared_ptr<const detail::RealRoot> offset_;
};

}  // namespace pge::oracle
