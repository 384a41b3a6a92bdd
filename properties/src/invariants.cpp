#include "pge/invariants.hpp"

#include "pge/constants.hpp"

#include <boost/multiprecision/cpp_int.hpp>

#include <cmath>
#include <limits>
#include <sstream>

namespace pge {
namespace {

using Rational = boost::multiprecision::cpp_rational;
constexpr double kEps = std::numeric_limits<double>::epsilon();

Rational exact(double x) { return Rational(x); }  // every double is a rational: exact

std::string describe(const char* what, double change, double bound) {
  std::ostringstream s;
  s.precision(6);
  s << what << " changed by " << change << ", bound " << bound;
  return s.str();
}

bool finite(const Vec2d& v) { return std::isfinite(v.x) && std::isfinite(v.y); }

}  // namespace

std::string_view failure_kind_name(FailureKind k) {
  switch (k) {
    case FailureKind::Exception: return "exception";
    case FailureKind::NonFinite: return "non-finite";
    case FailureKind::Overlap: return "overlap";
    case FailureKind::Momentum: return "momentum";
    case FailureKind::Energy: return "energy";
    case FailureKind::Storm: return "storm";
    case FailureKind::Miss: return "miss";
    case FailureKind::Phantom: return "phantom";
    case FailureKind::Rounding: return "rounding";
    case FailureKind::Count: break;
  }
  return "?";
}

bool momentum_conserved(const CollisionInfo<double>& c, double ma, double mb, std::string* detail) {
  for (int axis = 0; axis < 2; ++axis) {
    auto comp = [axis](const Vec2d& v) { return axis == 0 ? v.x : v.y; };
    const Rational before = exact(ma) * exact(comp(c.va_before)) + exact(mb) * exact(comp(c.vb_before));
    const Rational after = exact(ma) * exact(comp(c.va_after)) + exact(mb) * exact(comp(c.vb_after));
    const double scale = ma * (std::abs(comp(c.va_before)) + std::abs(comp(c.va_after))) +
                         mb * (std::abs(comp(c.vb_before)) + std::abs(comp(c.vb_after)));
    const double change = static_cast<double>(abs(after - before));
    const double bound = kMomentumEps * kEps * scale;
    if (change > bound) {
      if (detail) *detail = describe(axis == 0 ? "momentum x" : "momentum y", change, bound);
      return false;
    }
  }
  return true;
}

bool kinetic_energy_conserved(const CollisionInfo<double>& c, double ma, double mb, std::string* detail, double ia,
                              double ib) {
  auto ke = [](double m, const Vec2d& v, double inertia, double w) {
    if (m == 0) return Rational(0);
    return exact(m) * (exact(v.x) * exact(v.x) + exact(v.y) * exact(v.y)) / 2 + exact(inertia) * exact(w) * exact(w) / 2;
  };
  const Rational before = ke(ma, c.va_before, ia, c.wa_before) + ke(mb, c.vb_before, ib, c.wb_before);
  const Rational after = ke(ma, c.va_after, ia, c.wa_after) + ke(mb, c.vb_after, ib, c.wb_after);
  const double change = static_cast<double>(abs(after - before));
  const double bound = kCollisionEnergyEps * kEps * static_cast<double>(before + after);
  if (change > bound) {
    if (detail) *detail = describe("kinetic energy", change, bound);
    return false;
  }
  return true;
}

InvariantReport check_invariants(const Scene& scene, const InvariantOptions& options) {
  InvariantReport report;
  // The first failure is kept, filled in place: moving a temporary Failure in, g++ 12 -O2 with
  // the precompiled headers inlined the string's move otherwise and warned of a bounds error
  // that is not there (-Warray-bounds on char_traits' memcpy: an error with PGE_WERROR).
  auto fail = [&](FailureKind kind, double t, std::string_view detail) {
    if (report.failure) return;
    Failure& f = report.failure.emplace();
    f.kind = kind;
    f.time = t;
    f.detail = detail;
  };
  try {
    WorldOptions wo;
    wo.solver = options.solver;
    wo.broad_phase = options.broad_phase;
    World<double> w(scene, wo);
    w.on_collision([&](const CollisionInfo<double>& c) {
      std::string detail;
      if (!finite(c.va_after) || !finite(c.vb_after)) fail(FailureKind::NonFinite, c.time, "velocity after the impulse");
      const double ma = w.mass(c.a), mb = w.mass(c.b);
      if (ma > 0 && mb > 0 && !momentum_conserved(c, ma, mb, &detail)) fail(FailureKind::Momentum, c.time, detail);
      // A fixed body that turns (a turnstile: infinite mass and inertia, a constant rate) does work
      // on what strikes it, so an elastic impulse conserves the moving body's energy only when
      // neither is such a body (found by fuzz_engine: a ball off a rod spinning at 1 rad/s).
      const bool driven = (ma == 0 && c.wa_before != 0) || (mb == 0 && c.wb_before != 0);
      const bool elastic = w.restitution(c.a) == 1 && w.restitution(c.b) == 1 && !driven;
      if (elastic && !kinetic_energy_conserved(c, ma, mb, &detail, w.inertia(c.a), w.inertia(c.b)))
        fail(FailureKind::Energy, c.time, detail);
    });
    const double start_depth = w.largest_overlap().depth;
    while (!report.failure && w.step()) {
      report.events = w.counts().collisions + w.counts().grazes;
      const auto o = options.solver == SolverKind::Fast ? World<double>::Overlap{} : w.largest_overlap();
      if (overlap_past_bound(o.ulps, o.depth, start_depth)) {
        std::ostringstream s;
        s << "bodies \"" << w.body_id(o.a) << "\" and \"" << w.body_id(o.b) << "\" overlap by " << o.depth << " ("
          << o.ulps << " ulps, bound " << kOverlapBoundUlps << ")";
        fail(FailureKind::Overlap, w.time(), s.str());
      }
      for (BodyIndex i = 0; i < w.body_count() && !report.failure; ++i) {
        const BodySnapshot<double> s = w.snapshot(i);
        if (!finite(s.position) || !finite(s.velocity))
          fail(FailureKind::NonFinite, w.time(), "body \"" + w.body_id(i) + "\" has a non-finite state");
      }
    }
    report.stop = w.stop_reason();
    if (report.stop == StopReason::EventStorm && options.storms_fail) {
      const auto& st = w.storm();
      fail(FailureKind::Storm, st.time, "event storm between \"" + w.body_id(st.a) + "\" and \"" + w.body_id(st.b) + "\"");
    }
  } catch (const std::exception& e) {
    fail(FailureKind::Exception, 0, e.what());
  }
  return report;
}

}  // namespace pge
