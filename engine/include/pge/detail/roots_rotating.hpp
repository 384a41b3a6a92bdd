// The earliest downward zero of a contact function of rotating bodies, found with rigorous
// enclosures (interval.hpp): the robust solver's method for contacts whose functions mix
// polynomials in time with sin and cos of the bodies' angles (issue "Rotation", item 4).
//
// The function. Every feature pair of bodies whose centres follow quadratic paths and whose angles
// turn at constant rates (theta(t) = theta0 + omega (t - t0)) has a contact function of the form
//   f(t) = P(s) + sum_j [ C_j(s) cos(w_j s + phi_j) + S_j(s) sin(w_j s + phi_j) ],  s = t - origin,
// with P, C_j, S_j polynomials of degree <= 4 (a vertex against an edge: the edge's normal
// turns with one body, the vertex with the other, so the frequencies are the rates and their
// difference). WaveSum holds it with every coefficient an enclosure, so that the rounding of
// whoever derived it from the stored paths is inside. Its derivatives have the same form.
//
// The search. Boxes [a, b] of time are taken left to right (a stack, the left half first), so
// the first root found is the earliest. A box is dropped when f is certainly non-zero on it, or
// certainly increasing (no downward crossing), using the natural enclosure of f intersected with
// the mean-value form f(m) + f'([a, b]) ([a, b] - m). Where f is certainly decreasing and
// certainly positive at a and negative at b, the one crossing is narrowed by bisection on point
// enclosures to the first value of B where f is not certainly positive (narrow below: in the
// wider type where B cannot tell, so that a transversal crossing is placed within a few ulps). Where f is convex (f'' > 0) and may vanish, its one minimum is located
// (where f' changes sign) and decides the box: a minimum that is certainly positive is a near
// miss, dropped; certainly negative, the crossing lies between a and the minimum; within
// rounding of zero, the contact is a tangency, reported at the minimum (where the pair stops
// approaching, so the response sees no approach: a graze). Other boxes are halved; a box that
// cannot be halved and may hold a crossing is reported at its start.
//
// Work. Each box costs one enclosure of f, f' and f''. Near misses cost a number of boxes that
// grows with the logarithm of the box width at which the margin is proven (the mean-value form's
// excess shrinks with the square of the width), and a turn of the fastest wave holds a bounded
// number of minima of f: so a search over many turns costs about a constant per turn. A caller
// bounds it by max_boxes: past it the search stops with Undecided and `t` the time up to which no
// downward crossing exists, so that the caller can re-predict from there (bounded work per call,
// progress every call).
#pragma once

#include "pge/detail/interval.hpp"
#include "pge/roots.hpp"

#include <array>
#include <cstdint>
#include <limits>
#include <optional>
#include <type_traits>
#include <vector>

