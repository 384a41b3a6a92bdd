// The certified filter is conservative: turning it off changes no answer, on random states
// with every shape and on the events of real engine runs.
#include "oracle_states.hpp"
#include "pge/scene_io.hpp"
#include "spatial_filter.hpp"
#include "pge/world.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <filesystem>
#include <random>
#include <string>

namespace pge::oracle {
namespace {

using namespace testing;

bool same_pairs(const std::vector<PairContact>& x, const std::vector<PairContact>& y) {
  if (x.size() != y.size()) return false;
  for (std::size_t k = 0; k < x.size(); ++k)
    if (x[k].a != y[k].a || x[k].b != y[k].b || x[k].features != y[k].features ||
        x[k].overlap_rule != y[k].overlap_rule)
      return false;
  return true;
}

bool same_time(const std::optional<ExactTime>& x, const std::optional<ExactTime>& y) {
  if (x.has_value() != y.has_value()) return false;
  return !x || x->compare(*y) == 0;
}

// Random states on a grid of dyadic values (k / 8), so every run is the same everywhere:
// circles, fixed segments, moving and fixed polygons, with velocities and accelerations.
class Generator {
 public:
  explicit Generator(std::uint64_t seed) : rng_(seed) {}
  double coord(int span) { return static_cast<double>(pick(-8 * span, 8 * span)) / 8; }
  Vec2d vec(int span) { return {coord(span), coord(span)}; }
  int pick(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng_); }

  ExactBody body() {
    switch (pick(0, 4)) {
      case 0: {
        const Vec2d a = vec(6);
        return fixed_segment(a, a + Vec2d{coord(1), 1});  // never of zero length
      }
      case 1: return moving_polygon(square(0.5), vec(5), vec(2), 1, vec(1));
      case 2: return fixed_polygon(shifted(diamond(0.75), vec(5)));
      default: return moving_circle(0.25 + 0.125 * pick(0, 4), vec(5), vec(2), 1, vec(1));
    }
  }

