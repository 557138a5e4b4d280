#include "dp/timing_family_run.hpp"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

namespace ecorail::dp::timing {

namespace {

using physics::Control;
using physics::ControlProgram;
using physics::SimulationResult;

// The searches run at this step (RK4; steps end at the switches, so a coarse step moves a
// run's time by milliseconds); the run found is searched again near there at the engine's
// fine step, which is what is checked and returned.
constexpr double kSearchStep_m = 2.0;
// A hold slower than this is a crawl the family does not search (a grid's slowest speeds).
constexpr double kLowestHold_ms = 0.5;
// First-phase ends tried along the stretch before the root search (two neighbours whose times
// lie either side of the target bracket it).
constexpr int kScanPoints = 12;
constexpr int kBisections = 60;
// Bisections stop at brackets this narrow (m): a tenth of a millimetre moves a run's end speed
// by well under kZeroWidthSpeed_ms; the coarse search only places the fine one's brackets.
constexpr double kCoarseNarrowest_m = 1e-3;
constexpr double kFineNarrowest_m = 1e-4;
// The coarse search's arrival is this close to the target (the fine search then brackets it).
constexpr double kCoarseTime_s = 0.01;
// How far either side of the coarse search's positions the fine search starts looking (m).
constexpr double kFineBracket_m = 2.0;

struct Candidate {
  ControlProgram program;
  SimulationResult sim;
};

// A root of f on [lo, hi] where f(lo) and f(hi) have opposite signs: regula falsi with the
// Illinois halving (the running time is smooth in a switch), a bisection step where f is
// infinite (no run finishes there); done(f) ends it. Returns the point evaluated that is done,
// or NaN.
template <class F, class Done>
double find_root(F f, double lo, double hi, Done done) {
  double f_lo = f(lo);
  if (done(f_lo)) return lo;
  double f_hi = f(hi);
  if (done(f_hi)) return hi;
  if (!(f_lo < 0.0 ? f_hi > 0.0 : f_hi < 0.0)) return NAN;
  int side = 0;  // which end was kept last (-1 lo, +1 hi), for the Illinois halving
  for (int it = 0; it < kBisections; ++it) {
    double m = 0.5 * (lo + hi);
    if (std::isfinite(f_lo) && std::isfinite(f_hi)) {
      m = (lo * f_hi - hi * f_lo) / (f_hi - f_lo);
      if (!(m > lo && m < hi)) m = 0.5 * (lo + hi);
    }
    const double fm = f(m);
    if (done(fm)) return m;
    if ((fm < 0.0) == (f_lo < 0.0)) {
      lo = m;
      f_lo = fm;
      if (side == -1) f_hi *= 0.5;
      side = -1;
    } else {
      hi = m;
      f_hi = fm;
      if (side == 1) f_lo *= 0.5;
      side = 1;
    }
  }
  return NAN;
}

// The end of the set {f >= -tol} inside [lo, hi], where f is monotone and may be flat near 0
// on that side (an envelope that brakes the run to the end speed whatever the last phase
// does): bisected to narrowest_m, the point on the f >= -tol side; hi (rising: lo) when all of
// [lo, hi] is in the set, unless `bracket` asks for the end to lie inside [lo, hi] (a guess
// at where it lies, not the whole range: the end may lie beyond it); NaN when none of it is.
// rising: f grows with x.
template <class F>
double boundary(F f, double lo, double hi, double tol, double narrowest_m, bool rising,
                bool bracket) {
  const bool lo_in = f(lo) >= -tol, hi_in = f(hi) >= -tol;
  if (lo_in && hi_in) return bracket ? NAN : (rising ? lo : hi);
  if (!lo_in && !hi_in) return NAN;
  for (int it = 0; it < kBisections && hi - lo > narrowest_m; ++it) {
    const double m = 0.5 * (lo + hi);
    ((f(m) >= -tol) == lo_in ? lo : hi) = m;
  }
  return lo_in ? lo : hi;
}

// One family of runs: `first` from the start to s1, `middle` from s1 to the last phase's
// start s2, and a last phase that ends the run as the part asks (chosen by the end speed the
// middle phase would reach; with hold_at_goal, a hold from where a coast reaches the end
// speed).
struct Family {
  Control first, middle;
  bool hold_at_goal;
};

class FamilySearch {
 public:
  // The families follow `lead` before from_m.
  FamilySearch(const SectionEngine& engine, const StartState& start, const EndCheck& end,
               double target_s, const physics::ControlProgram& lead, double from_m,
               int* evaluations)
      : engine_(engine),
        start_(start),
        end_(end),
        target_s_(target_s),
        length_m_(engine.route().length_m()),
        from_m_(from_m),
        evaluations_(evaluations) {
    for (const physics::ProgramStep& step : lead) {
      if (step.from_m < from_m) lead_.push_back(step);
    }
  }