namespace pge::detail {

template <class B> struct IntervalPoly {
  std::array<Interval<B>, 5> c{};
  int degree = 0;

  Interval<B> operator()(const Interval<B>& s) const {
    Interval<B> r = c[static_cast<std::size_t>(degree)];
    for (int k = degree - 1; k >= 0; --k) r = r * s + c[static_cast<std::size_t>(k)];
    return r;
  }
  IntervalPoly derivative() const {
    IntervalPoly d;
    d.degree = degree > 0 ? degree - 1 : 0;
    for (int k = 1; k <= degree; ++k)
      d.c[static_cast<std::size_t>(k - 1)] = c[static_cast<std::size_t>(k)] * Interval<B>(B(k));
    return d;
  }
  friend IntervalPoly operator+(const IntervalPoly& a, const IntervalPoly& b) {
    IntervalPoly r;
    r.degree = std::max(a.degree, b.degree);
    for (int k = 0; k <= r.degree; ++k) {
      const auto i = static_cast<std::size_t>(k);
      r.c[i] = (k <= a.degree ? a.c[i] : Interval<B>()) + (k <= b.degree ? b.c[i] : Interval<B>());
    }
    return r;
  }
  friend IntervalPoly operator*(const Interval<B>& w, const IntervalPoly& p) {
    IntervalPoly r = p;
    for (int k = 0; k <= p.degree; ++k) r.c[static_cast<std::size_t>(k)] = w * p.c[static_cast<std::size_t>(k)];
    return r;
  }
};

template <class B> struct Wave {
  Interval<B> omega, phase;      // the argument w s + phi
  IntervalPoly<B> cos_part, sin_part;
};

template <class B> struct WaveSum {
  static constexpr int kMaxWaves = 3;
  B origin{};
  IntervalPoly<B> base;
  std::array<Wave<B>, kMaxWaves> waves{};
  int wave_count = 0;

  Interval<B> operator()(const Interval<B>& t) const { return (*this)(t, waves_at(t)); }

  // The sines and cosines of every wave's argument over t: what f, its derivatives and anything
  // else with the same waves (derivative() keeps them) share at t, computed once.
  using Phases = std::array<SinCos<B>, kMaxWaves>;
  Phases waves_at(const Interval<B>& t) const {
    const Interval<B> s = t - Interval<B>(origin);
    Phases out{};
    for (int j = 0; j < wave_count; ++j) {
      const Wave<B>& w = waves[static_cast<std::size_t>(j)];
      out[static_cast<std::size_t>(j)] = sin_cos(w.omega * s + w.phase);
    }
    return out;
  }
  // The same over t from their values at a point m of t (what the mean-value form needs there
  // anyway): for an argument x of the box and y its value at m, d = x - y lies in the difference
  // of their enclosures D, and sin x = sin y + d cos y - (d^2 / 2) sin z (Taylor with Lagrange's
  // remainder), so sin over t lies in S + C D + [-1, 1] D^2 / 2, cos in C - S D + [-1, 1] D^2 / 2.
  // One enclosure of sin and cos at a point instead of two at the ends: as tight to first order
  // for the narrow boxes a search spends most of its time on. Where D is not small (a box over a
  // good part of a turn) the ends' enclosures are taken instead.
  Phases waves_near(const Interval<B>& t, const B& m, const Phases& at_m) const {
    const Interval<B> s = t - Interval<B>(origin), sm = Interval<B>(m) - Interval<B>(origin);
    const Interval<B> unit(B(-1), B(1)), half(B(0.5));
    Phases out{};
    for (int j = 0; j < wave_count; ++j) {
      const auto k = static_cast<std::size_t>(j);
      const Wave<B>& w = waves[k];
      const Interval<B> arg = w.omega * s + w.phase;
      const Interval<B> d = arg - (w.omega * sm + w.phase);
      if (!(d.magnitude() < B(0.5))) {
        out[k] = sin_cos(arg);
        continue;
      }
      const Interval<B> rest = unit * (d.square() * half);
      const SinCos<B>& p = at_m[k];
      out[k].sin = intersect((p.sin + p.cos * d + rest).clamp(B(-1), B(1)), unit);
      out[k].cos = intersect((p.cos - p.sin * d + rest).clamp(B(-1), B(1)), unit);
    }
    return out;
  }
  // f over t from its waves' sines and cosines there (waves_at(t), of this sum or of one with
  // the same waves).
  Interval<B> operator()(const Interval<B>& t, const Phases& sc) const {
    const Interval<B> s = t - Interval<B>(origin);
    Interval<B> v = base(s);
    for (int j = 0; j < wave_count; ++j) {
      const Wave<B>& w = waves[static_cast<std::size_t>(j)];
      const SinCos<B>& p = sc[static_cast<std::size_t>(j)];
      v = v + w.cos_part(s) * p.cos + w.sin_part(s) * p.sin;
    }
    return v;
  }
  // d/ds [C cos(w s + phi) + S sin(w s + phi)] = (C' + w S) cos + (S' - w C) sin.
  WaveSum derivative() const {
    WaveSum d = *this;
    d.base = base.derivative();
    for (int j = 0; j < wave_count; ++j) {
      const Wave<B>& w = waves[static_cast<std::size_t>(j)];
      Wave<B>& dw = d.waves[static_cast<std::size_t>(j)];
      dw.cos_part = w.cos_part.derivative() + w.omega * w.sin_part;
      dw.sin_part = w.sin_part.derivative() + (-w.omega) * w.cos_part;
    }
    return d;
  }
  // The largest |w_j| (rad per unit of time), for budgets and callers' bounds.
  B fastest_rate() const {
    B m = B(0);
    for (int j = 0; j < wave_count; ++j) m = std::max(m, waves[static_cast<std::size_t>(j)].omega.magnitude());
    return m;
  }
};

// The same function in a wider type W (its enclosures convert exactly): a narrower evaluation
// where the coefficients are exact (values of B, or the caller built them in W).
template <class W, class B> Interval<W> widen(const Interval<B>& x) { return Interval<W>(W(x.lo()), W(x.hi())); }
template <class W, class B> IntervalPoly<W> widen(const IntervalPoly<B>& p) {
  IntervalPoly<W> r;
  r.degree = p.degree;
  for (std::size_t k = 0; k < p.c.size(); ++k) r.c[k] = widen<W>(p.c[k]);
  return r;
}
template <class W, class B> WaveSum<W> widen(const WaveSum<B>& f) {
  WaveSum<W> r;
  r.origin = W(f.origin);
  r.base = widen<W>(f.base);
  r.wave_count = f.wave_count;
  for (std::size_t j = 0; j < f.waves.size(); ++j) {
    r.waves[j].omega = widen<W>(f.waves[j].omega);
    r.waves[j].phase = widen<W>(f.waves[j].phase);
    r.waves[j].cos_part = widen<W>(f.waves[j].cos_part);
    r.waves[j].sin_part = widen<W>(f.waves[j].sin_part);
  }
  return r;
}

template <class B> struct WaveRoot {
  RootStatus status = RootStatus::None;
  // Root: the contact time. Undecided: the search stopped at the box budget; no downward
  // crossing lies in [lo, t). None: t = hi.
  B t{};
  bool at_start_overlap = false;  // the overlap rule: negative and decreasing at lo
  bool tangent = false;           // a minimum within rounding of zero, reported at the minimum
  std::uint64_t boxes = 0;        // boxes enclosed: the work done
};

template <class B> class WaveRootFinder {
 public:
  WaveRootFinder(const WaveSum<B>& f, StartRule rule) : f_(f), d1_(f.derivative()), d2_(d1_.derivative()), rule_(rule) {}

  // Only crossings where `along` may lie in [0, length_sq] count (a point against an edge: the
  // point's place along the edge's line); a box where it certainly lies outside is dropped before
  // f is enclosed on it. Most boxes of a vertex against an edge are such boxes, and a crossing of
  // the edge's line beyond its ends would otherwise be narrowed to adjacent values first.
  void only_where(const WaveSum<B>* along, const Interval<B>& length_sq) {
    along_ = along;
    length_sq_ = length_sq;
    const auto same = [](const Interval<B>& x, const Interval<B>& y) { return x.lo() == y.lo() && x.hi() == y.hi(); };
    along_same_waves_ = along->wave_count == f_.wave_count;
    for (int j = 0; j < f_.wave_count && along_same_waves_; ++j) {
      const Wave<B>& u = f_.waves[static_cast<std::size_t>(j)];
      const Wave<B>& v = along->waves[static_cast<std::size_t>(j)];
      along_same_waves_ = same(u.omega, v.omega) && same(u.phase, v.phase) && along->origin == f_.origin;
    }
  }

  // A crossing's place is wanted only as a bound: the last value of B at which f is certainly
  // positive, found in B alone (narrow stops where B cannot tell the sign; no wider type). For
  // a function that is positive from lo to its first crossing, every time before the root
  // returned is one at which f is certainly positive. (The bounding circles' meeting: a start
  // for the features' searches, placed to the ulp in the wider type it cost a tenth of a
  // spinning gas's time, twice per prediction.)
  void bound_only() { bound_only_ = true; }

  WaveRoot<B> earliest(const B& lo, const B& hi, std::uint64_t max_boxes) {
    WaveRoot<B> out;
    out.t = hi;
    if (!(lo <= hi)) return out;
    const Interval<B> f_lo = f_(Interval<B>(lo)), d_lo = d1_(Interval<B>(lo));
    if (f_lo.negative()) {
      if (rule_ == StartRule::OverlapCollides && d_lo.negative()) {
        out.status = RootStatus::Root;
        out.t = lo;
        out.at_start_overlap = true;
        return out;
      }
    } else if (f_lo.contains_zero() && d_lo.negative()) {
      out.status = RootStatus::Root;  // touching at lo and approaching
      out.t = lo;
      return out;
    }
    stack_.clear();
    stack_.push_back({lo, hi});
    while (!stack_.empty()) {
      const Box box = stack_.back();
      stack_.pop_back();
      if (out.boxes >= max_boxes) {
        out.status = RootStatus::Undecided;
        out.t = box.a;
        return out;
      }
      ++out.boxes;
      if (const auto root = visit(box)) {
        out.status = RootStatus::Root;
        out.t = root->t;
        out.tangent = root->tangent;
        return out;
      }
    }
    return out;
  }

 private:
  struct Box {
    B a, b;
  };
  struct Found {
    B t;
    bool tangent = false;
  };

  static B midpoint(const B& a, const B& b) { return a + (b - a) / B(2); }
  static bool splittable(const B& a, const B& b, const B& m) { return a < m && m < b; }

  Interval<B> at(const WaveSum<B>& g, const B& x) const { return g(Interval<B>(x)); }

  // f over [a, b]: the natural enclosure and the mean-value form about the middle m, intersected
  // (f_x: f over the box; f_m: f at m).
  static Interval<B> enclose(const Box& box, const B& m, const Interval<B>& slope, const Interval<B>& f_x,
                             const Interval<B>& f_m) {
    return intersect(f_x, f_m + slope * (Interval<B>(box.a, box.b) - Interval<B>(m)));
  }
  Interval<B> enclose(const Box& box, const Interval<B>& slope) const {
    const B m = midpoint(box.a, box.b);
    return enclose(box, m, slope, f_(Interval<B>(box.a, box.b)), at(f_, m));
  }

  // Splits the box (right half pushed first, so the left is visited first); false if it cannot
  // be split.
  bool split(const Box& box) {
    const B m = midpoint(box.a, box.b);
    if (!splittable(box.a, box.b, m)) return false;
    stack_.push_back({m, box.b});
    stack_.push_back({box.a, m});
    return true;
  }

  std::optional<Found> visit(const Box& box) {
    const Interval<B> x(box.a, box.b);
    // f, f' and f'' over the box share its waves' sines and cosines, and so does `along` where
    // it has the same waves (a point against an edge: built wave for wave with the gap).
    const B m = midpoint(box.a, box.b);
    const typename WaveSum<B>::Phases at_m = f_.waves_at(Interval<B>(m));
    const typename WaveSum<B>::Phases phases = f_.waves_near(x, m, at_m);
    if (along_) {
      const Interval<B> s = along_same_waves_ ? (*along_)(x, phases) : (*along_)(x);
      if (s.hi() < B(0) || s.lo() > length_sq_.hi()) return std::nullopt;  // off the edge throughout
    }
    const Interval<B> slope = d1_(x, phases);
    const Interval<B> value = enclose(box, m, slope, f_(x, phases), f_(Interval<B>(m), at_m));
    if (value.positive() || value.negative()) return std::nullopt;  // no zero
    if (slope.positive()) return std::nullopt;                      // rising: no downward zero
    if (slope.negative()) return monotone(box);
    const Interval<B> curve = d2_(x, phases);
    if (curve.positive()) return convex(box);
    if (split(box)) return std::nullopt;
    return Found{box.a};  // a box of adjacent values that may hold a crossing
  }

  // f decreasing on the box.
  std::optional<Found> monotone(const Box& box) {
    const Interval<B> fa = at(f_, box.a), fb = at(f_, box.b);
    if (fa.negative() || fb.positive()) return std::nullopt;
    if (fa.positive() && fb.negative()) return Found{narrow(box.a, box.b)};
    if (split(box)) return std::nullopt;
    return Found{fa.positive() ? box.b : box.a};
  }

  // f convex on the box: f' rises, so f falls to one minimum and then rises. A downward zero
  // exists iff f(box.a) > 0 and the minimum is < 0 (a tangency if it is 0).
  std::optional<Found> convex(const Box& box) {
    const Interval<B> f_start = at(f_, box.a);
    if (f_start.negative()) return std::nullopt;  // below zero and then at most one rise
    if (at(d1_, box.b).negative()) return monotone(box);  // f' < 0 throughout
    // f' > 0 at the start: rising throughout (f' rises), no downward zero. Without this a box
    // whose enclosure of f' was too wide to show it (one about a middle over a wide box) would
    // report a tangency at its start, and a search resumed past a graze (past_tangency, an ulp
    // on) would find it again an ulp later, for ever.
    if (at(d1_, box.a).positive()) return std::nullopt;
    // Bisect for the minimum t*, keeping f'(a) < 0 certainly and f'(b) not certainly < 0.
    B a = box.a, b = box.b;
    const bool falls = at(d1_, a).negative();
    if (falls) {
      for (;;) {
        const B m = midpoint(a, b);
        if (!splittable(a, b, m)) break;
        if (at(d1_, m).negative()) a = m;
        else b = m;
      }
    } else {
      b = a;  // f' >= 0 at a up to rounding: the minimum is at a, or in a flat stretch after it
    }
    // f on [box.a, a] is at least f(a) (it falls there); on [a, b] (adjacent values) its
    // enclosure; on [b, box.b] above its tangent at b (convexity): f(b) + f'(b) (x - b), whose
    // least value uses f'(b)'s lower bound when that is negative (within rounding of zero).
    const Interval<B> f_ab = enclose({a, b}, d1_(Interval<B>(a, b)));
    const Interval<B> fb = at(f_, b), db = at(d1_, b);
    Interval<B> after = fb;
    if (db.lo() < B(0)) after = fb + Interval<B>(db.lo()) * (Interval<B>(box.b) - Interval<B>(b));
    const B lower = std::min(f_ab.lo(), after.lo());
    if (lower > B(0)) return std::nullopt;  // a near miss: f > 0 at its minimum
    for (const B& x : {a, b}) {
      if (at(f_, x).negative()) {
        if (f_start.positive()) return Found{narrow(box.a, x)};
        return Found{box.a};  // f(box.a) within rounding of zero, then falling below
      }
    }
    return Found{a, true};  // the minimum is within rounding of zero: a tangency
  }

  // A downward crossing in (a, b) with f(a) > 0 > f(b), f decreasing: the first value of B
  // where f is not certainly positive, found by bisection on that predicate to adjacent values
  // (b returned), so that any bracket of the crossing gives the same answer. f is evaluated in
  // the wider type once B cannot tell its sign near the crossing (robust's retry, as for
  // polynomials): the place is then known to B's own precision wherever the coefficients are
  // exact in B (the stored doubles, say), however small the time against the turn. In B alone f,
  // a difference of terms of size one near a root, would leave eps / |f'| of doubt.
  //
  // The probes are placed by regula falsi on the enclosures' middles (Illinois variant: the end
  // kept twice in a row has its value halved, so that both ends move), at least a value of B
  // inside the bracket, with a bisection after three probes in a row that did not halve it: the
  // same first value as bisection alone wherever the predicate switches once (any bracket gives
  // it), in a fraction of the probes on a transversal crossing, and never more than four times
  // bisection's on any.
  B narrow(B a, B b) {
    bool wide = false;
    B fa = at(f_, a).mid(), fb = at(f_, b).mid();
    int kept = 0;  // +1: the last probe kept a (moved b), -1: kept b; 0: a bisection
    int slow = 0;  // probes in a row that did not halve the bracket
    for (;;) {
      const B m = midpoint(a, b);
      if (!splittable(a, b, m)) return bound_only_ ? a : b;
      B x = m;
      if (slow < 3 && fa > B(0) && fb < B(0)) {
        // Regula falsi, at least one value of B inside either end (the step an estimate within
        // an ulp of the crossing needs to land on its other side).
        const B guess = a + (b - a) * (fa / (fa - fb));
        x = std::clamp(guess, interval_next_up(a), interval_next_down(b));
        if (!(a < x && x < b)) x = m;
      }
      Probe p = wide ? probe_wide(x) : probe(x);
      if (p.sign == 0 && bound_only_) return a;
      if (p.sign == 0 && !wide && has_wider) {
        // The ends' values again in the wider type: in B they are mostly rounding this close to
        // the crossing, and secant steps on them would be guesses.
        wide = true;
        p = probe_wide(x);
        fa = probe_wide(a).value;
        fb = probe_wide(b).value;
        kept = 0;
      }
      const B width = b - a;
      using std::abs;
      if (p.sign > 0) {
        a = x;
        fa = p.value;
        if (kept == -1) fb = fb / B(2);
        kept = x == m ? 0 : -1;
      } else {
        b = x;
        // Within rounding of zero the middle may even be positive: the crossing is within the
        // enclosure's width of x, which is what the secant needs to know.
        fb = p.value < B(0) ? p.value : -std::max(abs(p.value), std::numeric_limits<B>::denorm_min());
        if (kept == 1) fa = fa / B(2);
        kept = x == m ? 0 : 1;
      }
      slow = b - a > width / B(2) ? slow + 1 : 0;
    }
  }

  // f's sign at x (0: the enclosure holds zero) and an estimate of its value (the middle).
  struct Probe {
    int sign;
    B value;
  };
  Probe probe(const B& x) const {
    const Interval<B> v = at(f_, x);
    return {v.sign(), v.mid()};
  }
  using Wide = typename Wider<B>::type;
  static constexpr bool has_wider = !std::is_void_v<Wide> && !std::is_same_v<B, Quad>;
  // The same, f evaluated in the wider type.
  Probe probe_wide(const B& x) {
    if constexpr (has_wider) {
      if (!wide_) wide_ = widen<Wide>(f_);
      const Interval<Wide> v = (*wide_)(Interval<Wide>(Wide(x)));
      return {v.sign(), B(v.mid())};
    } else {
      return probe(x);
    }
  }

  const WaveSum<B>& f_;
  WaveSum<B> d1_, d2_;
  StartRule rule_;
  const WaveSum<B>* along_ = nullptr;
  Interval<B> length_sq_;
  bool along_same_waves_ = false;
  bool bound_only_ = false;
  std::vector<Box> stack_;
  struct NoWide {};
  std::optional<std::conditional_t<has_wider, WaveSum<Wide>, NoWide>> wide_;
};

// The earliest t in [lo, hi] where f crosses zero going down, by WaveRootFinder.
template <class B>
WaveRoot<B> earliest_wave_root(const WaveSum<B>& f, const B& lo, const B& hi, StartRule rule,
                               std::uint64_t max_boxes) {
  WaveRootFinder<B> finder(f, rule);
  return finder.earliest(lo, hi, max_boxes);
}

// The same, counting only crossings where `along` may lie in [0, length_sq]
// (WaveRootFinder::only_where).
template <class B>
WaveRoot<B> earliest_wave_root_on(const WaveSum<B>& f, const WaveSum<B>& along, const Interval<B>& length_sq,
                                  const B& lo, const B& hi, StartRule rule, std::uint64_t max_boxes) {
  WaveRootFinder<B> finder(f, rule);
  finder.only_where(&along, length_sq);
  return finder.earliest(lo, hi, max_boxes);
}

// The first step of past_crossing and past_tangency: an ulp of t, but not below the smallest
// double (2^-1074 s). At t = 0 an ulp of quad's cpp_bin_float<113> is 2^-16494, and doubling from
// there to a search's end took 16,000 evaluations in software arithmetic per call (a box lying
// still on a floor at t = 0: 4 minutes to build the world in quad). No scene or trace resolves a
// time below 2^-1074; float and double step exactly as before (their ulps are never smaller).
template <class B> B first_step_past(const B& t) {
  const B ulp = interval_next_up(t) - t;
  const B floor = B(std::numeric_limits<double>::denorm_min());
  return ulp < floor ? floor : ulp;
}

// Where a search for the next downward crossing may start after one at t: the first of t plus
// 1, 2, 4, ... ulps at which f is certainly negative (or hi). Just after a crossing f's
// enclosure still holds zero, and a start that touches zero while decreasing counts as a
// crossing, so a search from the next value of B would find the same crossing again, an ulp at a
// time. The caller is one that rejects a crossing (a vertex on an edge's line beyond the edge).
template <class B> B past_crossing(const WaveSum<B>& f, const B& t, const B& hi) {
  B step = first_step_past(t);
  for (B x = t + step; x < hi; x = t + step) {
    if (f(Interval<B>(x)).negative()) return x;
    step = step * B(2);
  }
  return hi;
}

// Where a search may start after a tangency at t that it must not report again (a graze already
// processed): the first of t plus 1, 2, 4, ... ulps at which f is certainly positive or certainly
// rising (hi if none before it); nothing if f is certainly negative there first (the "tangency"
// was a crossing within rounding, which the caller takes).
template <class B> std::optional<B> past_tangency(const WaveSum<B>& f, const B& t, const B& hi) {
  const WaveSum<B> d = f.derivative();
  B step = first_step_past(t);
  for (B x = t + step; x < hi; x = t + step) {
    const Interval<B> v = f(Interval<B>(x));
    if (v.negative()) return std::nullopt;
    if (v.positive() || d(Interval<B>(x)).positive()) return x;
    step = step * B(2);
  }
  return hi;
}

}  // namespace pge::detail
