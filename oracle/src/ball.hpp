// Arb's real balls (mid +- rad, every operation's result holding the exact one: rigorous sin and
// cos included) for the oracle's transcendental contacts, with the working precision of the
// calling thread. Only rotating.cpp and turn.cpp include it: Arb stays out of every other
// translation unit.
#pragma once

#include "pge/oracle_exact.hpp"

#include <arb.h>
#include <flint/fmpq.h>

namespace pge::oracle::detail {

// Bits of the midpoints' significands for the operations of this thread (Arb's `prec`).
inline thread_local slong g_ball_prec = 128;

class Precision {  // sets the thread's working precision for a scope
 public:
  explicit Precision(slong bits) : saved_(g_ball_prec) { g_ball_prec = bits; }
  ~Precision() { g_ball_prec = saved_; }
  Precision(const Precision&) = delete;
  Precision& operator=(const Precision&) = delete;

 private:
  slong saved_;
};

inline void set_arf(arf_t r, const Dyadic& d) {
  arf_set_mpz(r, d.mantissa().get_mpz_t());
  arf_mul_2exp_si(r, r, d.exponent());
}

inline Dyadic dyadic_of(const arf_t x) {
  fmpz_t man, exp;
  fmpz_init(man);
  fmpz_init(exp);
  arf_get_fmpz_2exp(man, exp, x);
  mpz_class m;
  fmpz_get_mpz(m.get_mpz_t(), man);
  const long e = fmpz_get_si(exp);
  fmpz_clear(man);
  fmpz_clear(exp);
  return Dyadic(std::move(m), e);
}

class Ball {
 public:
  Ball() { arb_init(x_); }
  explicit Ball(const Dyadic& d) {  // exact
    arb_init(x_);
    set_arf(arb_midref(x_), d);
  }
  ~Ball() { arb_clear(x_); }
  Ball(const Ball& o) {
    arb_init(x_);
    arb_set(x_, o.x_);
  }
  Ball(Ball&& o) noexcept {
    arb_init(x_);
    arb_swap(x_, o.x_);
  }
  Ball& operator=(const Ball& o) {
    if (this != &o) arb_set(x_, o.x_);
    return *this;
  }
  Ball& operator=(Ball&& o) noexcept {
    arb_swap(x_, o.x_);
    return *this;
  }

  // A ball holding [lo, hi].
  static Ball hull(const Dyadic& lo, const Dyadic& hi) {
    Ball b;
    arf_t l, h;
    arf_init(l);
    arf_init(h);
    set_arf(l, lo);
    set_arf(h, hi);
    arb_set_interval_arf(b.x_, l, h, g_ball_prec);
    arf_clear(l);
    arf_clear(h);
    return b;
  }
  static Ball rational(const mpq_class& q) {
    Ball b;
    fmpq_t f;
    fmpq_init(f);
    fmpq_set_mpq(f, q.get_mpq_t());
    arb_set_fmpq(b.x_, f, g_ball_prec);
    fmpq_clear(f);
    return b;
  }

  arb_ptr get() { return x_; }
  arb_srcptr get() const { return x_; }

  bool positive() const { return arb_is_positive(x_) != 0; }  // every point > 0
  bool negative() const { return arb_is_negative(x_) != 0; }  // every point < 0
  bool exact_zero() const { return arb_is_zero(x_) != 0; }
  // -1 / 1 when certain, 0 for an exact zero, 2 when the ball holds zero and more.
  int sign() const { return positive() ? 1 : (negative() ? -1 : (exact_zero() ? 0 : 2)); }
  Dyadic mid() const { return dyadic_of(arb_midref(x_)); }
  double mid_double() const { return arf_get_d(arb_midref(x_), ARF_RND_NEAR); }

  friend Ball operator+(const Ball& a, const Ball& b) {
    Ball r;
    arb_add(r.x_, a.x_, b.x_, g_ball_prec);
    return r;
  }
  friend Ball operator-(const Ball& a, const Ball& b) {
    Ball r;
    arb_sub(r.x_, a.x_, b.x_, g_ball_prec);
    return r;
  }
  friend Ball operator*(const Ball& a, const Ball& b) {
    Ball r;
    arb_mul(r.x_, a.x_, b.x_, g_ball_prec);
    return r;
  }
  friend Ball operator/(const Ball& a, const Ball& b) {
    Ball r;
    arb_div(r.x_, a.x_, b.x_, g_ball_prec);
    return r;
  }
  Ball operator-() const {
    Ball r;
    arb_neg(r.x_, x_);
    return r;
  }
  Ball scaled(long k) const {  // * 2^k, exact
    Ball r;
    arb_mul_2exp_si(r.x_, x_, k);
    return r;
  }
  friend Ball sqrt(const Ball& a) {
    Ball r;
    arb_sqrt(r.x_, a.x_, g_ball_prec);
    return r;
  }
  friend void sin_cos(Ball& s, Ball& c, const Ball& a) { arb_sin_cos(s.x_, c.x_, a.x_, g_ball_prec); }
  // The intersection of two balls that both hold the true value.
  friend Ball meet(const Ball& a, const Ball& b) {
    Ball r;
    if (!arb_intersection(r.x_, a.x_, b.x_, g_ball_prec)) return a;  // cannot happen for true enclosures
    return r;
  }

 private:
  arb_t x_;
};

}  // namespace pge::oracle::detail
