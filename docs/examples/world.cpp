// The engine (pge/world.hpp, pge/step_loop.hpp): a ball dropped onto a floor, every collision
// printed from the collision callback, the run stepped to its end with the energy measured
// before and after. Links pge::engine.
//
// Expected output, by hand: the ball's lowest point starts h = 5 m above the floor (centre at
// 5.1 m, radius 0.1 m) under g = 9.81 m/s^2, so it first touches at t1 = sqrt(2 h / g)
// = 1.009638 s at speed g t1 = sqrt(2 g h) = 9.904544 m/s. The bounce is elastic (restitution
// 1): it rises back to 5.1 m and falls again, touching at 3 t1 = 3.028913 s at the same speed.
// By the horizon, 4 s, it is tau = 4 - 3 t1 = 0.971087 s past the second bounce, at height
// 0.1 + g t1 tau - g tau^2 / 2 = 5.092711 m. Its energy, m g y (potential of the field, measured
// from y = 0) plus kinetic, is 1 kg * 9.81 * 5.1 = 50.031 J throughout.
#include "pge/scene.hpp"
#include "pge/step_loop.hpp"
#include "pge/world.hpp"

#include <cstdio>
#include <string>

int main() {
  pge::Scene scene;
  scene.name = "drop";
  scene.world.gravity = {0, -9.81};  // m/s^2
  scene.run.until = 4;               // s

  pge::BodyDesc ball;
  ball.id = "ball";
  ball.shape = pge::ShapeKind::Circle;
  ball.radius = 0.1;       // m
  ball.position = {0, 5.1};  // m
  ball.mass = 1;           // kg
  scene.bodies.push_back(ball);

  pge::BodyDesc floor;
  floor.id = "floor";
  floor.shape = pge::ShapeKind::Segment;
  floor.a = {-1, 0};
  floor.b = {1, 0};
  floor.fixed = true;
  scene.bodies.push_back(floor);

  pge::World<double> world(scene);  // throws std::invalid_argument for an invalid scene
  world.on_collision([&world](const pge::CollisionInfo<double>& c) {
    std::printf("collision: %s-%s at t = %.6f s, approach speed %.6f m/s\n", world.body_id(c.a).c_str(),
                world.body_id(c.b).c_str(), c.time, c.approach_speed);
  });

  // step_to_end calls World::step() until the run is over; world_totals measures before and after.
  const auto run = pge::step_to_end(world, [](const pge::World<double>& w) { return pge::world_totals(w); });

  const pge::BodySnapshot<double> end = world.snapshot(0);  // body 0: "ball", in scene order
  std::printf("stopped: %s at t = %g s after %llu collisions\n",
              std::string(pge::stop_reason_name(run.stop)).c_str(), world.time(),
              static_cast<unsigned long long>(world.counts().collisions));
  std::printf("ball at height %.6f m\n", end.position.y);
  std::printf("energy %.6f J at the start, %.6f J at the end\n", run.start.energy(), run.end.energy());
}
