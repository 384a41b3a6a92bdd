// The certified filter is conservative: turning it off changes no answer, on random states
// with every shape and on the events of real engine runs.
#include "oracle_states.hpp"
#include "pge/scene_io.hpp"
#include "pge/world.hpp"

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace pge::oracle
