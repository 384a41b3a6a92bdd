// World<T>::Impl, part of world_impl.hpp. The event loop: construction from a scene, and step(),
// which merges contacts, cell crossings, timers and frames in their fixed order.
#pragma once

#include "world_impl.hpp"

namespace pge {

template <class T> World<T>::World(const Scene& scene, const WorldOptions& options) : impl_(std::make_unique<Impl>()) {
  BroadPhase mode = options.broad_phase;
  if (mode == BroadPhase::Auto) {
    const char* env = std::getenv("PGE_BROAD_PHASE");
    if (env && *env && !parse_broad_phase(env, mode))
      throw std::invalid_argument(std::string("PGE_BROAD_PHASE: expected auto, grid or all-pairs, got \"") + env + "\"");
  }
  if (auto problem = validate_scene(scene)) {
    std::string where = problem->body >= 0 ? "body \"" + scene.bodies[problem->body].id + "\": " : "";
    throw std::invalid_argument(where + problem->field + ": " + problem->message);
  }
  if (scene.bodies.size() > kMaxBodies)
    throw UnsupportedScene(-1, std::to_string(scene.bodies.size()) + " bodies: at most " + std::to_string(kMaxBodies));
  if (mode == BroadPhase::AllPairs && scene.bodies.size() > kMaxBodiesWithoutBroadPhase)
    throw UnsupportedScene(-1, std::to_string(scene.bodies.size()) + " bodies: at most " +
                                   std::to_string(kMaxBodiesWithoutBroadPhase) +
                                   " without the broad phase (every pair is predicted once at the start)");
  Impl& w = *impl_;
  if (std::any_of(scene.bodies.begin(), scene.bodies.end(), [](const BodyDesc& d) { return d.rotates; }))
    w.spins.resize(scene.bodies.size());
  w.horizon = T(options.until >= 0 ? options.until : scene.run.until);
  w.solver = options.solver.value_or(scene.run.solver);
  w.max_events = options.max_events > 0 ? options.max_events : scene.run.max_events;
  w.fps = options.frames_per_second >= 0 ? options.frames_per_second : scene.run.frames_per_second;
  // The overrides get the scene's own checks (validate_scene): a horizon in the supported
  // range, and a bounded number of frames, which max_events does not limit.
  const double until = options.until >= 0 ? options.until : scene.run.until;
  auto shortest = [](double x) {
    std::ostringstream s;
    s << x;
    return s.str();
  };
  if (!(until <= kMaxSceneMagnitude))
    throw std::invalid_argument("until: out of the supported range: at most " + shortest(kMaxSceneMagnitude) +
                                " seconds, got " + shortest(until));
  if (!(std::isfinite(w.fps) && w.fps * until <= kMaxFramesPerRun))
    throw std::invalid_argument("frames per second: " + shortest(w.fps) + " gives more than the supported " +
                                shortest(kMaxFramesPerRun) + " frames over " + shortest(until) + " s");
  w.bodies.reserve(scene.bodies.size());
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    const BodyDesc& d = scene.bodies[i];
    typename Impl::Body b;
    b.id = d.id;
    b.shape = make_body_shape<T>(d);
    b.fixed = d.fixed;
    b.mass = d.fixed ? T(0) : T(d.mass);
    b.inv_mass = d.fixed ? T(0) : T(1) / T(d.mass);
    b.restitution = T(d.restitution >= 0 ? d.restitution : scene.world.restitution);
    b.p0 = vec_cast<T>(d.position);
    if (!d.fixed) {
      b.v0 = vec_cast<T>(d.velocity);
      const Vec2d total = d.acceleration + (d.gravity ? scene.world.gravity : Vec2d{});
      b.acc = vec_cast<T>(total);
      b.field_acc = b.acc;
      w.moving.push_back(static_cast<BodyIndex>(i));
    }
    if (d.rotates) w.setup_spin(i, b, d);
    w.bodies.push_back(std::move(b));
  }
  w.heap.reset(w.bodies.size(), w.moving);
  w.prefetching = w.bodies.size() >= Impl::kPrefetchMinBodies;
  w.heap.set_prefetching(w.prefetching);
  w.setup_grid(mode);
  w.schedule_all();
#ifdef PGE_VALIDATE
  if (w.bodies.size() <= Impl::kValidateScanMaxBodies) w.start_overlap_depth = largest_overlap().depth;
#endif
  if (options.watch_tunnels || Impl::kValidating) w.tunnel_watch.emplace(scene);
}

template <class T> World<T>::~World() = default;
template <class T> World<T>::World(World&&) noexcept = default;
template <class T> World<T>& World<T>::operator=(World&&) noexcept = default;

template <class T> void World<T>::on_collision(CollisionCallback cb) { impl_->on_collision = std::move(cb); }
template <class T> void World<T>::on_frame(FrameCallback cb) { impl_->on_frame = std::move(cb); }
template <class T> void World<T>::on_motion_change(MotionCallback cb) { impl_->on_motion_change = std::move(cb); }
template <class T> void World<T>::add_timer(T time, TimerCallback cb) {
  if (time < impl_->now || time > impl_->horizon) return;
  impl_->timers.push({time, impl_->timer_seq++, std::move(cb)});
}

