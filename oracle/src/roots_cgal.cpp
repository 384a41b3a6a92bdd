// CGAL's Algebraic_kernel_d_1 over GMP integers: square-free factorisation and Descartes
// isolation of real roots, exact signs of polynomials at algebraic reals (gcd based when the
// value is zero), exact comparison. The only translation unit that includes CGAL.
#include "roots.hpp"

// GCC 12 reports a use after free inside CGAL's reference-counted handles (Handle_with_policy)
// when they are inlined into a priority queue: the count is read before the delete on every
// path (a known false positive of -Wuse-after-free on reference counting). Scoped to this file.
#pragma GCC diagnostic ignored "-Wuse-after-free"

#include <CGAL/Algebraic_kernel_d_1.h>
#include <CGAL/Gmpq.h>
#include <CGAL/Gmpz.h>

#include <iterator>

namespace pge::oracle::detail {

using Kernel = CGAL::Algebraic_kernel_d_1<CGAL::Gmpz>;
using Polynomial = Kernel::Polynomial_1;
using Algebraic = Kernel::Algebraic_real_1;
using Bound = Kernel::Bound;  // CGAL::Gmpq

class RealRoot {
 public:
  explicit RealRoot(Algebraic a) : value(std::move(a)) {}
  Algebraic value;  // CGAL refines its interval in place (a shared, mutable representation)
};

namespace {

const Kernel& kernel() {
  static const Kernel k;
  return k;
}

Polynomial to_cgal(const IntPoly& p) {
  std::vector<CGAL::Gmpz> c;
  c.reserve(p.size());
  for (const mpz_class& v : p) c.emplace_back(v.get_mpz_t());
  if (c.empty()) c.emplace_back(0);
  return Polynomial(c.begin(), c.end());
}

Bound to_bound(const Dyadic& x) {
  const mpq_class q = x.to_mpq();
  return Bound(q.get_mpq_t());
}

mpq_class to_mpq(const Bound& b) { return mpq_class(b.mpq()); }

int to_int(CGAL::Sign s) { return s == CGAL::NEGATIVE ? -1 : (s == CGAL::POSITIVE ? 1 : 0); }

}  // namespace

std::vector<RootWithMultiplicity> real_roots(const IntPoly& p) {
  std::vector<std::pair<Algebraic, int>> found;
  kernel().solve_1_object()(to_cgal(p), std::back_inserter(found));
  std::vector<RootWithMultiplicity> out;
  out.reserve(found.size());
  for (auto& [root, mult] : found) out.push_back({std::make_shared<const RealRoot>(root), mult});
  return out;
}

int sign_at(const IntPoly& p, const RealRoot& r) {
  return to_int(kernel().sign_at_1_object()(to_cgal(p), r.value));
}

int compare(const RealRoot& a, const RealRoot& b) {
  return to_int(kernel().compare_1_object()(a.value, b.value));
}

int compare(const RealRoot& a, const Dyadic& x) {
  return to_int(kernel().compare_1_object()(a.value, to_bound(x)));
}

int compare(const RealRoot& a, const mpq_class& x) {
  return to_int(kernel().compare_1_object()(a.value, Bound(x.get_mpq_t())));
}

RootHandle root_at(const Dyadic& x) {
  return std::make_shared<const RealRoot>(kernel().construct_algebraic_real_1_object()(to_bound(x)));
}

std::pair<mpq_class, mpq_class> bracket(const RealRoot& r, long bits) {
  const auto [lo, hi] = kernel().approximate_absolute_1_object()(r.value, static_cast<int>(bits));
  return {to_mpq(lo), to_mpq(hi)};
}

bool rational_value(const RealRoot& r, mpq_class& value) {
  if (r.value.low() != r.value.high()) return false;
  value = to_mpq(r.value.low());
  return true;
}

}  // namespace pge::oracle::detail