  // Every family that reaches the time; the cheapest run. A coast wastes more time than a
  // hold for the traction it costs (the speed it loses is won back for what the hold would
  // have spent), so the families that coast down after braking usually win; a hold is needed
  // where a coast would run on too fast or too slow.
  std::optional<LambdaRun> search(FamilySet set) {
    std::vector<Family> families;
    if (set == FamilySet::Any) {
      families = {{Control::MaxTraction, Control::Coast, false},
                  {Control::MaxTraction, Control::Hold, false}};
    }
    // (A run at rest at from_m has no slowing family: each is refused at its hold start.)
    families.insert(families.end(), {{Control::Coast, Control::Hold, false},
                                     {Control::MaxBrake, Control::Hold, false},
                                     {Control::MaxBrake, Control::Coast, false},
                                     {Control::MaxBrake, Control::Coast, true}});
    std::optional<LambdaRun> best;
    for (const Family& family : families) {
      if (family.hold_at_goal && !end_.moving) continue;
      std::optional<LambdaRun> run = search(family);
      if (run && (!best || run->cost_J < best->cost_J)) best = std::move(run);
    }
    return best;
  }

 private:
  // How one search places its switches: the step it simulates at, how narrow its brackets
  // end, how close to the target its time must come, and where its last phase is looked for
  // first ([s2_lo, s2_hi]; NaN: anywhere after s1).
  struct Stage {
    double step_m = 0.0, narrowest_m = 0.0, time_tol_s = 0.0;
    double s2_lo = NAN, s2_hi = NAN;
  };

  std::optional<LambdaRun> search(const Family& family) {
    Stage coarse{engine_.search_step_m(kSearchStep_m), kCoarseNarrowest_m, kCoarseTime_s};
    double s1 = s1_for_time(family, coarse, from_m_, last_s1(family, coarse.step_m), /*scan=*/true);
    if (!std::isfinite(s1)) return std::nullopt;
    const std::optional<Candidate> rough = finish(family, s1, coarse);
    if (!rough) return std::nullopt;
    // The fine search near the coarse one's switches (a bracket four times wider each time it
    // holds no root).
    Stage fine{engine_.options().resim_step_m, kFineNarrowest_m, 0.25 * kZeroWidthTime_s};
    const double s2 = rough->program.back().from_m;
    for (double half = kFineBracket_m; half <= 64.0 * kFineBracket_m; half *= 4.0) {
      fine.s2_lo = s2 - half;
      fine.s2_hi = s2 + half;
      const double at = s1_for_time(family, fine, std::max(from_m_, s1 - half),
                                    std::min(length_m_, s1 + half), /*scan=*/false);
      if (!std::isfinite(at)) continue;
      std::optional<Candidate> c = finish(family, at, fine);
      if (!c || std::abs(c->sim.running_time_s - target_s_) > kZeroWidthTime_s) continue;
      LambdaRun run;
      run.lambda = NAN;
      run.start = start_;
      run.program = std::move(c->program);
      run.sim = std::move(c->sim);
      run.cost_J = engine_.energy_cost_J(run.sim);
      return run;
    }
    return std::nullopt;
  }

  SimulationResult simulate(const ControlProgram& p, double step, const SimulationResult* earlier) {
    ++*evaluations_;
    return earlier ? engine_.resimulate(p, start_, step, *earlier)
                   : engine_.simulate(p, start_, step);
  }

  // The lead, then `first` from from_m_ (the family's run up to s1).
  ControlProgram program_to(const Family& family, double s1) const {
    ControlProgram p = lead_;
    if (s1 > from_m_ || p.empty()) p.push_back({from_m_, family.first});
    return p;
  }

  // The latest s1 worth trying: where the first phase alone falls to kLowestHold_ms (or the
  // end).
  double last_s1(const Family& family, double step) {
    const SimulationResult sim = simulate(program_to(family, length_m_), step, nullptr);
    for (const physics::TracePoint& p : sim.trace) {
      if (p.s_m > from_m_ && p.v_ms < kLowestHold_ms) return p.s_m;
    }
    return length_m_;
  }

  // The s1 in [lo, hi] whose finished run arrives at the target (within the stage's
  // time_tol_s); NaN when none does. scan: look for the bracket along [lo, hi] first (the
  // running time is monotone in s1, rising for a first phase that slows the run and falling
  // for traction, and infinite where no last phase finishes the run).
  double s1_for_time(const Family& family, const Stage& stage, double lo, double hi, bool scan) {
    auto late_s = [&](double s1) {
      const std::optional<Candidate> c = finish(family, s1, stage);
      return c ? c->sim.running_time_s - target_s_ : kInf;
    };
    auto done = [&](double e) { return std::abs(e) <= stage.time_tol_s; };
    // (No narrowest bracket: a hold after braking hard moves the time by a minute per metre of
    // its start.)
    if (!scan) return find_root(late_s, lo, hi, done);
    double prev = lo, e_prev = NAN;
    for (int k = 0; k <= kScanPoints; ++k) {
      const double s1 = lo + (hi - lo) * k / kScanPoints;
      const double e = late_s(s1);
      if (done(e)) return s1;
      if (k > 0 && (e_prev > 0.0) != (e > 0.0)) return find_root(late_s, prev, s1, done);
      prev = s1;
      e_prev = e;
    }
    return NAN;
  }

