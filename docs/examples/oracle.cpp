// The exact referee (pge/oracle.hpp): the exact first contact of a scene, then a Referee that
// judges every collision of an engine run as `pge check` does. Links pge::oracle and pge::io.
//
// Expected output, by hand: two balls of radius 0.5 m, 10 m apart centre to centre, approach at
// 2 m/s each (no gravity): the 9 m between their surfaces close at 4 m/s, so they touch at
// exactly t = 9 / 4 = 2.25 s (every number here is a double exactly: the exact time is 2.25,
// its decimals all 0 after "2.25"). Equal masses, elastic: they swap velocities, and fly apart;
// nothing else touches before the horizon, 5 s. The engine (robust solver) gives the exact time,
// so the verdict is agree, 0 ulps off; no contact is left before the end.
#include "pge/oracle.hpp"
#include "pge/oracle_state.hpp"
#include "pge/scene_io.hpp"
#include "pge/world.hpp"

#include <cstdio>
#include <string>

namespace {

constexpr const char* kScene = R"({
  "format": "pge-scene/1",
  "name": "head-on",
  "bodies": [
    {"id": "left", "circle": {"radius": 0.5}, "position": [-5, 0], "velocity": [2, 0], "mass": 1},
    {"id": "right", "circle": {"radius": 0.5}, "position": [5, 0], "velocity": [-2, 0], "mass": 1}
  ],
  "run": {"until": 5}
})";

}  // namespace

int main() {
  const pge::Scene scene = pge::parse_scene(kScene, "head-on.json").scene;  // throws pge::SceneError
  pge::World<double> world(scene);

  // The exact next event of the world's state before its first step.
  const pge::oracle::NextEvent next = pge::oracle::next_event(pge::oracle::exact_state(world));
  if (next.time) {
    const pge::oracle::PairContact& first = next.pairs.front();
    std::printf("exact first contact: %s-%s at t = %s s\n", world.body_id(first.a).c_str(),
                world.body_id(first.b).c_str(), next.time->decimal(20).c_str());
  }

  // A referee made from the same state, following the run: every collision judged.
  pge::oracle::Referee referee(pge::oracle::exact_state(world));
  pge::oracle::follow(world, referee,
                      [&world](const pge::CollisionInfo<double>& c, const pge::oracle::ExactEvent&,
                               const pge::oracle::Judgement& j) {
                        std::printf("engine: %s-%s at t = %.17g s: %s, %lld ulps off\n",
                                    world.body_id(c.a).c_str(), world.body_id(c.b).c_str(), c.time,
                                    std::string(pge::oracle::verdict_name(j.verdict)).c_str(), j.ulps);
                      });
  world.run();
  const pge::oracle::EndJudgement end = referee.judge_end();  // the run reached its horizon
  std::printf("contact left before the horizon: %s\n", end.miss ? "yes (a miss)" : "none");
  std::printf("velocities after: %g and %g m/s\n", world.snapshot(0).velocity.x, world.snapshot(1).velocity.x);
}
