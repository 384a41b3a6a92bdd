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

#include <atomic>
#include <iterator>
#include <optional>

namespace pge::oracle::detail {

using Kernel = CGAL::Algebraic_kernel_d_1<CGAL::Gmpz>;
using Polynomial = Kernel::Polynomial_1;
using Algebraic = Kernel::Algebraic_real_1;
using Bound = Kernel::Bound;  // CGAL::Gmpq

// A root is known to CGAL, to a certified enclosure of its own (root_enclosure.hpp), or both:
// every question is put to the enclosure first, and to CGAL only when the enclosure cannot
// answer it (a zero of another polynomial at the root, two equal roots, a root CGAL isolated
// on a non-dyadic interval). The CGAL number is made on demand from the enclosure: the same
// polynomial and an isolating interval of it.
class RealRoot {
 public:
  explicit RealRoot(Algebraic a) : cgal_(std::move(a)) {}
  explicit RealRoot(RootEnclosure e) : enclosure_(std::move(e)), tried_(true) {}
  explicit RealRoot(std::shared_ptr<const TranscendentalRoot> t) : transcendental_(std::move(t)), tried_(true) {}

  const Algebraic& cgal() const;
  RootEnclosure* enclosure() const;
  const TranscendentalRoot* transcendental() const { return transcendental_.get(); }

