#include "contact.hpp"

#include <algorithm>

namespace pge::oracle::detail {
namespace {

int top_degree(const Poly<Dyadic>& p) {
  int d = p.deg;
  while (d >= 0 && p.c[d].is_zero()) --d;
  return d;  // -1: the zero polynomial
}

// Sign of p just after 0 given p(0) = 0 ... or, for order >= 1, the sign of the first non-zero
// derivative at 0: whether p is decreasing (-1) or increasing (1) there; 0 if p is constant.
int first_derivative_sign(const Poly<Dyadic>& p) {
  for (int k = 1; k <= p.deg; ++k)
    if (!p.c[k].is_zero()) return p.c[k].sign();
  return 0;
}

// Where on the feature a contact point is: off it, inside, or (edges) exactly at end 0 or 1.
enum class Place { Off, Inside, End0, End1 };

// From the signs of the projection, of e.e - projection and of the side at the contact.
Place place_of(const ContactPolys<Dyadic>& c, int from_start, int to_end, int side) {
  if (c.needs_outside && side <= 0) return Place::Off;
  if (!c.on_edge) return Place::Inside;
  if (from_start < 0 || to_end < 0) return Place::Off;
  if (from_start == 0) return Place::End0;
  return to_end == 0 ? Place::End1 : Place::Inside;
}

Place place_at_zero(const ContactPolys<Dyadic>& c) {
  if (!c.on_edge) return place_of(c, 1, 1, c.side.c[0].sign());
  return place_of(c, c.projection.c[0].sign(), compare(c.length2, c.projection.c[0]), c.side.c[0].sign());
}

Place place_at(const ContactPolys<Dyadic>& c, const RealRoot& r) {
  if (!c.on_edge) return place_of(c, 1, 1, 1);
  const int side = c.needs_outside ? sign_at(to_int_poly(c.side), r) : 1;
  return place_of(c, sign_at(to_int_poly(c.projection), r),
                  sign_at(to_int_poly(Poly<Dyadic>::constant(c.length2) - c.projection), r), side);
}

// A contact at `place` counts: on the feature, and a vertex meeting a corner enters the body.
bool counts(const ContactPolys<Dyadic>& c, Place place, const RealRoot& r, const CornerTest& corner_enters) {
  if (place == Place::Off) return false;
  if (!c.vertex_point || place == Place::Inside) return true;
  return corner_enters(r, place == Place::End0 ? 0 : 1);
}

// The real roots of p with the sign p has just after each (between consecutive roots p keeps
// one sign; after the last it has the sign of the leading coefficient, and each root of odd
// multiplicity flips it going left).
struct SignedRoots {
  std::vector<RootWithMultiplicity> roots;
  std::vector<int> sign_after;
};
SignedRoots signed_roots(const Poly<Dyadic>& p, int top) {
  SignedRoots out;
  out.roots = real_roots(to_int_poly(p));
  out.sign_after.resize(out.roots.size());
  int sign = p.c[top].sign();
  for (std::size_t k = out.roots.size(); k-- > 0;) {
    out.sign_after[k] = sign;
    if (out.roots[k].multiplicity % 2 == 1) sign = -sign;
  }
  return out;
}

// The turning-overlap rule (DESIGN.md; the engine's StartRule::OverlapCollides, roots.hpp): f
// overlapping at 0 and rising. The first local maximum of f in (0, tau_hi] (the first root of
// f' where f' goes from positive to negative) is a contact if f is not positive there: the pair
// turns back while still overlapping (f < 0) or exactly touching (f = 0) instead of separating.
// f(m) is decided exactly, at the algebraic root m of f'.
struct Turn {
  RootHandle tau;
  int sign_at_max = 0;
};
std::optional<Turn> first_turn(const Poly<Dyadic>& f, int top, const Dyadic& tau_hi) {
  if (top < 2) return std::nullopt;  // a line never turns
  const Poly<Dyadic> slope = derivative(f);
  const SignedRoots s = signed_roots(slope, top - 1);
  const RootHandle zero = root_at(Dyadic());
  for (std::size_t k = 0; k < s.roots.size(); ++k) {
    const RealRoot& r = *s.roots[k].root;
    if (compare(r, *zero) <= 0) continue;
    if (compare(r, tau_hi) > 0) break;
    if (s.roots[k].multiplicity % 2 == 0 || s.sign_after[k] > 0) continue;  // not a maximum
    return Turn{s.roots[k].root, sign_at(to_int_poly(f), r)};
  }
  return std::nullopt;
}

}  // namespace

IntPoly to_int_poly(const Poly<Dyadic>& p) {
  const int top = top_degree(p);
  IntPoly out;
  if (top < 0) return out;
  long low = 0;
  bool first = true;
  for (int k = 0; k <= top; ++k) {
    if (p.c[k].is_zero()) continue;
    low = first ? p.c[k].exponent() : std::min(low, p.c[k].exponent());
    first = false;
  }
  out.resize(static_cast<std::size_t>(top) + 1);
  for (int k = 0; k <= top; ++k) {
    if (p.c[k].is_zero()) continue;
    mpz_class m = p.c[k].mantissa();
    m <<= static_cast<mp_bitcnt_t>(p.c[k].exponent() - low);
    out[static_cast<std::size_t>(k)] = m;
  }
  return out;
}

std::optional<Contact> earliest_contact(const ContactPolys<Dyadic>& c, const Dyadic& tau_hi,
                                        const std::function<bool()>& overlap_applies, const CornerTest& corner_enters) {
  if (c.degenerate) return std::nullopt;
  const int top = top_degree(c.f);
  if (top < 0) return std::nullopt;  // touching forever without approaching: never a collision
  const int at_zero = c.f.c[0].sign();
  const RootHandle zero = root_at(Dyadic());
  if (at_zero <= 0 && first_derivative_sign(c.f) < 0) {
    // Touching now (at_zero == 0) is an ordinary contact, corners included; overlapping now is
    // the overlap rule, whose own condition replaces the corner's.
    const Place place = place_at_zero(c);
    if (at_zero == 0 ? counts(c, place, *zero, corner_enters) : (place != Place::Off && overlap_applies()))
      return Contact{zero, at_zero < 0};
  }
  if (top == 0) return std::nullopt;
  if (at_zero < 0 && first_derivative_sign(c.f) > 0)
    if (const std::optional<Turn> turn = first_turn(c.f, top, tau_hi); turn && turn->sign_at_max <= 0)
      if (place_at(c, *turn->tau) != Place::Off && overlap_applies()) return Contact{turn->tau, turn->sign_at_max < 0};

  const SignedRoots s = signed_roots(c.f, top);
  const std::vector<RootWithMultiplicity>& roots = s.roots;
  const std::vector<int>& sign_after = s.sign_after;
  for (std::size_t k = 0; k < roots.size(); ++k) {
    const RealRoot& r = *roots[k].root;
    if (compare(r, *zero) <= 0) continue;  // tau = 0 was decided above
    if (compare(r, tau_hi) > 0) break;
    const bool crosses_down = roots[k].multiplicity % 2 == 1 && sign_after[k] < 0;
    if (crosses_down && counts(c, place_at(c, r), r, corner_enters)) return Contact{roots[k].root, false};
  }
  return std::nullopt;
}

bool may_touch(const ContactPolys<Interval>& c, const Interval& window) {
  if (c.undecided) return true;
  const Interval tau(0.0, window.hi());
  if (evaluate(c.f, tau).certainly_positive()) return false;
  if (evaluate(derivative(c.f), tau).certainly_positive()) return false;
  if (c.on_edge) {
    const Interval l = evaluate(c.projection, tau);
    if (l.certainly_negative() || l.lo() > c.length2.hi()) return false;
  }
  if (c.needs_outside && evaluate(c.side, tau).hi() <= 0) return false;
  return true;
}

}  // namespace pge::oracle::detail
