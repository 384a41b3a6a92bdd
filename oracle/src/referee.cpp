#include "judging.hpp"
#include "pge/oracle.hpp"
#include "roots.hpp"
#include "rotating.hpp"
#include "search.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <initializer_list>

namespace pge::oracle {

using namespace detail;

namespace {

using Clock = std::chrono::steady_clock;

long long abs_ulps(long long u) { return u < 0 ? -u : u; }

struct Found {
  BodyPair pair;
  PairResult result;
};

// The earliest of the contacts found, with every pair touching then (ascending pairs).
NextEvent earliest_of(const Dyadic& now, const std::vector<Found>& found) {
  NextEvent next;
  const RealRoot* best = nullptr;
  for (const Found& f : found)
    if (!best || compare(*f.result.tau, *best) < 0) best = f.result.tau.get();
  if (!best) return next;
  for (const Found& f : found) {
    if (compare(*f.result.tau, *best) != 0) continue;
    if (!next.time) next.time = ExactTime(now, f.result.tau);
    next.pairs.push_back({f.pair.first, f.pair.second, f.result.features, f.result.overlap_rule});
  }
  std::sort(next.pairs.begin(), next.pairs.end(),
            [](const PairContact& p, const PairContact& q) { return std::pair(p.a, p.b) < std::pair(q.a, q.b); });
  return next;
}

// The window's end is rounded up to a multiple of 2^-kWindowBits seconds from the engine pair's
// exact time (an upper bound of it). A wider window only costs candidate pairs, never
// correctness; 2^-64 s is below one ulp of every time from 2^-11 s on. Bits below the point.
constexpr long kWindowBits = 64;

// grid_ceil(t.bracket(kWindowBits).second, kWindowBits), from the dyadic bracket when the time
// keeps one (no rationals): the same narrowing and the same upper end, rounded up the same way.
Dyadic window_ceil(const ExactTime& t) {
  const auto b = dyadic_bracket(*t.offset(), kWindowBits);
  if (!b) return grid_ceil(t.bracket(kWindowBits).second, kWindowBits);
  const Dyadic hi = b->second + t.base();
  if (hi.exponent() >= -kWindowBits) return hi;
  mpz_class n;
  mpz_cdiv_q_2exp(n.get_mpz_t(), hi.mantissa().get_mpz_t(), static_cast<mp_bitcnt_t>(-kWindowBits - hi.exponent()));
  return Dyadic(n, -kWindowBits);
}

}  // namespace

struct Referee::Impl {
  ExactState state;
  RefereeOptions options;
  RefereeStats stats;
  std::vector<MotionMiss> motion_misses;
  std::vector<BodyModel<Dyadic>> exact;
  std::vector<BodyModel<Interval>> interval;
  FeatureCache features;
  std::optional<SpatialFilter> spatial;  // with options.filter and options.spatial
  std::uint64_t total_pairs = 0;

  Frame frame() const { return Frame(exact, interval, state.now); }

  void count(const SearchCounters& n) {
    stats.pairs_examined += n.pairs_examined;
    stats.pairs_filtered += n.pairs_filtered;
    stats.pairs_exact += n.pairs_exact;
    stats.features_exact += n.features_exact;
  }

  // Exact contacts of the candidate pairs (and of `extra`, already solved) up to tau_hi.
  NextEvent search(Frame& fr, const Dyadic& tau_hi, BodyPair skip, std::vector<Found> found) {
    SearchCounters n;
    const Interval window(0.0, Interval::enclose(tau_hi).hi());
    const std::vector<BodyPair> pairs =
        candidate_pairs(fr, features, tau_hi, options.filter, spatial ? &*spatial : nullptr, total_pairs, skip, n);
    n.pairs_exact += pairs.size();
    for (const BodyPair& p : pairs)
      if (auto r = pair_contact(fr, features, p.first, p.second, tau_hi, window, options.filter, n))
        found.push_back({p, *r});
    count(n);
    return earliest_of(fr.now(), found);
  }

  // The engine's pair, solved exactly to the horizon. A rotating pair is first searched only up
  // to the engine's time (plus agree_ulps + 1 ulps): its earliest contact there, if it has one,
  // is its earliest up to the horizon, and the search's cost grows with the log of the
  // interval's length over the contact's distance (bisected from tau = 0, each level in Arb's
  // balls: the horizon is often a thousand seconds away, the event a hundred microseconds).
  // Without a contact there (or undecided there) the whole interval is searched, as before.
  std::optional<PairResult> own_contact(Frame& fr, const ExactEvent& e) {
    SearchCounters n;
    n.pairs_exact = 1;
    const Dyadic tau = time_to_horizon();
    const Dyadic near = window_end(e, std::nullopt);
    if (rotating_pair(fr, e.a, e.b) && near.sign() > 0 && near < tau) {
      try {
        if (auto own = pair_contact(fr, features, e.a, e.b, near, Interval(0.0, Interval::enclose(near).hi()),
                                    options.filter, n)) {
          count(n);
          return own;
        }
      } catch (const UndecidedTime&) {
        // decided (or reported undecided) by the search to the horizon below
      }
    }
    auto own = pair_contact(fr, features, e.a, e.b, tau, Interval(0.0, Interval::enclose(tau).hi()), options.filter, n);
    count(n);
    return own;
  }