template <class T> bool World<T>::step() {
  Impl& w = *impl_;
  while (!w.finished) {
    if (w.stop_requested) {
      w.reason = StopReason::Stopped;
      w.finished = true;
      break;
    }
    // The three sources, merged in the fixed order: time, then kind (collision, timer, frame).
    // When the heap's earliest event is a cell crossing, every contact is at or after it.
    const bool crossing_first = !w.heap.empty() && w.heap.top_is_crossing();
    // The events after this one are most likely its children's in the heap: their entries and
    // bodies are fetched while this one is processed (with 1e5 bodies each is a cache miss).
    if (w.prefetching) {
      w.heap.visit_next([&](BodyIndex j, BodyIndex partner) {
        w.heap.prefetch(j);
        Impl::prefetch_hot(w.bodies[j]);
        if (partner == kNoBody) return;
        w.heap.prefetch(partner);
        Impl::prefetch_hot(w.bodies[partner]);
      });
    }
    const Scheduled<T>* contact = w.heap.empty() || crossing_first ? nullptr : &w.heap.top();
    const bool has_contact = contact && contact->valid();
    // This event's bodies, fetched one step ago, name their cells: the cells' records are
    // fetched now, while the event's time is re-derived and its impulse applied.
    if (has_contact && w.grid_on && w.prefetching) {
      w.prefetch_cells(w.heap.top_index());
      w.prefetch_cells(contact->partner);
    }
    const bool has_timer = !w.timers.empty();
    const bool has_frame = w.fps > 0 && w.frame_time(w.next_frame) <= w.horizon;
    // A cell crossing due no later than every other event is bookkeeping: no motion changes
    // and the clock stays where it is (cross()). Robust and certified take crossings up to the
    // refinement bound past the horizon, so that a contact predicted there (behind the
    // crossing in the heap) is still re-derived exactly below.
    if (crossing_first) {
      const T at = w.heap.top_time();
      const T last = w.solver == SolverKind::Fast ? w.horizon : Impl::refine_bound(w.horizon);
      if (at <= last && (!has_timer || !(w.timers.top().time < at)) && (!has_frame || !(w.frame_time(w.next_frame) < at))) {
        w.cross(w.heap.top_index(), at);
        continue;
      }
    }
    T best = std::numeric_limits<T>::infinity();
    EventKind kind = EventKind::Collision;
    // Robust and certified: a contact predicted just past the horizon is re-derived exactly
    // before the horizon check (its exact time may be the horizon).
    if (has_contact && w.solver != SolverKind::Fast && !contact->refined && contact->time > w.horizon &&
        contact->time <= Impl::refine_bound(w.horizon) && w.refine_near_top())
      continue;
    if (has_contact) best = contact->time;
    if (has_timer && w.timers.top().time < best) { best = w.timers.top().time; kind = EventKind::Timer; }
    if (has_frame && w.frame_time(w.next_frame) < best) { best = w.frame_time(w.next_frame); kind = EventKind::Frame; }
    if (!(best <= w.horizon)) {
      w.now = w.horizon;
      w.reason = StopReason::ReachedUntil;
      w.finished = true;
      break;
    }
    if (kind == EventKind::Collision && contact->leave) {
      const Scheduled<T> s = *contact;
      const BodyIndex owner = w.heap.top_index();
      w.now = std::max(w.now, s.time);
      w.watch_path(owner);
      w.leave(s, owner);
      if (w.on_motion_change) w.on_motion_change(owner, w.now);
      continue;
    }
    if (kind == EventKind::Collision && contact->resume) {
      // A rotating pair's search that ran out of its budget: nothing touches before this time,
      // and the owner is predicted again from it (no motion changes).
      const BodyIndex owner = w.heap.top_index();
      w.now = std::max(w.now, contact->time);
      w.reschedule(owner);
      continue;
    }
    if (kind == EventKind::Collision) {
      const Scheduled<T> s = *contact;
      const BodyIndex owner = w.heap.top_index();
      const auto& partner = w.bodies[s.partner];
      if (!partner.fixed && partner.version != s.partner_version) {
        ++w.counts.stale;  // the partner moved differently since this was predicted
        w.reschedule(owner);
        continue;
      }
      // Robust and certified: the event's time, and the time of every other contact that might
      // be the same instant or earlier, are re-derived from the exact paths before any is
      // processed; then the queue is merged again (see refine_near_top).
      if (w.solver != SolverKind::Fast && w.refine_near_top()) continue;
      // A contact exactly at the horizon counts only if it is a collision: the solvers take a
      // touch arriving at the horizon as a root (what follows it is beyond the run), but one
      // that is not approaching there is a graze, which is no event (the oracle agrees). The
      // run ends instead of reporting a zero-impulse event.
      if (s.time >= w.horizon && !w.collides_at_horizon(s)) {
        w.now = w.horizon;
        w.reason = StopReason::ReachedUntil;
        w.finished = true;
        break;
      }
      w.now = std::max(w.now, s.time);
      w.watch_path(owner);
      w.watch_path(s.partner);
      w.collide(s);
#ifdef PGE_VALIDATE
      w.validate(*this);
#endif
      return true;
    }
    if (kind == EventKind::Timer) {
      typename Impl::Timer t = w.timers.top();
      w.timers.pop();
      w.now = std::max(w.now, t.time);
      ++w.counts.timers;
      t.callback(*this, w.now);
      return true;
    }
    w.now = std::max(w.now, best);
    ++w.next_frame;
    ++w.counts.frames;
    if (w.on_frame) w.on_frame(*this, w.now);
    return true;
  }
  w.watch_end();
  return false;
}

template <class T> StopReason World<T>::run() {
  while (step()) {
  }
  return impl_->reason;
}

}  // namespace pge
