// Steps mode of the trace referee (pge/judge.hpp): a stepping engine's steps, each judged from
// its start state on the scene's closed-form paths with the oracle's exact pair search.
#include "judge_scene.hpp"
#include "search.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>

namespace pge::oracle {

using namespace detail;

namespace {

using Pair = std::pair<BodyIndex, BodyIndex>;  // first < second

// Every body at one instant (fixed: its position, at rest). A rotating body's position is its
// pivot (judge_scene.hpp, pivot_of), with its angle and angular velocity (0, 0 for one that does
// not rotate).
struct Instant {
  std::vector<ExactVec> position, velocity;
  std::vector<Dyadic> angle, omega;
};

// The pairs (not both fixed) whose boxes overlap: a sweep over x.
std::vector<Pair> box_pairs(const ExactState& s, const std::vector<Box>& boxes) {
  const std::size_t n = boxes.size();
  std::vector<BodyIndex> order(n);
  for (BodyIndex i = 0; i < n; ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&boxes](BodyIndex i, BodyIndex j) {
    return boxes[i].lo_x < boxes[j].lo_x || (boxes[i].lo_x == boxes[j].lo_x && i < j);
  });
  std::vector<Pair> out;
  for (std::size_t p = 0; p < n; ++p) {
    const BodyIndex i = order[p];
    for (std::size_t q = p + 1; q < n && boxes[order[q]].lo_x <= boxes[i].hi_x; ++q) {
      const BodyIndex j = order[q];
      if (s.bodies[i].fixed && s.bodies[j].fixed) continue;
      if (boxes[j].lo_y > boxes[i].hi_y || boxes[i].lo_y > boxes[j].hi_y) continue;
      out.push_back(std::minmax(i, j));
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

// Every overlapping pair at one instant, with its depth.
std::map<Pair, double> overlaps(const ExactState& s, const Instant& x) {
  std::vector<Placed> placed;
  std::vector<Box> boxes;
  for (BodyIndex i = 0; i < s.bodies.size(); ++i) {
    placed.push_back(place(s.bodies[i], x.position[i], x.angle[i]));
    boxes.push_back(bounding_box(placed.back()));
  }
  std::map<Pair, double> out;
  for (const Pair& p : box_pairs(s, boxes)) {
    const Separation sep = separation(placed[p.first], placed[p.second]);
    if (sep.sign < 0) out.emplace(p, sep.depth);
  }
  return out;
}

// A box holding the body all through a step of length dt from x: its box at the start (a
// rotating body's at every angle) grown by |v| dt + |a| dt^2 / 2 (and 1/1000 of that more, for the
// rounding of these doubles).
Box swept_box(const ExactBody& b, const ExactVec& p, const ExactVec& v, double dt) {
  Box box = reach_box(b, p);
  if (b.fixed) return box;
  const double reach_x = std::abs(v.x.to_double()) * dt + std::abs(b.field_acc.x.to_double()) * dt * dt / 2;
  const double reach_y = std::abs(v.y.to_double()) * dt + std::abs(b.field_acc.y.to_double()) * dt * dt / 2;
  constexpr double kGrow = 1.001;
  box.lo_x -= reach_x * kGrow;
  box.hi_x += reach_x * kGrow;
  box.lo_y -= reach_y * kGrow;
  box.hi_y += reach_y * kGrow;
  return box;
}

struct Totals {
  Dyadic energy;
  ExactVec momentum;
};

Totals totals(const ExactState& s, const Instant& x) {
  Totals t;
  for (BodyIndex i = 0; i < s.bodies.size(); ++i) {
    const ExactBody& b = s.bodies[i];
    if (b.fixed) continue;
    t.energy += body_energy(b, x.position[i], x.velocity[i], x.omega[i]);
    t.momentum.x += b.mass * x.velocity[i].x;
    t.momentum.y += b.mass * x.velocity[i].y;
  }
  return t;
}

// change / |scale|, infinite for a change from 0.
double relative(double change, double scale) {
  if (scale != 0) return change / std::abs(scale);
  return change == 0 ? 0.0 : std::copysign(std::numeric_limits<double>::infinity(), change);
}

// A contact found in a step, waiting for its report.
struct Open {
  std::size_t contact;  // index into the judgement's contacts
  std::size_t step;
};

class StepReferee {
 public:
  StepReferee(const Scene& scene, const Trace& trace, const JudgeOptions& options)
      : trace_(trace), failer_(trace), options_(options), model_(scene_model(scene)) {
    if (trace.mode != TraceMode::Steps) failer_.fail(trace.header_line, "header", "mode", "judge_steps needs a steps trace");
    const ExactState& s = model_.state;
    for (const ExactBody& b : s.bodies) {
      exact_.push_back(exact_model(b));
      interval_.push_back(interval_model(b));
    }
    map_bodies();
    for (const ExactBody& b : s.bodies) {
      start_.position.push_back(b.motion.p0);
      start_.velocity.push_back(b.motion.v0);
      start_.angle.push_back(b.motion.theta0);
      start_.omega.push_back(b.motion.omega);
    }
  }

  StepJudgement run() {
    const ExactState& s = model_.state;
    Instant before = start_;
    std::map<Pair, double> overlap_before = overlaps(s, before);
    const Totals first = totals(s, before);
    out_.summary.energy_start = out_.summary.energy_end = first.energy.to_double();
    double t_before = 0;
    std::size_t k = 0;
    if (!trace_.steps.empty() && trace_.steps[0].t == 0) {
      check_start();
      out_.depth.push_back(0);
      out_.energy_drift.push_back(0);
      k = 1;
    }
    for (; k < trace_.steps.size(); ++k) {
      const TraceStep& step = trace_.steps[k];
      const Instant after = instant_of(k, t_before);
      const std::map<Pair, double> overlap_after = overlaps(s, after);
      judge_step(k, t_before, before, overlap_before, overlap_after, reports_of(k));
      measure(after, overlap_after, first);
      before = after;
      overlap_before = overlap_after;
      t_before = step.t;
    }
    for (const auto& [pair, open] : open_) miss(open.contact, MissKind::Unreported);
    out_.summary.steps = trace_.steps.size();
    return std::move(out_);
  }

 private:
  // Header: the ids, every moving body once.
  void map_bodies() {
    const ExactState& s = model_.state;
    std::vector<bool> listed(s.bodies.size(), false);
    for (std::size_t k = 0; k < trace_.bodies.size(); ++k) {
      const std::string field = fmt::format("bodies[{}]", k);
      const BodyIndex i = failer_.body(model_, trace_.header_line, "header", field, trace_.bodies[k]);
      if (s.bodies[i].fixed)
        failer_.fail(trace_.header_line, "header", field,
                     fmt::format("body \"{}\" is fixed: a steps trace gives the states of moving bodies only", trace_.bodies[k]));
      if (listed[i]) failer_.fail(trace_.header_line, "header", field, fmt::format("body \"{}\" is listed twice", trace_.bodies[k]));
      listed[i] = true;
      column_.push_back(i);
    }
    for (BodyIndex i = 0; i < s.bodies.size(); ++i)
      if (!s.bodies[i].fixed && !listed[i])
        failer_.fail(trace_.header_line, "header", "bodies",
                     fmt::format("moving body \"{}\" of the scene is missing: a steps trace gives every moving body's state",
                                 model_.ids[i]));
  }

  // A step at t = 0 is the start state: exactly the scene's, and no contacts.
  void check_start() {
    const TraceStep& s0 = trace_.steps[0];
    const std::string element = "steps[0]";
    check_shape(0);
    for (std::size_t c = 0; c < column_.size(); ++c) {
      const BodyIndex i = column_[c];
      const TraceState& x = s0.bodies[c];
      // A rotating body's position in a trace is its reference point: the scene's position.
      const bool rotates = model_.state.bodies[i].rotates;
      const Vec2d at = rotates ? model_.reference[i] : Vec2d{start_.position[i].x.to_double(), start_.position[i].y.to_double()};
      const double want[4] = {at.x, at.y, start_.velocity[i].x.to_double(), start_.velocity[i].y.to_double()};
      const double got[4] = {x.position.x, x.position.y, x.velocity.x, x.velocity.y};
      for (int q = 0; q < 4; ++q)
        if (!(Dyadic::from(got[q]) == Dyadic::from(want[q])))
          failer_.fail(s0.line, element, fmt::format("bodies[{}][{}]", c, q),
                       fmt::format("the state at t = 0 is the scene's: body \"{}\" has {} {} there, the trace {}", model_.ids[i],
                                   q < 2 ? "position" : "velocity", want[q], got[q]));
      if (!rotates) continue;
      const double want_turn[2] = {start_.angle[i].to_double(), start_.omega[i].to_double()};
      const double got_turn[2] = {s0.turns[c].angle, s0.turns[c].angular_velocity};
      for (int q = 0; q < 2; ++q)
        if (!(Dyadic::from(got_turn[q]) == Dyadic::from(want_turn[q])))
          failer_.fail(s0.line, element, fmt::format("turns[{}][{}]", c, q),
                       fmt::format("the state at t = 0 is the scene's: body \"{}\" has {} {} there, the trace {}", model_.ids[i],
                                   q == 0 ? "angle" : "angular velocity", want_turn[q], got_turn[q]));
    }
    if (!s0.contacts.empty()) failer_.fail(s0.line, element, "contacts", "the step at t = 0 is the start state: it has no contacts");
  }

  void check_shape(std::size_t k) const {
    const TraceStep& s = trace_.steps[k];
    const std::string element = fmt::format("steps[{}]", k);
    failer_.finite(s.t, s.line, element, "t");
    if (s.bodies.size() != column_.size())
      failer_.fail(s.line, element, "bodies", fmt::format("has {} states, the trace lists {} bodies", s.bodies.size(), column_.size()));
    for (std::size_t c = 0; c < s.bodies.size(); ++c) failer_.finite(s.bodies[c], s.line, element, fmt::format("bodies[{}]", c));
    if (s.turns.empty()) {
      for (std::size_t c = 0; c < column_.size(); ++c)
        if (model_.state.bodies[column_[c]].rotates)
          failer_.fail(s.line, element, "turns",
                       fmt::format("missing: body \"{}\" rotates, and a step gives each listed body's [angle, angular "
                                   "velocity] in a scene with rotation",
                                   model_.ids[column_[c]]));
      return;
    }
    if (s.turns.size() != column_.size())
      failer_.fail(s.line, element, "turns", fmt::format("has {} turns, the trace lists {} bodies", s.turns.size(), column_.size()));
    for (std::size_t c = 0; c < s.turns.size(); ++c) {
      failer_.finite(s.turns[c].angle, s.line, element, fmt::format("turns[{}][0]", c));
      failer_.finite(s.turns[c].angular_velocity, s.line, element, fmt::format("turns[{}][1]", c));
    }
  }

  Instant instant_of(std::size_t k, double t_before) const {
    const TraceStep& s = trace_.steps[k];
    check_shape(k);
    if (!(s.t > t_before))
      failer_.fail(s.line, fmt::format("steps[{}]", k), "t",
                   fmt::format("{} is not after the previous step's end {}: step times increase", s.t, t_before));
    Instant x = start_;
    const Dyadic t = Dyadic::from(s.t);
    for (BodyIndex i = 0; i < x.angle.size(); ++i)  // fixed bodies that spin, at their constant rate
      if (model_.state.bodies[i].fixed) x.angle[i] = angle_at(model_.state.bodies[i].motion, t);
    for (std::size_t c = 0; c < column_.size(); ++c) {
      const BodyIndex i = column_[c];
      x.velocity[i] = ExactVec::from(s.bodies[c].velocity);
      if (!model_.state.bodies[i].rotates) {  // a turn given for it (0, 0 from a peer) is not read
        x.position[i] = ExactVec::from(s.bodies[c].position);
        continue;
      }
      x.angle[i] = Dyadic::from(s.turns[c].angle);
      x.omega[i] = Dyadic::from(s.turns[c].angular_velocity);
      x.position[i] = pivot_of(model_, i, s.bodies[c].position, s.turns[c].angle);
    }
    return x;
  }

  std::set<Pair> reports_of(std::size_t k) const {
    const TraceStep& s = trace_.steps[k];
    const std::string element = fmt::format("steps[{}]", k);
    std::set<Pair> out;
    for (std::size_t c = 0; c < s.contacts.size(); ++c) {
      const std::string field = fmt::format("contacts[{}]", c);
      const BodyIndex a = failer_.body(model_, s.line, element, field + "[0]", s.contacts[c].a);
      const BodyIndex b = failer_.body(model_, s.line, element, field + "[1]", s.contacts[c].b);
      if (a == b) failer_.fail(s.line, element, field, "a body cannot be in contact with itself");
      if (model_.state.bodies[a].fixed && model_.state.bodies[b].fixed)
        failer_.fail(s.line, element, field, "two fixed bodies are never reported: they never meet");
      out.insert(std::minmax(a, b));
    }
    return out;
  }

  // The exact first contacts in the step from `x` (at t_before) to t_after, of pairs apart at
  // its start: each body followed on its start-state path up to its first contact (a rotating
  // body turning from its recorded angle at its recorded angular velocity). Pairs whose contact
  // the rotating search cannot decide (UndecidedTime) are returned apart, with the reason.
  struct StepContacts {
    std::map<Pair, double> times;
    std::map<Pair, std::string> undecided;
  };
  StepContacts exact_contacts(double t_before, double t_after, const Instant& x, const std::map<Pair, double>& overlap_before) {
    const ExactState& s = model_.state;
    const Dyadic now = Dyadic::from(t_before);
    for (BodyIndex i = 0; i < s.bodies.size(); ++i) {
      if (s.bodies[i].fixed) continue;
      const ExactMotion m{now, x.position[i], x.velocity[i], s.bodies[i].field_acc, {kNoBody, kNoBody}, x.angle[i], x.omega[i]};
      set_motion(exact_[i], m);
      set_motion(interval_[i], m);
    }
    Frame frame(exact_, interval_, now);
    const Dyadic tau_hi = Dyadic::from(t_after) - now;
    const Interval window(0.0, Interval::enclose(tau_hi).hi());
    SearchCounters n;
    struct Found {
      Pair pair;
      ExactTime time;
    };
    std::vector<Found> found;
    StepContacts out;
    // dt rounded up: the boxes must hold the whole step.
    const double dt = std::nextafter(tau_hi.to_double(), std::numeric_limits<double>::infinity());
    std::vector<Box> boxes;
    for (BodyIndex i = 0; i < s.bodies.size(); ++i) boxes.push_back(swept_box(s.bodies[i], x.position[i], x.velocity[i], dt));
    for (const Pair& p : box_pairs(s, boxes)) {
      if (overlap_before.count(p)) continue;  // overlapping at the start: a contact already
      try {
        if (const auto r = pair_contact(frame, features_, p.first, p.second, tau_hi, window, options_.referee.filter, n))
          found.push_back({p, ExactTime(now, r->tau)});
      } catch (const UndecidedTime& e) {
        out.undecided.emplace(p, e.what());
      }
    }
    std::stable_sort(found.begin(), found.end(), [](const Found& f, const Found& g) { return f.time < g.time; });
    std::map<BodyIndex, ExactTime> first;
    for (const Found& f : found) {
      bool earliest = true;
      for (const BodyIndex i : {f.pair.first, f.pair.second}) {
        if (s.bodies[i].fixed) continue;
        const auto it = first.find(i);
        if (it != first.end() && it->second < f.time) earliest = false;
      }
      if (!earliest) continue;  // its body's path changed at an earlier contact
      for (const BodyIndex i : {f.pair.first, f.pair.second})
        if (!s.bodies[i].fixed) first.emplace(i, f.time);
      out.times.emplace(f.pair, f.time.to_double());
    }
    return out;
  }

  void judge_step(std::size_t k, double t_before, const Instant& x, const std::map<Pair, double>& overlap_before,
                  const std::map<Pair, double>& overlap_after, std::set<Pair> reports) {
    const double t_after = trace_.steps[k].t;
    // Contacts waiting for a report: overlapping at this step's start.
    for (auto it = open_.begin(); it != open_.end();) {
      if (reports.erase(it->first)) {
        StepContact& c = out_.contacts[it->second.contact];
        c.verdict = StepVerdict::Late;
        c.late_steps = k - it->second.step;
        c.reported_step = k;
        it = open_.erase(it);
      } else if (settle(it->second.contact, it->first, overlap_after)) {
        it = open_.erase(it);
      } else {
        ++it;
      }
    }
    const StepContacts found = exact_contacts(t_before, t_after, x, overlap_before);
    std::map<Pair, std::optional<double>> fresh;
    for (const auto& [pair, time] : found.times) fresh.emplace(pair, time);
    for (const auto& [pair, depth] : overlap_after)
      if (!overlap_before.count(pair) && !fresh.count(pair) && !open_.count(pair) && !found.undecided.count(pair))
        fresh.emplace(pair, std::nullopt);
    for (const auto& [pair, time] : fresh) {
      StepContact c = contact_of(pair, k);
      c.exact_time = time;
      c.off_path = !time;
      out_.contacts.push_back(c);
      const std::size_t index = out_.contacts.size() - 1;
      if (reports.erase(pair)) {
        out_.contacts[index].reported_step = k;
        measure_depth(index, pair, overlap_after);
      } else if (!settle(index, pair, overlap_after)) {
        open_.emplace(pair, Open{index, k});
      }
    }
    // The moving bodies with a contact in this step: their paths changed inside it, at a time
    // the start-state paths do not follow past (a peer resolving contacts one after another
    // inside a step, as Box2D's continuous sub-steps do, may meet another body on the new path).
    std::set<BodyIndex> moved;
    const auto move = [&moved, this](const Pair& pair) {
      for (const BodyIndex i : {pair.first, pair.second})
        if (!model_.state.bodies[i].fixed) moved.insert(i);
    };
    for (const auto& [pair, time] : fresh) move(pair);
    // A pair whose contact in the step the referee cannot decide: undecided, reported or not (a
    // report of it is neither on time nor a phantom); its bodies' paths may have changed in the
    // step, as after a contact.
    for (const auto& [pair, reason] : found.undecided) {
      StepContact c = contact_of(pair, k);
      c.verdict = StepVerdict::Undecided;
      c.undecided_reason = reason;
      if (reports.erase(pair)) c.reported_step = k;
      out_.contacts.push_back(c);
      move(pair);
    }
    for (const Pair& pair : reports) {
      // Overlapping or exactly touching at the step's start: a contact already (a phantom is a
      // report whose pair stays apart, with a positive gap, through the whole step).
      if (overlap_before.count(pair) ||
          separation(place(model_.state.bodies[pair.first], x.position[pair.first], x.angle[pair.first]),
                     place(model_.state.bodies[pair.second], x.position[pair.second], x.angle[pair.second]))
                  .sign <= 0) {
        ++out_.summary.continuing_reports;
        continue;
      }
      if (moved.count(pair.first) || moved.count(pair.second)) {
        ++out_.summary.unfollowed_reports;
        continue;
      }
      StepContact c = contact_of(pair, k);
      c.verdict = StepVerdict::Phantom;
      c.reported_step = k;
      out_.contacts.push_back(c);
    }
  }

  StepContact contact_of(const Pair& pair, std::size_t step) const {
    StepContact c;
    c.a = model_.ids[pair.first];
    c.b = model_.ids[pair.second];
    c.step = step;
    return c;
  }

  void measure_depth(std::size_t index, const Pair& pair, const std::map<Pair, double>& overlap) {
    const auto it = overlap.find(pair);
    if (it == overlap.end()) return;
    StepContact& c = out_.contacts[index];
    const double distance = contact_distance(model_.state.bodies[pair.first], model_.state.bodies[pair.second]);
    c.depth = std::max(c.depth, it->second);
    if (distance > 0) c.relative_depth = std::max(c.relative_depth, it->second / distance);
  }

  // An unreported contact at a step's end: missed if the pair is apart again (it passed through)
  // or overlaps past the bound; true when it is settled so.
  bool settle(std::size_t index, const Pair& pair, const std::map<Pair, double>& overlap_after) {
    if (!overlap_after.count(pair)) {
      miss(index, MissKind::PassThrough);
      return true;
    }
    measure_depth(index, pair, overlap_after);
    if (out_.contacts[index].relative_depth > options_.overlap_bound) {
      miss(index, MissKind::Overlap);
      return true;
    }
    return false;
  }

  void miss(std::size_t index, MissKind why) {
    out_.contacts[index].verdict = StepVerdict::Missed;
    out_.contacts[index].miss = why;
  }

  void measure(const Instant& after, const std::map<Pair, double>& overlap_after, const Totals& first) {
    const ExactState& s = model_.state;
    double deepest = 0;
    for (const auto& [pair, depth] : overlap_after) {
      deepest = std::max(deepest, depth);
      const double distance = contact_distance(s.bodies[pair.first], s.bodies[pair.second]);
      if (distance > 0) out_.summary.largest_relative_depth = std::max(out_.summary.largest_relative_depth, depth / distance);
    }
    out_.depth.push_back(deepest);
    out_.summary.largest_depth = std::max(out_.summary.largest_depth, deepest);
    const Totals t = totals(s, after);
    const double drift = relative((t.energy - first.energy).to_double(), first.energy.to_double());
    out_.energy_drift.push_back(drift);
    out_.summary.largest_energy_drift = std::max(out_.summary.largest_energy_drift, std::abs(drift));
    out_.summary.energy_end = t.energy.to_double();
    const double dpx = (t.momentum.x - first.momentum.x).to_double(), dpy = (t.momentum.y - first.momentum.y).to_double();
    const double p0 = std::hypot(first.momentum.x.to_double(), first.momentum.y.to_double());
    out_.summary.largest_momentum_drift = std::max(out_.summary.largest_momentum_drift, std::abs(relative(std::hypot(dpx, dpy), p0)));
  }

  const Trace& trace_;
  TraceFailer failer_;
  JudgeOptions options_;
  SceneModel model_;
  std::vector<BodyModel<Dyadic>> exact_;
  std::vector<BodyModel<Interval>> interval_;
  FeatureCache features_;
  std::vector<BodyIndex> column_;  // the body of each state in a step
  Instant start_;
  std::map<Pair, Open> open_;
  StepJudgement out_;
};

void summarise(StepJudgement& j) {
  StepSummary& s = j.summary;
  for (const StepContact& c : j.contacts) {
    switch (c.verdict) {
      case StepVerdict::OnTime: ++s.on_time; break;
      case StepVerdict::Late:
        ++s.late;
        s.largest_late_steps = std::max(s.largest_late_steps, c.late_steps);
        break;
      case StepVerdict::Missed:
        ++s.missed;
        if (c.miss == MissKind::PassThrough) ++s.tunnelled;
        break;
      case StepVerdict::Phantom: ++s.phantom; break;
      case StepVerdict::Undecided: ++s.undecided; break;
    }
  }
  s.contacts = s.on_time + s.late + s.missed;
}

}  // namespace

StepJudgement judge_steps(const Scene& scene, const Trace& trace, const JudgeOptions& options) {
  StepJudgement j = StepReferee(scene, trace, options).run();
  std::stable_sort(j.contacts.begin(), j.contacts.end(), [](const StepContact& a, const StepContact& b) { return a.step < b.step; });
  summarise(j);
  return j;
}

TraceJudgement judge_trace(const Scene& scene, const Trace& trace, const JudgeOptions& options) {
  TraceJudgement j;
  j.mode = trace.mode;
  if (trace.mode == TraceMode::Steps) {
    j.steps = judge_steps(scene, trace, options);
  } else {
    j.events = judge_events(scene, trace, options);
  }
  return j;
}

std::string_view step_verdict_name(StepVerdict v) {
  switch (v) {
    case StepVerdict::OnTime: return "on_time";
    case StepVerdict::Late: return "late";
    case StepVerdict::Missed: return "missed";
    case StepVerdict::Phantom: return "phantom";
    case StepVerdict::Undecided: return "undecided";
  }
  return "?";
}

std::string_view miss_kind_name(MissKind k) {
  switch (k) {
    case MissKind::None: return "";
    case MissKind::PassThrough: return "pass_through";
    case MissKind::Overlap: return "overlap";
    case MissKind::Unreported: return "unreported";
  }
  return "?";
}

std::string contact_text(const StepContact& c) {
  std::string when = c.exact_time ? fmt::format(" (exact t = {:.17g})", *c.exact_time) : (c.off_path ? " (off path)" : "");
  std::string verdict;
  switch (c.verdict) {
    case StepVerdict::OnTime: verdict = "on time"; break;
    case StepVerdict::Late: verdict = fmt::format("late by {} step{}", c.late_steps, c.late_steps == 1 ? "" : "s"); break;
    case StepVerdict::Phantom: verdict = "phantom (reported, but the pair stays apart through the step)"; break;
    case StepVerdict::Undecided:
      verdict = fmt::format("undecided ({}{})", c.undecided_reason, c.reported_step ? "; reported in the step" : "");
      break;
    case StepVerdict::Missed:
      switch (c.miss) {
        case MissKind::PassThrough: verdict = "missed (pass-through: tunnelling, never reported)"; break;
        case MissKind::Overlap: verdict = fmt::format("missed (overlap {:.3g} of the contact distance before a report)", c.relative_depth); break;
        default: verdict = "missed (never reported before the trace ends)"; break;
      }
      break;
  }
  return fmt::format("contact \"{}\"-\"{}\" in step {}{}: {}", c.a, c.b, c.step, when, verdict);
}

std::string failure_text(const TraceJudgement& j) {
  std::string out;
  const auto line = [&out](const std::string& s) { out += (out.empty() ? "" : "\n") + s; };
  if (j.mode == TraceMode::Steps) {
    for (const StepContact& c : j.steps.contacts)
      if (c.verdict == StepVerdict::Missed || c.verdict == StepVerdict::Phantom) line(contact_text(c));
    return out;
  }
  for (const EventVerdict& e : j.events.events)
    if (is_failure(e.judgement.verdict))
      line(fmt::format("collision {} \"{}\"-\"{}\" at t = {:.17g}: {}", e.index, e.a, e.b, e.t, verdict_name(e.judgement.verdict)));
  if (j.events.end && j.events.end->miss) line("a contact is left before the end of the run: miss");
  return out;
}

}  // namespace pge::oracle