 private:
  static std::vector<Vec2d> shifted(std::vector<Vec2d> v, Vec2d by) {
    for (Vec2d& p : v) p = p + by;
    return v;
  }
  std::mt19937_64 rng_;
};

TEST(OracleFilter, RandomStatesGiveTheSameNextEventWithAndWithoutTheFilter) {
  // 300 states of 6 bodies over a horizon of 4 s: enough to hit every feature kind, overlaps
  // (the bodies are placed at random) and pairs the filter does and does not rule out.
  constexpr int kStates = 300, kBodies = 6;
  Generator g(20261121);
  int with_contact = 0;
  for (int k = 0; k < kStates; ++k) {
    std::vector<ExactBody> bodies;
    for (int i = 0; i < kBodies; ++i) bodies.push_back(g.body());
    const ExactState s = state_of(std::move(bodies), 4);
    const NextEvent on = next_event(s, {true, kAgreeUlps});
    const NextEvent off = next_event(s, {false, kAgreeUlps});
    ASSERT_TRUE(same_time(on.time, off.time)) << "state " << k;
    ASSERT_TRUE(same_pairs(on.pairs, off.pairs)) << "state " << k;
    with_contact += on.time ? 1 : 0;
  }
  EXPECT_GT(with_contact, kStates / 4);  // the comparison is not vacuous
}

// Runs a bundled scene to `until` and judges every event with the filter on or off.
std::vector<Judgement> judge_scene(const std::string& name, double until, bool filter, RefereeStats* stats = nullptr) {
  const LoadedScene loaded = read_scene_file(std::string(PGE_SCENES_DIR) + "/basics/" + name);
  WorldOptions wo;
  wo.until = until;
  World<double> world(loaded.scene, wo);
  Referee referee(exact_state(world), {filter, kAgreeUlps});
  std::vector<Judgement> out;
  world.on_collision([&](const CollisionInfo<double>& c) {
    out.push_back(referee.judge(exact_event(c), exact_motion(world.motion(c.a)), exact_motion(world.motion(c.b))));
  });
  world.run();
  if (stats) *stats = referee.stats();
  return out;
}

TEST(OracleFilter, EngineRunsGetTheSameVerdictsWithAndWithoutTheFilter) {
  for (const char* scene : {"box-bounce.json", "gravity-box.json", "newtons-cradle.json", "drop-on-peg.json"}) {
    RefereeStats stats;
    const std::vector<Judgement> on = judge_scene(scene, 8, true, &stats);
    const std::vector<Judgement> off = judge_scene(scene, 8, false);
    ASSERT_EQ(on.size(), off.size()) << scene;
    EXPECT_GE(on.size(), 1u) << scene;
    for (std::size_t k = 0; k < on.size(); ++k) {
      EXPECT_EQ(on[k].verdict, off[k].verdict) << scene << " event " << k;
      EXPECT_EQ(on[k].ulps, off[k].ulps) << scene << " event " << k;
      EXPECT_TRUE(same_time(on[k].earliest_time, off[k].earliest_time)) << scene << " event " << k;
      EXPECT_TRUE(same_pairs(on[k].earliest, off[k].earliest)) << scene << " event " << k;
      EXPECT_FALSE(is_failure(on[k].verdict)) << scene << " event " << k;
    }
    EXPECT_GT(stats.pairs_filtered, 0u) << scene;  // the filter did decide something
  }
}

// The spatial filter must keep a pair that is far apart but fast, or at rest but accelerating:
// time is stepped on (take_motion of a bystander, which searches up to each step) until the
// referee reports the contact it passed; the spatial filter's answers equal those of the
// interval filter on every pair (the O(N) sweep it replaces, independent of its grid) at every
// step, and the contact is the one the mathematics gives. (Every pair solved exactly at every
// step, 5,000 pairs of CGAL, took a minute under the sanitizers; the fixture scenes compare all
// three referees.)
struct SteppedContact {
  std::optional<ExactTime> time;
  std::vector<PairContact> pairs;
};

SteppedContact step_until_contact(const ExactState& s, double step, int steps) {
  Referee with(s, {true, kAgreeUlps, true}), without(s, {true, kAgreeUlps, false});
  const ExactMotion still = s.bodies[0].motion;  // body 0: a bystander that never moves
  for (int k = 1; k <= steps; ++k) {
    const Dyadic t = Dyadic::from(step * k);
    const EndJudgement on = with.take_motion(0, still, t), off = without.take_motion(0, still, t);
    EXPECT_EQ(on.miss, off.miss) << "step " << k;
    EXPECT_TRUE(same_time(on.next.time, off.next.time)) << "step " << k;
    EXPECT_TRUE(same_pairs(on.next.pairs, off.next.pairs)) << "step " << k;
    if (on.miss) return {on.next.time, on.next.pairs};
  }
  return {};
}

// A 10 x 10 block of resting discs far from the action, so that the filter's grid is a real one.
std::vector<ExactBody> bystanders() {
  std::vector<ExactBody> out;
  for (int i = 0; i < 10; ++i)
    for (int j = 0; j < 10; ++j) out.push_back(moving_circle(0.25, {i * 1.0, 10.0 + j}, {0, 0}));
  return out;
}

TEST(OracleSpatialFilter, KeepsAFarFastBullet) {
  // Surfaces 1023 apart, closing at 1024: contact at 1023/1024 s. Each step of 1/64 s the bullet
  // crosses 16 m, hundreds of its own radii.
  std::vector<ExactBody> bodies = bystanders();
  const BodyIndex bullet = static_cast<BodyIndex>(bodies.size());
  bodies.push_back(moving_circle(0.5, {0, -5}, {1024, 0}));
  bodies.push_back(moving_circle(0.5, {1024, -5}, {0, 0}));
  const SteppedContact c = step_until_contact(state_of(std::move(bodies), 4), 1.0 / 64, 128);
  ASSERT_TRUE(c.time.has_value());
  EXPECT_EQ(c.time->compare(Dyadic::from(1023.0 / 1024)), 0);
  ASSERT_EQ(c.pairs.size(), 1u);
  EXPECT_EQ(c.pairs[0].a, bullet);
  EXPECT_EQ(c.pairs[0].b, bullet + 1);
}

TEST(OracleSpatialFilter, KeepsABodyAcceleratingFromRest) {
  // At rest with acceleration 1 towards a wall 2 m away (surface to wall): x(t) = t^2 / 2, contact
  // at t = 2 s. At rest its box lasts long; the filter must not vouch for the pair past t = 2.
  std::vector<ExactBody> bodies = bystanders();
  const BodyIndex ball = static_cast<BodyIndex>(bodies.size());
  bodies.push_back(moving_circle(0.5, {0, -20}, {0, 0}, 1, {1, 0}));
  bodies.push_back(fixed_segment({2.5, -25}, {2.5, -15}));
  const SteppedContact c = step_until_contact(state_of(std::move(bodies), 8), 1.0 / 16, 128);
  ASSERT_TRUE(c.time.has_value());
  EXPECT_EQ(c.time->compare(Dyadic::from(2.0)), 0);
  ASSERT_EQ(c.pairs.size(), 1u);
  EXPECT_EQ(c.pairs[0].a, ball);
  EXPECT_EQ(c.pairs[0].b, ball + 1);
}

// The interval product picks its two ends from the factors' signs. Against the definition: the
// exact products of the four corner pairs (Dyadic, no rounding) all lie in the result, and where
// no product underflows the result is the four rounded products' hull moved one double outward,
// no wider. Factors: points, zeros of both signs, one-signed and straddling intervals, infinite
// ends, values near underflow and overflow.
TEST(OracleInterval, ProductEnclosesTheFourExactCornerProductsAndNoMore) {
  std::mt19937_64 rng(2026);
  const double special[] = {0.0, -0.0, 1.0, -1.0, 0x1p-1074, -0x1p-600, 0x1p600, 1e308, -1e308,
                            std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
  const auto value = [&] {
    if (rng() % 4 == 0) return special[rng() % std::size(special)];
    const double m = std::uniform_real_distribution<double>(-4, 4)(rng);
    return std::ldexp(m, static_cast<int>(rng() % 41) - 20);
  };
  const auto interval = [&] {
    const double x = value(), y = rng() % 3 == 0 ? x : value();
    return detail::Interval(std::min(x, y), std::max(x, y));
  };
  int checked = 0;
  for (int n = 0; n < 200000; ++n) {
    const detail::Interval a = interval(), b = interval();
    const detail::Interval p = a * b;
    const double xs[4] = {a.lo(), a.lo(), a.hi(), a.hi()}, ys[4] = {b.lo(), b.hi(), b.lo(), b.hi()};
    bool finite = true, underflow = false;
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (int k = 0; k < 4; ++k) {
      if (!std::isfinite(xs[k]) || !std::isfinite(ys[k])) {
        finite = false;
        continue;
      }
      const double r = xs[k] * ys[k];
      underflow = underflow || (xs[k] != 0 && ys[k] != 0 && std::abs(r) < 0x1p-1000);
      lo = std::min(lo, r);
      hi = std::max(hi, r);
      const Dyadic exact = Dyadic::from(xs[k]) * Dyadic::from(ys[k]);
      if (std::isfinite(p.lo())) ASSERT_LE(Dyadic::from(p.lo()), exact) << a.lo() << " " << a.hi() << " x " << b.lo() << " " << b.hi();
      else ASSERT_EQ(p.lo(), -std::numeric_limits<double>::infinity());
      if (std::isfinite(p.hi())) ASSERT_GE(Dyadic::from(p.hi()), exact) << a.lo() << " " << a.hi() << " x " << b.lo() << " " << b.hi();
      else ASSERT_EQ(p.hi(), std::numeric_limits<double>::infinity());
    }
    if (!finite || underflow) continue;
    // No wider than the four rounded products' hull, one double outward (or exact at 0).
    EXPECT_EQ(p.lo(), lo == 0 ? 0.0 : std::nextafter(lo, -std::numeric_limits<double>::infinity()));
    EXPECT_EQ(p.hi(), hi == 0 ? 0.0 : std::nextafter(hi, std::numeric_limits<double>::infinity()));
    ++checked;
  }
  EXPECT_GT(checked, 100000);
}

// The spatial filter unit by unit, against contact times from the mathematics. A pair bound of
// two discs is the first root of a lower bound of their squared distance (on straight paths) or
// of their gap along the line of centres (accelerating); the filter keeps each body's path from
// `now` until the body moves (SpatialFilter::moved).
bool has_pair(const std::vector<detail::BodyPair>& pairs, BodyIndex a, BodyIndex b) {
  return std::find(pairs.begin(), pairs.end(), detail::BodyPair{a, b}) != pairs.end();
}

TEST(OracleSpatialFilter, DiscBoundsAreTheContactTimesOfTheMathematics) {
  // b at rest accelerating at 1 towards a: the gap 2 closes as t^2 / 2, contact at t = 2.
  // c closing on d at 4 m/s from a gap of 3: contact at t = 3 / 4.
  std::vector<detail::BodyModel<detail::Interval>> m;
  m.push_back(detail::interval_model(moving_circle(0.5, {0, 0}, {0, 0})));
  m.push_back(detail::interval_model(moving_circle(0.5, {3, 0}, {0, 0}, 1, {-1, 0})));
  m.push_back(detail::interval_model(moving_circle(0.5, {0, 50}, {2, 0})));
  m.push_back(detail::interval_model(moving_circle(0.5, {4, 50}, {-2, 0})));
  detail::SpatialFilter f(m, Dyadic());
  EXPECT_TRUE(has_pair(f.pairs_within(Dyadic(), Dyadic::from(2.0)), 0, 1));
  EXPECT_FALSE(has_pair(f.pairs_within(Dyadic(), Dyadic::from(1.75)), 0, 1));  // apart until 2
  EXPECT_TRUE(has_pair(f.pairs_within(Dyadic(), Dyadic::from(0.75)), 2, 3));
  EXPECT_FALSE(has_pair(f.pairs_within(Dyadic(), Dyadic::from(0.625)), 2, 3));
}

TEST(OracleSpatialFilter, StraightDiscsAreBoundByTheirDistance) {
  // a and b (radius 1/2) pass each other on the diagonals y = x and y = x - 2, closing at
  // (2, 2) from (8, 6) apart: their distance is never below |8 - 6| / sqrt(2) = 1.41 > 1, so no
  // window lists them (along the line of centres at t = 0 the gap 10 - 2.8 t - 1 closes at
  // t = 3.2, and their boxes over a long window overlap).
  // c and d (radius 1/2) on lines 1/2 apart, closing at 1 m/s from 8 apart: |D|^2 =
  // (8 - t)^2 + 1/4 reaches 1 at t = 8 - sqrt(3/4) = 7.1339746... (the contact: in the window
  // up to 7.14 and not in the one up to 7.13; the line of centres at t = 0 closes at 7.03).
  std::vector<detail::BodyModel<detail::Interval>> m;
  m.push_back(detail::interval_model(moving_circle(0.5, {0, 0}, {1, 1})));
  m.push_back(detail::interval_model(moving_circle(0.5, {8, 6}, {-1, -1})));
  m.push_back(detail::interval_model(moving_circle(0.5, {0, 10000}, {0.5, 0})));
  m.push_back(detail::interval_model(moving_circle(0.5, {8, 10000.5}, {-0.5, 0})));
  detail::SpatialFilter f(m, Dyadic());
  EXPECT_FALSE(has_pair(f.pairs_within(Dyadic(), Dyadic::from(1000.0)), 0, 1));
  EXPECT_TRUE(has_pair(f.pairs_within(Dyadic(), Dyadic::from(7.14)), 2, 3));
  EXPECT_FALSE(has_pair(f.pairs_within(Dyadic(), Dyadic::from(7.13)), 2, 3));
}

TEST(OracleSpatialFilter, ABodyThatMovedIsBoundOnItsNewPath) {
  // a and b collide at t = 1/2 (gap 1 closing at 2) and swap velocities. b then closes on c at
  // 1 m/s from a gap of 3/2: contact at t = 2. A filter that kept b's old path (moving away from
  // c) would vouch for b and c past 2. Told of both at once (the referee's way: both models
  // hold their new motions first), and one at a time (a's pairs made while b is still on its
  // old path, towards a).
  for (const bool together : {true, false}) {
    SCOPED_TRACE(together ? "both at once" : "one at a time");
    std::vector<detail::BodyModel<detail::Interval>> m;
    m.push_back(detail::interval_model(moving_circle(0.5, {0, 0}, {1, 0})));
    m.push_back(detail::interval_model(moving_circle(0.5, {2, 0}, {-1, 0})));
    m.push_back(detail::interval_model(moving_circle(0.5, {4, 0}, {0, 0})));
    detail::SpatialFilter f(m, Dyadic());
    EXPECT_TRUE(has_pair(f.pairs_within(Dyadic(), Dyadic::from(0.5)), 0, 1));
    const Dyadic half = Dyadic::from(0.5);
    const BodyIndex a[1] = {0}, b[1] = {1}, both[2] = {0, 1};
    detail::set_motion(m[0], motion({0.5, 0}, {-1, 0}, {}, 0.5));
    if (!together) f.moved(a, half);
    detail::set_motion(m[1], motion({1.5, 0}, {1, 0}, {}, 0.5));
    if (together) f.moved(both, half);
    else f.moved(b, half);
    const std::vector<detail::BodyPair> to_contact = f.pairs_within(half, Dyadic::from(1.5));
    EXPECT_TRUE(has_pair(to_contact, 1, 2));
    EXPECT_TRUE(has_pair(to_contact, 0, 1));  // touching at 1/2: no gap to vouch with
    EXPECT_FALSE(has_pair(f.pairs_within(half, Dyadic::from(1.25)), 1, 2));  // apart until 2
  }
}

// Every scene in fixtures/scenes and fixtures/regressions, judged event by event by three
// referees following one engine run: the spatial filter, the interval filter on every pair (the
// O(N) sweep the spatial filter replaces) and, for scenes of few bodies, no filter at all (every
// pair exact). Their verdicts, times, pairs and features must be identical.
bool same_judgement(const Judgement& x, const Judgement& y) {
  return x.verdict == y.verdict && x.ulps == y.ulps && same_time(x.pair_time, y.pair_time) &&
         x.pair_features == y.pair_features && same_time(x.earliest_time, y.earliest_time) &&
         same_pairs(x.earliest, y.earliest);
}

struct SceneComparison {
  std::uint64_t events = 0;
  std::uint64_t motions = 0;
};

SceneComparison compare_referees(const std::string& path) {
  const LoadedScene loaded = read_scene_file(path);
  const std::uint64_t n = loaded.scene.bodies.size();
  const bool exact_too = n <= 16;
  // The interval sweep costs N^2 / 2 pair tests per event: a budget of pair tests per scene. A
  // turning pair's test costs about a hundred times a translating one's (the certified search
  // over sin and cos), so the budget of a scene with rotation is a fiftieth, and at least 2
  // events (the 200-polygon spinning gas: 2 events, 40,000 pair searches without the filter).
  const bool rotation = std::any_of(loaded.scene.bodies.begin(), loaded.scene.bodies.end(),
                                    [](const BodyDesc& b) { return b.rotates; });
  const std::uint64_t budget = rotation ? 40'000 : 2'000'000;
  const std::uint64_t cap = std::clamp<std::uint64_t>(budget / std::max<std::uint64_t>(n * n / 2, 1), rotation ? 2 : 8, 300);
  WorldOptions wo;
  wo.max_events = std::min<std::uint64_t>(cap, loaded.scene.run.max_events ? loaded.scene.run.max_events : cap);
  World<double> world(loaded.scene, wo);
  std::vector<Referee> referees;
  referees.emplace_back(exact_state(world), RefereeOptions{true, kAgreeUlps, true});
  referees.emplace_back(exact_state(world), RefereeOptions{true, kAgreeUlps, false});
  if (exact_too) referees.emplace_back(exact_state(world), RefereeOptions{false, kAgreeUlps});
  SceneComparison out;
  world.on_collision([&](const CollisionInfo<double>& c) {
    const ExactEvent e = exact_event(c);
    const ExactMotion ma = exact_motion(world.motion(c.a)), mb = exact_motion(world.motion(c.b));
    const Judgement first = referees[0].judge(e, ma, mb);
    for (std::size_t r = 1; r < referees.size(); ++r)
      EXPECT_TRUE(same_judgement(first, referees[r].judge(e, ma, mb))) << path << " event " << out.events << " referee " << r;
    ++out.events;
  });
  world.on_motion_change([&](BodyIndex i, double time) {
    const ExactMotion m = exact_motion(world.motion(i));
    const EndJudgement first = referees[0].take_motion(i, m, Dyadic::from(time));
    for (std::size_t r = 1; r < referees.size(); ++r) {
      const EndJudgement other = referees[r].take_motion(i, m, Dyadic::from(time));
      EXPECT_EQ(first.miss, other.miss) << path << " motion " << out.motions;
      EXPECT_TRUE(same_time(first.next.time, other.next.time)) << path << " motion " << out.motions;
      EXPECT_TRUE(same_pairs(first.next.pairs, other.next.pairs)) << path << " motion " << out.motions;
    }
    ++out.motions;
  });
  world.run();
  if (world.stop_reason() == StopReason::ReachedUntil) {
    const EndJudgement first = referees[0].judge_end();
    for (std::size_t r = 1; r < referees.size(); ++r) {
      const EndJudgement other = referees[r].judge_end();
      EXPECT_EQ(first.miss, other.miss) << path << " end";
      EXPECT_TRUE(same_time(first.next.time, other.next.time)) << path << " end";
      EXPECT_TRUE(same_pairs(first.next.pairs, other.next.pairs)) << path << " end";
    }
  }
  return out;
}

TEST(OracleSpatialFilter, EveryFixtureSceneGetsTheSameVerdictsWithAndWithoutIt) {
  std::vector<std::string> paths;
  for (const char* dir : {PGE_SCENES_DIR, PGE_REGRESSIONS_DIR})
    for (const auto& f : std::filesystem::recursive_directory_iterator(dir))
      if (f.is_regular_file() && f.path().extension() == ".json") paths.push_back(f.path().string());
  std::sort(paths.begin(), paths.end());
  ASSERT_GE(paths.size(), 50u);
  std::uint64_t events = 0;
  for (const std::string& p : paths) {
    SCOPED_TRACE(p);
    events += compare_referees(p).events;
  }
  EXPECT_GT(events, 3000u);  // not vacuous
}

}  // namespace
}  // namespace pge::oracle