  // The search window's end, as time since now: every contact that can decide the verdict lies
  // before the engine's time plus agree_ulps + 1 ulps, or the engine pair's own exact time,
  // whichever is later (never past the horizon).
  Dyadic window_end(const ExactEvent& e, const std::optional<ExactTime>& own) const {
    Dyadic t_hi = format_step(round_to_format(e.time, state.format), options.agree_ulps + 1, state.format);
    if (own) t_hi = std::max(t_hi, window_ceil(*own));
    const Dyadic tau = std::min(t_hi, state.horizon) - state.now;
    return tau.sign() < 0 ? Dyadic() : tau;
  }

  Dyadic time_to_horizon() const {
    const Dyadic tau = state.horizon - state.now;
    return tau.sign() < 0 ? Dyadic() : tau;
  }

  void advance(const ExactEvent& e, const ExactMotion& a_after, const ExactMotion& b_after) {
    state.now = std::max(state.now, e.time);
    set_body_motions({{e.a, &a_after}, {e.b, &b_after}});
  }

  // Bodies continue on new motions from the state's time on. The filter hears of them together
  // once every model holds its new motion: a pair of them gets one bound, from both new paths.
  void set_body_motions(std::initializer_list<std::pair<BodyIndex, const ExactMotion*>> updates) {
    BodyIndex changed[2];
    std::size_t n = 0;
    for (const auto& [i, motion] : updates) {
      if (state.bodies[i].fixed) continue;
      state.bodies[i].motion = *motion;
      set_motion(exact[i], *motion);
      set_motion(interval[i], *motion);
      changed[n++] = i;
    }
    if (spatial) spatial->moved({changed, n}, state.now);
  }
};

Referee::Referee(ExactState state, RefereeOptions options) : impl_(std::make_unique<Impl>()) {
  impl_->state = std::move(state);
  impl_->options = options;
  for (const ExactBody& b : impl_->state.bodies) {
    impl_->exact.push_back(exact_model(b));
    impl_->interval.push_back(interval_model(b));
  }
  impl_->total_pairs = pair_count(impl_->frame());
  if (options.filter && options.spatial) impl_->spatial.emplace(impl_->interval, impl_->state.now);
}

Referee::~Referee() = default;
Referee::Referee(Referee&&) noexcept = default;
Referee& Referee::operator=(Referee&&) noexcept = default;

const ExactState& Referee::state() const { return impl_->state; }
const RefereeStats& Referee::stats() const { return impl_->stats; }
const std::vector<MotionMiss>& Referee::motion_misses() const { return impl_->motion_misses; }

Judgement Referee::judge(const ExactEvent& e, const ExactMotion& a_after, const ExactMotion& b_after) {
  const auto start = Clock::now();
  Impl& m = *impl_;
  const ExactState& s = m.state;
  if (e.a >= e.b || e.b >= s.bodies.size()) throw std::invalid_argument("Referee::judge: event bodies out of order or range");
  Frame fr = m.frame();
  Judgement j;
  const GapMeasure g = measure_gap(fr, m.features, e.a, e.b, {e.contact, e.feature_a, e.feature_b}, e.time - s.now);

  try {
    const std::optional<PairResult> own = m.own_contact(fr, e);
    if (own) {
      j.pair_time = ExactTime(s.now, own->tau);
      j.pair_features = own->features;
      j.features_match = std::find(own->features.begin(), own->features.end(),
                                   FeaturePair{e.contact, e.feature_a, e.feature_b}) != own->features.end();
      // The relative error first: it refines the exact time far enough that the rounding
      // comparisons of ulps_from are decided by the bracket it leaves (the same answers).
      j.relative_error = relative_error(e.time, *j.pair_time);
      j.ulps = ulps_from(e.time, *j.pair_time, s.format);
    }
    const Dyadic tau_hi = m.window_end(e, j.pair_time);
    std::vector<Found> found;
    if (own && compare(*own->tau, tau_hi) <= 0) found.push_back({{e.a, e.b}, *own});
    const NextEvent earliest = m.search(fr, tau_hi, {e.a, e.b}, std::move(found));
    j.earliest_time = earliest.time;
    j.earliest = earliest.pairs;
    j.verdict = decide(j.pair_time, own ? std::optional<long long>(j.ulps) : std::nullopt, earliest, e.time, s.format,
                       m.options.agree_ulps);
    // An event at an exact graze of a rotating pair (a tangency: the normal speed is exactly
    // zero there, so an engine's approach test and impulse are rounding, zero or an eps): not a
    // contact to agree with, nor a phantom of a pair far apart. Undecided, with the reason.
    // "At" the graze: within agree_ulps of its time, or within the square root of the format's
    // epsilon of it (relative, from 1 s on) where the exact gap of the engine's features is
    // within agree_ulps roundings of the pair's coordinates. A tangency's time is ill-conditioned
    // (the gap grows with the square of the distance from it: rounding e in the gap moves it by
    // about sqrt(e)), so an engine places it only as well as it can tell the gap from zero: a
    // kite's corner grazing a resting ball was reported 6 ulps early, where the gap is 1e-32
    // (fixtures/regressions/rotation/kite-corner-grazes-a-resting-ball.json).
    if (j.verdict == Verdict::Phantom && rotating_pair(fr, e.a, e.b))
      if (const std::optional<Dyadic> graze = rotating_graze(fr, e.a, e.b, m.time_to_horizon())) {
        const Dyadic at = s.now + *graze;
        const Dyadic window = std::max(at.abs(), Dyadic(1)).scaled(-(s.format.digits - 1) / 2);
        const double rounding = std::ldexp(static_cast<double>(m.options.agree_ulps), 1 - s.format.digits) *
                                rotating_pair_scale(fr, e.a, e.b, e.time - s.now);
        const bool near = (e.time - at).abs() <= window && std::abs(g.gap) <= rounding;
        if (abs_ulps(ulps_from(e.time, ExactTime(s.now, root_at(*graze)), s.format)) <= m.options.agree_ulps || near) {
          j.verdict = Verdict::Undecided;
          j.undecided_reason = "a graze at t = " + at.to_string() +
                               " (a tangency, no contact): the engine's event is within rounding of it";
          ++m.stats.undecided;
        }
      }
  } catch (const UndecidedTime& u) {
    // Only a rotating pair's transcendental contact throws this: reported, never agreement.
    j = Judgement{};
    j.verdict = Verdict::Undecided;
    j.undecided_reason = u.what();
    ++m.stats.undecided;
  }

  j.conservation = measure_conservation(s.bodies[e.a], s.bodies[e.b], e, a_after, b_after);
  j.gap = g.gap;
  j.contact_distance = g.contact_distance;

  m.advance(e, a_after, b_after);
  ++m.stats.events;
  m.stats.seconds += std::chrono::duration<double>(Clock::now() - start).count();
  return j;
}

EndJudgement Referee::take_motion(BodyIndex i, const ExactMotion& motion, const Dyadic& time) {
  const auto start = Clock::now();
  Impl& m = *impl_;
  if (i >= m.state.bodies.size()) throw std::invalid_argument("Referee::take_motion: body out of range");
  EndJudgement out;
  const Dyadic tau = time - m.state.now;
  if (tau.sign() > 0) {
    Frame fr = m.frame();
    try {
      out.next = m.search(fr, tau, {kNoBody, kNoBody}, {});
      out.miss = out.next.time && out.next.time->compare(time) < 0;
    } catch (const UndecidedTime& u) {
      out = EndJudgement{};
      out.undecided = true;
      out.undecided_reason = u.what();
      ++m.stats.undecided;
    }
    if (out.miss) {
      ++m.stats.misses_between_events;
      m.motion_misses.push_back({i, time, out.next});
    }
  }
  m.state.now = std::max(m.state.now, time);
  m.set_body_motions({{i, &motion}});
  m.stats.seconds += std::chrono::duration<double>(Clock::now() - start).count();
  return out;
}

NextEvent Referee::next_event() {
  const auto start = Clock::now();
  Frame fr = impl_->frame();
  const NextEvent next = impl_->search(fr, impl_->time_to_horizon(), {kNoBody, kNoBody}, {});
  impl_->stats.seconds += std::chrono::duration<double>(Clock::now() - start).count();
  return next;
}

EndJudgement Referee::judge_end() {
  EndJudgement end;
  try {
    end.next = next_event();
  } catch (const UndecidedTime& u) {
    end.undecided = true;
    end.undecided_reason = u.what();
    ++impl_->stats.undecided;
    return end;
  }
  end.miss = end.next.time.has_value();
  return end;
}

NextEvent next_event(const ExactState& state, const RefereeOptions& options) {
  Referee r(state, options);
  return r.next_event();
}

std::string_view verdict_name(Verdict v) {
  switch (v) {
    case Verdict::Agree: return "agree";
    case Verdict::Tie: return "tie";
    case Verdict::TimeError: return "time_error";
    case Verdict::Misorder: return "misorder";
    case Verdict::Miss: return "miss";
    case Verdict::Phantom: return "phantom";
    case Verdict::Undecided: return "undecided";
  }
  return "?";
}

}  // namespace pge::oracle
