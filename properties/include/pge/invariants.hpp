// Invariants every run must keep, measured exactly where measurement could add error: used by
// the property tests and by `pge fuzz` (one definition of each bound).
#pragma once

#include "pge/constants.hpp"
#include "pge/roots.hpp"
#include "pge/scene.hpp"
#include "pge/world.hpp"

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace pge {

// --- Bounds, each with its reason; all are multiples of epsilon(double). -----------------------
// Momentum of a collision between two moving bodies: each velocity update v' = v - n (j / m)
// rounds three times (j / m, the product with n, the sum) and 1/m itself is rounded, so each
// body's momentum change is off by a few eps of m (|v| + |v'|); 8 eps of the sum over both
// bodies, per component, leaves a factor of 2 of margin.
inline constexpr double kMomentumEps = 8;
// Kinetic energy of an elastic (e = 1) collision: velocities rounded at eps |v| change m v^2 / 2
// by about eps m |v|^2 per component and body: 32 eps of the pair's energy before plus after.
inline constexpr double kCollisionEnergyEps = 32;
// Mechanical energy over a run: per event, positions and velocities are re-rounded once (lazy
// rebase) and impulses round as above: 64 eps of the energy scale sum m (|v|^2 / 2 + |a| |p|)
// per event.
inline constexpr double kRunEnergyEpsPerEvent = 64;

// Exact momentum and energy checks of one collision; on failure, `detail` says by how much.
bool momentum_conserved(const CollisionInfo<double>& c, double mass_a, double mass_b, std::string* detail);
// With inertia_a, inertia_b (World::inertia: 0 for a body that does not turn) the energy includes
// I w^2 / 2 from the event's angular velocities.
bool kinetic_energy_conserved(const CollisionInfo<double>& c, double mass_a, double mass_b, std::string* detail,
                              double inertia_a = 0, double inertia_b = 0);

enum class FailureKind : std::uint8_t {
  Exception,   // the engine threw (other than rejecting the scene)
  NonFinite,   // a position or velocity became NaN or infinite
  Overlap,     // two bodies overlap past kOverlapBoundUlps (robust and certified; see below)
  Momentum,    // a collision between moving bodies changed momentum past kMomentumEps
  Energy,      // an elastic collision changed kinetic energy past kCollisionEnergyEps
  Storm,       // an event storm (counted as a failure only when asked)
  // Judged by the exact oracle (pge fuzz; not by check_invariants, which has no oracle):
  Miss,        // the engine skipped a contact that comes exactly earlier
  Phantom,     // the engine processed a contact the exact paths do not make
  Rounding,    // certified: an event time that is not the exact time correctly rounded
  Count,
};
std::string_view failure_kind_name(FailureKind k);

struct Failure {
  FailureKind kind = FailureKind::Exception;
  double time = 0;
  std::string detail;
};

// check_invariants: the scene run with options.solver, and after every event: finite states,
// exact momentum of collisions between moving bodies, exact kinetic energy of elastic ones (the
// impulse's arithmetic, the same for every solver), and, for robust and certified, the overlap
// bound. The fast solver's closed forms are the contrast baseline, known to lose a contact's
// time (a disc at 1.3e8 m/s under a relative acceleration, a quartic, hits a fixed disc 6e-9 s
// late and 0.8 deep: found by fuzz_engine, kept in fixtures/regressions/ as
// fast-quartic-late-contact.json): it is held to no accuracy bound, as the oracle judges only
// robust and certified (pge fuzz, pge check).
struct InvariantOptions {
  SolverKind solver = SolverKind::Robust;
  bool storms_fail = false;
  BroadPhase broad_phase = BroadPhase::Auto;
};

struct InvariantReport {
  std::optional<Failure> failure;  // the first failure, if any
  std::uint64_t events = 0;        // collisions and grazes processed
  StopReason stop = StopReason::ReachedUntil;
};

// Runs the scene (double precision) and checks after every collision: finite states, the
// overlap bound (robust and certified, see InvariantOptions), exact momentum conservation for
// moving pairs, exact kinetic energy conservation where both bodies have restitution 1.
InvariantReport check_invariants(const Scene& scene, const InvariantOptions& options = {});

}  // namespace pge