 private:
  std::shared_ptr<const TranscendentalRoot> transcendental_;  // not algebraic: neither of the others
  mutable std::optional<Algebraic> cgal_;  // CGAL refines its interval in place (a shared, mutable representation)
  mutable std::optional<RootEnclosure> enclosure_;
  mutable bool tried_ = false;  // the enclosure was made, or cannot be made
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

IntPoly from_cgal(const Polynomial& p) {
  IntPoly out;
  for (int k = 0; k <= p.degree(); ++k) out.emplace_back(p[k].mpz());
  while (!out.empty() && out.back() == 0) out.pop_back();
  return out;
}

Bound to_bound(const Dyadic& x) {
  const mpq_class q = x.to_mpq();
  return Bound(q.get_mpq_t());
}

mpq_class to_mpq(const Bound& b) { return mpq_class(b.mpq()); }

// A rational that is a dyadic number, exactly.
std::optional<Dyadic> dyadic_of(const Bound& b) {
  const mpq_class q = to_mpq(b);
  const mpz_class& den = q.get_den();
  if (mpz_popcount(den.get_mpz_t()) != 1) return std::nullopt;
  return Dyadic(q.get_num(), -static_cast<long>(mpz_scan1(den.get_mpz_t(), 0)));
}

int to_int(CGAL::Sign s) { return s == CGAL::NEGATIVE ? -1 : (s == CGAL::POSITIVE ? 1 : 0); }

}  // namespace

const Algebraic& RealRoot::cgal() const {
  if (!cgal_) {
    const RootEnclosure& e = *enclosure_;
    if (e.is_point())
      cgal_ = kernel().construct_algebraic_real_1_object()(to_bound(e.lo()));
    else  // the enclosure's invariant is CGAL's precondition: one root, non-zero opposite signs at the ends
      cgal_ = kernel().construct_algebraic_real_1_object()(to_cgal(e.polynomial()), to_bound(e.lo()), to_bound(e.hi()));
  }
  return *cgal_;
}

RootEnclosure* RealRoot::enclosure() const {
  if (!tried_) {
    tried_ = true;
    const Algebraic& a = *cgal_;
    if (a.is_rational()) {
      if (const std::optional<Dyadic> x = dyadic_of(a.rational())) enclosure_ = RootEnclosure::point(*x);
    } else {
      // CGAL's isolating interval of its square-free defining polynomial, if its ends are dyadic.
      const std::optional<Dyadic> lo = dyadic_of(a.low()), hi = dyadic_of(a.high());
      if (lo && hi) enclosure_ = RootEnclosure::isolated(from_cgal(a.polynomial()), *lo, *hi);
    }
  }
  return enclosure_ ? &*enclosure_ : nullptr;
}

std::vector<RootWithMultiplicity> real_roots(const IntPoly& p) {
  std::vector<RootWithMultiplicity> out;
  if (p.size() == 3) {
    const mpz_class disc = p[1] * p[1] - 4 * p[0] * p[2];
    if (sgn(disc) < 0) return out;  // no real root: the exact discriminant says so
    if (auto two = quadratic_roots(p)) {
      out.push_back({std::make_shared<const RealRoot>(std::move(two->first)), 1});
      out.push_back({std::make_shared<const RealRoot>(std::move(two->second)), 1});
      return out;
    }
  }
  std::vector<std::pair<Algebraic, int>> found;
  kernel().solve_1_object()(to_cgal(p), std::back_inserter(found));
  out.reserve(found.size());
  for (auto& [root, mult] : found) out.push_back({std::make_shared<const RealRoot>(root), mult});
  return out;
}

namespace {

std::atomic<std::uint64_t> g_tied_within_cap{0};

// Two roots, one transcendental at least: brackets narrowed until they are apart, or equal
// within 2^-kTranscendentalTieBits.
int compare_by_brackets(const RealRoot& a, const RealRoot& b) {
  for (long bits = 64;; bits *= 2) {
    const bool last = bits >= kTranscendentalTieBits;
    const long k = std::min(bits, kTranscendentalTieBits);
    const auto [al, ah] = bracket(a, k);
    const auto [bl, bh] = bracket(b, k);
    if (ah < bl) return -1;
    if (bh < al) return 1;
    if (al == ah && bl == bh && al == bl) return 0;
    if (last) {
      ++g_tied_within_cap;
      return 0;
    }
  }
}

}  // namespace

RootHandle transcendental_root(std::shared_ptr<const TranscendentalRoot> t) {
  return std::make_shared<const RealRoot>(std::move(t));
}

const TranscendentalRoot* transcendental_of(const RealRoot& r) { return r.transcendental(); }

std::uint64_t tied_within_cap() { return g_tied_within_cap.load(); }

int sign_at(const IntPoly& p, const RealRoot& r) {
  if (r.transcendental()) throw std::logic_error("oracle: a polynomial's sign at a transcendental root");
  if (RootEnclosure* e = r.enclosure())
    if (const std::optional<int> s = e->sign_of(p)) return *s;
  return to_int(kernel().sign_at_1_object()(to_cgal(p), r.cgal()));
}

int compare(const RealRoot& a, const RealRoot& b) {
  if (&a == &b) return 0;
  if (a.transcendental() || b.transcendental()) return compare_by_brackets(a, b);
  RootEnclosure* ea = a.enclosure();
  RootEnclosure* eb = b.enclosure();
  if (ea && eb)
    if (const std::optional<int> c = compare(*ea, *eb)) return *c;
  return to_int(kernel().compare_1_object()(a.cgal(), b.cgal()));
}

int compare(const RealRoot& a, const Dyadic& x) {
  if (const TranscendentalRoot* t = a.transcendental()) return t->compare(x);
  if (RootEnclosure* e = a.enclosure()) return e->compare(x);
  return to_int(kernel().compare_1_object()(a.cgal(), to_bound(x)));
}

int compare(const RealRoot& a, const mpq_class& x) {
  if (const TranscendentalRoot* t = a.transcendental()) return t->compare(x);
  if (RootEnclosure* e = a.enclosure()) return e->compare(x);
  return to_int(kernel().compare_1_object()(a.cgal(), Bound(x.get_mpq_t())));
}

RootHandle root_at(const Dyadic& x) { return std::make_shared<const RealRoot>(RootEnclosure::point(x)); }

std::pair<mpq_class, mpq_class> bracket(const RealRoot& r, long bits) {
  if (const TranscendentalRoot* t = r.transcendental()) {
    t->narrow(bits);
    return {t->lo().to_mpq(), t->hi().to_mpq()};
  }
  if (RootEnclosure* e = r.enclosure()) {
    e->narrow(bits);
    return {e->lo().to_mpq(), e->hi().to_mpq()};
  }
  const auto [lo, hi] = kernel().approximate_absolute_1_object()(r.cgal(), static_cast<int>(bits));
  return {to_mpq(lo), to_mpq(hi)};
}

std::optional<std::pair<Dyadic, Dyadic>> dyadic_bracket(const RealRoot& r, long bits) {
  if (const TranscendentalRoot* t = r.transcendental()) {
    t->narrow(bits);
    return std::pair{t->lo(), t->hi()};
  }
  if (RootEnclosure* e = r.enclosure()) {
    e->narrow(bits);
    return std::pair{e->lo(), e->hi()};
  }
  return std::nullopt;
}

void refine_near(const RealRoot& r, const Dyadic& x, long bits) {
  if (r.transcendental()) return;  // a hint only: its own narrowing is Newton's already
  if (RootEnclosure* e = r.enclosure()) e->newton_from(x, bits);
}

bool rational_value(const RealRoot& r, mpq_class& value) {
  if (const TranscendentalRoot* t = r.transcendental()) {
    if (t->lo() != t->hi()) return false;
    value = t->lo().to_mpq();
    return true;
  }
  if (RootEnclosure* e = r.enclosure(); e && e->is_point()) {
    value = e->lo().to_mpq();
    return true;
  }
  const Algebraic& a = r.cgal();
  if (a.low() != a.high()) return false;
  value = to_mpq(a.low());
  return true;
}

}  // namespace pge::oracle::detail
