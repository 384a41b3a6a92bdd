// The event trace: JSON Lines, one object per line (format "pge-trace/2" in events mode, see
// docs/formats.md), which `pge judge` reads.
// Numbers are written in shortest round-trip form; extended scalars are rounded to double.
#pragma once

#include "pge/scene.hpp"
#include "pge/world.hpp"

#include <fmt/core.h>

#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>

namespace pge::cli {

// A JSON string literal for `s` (quotes and control characters escaped).
std::string json_quoted(std::string_view s);

class TraceWriter {
 public:
  TraceWriter() = default;
  TraceWriter(const TraceWriter&) = delete;
  TraceWriter& operator=(const TraceWriter&) = delete;
  ~TraceWriter();

  bool open(const std::string& path);
  bool close();  // false if anything failed to write
  const std::string& error() const { return error_; }

  void header(const Scene& scene, std::string_view scalar, std::string_view solver, double horizon);

  // Called from the world's collision callback: the world holds the pair's motions after the
  // collision, rebased to its time, so their p0 are the positions at the contact.
  // A rotating body's position is its reference point (the scene's `position`, World::snapshot),
  // not its path's pivot; a pair with a rotating body adds "turn" (each body's angle and angular
  // velocity before) and "wa", "wb" (the angular velocities after).
  template <class T> void collision(const Scene& scene, const World<T>& w, const CollisionInfo<T>& c) {
    const auto at = [&](BodyIndex i) { return w.rotates(i) ? w.snapshot(i).position : w.motion(i).p0; };
    const Vec2<T> pa = at(c.a), pb = at(c.b);
    const bool turning = w.rotates(c.a) || w.rotates(c.b);
    fmt::print(file_,
               "{{\"event\":\"collision\",\"t\":{},\"a\":{},\"b\":{},\"contact\":\"{}\",\"features\":[{},{}],"
               "\"normal\":[{},{}],\"point\":[{},{}],\"approach_speed\":{},\"impulse\":{},\"gap\":{},"
               "\"overlap_rule\":{},\"before\":[[{},{},{},{}],[{},{},{},{}]],\"va\":[{},{}],\"vb\":[{},{}]",
               d(c.time), quoted(scene.bodies[c.a].id), quoted(scene.bodies[c.b].id), contact_kind_name(c.contact),
               c.feature_a, c.feature_b, d(c.normal.x), d(c.normal.y), d(c.point.x), d(c.point.y),
               d(c.approach_speed), d(c.impulse), d(c.gap), c.at_start_overlap ? "true" : "false", d(pa.x), d(pa.y),
               d(c.va_before.x), d(c.va_before.y), d(pb.x), d(pb.y), d(c.vb_before.x), d(c.vb_before.y), d(c.va_after.x),
               d(c.va_after.y), d(c.vb_after.x), d(c.vb_after.y));
    if (turning)
      fmt::print(file_, ",\"turn\":[[{},{}],[{},{}]],\"wa\":{},\"wb\":{}", d(w.snapshot(c.a).angle), d(c.wa_before),
                 d(w.snapshot(c.b).angle), d(c.wb_before), d(c.wa_after), d(c.wb_after));
    fmt::print(file_, "}}\n");
  }

  template <class T> void frame(const World<T>& w, T t) {
    fmt::print(file_, "{{\"event\":\"frame\",\"t\":{},\"bodies\":[", d(t));
    for (BodyIndex i = 0; i < w.body_count(); ++i) {
      const BodySnapshot<T> s = w.snapshot(i);
      fmt::print(file_, "{}[{},{},{},{}]", i ? "," : "", d(s.position.x), d(s.position.y), d(s.velocity.x),
                 d(s.velocity.y));
    }
    fmt::print(file_, "]");
    if (rotating_) {  // each body's [angle, angular velocity], scene order (0, 0 if it does not turn)
      fmt::print(file_, ",\"turns\":[");
      for (BodyIndex i = 0; i < w.body_count(); ++i) {
        const BodySnapshot<T> s = w.snapshot(i);
        fmt::print(file_, "{}[{},{}]", i ? "," : "", d(s.angle), d(s.angular_velocity));
      }
      fmt::print(file_, "]");
    }
    fmt::print(file_, "}}\n");
  }

  template <class T> void end(const World<T>& w, std::uint64_t hash) {
    fmt::print(file_, "{{\"event\":\"end\",\"t\":{},\"stop\":\"{}\",\"collisions\":{},\"state_hash\":\"{:#018x}\"}}\n",
               d(w.time()), stop_reason_name(w.stop_reason()), w.counts().collisions, hash);
  }

 private:
  template <class T> static double d(const T& x) { return static_cast<double>(x); }
  static std::string quoted(std::string_view s) { return json_quoted(s); }

  bool rotating_ = false;  // the scene has a rotating body: frames carry "turns"
  std::FILE* file_ = nullptr;
  std::string path_;
  std::string error_;
};

}  // namespace pge::cli
