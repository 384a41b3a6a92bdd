// Properties of the engine on generated scenes (rapidcheck). Conservation is measured exactly:
// sums of the engine's doubles in rationals, so the measurement adds no error of its own.
// Reproduce a failure with the RC_PARAMS string rapidcheck prints, e.g.
//   RC_PARAMS="reproduce=..." build/properties/tests/test_properties
// and run longer with RC_PARAMS="seed=1 max_success=100000".
#include "pge/constants.hpp"
#include "pge/generators.hpp"
#include "pge/invariants.hpp"
#include "pge/validate.hpp"
#include "pge/world.hpp"

#include <boost/multiprecision/cpp_int.hpp>
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <tuple>
#include <vector>

namespace pge {
namespace {

using Rational = boost::multiprecision::cpp_rational;
constexpr double kEps = std::numeric_limits<double>::epsilon();

// Reversibility: positions come back to within 2^20 ulps of their magnitude (2.3e-10 relative)
// after a forward and a backward run of a few events. Rounding errors of a few ulps per event
// grow by the scene's amplification at each collision; 2^20 allows ~10 events of doubling.
constexpr double kReversibleUlps = 1048576;

Rational exact(double x) { return Rational(x); }

struct Recorded {
  std::vector<CollisionInfo<double>> events;
  StopReason stop{};
  std::uint64_t hash = 0;
};

Recorded run_scene(const Scene& s, double until = -1) {
  WorldOptions o;
  o.until = until;
  World<double> w(s, o);
  Recorded r;
  w.on_collision([&](const CollisionInfo<double>& c) { r.events.push_back(c); });
  r.stop = w.run();
  r.hash = w.state_hash();
  return r;
}

GenOptions circles_only() {
  GenOptions o;
  o.polygons = false;  // polygons: with the polygon engine
  return o;
}

// rapidcheck reports the share of each combination of labels; three labels keep that table
// readable. The share of each motif kind is reported by GeneratorsCoverEveryMotif.
void classify(const GeneratedScene& g) {
  const bool degenerate = std::any_of(g.motifs.begin(), g.motifs.end(), [](Motif m) { return m != Motif::Free; });
  RC_CLASSIFY(degenerate, "degenerate");
  RC_CLASSIFY(g.gravity, "gravity");
  RC_CLASSIFY(g.mixed_scale, "mixed-scale");
}

// 1. A collision between two moving bodies conserves momentum, measured exactly.
RC_GTEST_PROP(Properties, MomentumIsConservedByEachCollision, ()) {
  const GeneratedScene g = *gen_scene(circles_only());
  classify(g);
  World<double> w(g.scene);
  std::size_t checked = 0;
  w.on_collision([&](const CollisionInfo<double>& c) {
    if (w.is_fixed(c.a) || w.is_fixed(c.b)) return;
    std::string detail;
    RC_ASSERT(momentum_conserved(c, w.mass(c.a), w.mass(c.b), &detail));
    ++checked;
  });
  w.run();
  RC_CLASSIFY(checked > 0, "has moving-pair collisions");
}

// 2a. With restitution 1 each collision conserves kinetic energy, measured exactly.
RC_GTEST_PROP(Properties, ElasticCollisionsConserveKineticEnergy, ()) {
  GenOptions o = circles_only();
  o.inelastic = false;
  const GeneratedScene g = *gen_scene(o);
  classify(g);
  World<double> w(g.scene);
  w.on_collision([&](const CollisionInfo<double>& c) {
    std::string detail;
    RC_ASSERT(kinetic_energy_conserved(c, w.mass(c.a), w.mass(c.b), &detail));
  });
  w.run();
}

// 2b. Under gravity, total mechanical energy drifts by at most a bound per event over a run.
RC_GTEST_PROP(Properties, MechanicalEnergyDriftIsBoundedPerEvent, ()) {
  GenOptions o = circles_only();
  o.inelastic = false;
  const GeneratedScene g = *gen_scene(o);
  classify(g);
  World<double> w(g.scene);
  auto energy = [&w](double& scale) {
    Rational e = 0;
    scale = 0;
    for (BodyIndex i = 0; i < w.body_count(); ++i) {
      if (w.is_fixed(i)) continue;
      const BodySnapshot<double> s = w.snapshot(i);
      // The field's acceleration (gravity and the body's own), not the path's: a resting body's
      // path drops the normal part, which the face's reaction balances and which does no work.
      const Vec2d acc = w.field_acceleration(i);
      const Rational mass = exact(w.mass(i));
      e += mass * (exact(s.velocity.x) * exact(s.velocity.x) + exact(s.velocity.y) * exact(s.velocity.y)) / 2;
      e -= mass * (exact(acc.x) * exact(s.position.x) + exact(acc.y) * exact(s.position.y));
      scale += w.mass(i) * (dot(s.velocity, s.velocity) / 2 +
                            std::hypot(acc.x, acc.y) * std::hypot(s.position.x, s.position.y));
    }
    return e;
  };
  double scale0 = 0, scale1 = 0;
  const Rational e0 = energy(scale0);
  w.run();
  const Rational e1 = energy(scale1);
  const double events = static_cast<double>(w.counts().collisions + w.counts().grazes + 1);
  RC_ASSERT(static_cast<double>(abs(e1 - e0)) <= kRunEnergyEpsPerEvent * kEps * std::max(scale0, scale1) * events);
}

// 4. No overlap between events beyond the documented bound.
RC_GTEST_PROP(Properties, NoOverlapBeyondTheBound, ()) {
  const GeneratedScene g = *gen_scene(circles_only());
  classify(g);
  World<double> w(g.scene);
  while (w.step()) {
    const auto o = w.largest_overlap();
    RC_ASSERT(o.ulps <= kOverlapBoundUlps);
  }
}

// 4b. Stacks (two moving boxes pressed together on a floor, off in the default generator: a
// resting contact between moving bodies, which the engine reports as an event storm by design)
// may storm, but never sink into each other or through the floor: the overlap bound holds at
// every event until the run ends. Runs stop at 200 collisions, before a storm (kStormCollisions)
// is declared: the storms' cost, not their report, is what this leaves out.
RC_GTEST_PROP(Properties, StacksStormButNeverOverlap, ()) {
  GenOptions o;
  o.motif_mask = motif_bit(Motif::Stack);
  o.max_motifs = 2;
  o.max_events = 200;
  const GeneratedScene g = *gen_scene(o);
  classify(g);
  World<double> w(g.scene);
  while (w.step()) RC_ASSERT(w.largest_overlap().ulps <= kOverlapBoundUlps);
  RC_CLASSIFY(w.stop_reason() == StopReason::MaxEvents, "stopped at max_events");
}

// Events as (time, lower id, higher id), up to (not including) the first instant at which two
// events share a moving body: there the sequential order of impulses, which depends on body
// indices, decides the outcome, so relabelled or mirrored scenes may legitimately part ways
// after it. An "instant" groups events less than kInstantRelative * max(1, |t|) apart: after
// the first impulse of a simultaneous pair the second contact is re-predicted from rounded
// positions and may land an ulp or so later. Two runs are compared up to the earlier of their
// two ambiguous instants: when three bodies touch at once, one order of impulses may process
// only two of the three contacts (the third no longer approaching) and look unambiguous, while
// the other order processes all three (found at 100,000 cases: three circles meeting at one
// point; a flaw of this comparison, not of the engine).
constexpr double kInstantRelative = 1e-9;
using EventKey = std::tuple<double, std::string, std::string>;

// The start of the first instant at which a moving body takes part in two events (infinity if none).
double first_ambiguous_instant(const Scene& s, const std::vector<CollisionInfo<double>>& events) {
  std::size_t i = 0;
  while (i < events.size()) {
    std::size_t j = i + 1;
    const double window = kInstantRelative * std::max(1.0, std::abs(events[i].time));
    while (j < events.size() && events[j].time - events[j - 1].time <= window) ++j;
    std::map<BodyIndex, int> uses;
    for (std::size_t k = i; k < j; ++k) {
      ++uses[events[k].a];
      ++uses[events[k].b];
    }
    for (const auto& [body, n] : uses)
      if (n > 1 && !s.bodies[body].fixed) return events[i].time;
    i = j;
  }
  return std::numeric_limits<double>::infinity();
}

// The events strictly before the instant that starts at `cut`, as sorted keys.
std::vector<EventKey> events_before(const Scene& s, const std::vector<CollisionInfo<double>>& events, double cut) {
  std::vector<EventKey> out;
  const double window = kInstantRelative * std::max(1.0, std::abs(cut));
  for (const CollisionInfo<double>& e : events) {
    if (!(e.time < cut - window)) break;
    std::string a = s.bodies[e.a].id, b = s.bodies[e.b].id;
    if (b < a) std::swap(a, b);
    out.emplace_back(e.time, a, b);
  }
  std::sort(out.begin(), out.end());
  return out;
}

// Whether two runs of equivalent scenes agree up to the first ambiguous instant of either.
bool same_unambiguous_events(const Scene& sa, const std::vector<CollisionInfo<double>>& a, const Scene& sb,
                             const std::vector<CollisionInfo<double>>& b) {
  const double cut = std::min(first_ambiguous_instant(sa, a), first_ambiguous_instant(sb, b));
  return events_before(sa, a, cut) == events_before(sb, b, cut);
}

Scene mirrored_in_x(Scene s) {
  for (BodyDesc& b : s.bodies) {
    b.position.x = -b.position.x;
    b.velocity.x = -b.velocity.x;
    b.acceleration.x = -b.acceleration.x;
    b.a.x = -b.a.x;
    b.b.x = -b.b.x;
    for (Vec2d& v : b.vertices) v.x = -v.x;
    std::reverse(b.vertices.begin(), b.vertices.end());  // mirroring turns CCW into CW
  }
  s.world.gravity.x = -s.world.gravity.x;
  return s;
}

// 5a. Mirroring in x (exact in floating point) gives the same events bit for bit.
RC_GTEST_PROP(Properties, MirroringInXGivesTheSameEvents, ()) {
  const GeneratedScene g = *gen_scene(circles_only());
  classify(g);
  const Recorded a = run_scene(g.scene);
  const Scene m = mirrored_in_x(g.scene);
  const Recorded b = run_scene(m);
  RC_ASSERT(same_unambiguous_events(g.scene, a.events, m, b.events));
}

// 5b. Relabelling (reversing the body order) gives the same events, bit for bit, up to the first
// instant where the order of simultaneous impulses on one body matters.
RC_GTEST_PROP(Properties, RelabellingGivesTheSameEvents, ()) {
  const GeneratedScene g = *gen_scene(circles_only());
  classify(g);
  Scene r = g.scene;
  std::reverse(r.bodies.begin(), r.bodies.end());
  const Recorded a = run_scene(g.scene);
  const Recorded b = run_scene(r);
  RC_ASSERT(same_unambiguous_events(g.scene, a.events, r, b.events));
}

// 5c. Swapping the two bodies of a two-body scene gives the same events bit for bit (the pair's
// computations are antisymmetric in the relative coordinates, and negation is exact).
RC_GTEST_PROP(Properties, SwappingAPairGivesTheSameEvents, ()) {
  GenOptions o = circles_only();
  o.max_motifs = 1;
  o.gravity = false;
  o.motif_mask = motif_bit(Motif::TouchingPair) | motif_bit(Motif::Graze) | motif_bit(Motif::NearGraze);
  const GeneratedScene g = *gen_scene(o);
  classify(g);
  RC_PRE(g.scene.bodies.size() == 2u);
  Scene swapped = g.scene;
  std::swap(swapped.bodies[0], swapped.bodies[1]);
  const Recorded a = run_scene(g.scene);
  const Recorded b = run_scene(swapped);
  RC_ASSERT(same_unambiguous_events(g.scene, a.events, swapped, b.events));
}

// 5d. Translating by a dyadic offset that keeps every starting coordinate exact gives the same
// first event bit for bit (predictions from the starting state see the same relative
// coordinates). Later events are predicted from positions rounded at the new magnitude, so
// only the first is compared bit for bit.
RC_GTEST_PROP(Properties, DyadicTranslationGivesTheSameFirstEvent, ()) {
  const GeneratedScene g = *gen_scene(circles_only());
  classify(g);
  const int k = *rc::gen::inRange(-4, 5);
  const double dx = std::ldexp(1.0, k), dy = std::ldexp(3.0, k);
  Scene t = g.scene;
  bool exact_shift = true;
  for (BodyDesc& b : t.bodies) {
    const Vec2d p = b.position;
    b.position = {p.x + dx, p.y + dy};
    exact_shift = exact_shift && b.position.x - dx == p.x && b.position.y - dy == p.y &&
                  exact(b.position.x) - exact(dx) == exact(p.x) && exact(b.position.y) - exact(dy) == exact(p.y);
  }
  RC_PRE(exact_shift);
  const Recorded a = run_scene(g.scene);
  const Recorded b = run_scene(t);
  RC_ASSERT(a.events.empty() == b.events.empty());
  if (a.events.empty()) return;
  RC_ASSERT(a.events[0].time == b.events[0].time);
  RC_ASSERT(a.events[0].a == b.events[0].a);
  RC_ASSERT(a.events[0].b == b.events[0].b);
}

// 6. The same scene twice gives the same state hash.
RC_GTEST_PROP(Properties, RunsAreDeterministic, ()) {
  const GeneratedScene g = *gen_scene(circles_only());
  classify(g);
  const Recorded a = run_scene(g.scene);
  const Recorded b = run_scene(g.scene);
  RC_ASSERT(a.hash == b.hash);
  RC_ASSERT(a.events.size() == b.events.size());
}

// 7. Elastic scenes without gravity are reversible: run for T, reverse every velocity, run for T
// again, and every body is back where it started. Motifs whose outcome hangs on a tie or a
// one-ulp decision (grazes, simultaneous impacts, corner-on-corner) are left out: their
// reverse is not the mirror of their forward run under sequential impulses.
RC_GTEST_PROP(Properties, ElasticRunsAreReversible, ()) {
  GenOptions o = circles_only();
  o.gravity = false;
  o.inelastic = false;
  o.accelerations = false;
  o.motif_mask = motif_bit(Motif::Free) | motif_bit(Motif::TouchingPair) | motif_bit(Motif::Cradle) |
                 motif_bit(Motif::WallHit);
  const GeneratedScene g = *gen_scene(o);
  classify(g);
  const double t = 1;
  WorldOptions wo;
  wo.until = t;
  World<double> forward(g.scene, wo);
  forward.run();
  RC_PRE(forward.stop_reason() == StopReason::ReachedUntil);
  RC_CLASSIFY(forward.counts().collisions > 0, "collided");
  Scene back = g.scene;
  for (BodyIndex i = 0; i < back.bodies.size(); ++i) {
    if (back.bodies[i].fixed) continue;
    const BodySnapshot<double> s = forward.snapshot(i);
    back.bodies[i].position = s.position;
    back.bodies[i].velocity = {-s.velocity.x, -s.velocity.y};
  }
  World<double> backward(back, wo);
  backward.run();
  for (BodyIndex i = 0; i < back.bodies.size(); ++i) {
    if (back.bodies[i].fixed) continue;
    const Vec2d p0 = g.scene.bodies[i].position;
    const Vec2d p1 = backward.snapshot(i).position;
    const double magnitude = std::max({std::abs(p0.x), std::abs(p0.y), g.scene.bodies[i].radius});
    RC_ASSERT(std::hypot(p1.x - p0.x, p1.y - p0.y) <= kReversibleUlps * kEps * magnitude);
  }
}

// The generators make every motif kind; the classification shows each kind's share, and every
// case's single motif is checked to be what the scene holds. (Stack included here: the default
// mask leaves it out, see GenOptions::motif_mask.)
RC_GTEST_PROP(Properties, GeneratorsCoverEveryMotif, ()) {
  GenOptions o;
  o.max_motifs = 1;
  o.motif_mask = ~0u;
  const GeneratedScene g = *gen_scene(o);
  RC_ASSERT(g.motifs.size() == 1u);
  RC_CLASSIFY(true, std::string(motif_name(g.motifs[0])));
}

// The generators make valid scenes (a property of the generators themselves).
RC_GTEST_PROP(Properties, GeneratedScenesAreValid, ()) {
  const GeneratedScene g = *gen_scene();
  classify(g);
  const auto problem = validate_scene(g.scene);
  RC_ASSERT(!problem.has_value());
}

}  // namespace
}  // namespace pge
