// pge::Quad's sin, cos, acos and cbrt: the old software type's (scalar.hpp says why). Both types
// hold the same binary128 values (but for subnormals, which the old type flushes to zero), so the
// conversions either way are exact.
#include "pge/scalar.hpp"

namespace pge::detail {

namespace {
QuadSoftware soft(const Quad& x) { return static_cast<QuadSoftware>(x); }
Quad hard(const QuadSoftware& x) { return static_cast<Quad>(x); }
}  // namespace

Quad quad_sin(const Quad& x) { return hard(boost::multiprecision::sin(soft(x))); }
Quad quad_cos(const Quad& x) { return hard(boost::multiprecision::cos(soft(x))); }
Quad quad_acos(const Quad& x) { return hard(boost::multiprecision::acos(soft(x))); }
Quad quad_cbrt(const Quad& x) { return hard(boost::multiprecision::cbrt(soft(x))); }

}  // namespace pge::detail