  // The family's run with its first phase ending at s1, its last phase placed so the run ends
  // as the part asks; nullopt when none does.
  std::optional<Candidate> finish(const Family& family, double s1, const Stage& stage) {
    ControlProgram base = program_to(family, s1);
    if (base.back().from_m == s1) base.pop_back();  // no first phase
    base.push_back({s1, family.middle});
    SimulationResult b = simulate(base, stage.step_m, nullptr);
    const Passing at = passing_at(b.trace, s1);
    if (!finite(at.v_ms) || at.v_ms < kLowestHold_ms) return std::nullopt;
    if (end_.moving && end_.reaches_end(b) && speed_ok(b) && !family.hold_at_goal) {
      return Candidate{base, std::move(b)};
    }
    // The end speed the last phase aims at: the middle phase's own (its speed at s1 for a
    // hold, at the end for a coast) brought into the end's window.
    const double goal =
        goal_ms(family.middle == Control::Hold || !end_.reaches_end(b) ? at.v_ms : b.end_speed_ms);
    auto with_last = [&](Control last, double s2, SimulationResult* out) {
      ControlProgram p = base;
      p.push_back({s2, last});
      SimulationResult sim = simulate(p, stage.step_m, &b);
      const double e = error(sim, goal);
      if (out) *out = std::move(sim);
      return e;
    };
    Control last = Control::MaxBrake;
    if (family.hold_at_goal) {
      last = Control::Hold;  // where the coast has slowed to the goal
    } else if (end_.moving) {
      const double middle_end =
          family.middle == Control::Hold ? at.v_ms : (end_.reaches_end(b) ? b.end_speed_ms : 0.0);
      last = middle_end < goal ? Control::MaxTraction : Control::Coast;
      // A coast after s1 may not slow it enough (or it coasts already): brake.
      if (last == Control::Coast &&
          (family.middle == Control::Coast || with_last(last, s1 + 1e-6, nullptr) > 0.0)) {
        last = Control::MaxBrake;
      }
    }
    // The latest traction or hold, or the earliest coast or brake, that ends the run as asked:
    // near the stage's guess first, then anywhere after s1.
    auto f = [&](double x) { return with_last(last, x, nullptr); };
    const double tol = end_.moving ? 0.5 * kZeroWidthSpeed_ms : 0.0;
    const bool rising = last != Control::MaxTraction && last != Control::Hold;
    const double lo = s1 + 1e-6, hi = length_m_ - 1e-6;
    double s2 = NAN;
    if (std::isfinite(stage.s2_lo)) {
      s2 = boundary(f, std::clamp(stage.s2_lo, lo, hi), std::clamp(stage.s2_hi, lo, hi), tol,
                    stage.narrowest_m, rising, /*bracket=*/true);
    }
    if (!std::isfinite(s2)) s2 = boundary(f, lo, hi, tol, stage.narrowest_m, rising, false);
    if (!std::isfinite(s2)) return std::nullopt;
    Candidate c;
    c.program = base;
    c.program.push_back({s2, last});
    with_last(last, s2, &c.sim);
    if (!end_(c.sim) || (end_.moving && !speed_ok(c.sim))) return std::nullopt;
    return c;
  }

  // The end speed a moving end is finished to from a speed v_ms: the window's speed when it
  // has zero width, else v_ms brought a quarter of the tolerance inside the window.
  double goal_ms(double v_ms) const {
    if (!end_.moving) return 0.0;
    if (end_.min_ms == end_.max_ms) return end_.min_ms;
    const double in = std::min(0.25 * end_.tol_ms, 0.5 * (end_.max_ms - end_.min_ms));
    return std::clamp(v_ms, end_.min_ms + in, end_.max_ms - in);
  }
  bool speed_ok(const SimulationResult& sim) const {
    if (end_.min_ms != end_.max_ms) return end_(sim);
    return std::abs(sim.end_speed_ms - end_.min_ms) <= kZeroWidthSpeed_ms;
  }
  // What the last phase's start is bisected on: the end speed minus goal_ms for a moving end
  // (-infinity when the run stops short); for a stop, how far short of it the run comes to
  // rest (negative), or 1 when it arrives.
  double error(const SimulationResult& sim, double goal_ms) const {
    if (end_.moving) {
      if (!end_.reaches_end(sim)) return -kInf;
      return sim.end_speed_ms - goal_ms;
    }
    if (sim.stopped_early) return std::min(-1e-9, sim.end_position_m - length_m_);
    return 1.0;
  }

  const SectionEngine& engine_;
  StartState start_;
  const EndCheck& end_;
  double target_s_ = 0.0, length_m_ = 0.0, from_m_ = 0.0;
  ControlProgram lead_;
  int* evaluations_;
};

}  // namespace

std::optional<LambdaRun> family_run(const SectionEngine& engine, const StartState& start,
                                    const EndCheck& end, double target_s,
                                    const physics::ControlProgram& lead, double from_m,
                                    FamilySet set, int* evaluations) {
  return FamilySearch(engine, start, end, target_s, lead, from_m, evaluations).search(set);
}

}  // namespace ecorail::dp::timing
