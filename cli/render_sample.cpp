// `pge render`, sampling: a run in double, every moving body's path thinned to what a picture
// can show.
#include "render_parts.hpp"

#include "pge/step_loop.hpp"

#include <algorithm>
#include <cmath>

namespace pge::cli::render {
namespace {

// Keeps at most `cap` items of a stream of unknown length, evenly spread, in O(cap) memory:
// every stride-th item is kept, and when 2 * cap are kept every other one is dropped and the
// stride doubles. finish() then picks `cap` evenly from those, the first and last item always.
template <class Item> class Thinned {
 public:
  explicit Thinned(std::size_t cap) : cap_(std::max<std::size_t>(cap, 2)) {}

  void add(const Item& item) {
    last_ = item;
    last_kept_ = seen_ % stride_ == 0;
    ++seen_;
    if (!last_kept_) return;
    kept_.push_back(item);
    if (kept_.size() >= 2 * cap_) halve();
  }

  std::uint64_t seen() const { return seen_; }

  std::vector<Item> finish() const {
    std::vector<Item> all = kept_;
    if (seen_ > 0 && !last_kept_) all.push_back(last_);
    if (all.size() <= cap_) return all;
    std::vector<Item> out;
    out.reserve(cap_);
    for (std::size_t k = 0; k < cap_; ++k) out.push_back(all[k * (all.size() - 1) / (cap_ - 1)]);
    return out;
  }

 private:
  void halve() {
    std::size_t j = 0;
    for (std::size_t i = 0; i < kept_.size(); i += 2) kept_[j++] = kept_[i];
    kept_.resize(j);
    stride_ *= 2;
    last_kept_ = false;  // the size was even: the last kept item had an odd index
  }

  std::size_t cap_;
  std::uint64_t stride_ = 1;
  std::uint64_t seen_ = 0;
  std::vector<Item> kept_;
  Item last_{};
  bool last_kept_ = false;
};

// The body's shape box relative to its position.
Box shape_box(const BodyDesc& b) {
  Box box;
  switch (b.shape) {
    case ShapeKind::Circle:
      box.add({-b.radius, -b.radius});
      box.add({b.radius, b.radius});
      break;
    case ShapeKind::Segment:
      box.add(b.a);
      box.add(b.b);
      break;
    case ShapeKind::Polygon:
      for (const Vec2d& v : b.vertices) box.add(v);
      break;
  }
  return box;
}

}  // namespace

Run simulate(const LoadedScene& loaded, const WorldOptions& options) {
  const Scene& scene = loaded.scene;
  World<double> world(scene, options);
  const std::size_t n = world.body_count();
  std::vector<BodyIndex> moving;
  for (BodyIndex i = 0; i < n; ++i)
    if (!world.is_fixed(i)) moving.push_back(i);
  const std::size_t cap =
      std::clamp(kMaxSamplesTotal / std::max<std::size_t>(moving.size(), 1), kMinSamplesPerBody, kMaxSamplesPerBody);

  Run run;
  run.loaded = &loaded;
  std::vector<Box> local(n);
  for (BodyIndex i = 0; i < n; ++i) local[i] = shape_box(scene.bodies[i]);
  std::vector<Thinned<Sample>> paths(n, Thinned<Sample>(cap));
  run.turning.resize(n);
  for (BodyIndex i = 0; i < n; ++i) {
    if (!world.rotates(i)) continue;
    run.turning[i] = world.pivot_vertices(i);
    // Whatever its angle, a turning body lies within its reach of the pivot.
    double reach = 0;
    for (const Vec2d& v : run.turning[i]) reach = std::max(reach, std::sqrt(dot(v, v)));
    local[i] = Box{};
    local[i].add({-reach, -reach});
    local[i].add({reach, reach});
  }
  auto place = [&](BodyIndex i) {
    const BodySnapshot<double> s = world.snapshot(i);
    if (run.turning[i].empty()) return Sample{world.time(), s.position, 0};
    return Sample{world.time(), s.position + rotated(s.angle, world.pivot(i)), s.angle};
  };
  auto sample = [&](BodyIndex i) {
    if (world.is_fixed(i)) return;
    const Sample here = place(i);
    paths[i].add(here);
    run.extent.add(local[i], here.p);
  };
  std::vector<Sample> fixed_start(n);
  for (BodyIndex i = 0; i < n; ++i) {
    if (world.is_fixed(i)) {
      fixed_start[i] = place(i);
      run.extent.add(local[i], run.turning[i].empty() ? scene.bodies[i].position : fixed_start[i].p);
    }
    sample(i);
  }

  Thinned<Mark> marks(kMaxMarks);
  world.on_collision([&](const CollisionInfo<double>& c) {
    sample(c.a);
    sample(c.b);
    if (c.impulse > 0) {  // a graze (predicted, not approaching) applies nothing: no mark
      marks.add({c.time, c.point, c.a, c.b});
      run.extent.add(c.point);
    }
  });
  world.on_motion_change([&](BodyIndex i, double) { sample(i); });
  world.on_frame([&](const World<double>& w, double) {
    for (const BodyIndex i : moving)
      if (!(w.motion(i).acc == Vec2d{})) sample(i);
  });
  step_to_end(world);
  for (const BodyIndex i : moving) sample(i);

  run.solver = std::string(solver_name(world.solver()));
  run.horizon = world.horizon();
  run.end = world.time();
  run.stop = world.stop_reason();
  run.collisions = world.counts().collisions;
  run.storm = world.storm();
  run.paths.resize(n);
  for (BodyIndex i = 0; i < n; ++i) {
    if (!world.is_fixed(i))
      run.paths[i] = paths[i].finish();
    else if (run.turning[i].empty())
      run.paths[i] = {{0, scene.bodies[i].position}};
    else
      run.paths[i] = {fixed_start[i], place(i)};
  }
  run.marks = marks.finish();
  run.marks_seen = marks.seen();
  return run;
}

std::vector<Vec2d> turned_outline(const Run& run, std::size_t i, const Sample& s) {
  std::vector<Vec2d> out;
  for (const Vec2d& v : run.turning[i]) out.push_back(s.p + rotated(s.angle, v));
  return out;
}

}  // namespace pge::cli::render
