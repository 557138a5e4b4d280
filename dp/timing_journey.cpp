#include "dp/timing_journey.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <stdexcept>

#include "dp/golden_section.hpp"
#include "dp/lambda_bracket.hpp"
#include "dp/regimes.hpp"
#include "dp/text_format.hpp"
#include "physics/speed_envelope.hpp"
#include "physics/units.hpp"

namespace ecorail::dp {

bool TimingJourneyOptions::IsValid(std::string* error) const {
  auto fail = [&](const char* why) {
    if (error) *error = why;
    return false;
  };
  if (!engine.IsValid(error)) return false;
  if (!(time_tolerance_s > 0.0 && time_tolerance_s <= 1.0)) {
    return fail("time_tolerance_s must be in (0, 1] s");
  }
  if (!(speed_tolerance_kmh > 0.0 && speed_tolerance_kmh <= 5.0)) {
    return fail("speed_tolerance_kmh must be in (0, 5] km/h");
  }
  if (max_evaluations < 10) return fail("max_evaluations must be at least 10");
  return true;
}

physics::Route slice_route(const physics::Route& route, double from_m, double to_m) {
  std::vector<physics::RouteSegment> out;
  for (const auto& seg : route.segments()) {
    const double a = std::max(seg.start_m, from_m), b = std::min(seg.end_m, to_m);
    if (b - a <= 1e-9) continue;
    physics::RouteSegment s = seg;
    s.start_m = a - from_m;
    s.end_m = b - from_m;
    out.push_back(s);
  }
  if (!out.empty()) {
    out.front().start_m = 0.0;
    out.back().end_m = to_m - from_m;
  }
  const int direction = route.km_post_m(1.0) >= route.km_post_m(0.0) ? 1 : -1;
  return physics::Route(std::move(out), route.km_post_m(from_m), direction,
                        format_text("%.1f m", from_m), format_text("%.1f m", to_m));
}

namespace {

using Clock = std::chrono::steady_clock;
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kMaxTrim_s = 1.0;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// Time and speed of a run where it passes s (linear between trace points); nullopt-like
// (t = NaN) when the trace does not reach s.
struct Passing {
  double t_s = NAN, v_ms = NAN;
};
Passing passing_at(const std::vector<physics::TracePoint>& trace, double s) {
  if (trace.empty() || s > trace.back().s_m + 1e-6) return {};
  const auto it =
      std::lower_bound(trace.begin(), trace.end(), s,
                       [](const physics::TracePoint& p, double x) { return p.s_m < x; });
  if (it == trace.begin()) return {it->t_s, it->v_ms};
  if (it == trace.end()) return {trace.back().t_s, trace.back().v_ms};
  const auto& b = *it;
  const auto& a = *(it - 1);
  const double w = b.s_m > a.s_m ? (s - a.s_m) / (b.s_m - a.s_m) : 1.0;
  return {a.t_s + w * (b.t_s - a.t_s), a.v_ms + w * (b.v_ms - a.v_ms)};
}

std::string point_name(int i, const TimingWindow& w) {
  return format_text("timing point %d (%.1f m)", i + 1, w.position_m);
}

bool finite(double x) {
  return std::isfinite(x);
}

// Whether a run reaches the end of its part as the part asks: at rest at the stop
// (run_arrives), or, for a part that ends moving, at the end of the stretch without coming to
// rest before it, with its end speed inside the last point's speed window (within tol_ms).
struct EndCheck {
  bool moving = false;
  double min_ms = 0.0, max_ms = 0.0, tol_ms = 0.0;
  bool reaches_end(const physics::SimulationResult& sim) const {
    if (!moving) return run_arrives(sim);
    return !sim.stopped_early && !sim.trace.empty() &&
           sim.trace.back().s_m >= sim.end_position_m - sim.stop_error_m - physics::kArrivalSlack_m;
  }
  bool operator()(const physics::SimulationResult& sim) const {
    if (!moving) return run_arrives(sim);
    return reaches_end(sim) && sim.end_speed_ms >= min_ms - tol_ms &&
           sim.end_speed_ms <= max_ms + tol_ms;
  }
};

// A passing point inside a part, as the part's engine sees it.
struct PartPoint {
  int index = 0;                            // into the journey's windows
  double s_m = 0.0;                         // position in the part
  int stage = 0;                            // grid stage of the price change and of the speed band
  double earliest_s = 0.0, latest_s = 0.0;  // relative to the part's departure
};

// Finds where f, falling in x, crosses 0 on [x_min, x_max]: steps from x0 (growing steps) until
// the sign changes, then regula falsi (Illinois). f may return +infinity ("too slow"). Stops
// when |f| <= tol, when the bracket cannot be found or is narrower than 1e-9, or after budget
// evaluations; the caller keeps the run it wants from its own evaluations.
template <typename F>
void falling_root(F f, double x0, double step, double x_min, double x_max, int budget, double tol) {
  int n = 0;
  auto eval = [&](double x) {
    ++n;
    return f(x);
  };
  double xa = std::clamp(x0, x_min, x_max), fa = eval(xa);
  if (std::abs(fa) <= tol) return;
  double xb = xa, fb = fa;
  if (fa > 0.0) {
    while (fb > 0.0 && n < budget && xb < x_max) {
      xa = xb, fa = fb;
      xb = std::min(x_max, xb + step);
      fb = eval(xb);
      if (std::abs(fb) <= tol) return;
      step *= 1.5;
    }
    if (fb > 0.0) return;
  } else {
    while (fa < 0.0 && n < budget && xa > x_min) {
      xb = xa, fb = fa;
      xa = std::max(x_min, xa - step);
      fa = eval(xa);
      if (std::abs(fa) <= tol) return;
      step *= 1.5;
    }
    if (fa < 0.0) return;
  }
  int side = 0;
  while (n < budget && xb - xa > 1e-9) {
    double xm = finite(fa) ? (xa * fb - xb * fa) / (fb - fa) : 0.5 * (xa + xb);
    if (!(xm > xa && xm < xb)) xm = 0.5 * (xa + xb);
    const double fm = eval(xm);
    if (std::abs(fm) <= tol) return;
    if (fm > 0.0) {
      xa = xm, fa = fm;
      if (side == -1) fb *= 0.5;
      side = -1;
    } else {
      xb = xm, fb = fm;
      if (side == 1) fa *= 0.5;
      side = 1;
    }
  }
}

// Moves one switch point of run's program with lo_m < position < hi_m (the end of a traction
// phase, or the onset of braking: later is faster for both) so that error(sim) (a time minus
// its target, falling as the switch moves later) is within tol_s; the first candidate that
// brackets the root is bisected. Switches outside (lo_m, hi_m) do not move, so a trim after a
// timing point leaves its passing time alone. A candidate must reach the end as `arrives` asks.
// Returns the evaluations used.
template <typename Error>
int trim_switch(const SectionEngine& engine, const EndCheck& arrives, LambdaRun& run, double lo_m,
                double hi_m, Error error, double tol_s, double max_trim_s = kMaxTrim_s) {
  int used = 0;
  // Only a last correction: a larger miss is the price search's to close, not a switch's.
  const double miss = std::abs(error(run.sim));
  if (miss <= tol_s || !(miss <= max_trim_s)) return used;
  const physics::ControlProgram program = run.program;
  const double length = engine.route().length_m();

  for (std::size_t k = 1; k < program.size(); ++k) {
    const bool traction_end = program[k - 1].control == physics::Control::MaxTraction;
    const bool brake_onset = program[k].control == physics::Control::MaxBrake;
    if (!(traction_end || brake_onset)) continue;
    if (!(program[k].from_m > lo_m && program[k].from_m < hi_m)) continue;
    double a = std::max(program[k - 1].from_m, lo_m) + 1e-6;
    double b = std::min(k + 1 < program.size() ? program[k + 1].from_m : length, hi_m) - 1e-6;
    if (!(b > a)) continue;
    auto at = [&](double x, physics::ControlProgram* p_out, physics::SimulationResult* s_out) {
      physics::ControlProgram p = program;
      p[k].from_m = x;
      physics::SimulationResult sim = engine.simulate(p, run.start);
      ++used;
      const double e = arrives(sim) ? error(sim) : kInf;
      if (p_out) *p_out = std::move(p);
      if (s_out) *s_out = std::move(sim);
      return e;
    };
    double fa = at(a, nullptr, nullptr), fb = at(b, nullptr, nullptr);
    if (!(fa >= 0.0 && fb <= 0.0) || !finite(fb)) continue;
    for (int it = 0; it < 40; ++it) {
      const double m = 0.5 * (a + b);
      physics::ControlProgram p;
      physics::SimulationResult sim;
      const double fm = at(m, &p, &sim);
      if (std::abs(fm) <= tol_s) {
        run.program = std::move(p);
        run.sim = std::move(sim);
        run.cost_J = engine.energy_cost_J(run.sim);
        return used;
      }
      (fm > 0.0 ? a : b) = m;
    }
  }
  return used;
}

// One part's search for its prices. First the plain running-time search for the latest
// arrival (one price): if every passing window holds, that is the optimum (a non-binding
// window changes nothing). Otherwise the most missed passing window binds at its bound, and
// each binding point gets the price of the stretch that ends at it (from the binding point
// before it, or the start); the stretch after the last binding point has lambda_after. The
// outer search is on the price before a binding point for its passing time, the inner on
// lambda_after for the arrival. With one binding point that is one root search; with several,
// each price is searched for its own point's time in turn (the others held), cycling until
// every binding point is within the search's tolerance (coordinate-wise; a price moves its own
// point most, and the later points only by the same shift, which their own prices take back).
// A window still missed joins the binding set and the search is repeated. The arrival is a
// window too: when even the lowest price after the last binding point arrives before the
// latest arrival, the arrival does not bind and that run is kept. Speed windows missed by the
// run are added as speed bands at their stage, and the search is repeated with them.
class PartSolver {
 public:
  PartSolver(const SectionEngine& engine, const StartState& start, const EndCheck& end,
             double target_s, double earliest_arrival_s, std::vector<PartPoint> points,
             const std::vector<TimingWindow>& windows, const TimingJourneyOptions& options)
      : engine_(engine),
        start_(start),
        end_(end),
        target_s_(target_s),
        earliest_arrival_s_(earliest_arrival_s),
        points_(std::move(points)),
        windows_(windows),
        options_(options) {}

  int evaluations() const { return evaluations_; }
  const std::vector<PartPoint>& points() const { return points_; }
  const std::vector<std::string>& notes() const { return notes_; }
  // The price of stretch k of the part (k = 0 .. points().size(): the stretch that ends at
  // point k, or at the arrival).
  double stretch_price(int k) const {
    for (std::size_t m = 0; m < binding_.size(); ++m) {
      if (k <= binding_[m]) return before_[m];
    }
    return lambda_after_;
  }
  // With several binding points, one that the others already keep well inside its window
  // (even its lowest price passes it early for a latest bound, late for an earliest one) does
  // not bind after all: its window is inactive at the optimum and is not reported as binding.
  bool inactive(std::size_t m) const { return m < inactive_.size() && inactive_[m]; }
  void mark_inactive(const LambdaRun& run) {
    inactive_.assign(binding_.size(), false);
    if (binding_.size() < 2) return;
    for (std::size_t m = 0; m < binding_.size(); ++m) {
      const PartPoint& p = points_[binding_[m]];
      const double t = passing_at(run.sim.trace, p.s_m).t_s;
      const double margin = 2.0 * kInside_s + options_.time_tolerance_s;
      inactive_[m] = finite(t) && t > p.earliest_s + margin && t < p.latest_s - margin;
    }
  }

  // How far inside its bound a binding passing point may pass (see search_target_s).
  double binding_slack_s() const { return binding_.size() > 1 ? 2.0 * kInside_s : 0.0; }
  // The sign of point k's multiplier: +1 its latest bound binds (the price before it is the
  // higher), -1 its earliest, 0 it does not bind.
  int binding_sign(int k) const {
    for (std::size_t m = 0; m < binding_.size(); ++m) {
      if (binding_[m] != k || inactive(m)) continue;
      const double next = m + 1 < binding_.size() ? before_[m + 1] : lambda_after_;
      return before_[m] > next ? 1 : -1;
    }
    return 0;
  }

  // before: the price of the stretch ending at each binding point (empty: one price, after).
  StagePrices prices(const std::vector<double>& before, double after) const {
    StagePrices p;
    const int transitions = engine_.grid().stage_count() - 1;
    p.lambda_J_per_s.assign(transitions, after);
    int from = 0;
    for (std::size_t m = 0; m < before.size(); ++m) {
      const int upto = std::clamp(points_[binding_[m]].stage, 0, transitions);
      for (int i = from; i < upto; ++i) p.lambda_J_per_s[i] = before[m];
      from = std::max(from, upto);
    }
    p.bands = bands_;
    p.end_moving = end_.moving;
    p.end_min_ms = end_.min_ms;
    p.end_max_ms = end_.max_ms;
    return p;
  }

  LambdaRun evaluate(const std::vector<double>& before, double after) {
    ++evaluations_;
    return engine_.run(prices(before, after), start_, engine_.options().resim_step_m);
  }

  // Signed miss of point k's time window: > 0 late, < 0 early, 0 inside.
  double time_miss_s(const LambdaRun& run, const PartPoint& p) const {
    const Passing at = passing_at(run.sim.trace, p.s_m);
    if (!finite(at.t_s)) return kInf;
    if (at.t_s > p.latest_s) return at.t_s - p.latest_s;
    if (at.t_s < p.earliest_s) return at.t_s - p.earliest_s;
    return 0.0;
  }
  bool speed_missed(const LambdaRun& run, const PartPoint& p) const {
    const Passing at = passing_at(run.sim.trace, p.s_m);
    const TimingWindow& w = windows_[p.index];
    const double tol = units::kmh_to_ms(options_.speed_tolerance_kmh);
    return !finite(at.v_ms) || at.v_ms < w.min_speed_ms - tol || at.v_ms > w.max_speed_ms + tol;
  }
  double arrival_error_s(const LambdaRun& run) const {
    return end_(run.sim) ? run.sim.running_time_s - target_s_ : kInf;
  }

  // For fixed prices before the binding points (before empty: one price everywhere), the run
  // whose arrival is the latest allowed, or the slowest-priced run if even that arrives
  // earlier (the arrival then does not bind). ok: the arrival is within its window.
  struct Inner {
    LambdaRun run;
    double x_after = 0.0;
    bool ok = false;
  };
  Inner solve_arrival(const std::vector<double>& before) {
    Inner best;
    double best_abs = kInf;
    Inner floor_run;
    double floor_x = kInf;
    auto f = [&](double x) {
      const double after = std::exp(x);
      LambdaRun run = evaluate(before, after);
      const double err = arrival_error_s(run);
      if (finite(err) && std::abs(err) < best_abs) {
        best_abs = std::abs(err);
        best = {run, x, best_abs <= kMaxTrim_s};
      }
      if (finite(err) && err < 0.0 && x < floor_x) {
        floor_x = x;
        floor_run = {std::move(run), x, false};
      }
      return err;
    };
    falling_root(f, x_after_guess_, 0.3, 0.0, 30.0, kInnerBudget, kArrivalTolerance_s);
    if (!best.ok && floor_x <= 1e-9) {
      // Too fast even at the lowest price: the arrival does not bind (if it is not too early).
      const double t = floor_run.run.sim.running_time_s;
      floor_run.ok = t >= earliest_arrival_s_ - options_.time_tolerance_s;
      best = std::move(floor_run);
      arrival_at_floor_ = true;
    } else {
      arrival_at_floor_ = false;
    }
    if (best.ok) x_after_guess_ = best.x_after;
    return best;
  }

  // The last hundredths of the arrival by one switch point after from_m (when the arrival
  // binds: the run is not early by more than the search's tolerance).
  // If the run is still late by more than the window's tolerance (no switch after from_m can
  // make it faster, e.g. it coasts from before the last binding point to the stop), one switch
  // anywhere is moved: the binding points are then passed a little earlier, which their latest
  // bounds allow (an earliest bound is checked on the re-simulation like every window).
  void trim_arrival(LambdaRun& run, double from_m) {
    auto arrival = [&](const physics::SimulationResult& sim) {
      return sim.running_time_s - target_s_;
    };
    // (A run that ends moving is searched on the stage-priced sweep alone, whose running time
    // is more ragged: its trim takes any miss within kMaxTrim_s.)
    const double reach_s = end_.moving ? kMaxTrim_s : kArrivalTolerance_s;
    if (run.sim.running_time_s > target_s_ - reach_s) {
      evaluations_ += trim_switch(engine_, end_, run, from_m, engine_.route().length_m(), arrival,
                                  kTrimTolerance_s);
    }
    if (from_m > 0.0 && arrival(run.sim) > options_.time_tolerance_s) {
      evaluations_ += trim_switch(engine_, end_, run, 0.0, engine_.route().length_m(), arrival,
                                  kTrimTolerance_s);
    }
  }

  LambdaRun solve(bool* met) {
    LambdaRun run;
    bool ok = false;
    if (!end_.moving) {
      TimeSearchOptions search;
      const TimeSearchResult plain = solve_for_time(engine_, target_s_, search, start_);
      evaluations_ += plain.iterations;
      run = plain.run;
      ok = plain.converged;
      lambda_after_ = run.lambda;
      x_after_guess_ = std::log(std::max(1.0, run.lambda));
    } else {
      // A run that ends moving: the plain search ends at rest, so the one price is searched
      // here, with the end's speed band (StagePrices::end_moving).
      Inner in = solve_arrival({});
      run = std::move(in.run);
      ok = in.ok;
      lambda_after_ = std::exp(in.x_after);
      if (ok) trim_arrival(run, 0.0);
    }
    for (int round = 0; round < 2 + static_cast<int>(std::max<std::size_t>(1, binding_.size()));
         ++round) {
      // Speed windows the run misses become bands.
      bool new_band = false;
      for (const auto& p : points_) {
        const TimingWindow& w = windows_[p.index];
        const bool banded = std::any_of(bands_.begin(), bands_.end(),
                                        [&](const SpeedBand& b) { return b.stage == p.stage; });
        if (!banded && speed_missed(run, p) && p.stage > 0 &&
            p.stage < engine_.grid().stage_count() - 1) {
          bands_.push_back({p.stage, w.min_speed_ms, w.max_speed_ms});
          new_band = true;
        }
      }
      // The most missed time window.
      int worst = -1;
      double worst_miss = 0.5 * options_.time_tolerance_s;
      for (std::size_t k = 0; k < points_.size(); ++k) {
        const double m = std::abs(time_miss_s(run, points_[k]));
        if (m > worst_miss) worst = static_cast<int>(k), worst_miss = m;
      }
      if (worst < 0 && !new_band) break;
      if (worst < 0 && binding_.empty()) {
        // Bands alone: one price, searched with them.
        Inner in = solve_arrival({});
        run = std::move(in.run);
        ok = in.ok;
        lambda_after_ = std::exp(in.x_after);
        if (ok) trim_arrival(run, 0.0);
        continue;
      }
      if (worst >= 0 && !add_binding(worst)) {
        ok = false;
        break;
      }
      // Each binding point binds at the bound its run misses (or the one it was given).
      for (std::size_t m = 0; m < binding_.size(); ++m) {
        const PartPoint& p = points_[binding_[m]];
        const double miss = time_miss_s(run, p);
        if (miss != 0.0) bound_s_[m] = miss > 0.0 ? p.latest_s : p.earliest_s;
      }
      if (!meet_bindings(run)) {
        ok = false;
        break;
      }
      ok = true;
      // The last hundredths by switch points (first-order neutral at the optimum): for each
      // binding point in turn one between the binding point before it and it (later points
      // shift with it and are trimmed next), then one after the last for the arrival.
      double lo = 0.0;
      for (std::size_t m = 0; m < binding_.size(); ++m) {
        const double s_k = points_[binding_[m]].s_m, bound = bound_s_[m];
        if (binding_.size() == 1) {  // several: see search_target_s
          evaluations_ += trim_switch(
              engine_, end_, run, lo, s_k,
              [&](const physics::SimulationResult& sim) {
                return passing_at(sim.trace, s_k).t_s - bound;
              },
              kTrimTolerance_s);
        }
        lo = s_k;
      }
      trim_arrival(run, lo);
    }
    if (ok && binding_.size() == 1 && !end_.moving) close_gap(run);
    mark_inactive(run);
    if (ok) {
      for (std::size_t m = 0; m < binding_.size(); ++m) {
        if (inactive(m)) continue;
        const PartPoint& p = points_[binding_[m]];
        const double off = std::abs(passing_at(run.sim.trace, p.s_m).t_s - bound_s_[m]);
        const double allowed =
            binding_.size() == 1 ? options_.time_tolerance_s : 2.0 * kInside_s + 1e-9;
        // (A run outside the window is reported as missing it, on the re-simulation.)
        const double t = passing_at(run.sim.trace, p.s_m).t_s;
        const bool inside = t >= p.earliest_s - options_.time_tolerance_s &&
                            t <= p.latest_s + options_.time_tolerance_s;
        if (off > allowed && inside) {
          // Inside the window but not at the bound the unconstrained run missed: feasible, and
          // possibly not the least energy (the prices could not be set closer on this grid).
          notes_.push_back(format_text(
              "the price search for %s ended %.2f s from its %s bound: every window can hold, "
              "but the run may not be the least-energy one",
              point_name(p.index, windows_[p.index]).c_str(), off,
              bound_s_[m] == p.latest_s ? "latest" : "earliest"));
        }
        // A latest bound is held by a dearer second before the point, an earliest one by a
        // cheaper one; the other sign means the window need not bind (a multiplier < 0).
        const int sign = binding_sign(binding_[m]);
        if (binding_.size() > 1 && (sign > 0) != (bound_s_[m] == p.latest_s)) {
          notes_.push_back(format_text(
              "%s binds with a multiplier of the wrong sign: every window holds, but the run "
              "may not be the least-energy one",
              point_name(p.index, windows_[p.index]).c_str()));
        }
      }
    }
    if (end_.moving && binding_.empty() && !arrival_at_floor_ && end_(run.sim) &&
        run.sim.running_time_s < target_s_ - options_.time_tolerance_s &&
        run.sim.running_time_s >= earliest_arrival_s_ - options_.time_tolerance_s) {
      // The running time of a run that ends moving can jump by seconds between neighbouring
      // prices (a slow approach to a low end speed): the search ends with a run inside the
      // arrival window but short of its latest bound. Feasible (every window is checked on the
      // re-simulation), possibly not the least energy.
      ok = true;
      notes_.push_back(format_text(
          "the arrival search ended %.2f s before the latest arrival: every window can hold, but "
          "the run may not be the least-energy one",
          target_s_ - run.sim.running_time_s));
    }
    *met = ok;
    return run;
  }

 private:
  // One binding point whose search ended away from its bound (the passing time jumps between
  // neighbouring prices, e.g. a stretch priced so low that a coast appears or vanishes, and
  // the run is seconds inside its window or a few tenths outside it): one switch before the
  // point is moved, however far, so the run passes at the bound, and the rest of the run from
  // there is re-solved from the state it passes in for the time left (the plain search from a
  // restart: the optimum of the rest, whatever came before). The stitched program is
  // re-simulated from the start and kept when it reaches its stop at the latest arrival and
  // passes the point at its bound, and either the run before missed the window or the
  // stitched one costs less.
  void close_gap(LambdaRun& run) {
    const PartPoint& p = points_[binding_[0]];
    const double bound = bound_s_[0];
    const double s_k = p.s_m;
    const double off = passing_at(run.sim.trace, s_k).t_s - bound;
    if (!(std::abs(off) > options_.time_tolerance_s)) return;
    LambdaRun trimmed = run;
    evaluations_ += trim_switch(
        engine_, end_, trimmed, 0.0, s_k,
        [&](const physics::SimulationResult& sim) {
          return passing_at(sim.trace, s_k).t_s - bound;
        },
        kTrimTolerance_s, std::abs(off) + kMaxTrim_s);
    const Passing at = passing_at(trimmed.sim.trace, s_k);
    if (!(std::abs(at.t_s - bound) <= kTrimTolerance_s) || !(at.v_ms > 0.0)) return;
    TimeSearchResult rest;
    try {
      rest = solve_for_time(engine_, target_s_ - at.t_s, TimeSearchOptions{}, {s_k, at.v_ms});
    } catch (const TimeRequestError&) {
      return;  // the time left is outside what the rest can run
    }
    evaluations_ += rest.iterations;
    if (!rest.converged) return;
    physics::ControlProgram stitched;
    for (const auto& step : trimmed.program) {
      if (step.from_m < s_k) stitched.push_back(step);
    }
    for (const auto& step : rest.run.program) {
      if (step.from_m >= s_k - 1e-9) stitched.push_back(step);
    }
    // The run as it is misses the window (early for an earliest bound, late for a latest one):
    // any feasible stitched run replaces it; otherwise only a cheaper one.
    const bool run_misses = off < 0.0 ? bound == p.earliest_s : bound == p.latest_s;
    LambdaRun out = run;
    out.program = simplify_program(stitched, 0.0);
    out.sim = engine_.simulate(out.program, start_);
    ++evaluations_;
    out.cost_J = engine_.energy_cost_J(out.sim);
    const Passing now = passing_at(out.sim.trace, s_k);
    if (!end_(out.sim) || !(std::abs(out.sim.running_time_s - target_s_) <= kArrivalTolerance_s) ||
        !(std::abs(now.t_s - bound) <= options_.time_tolerance_s) ||
        !(run_misses || out.cost_J < run.cost_J)) {
      return;
    }
    trim_arrival(out, s_k);
    run = std::move(out);
  }

  // Adds points_[k] to the binding set (kept in order along the part), its price starting at
  // the price its stretch has now, so the prices do not change. False (with a note) when the
  // point shares its grid stage with a binding point (no price can part them).
  bool add_binding(int k) {
    if (std::find(binding_.begin(), binding_.end(), k) != binding_.end()) return true;
    for (int b : binding_) {
      if (points_[b].stage == points_[k].stage) {
        notes_.push_back(format_text(
            "%s and %s lie on one grid stage: their windows cannot both be priced (use a finer "
            "--ds)",
            point_name(points_[b].index, windows_[points_[b].index]).c_str(),
            point_name(points_[k].index, windows_[points_[k].index]).c_str()));
        return false;
      }
    }
    const double price = stretch_price(k);
    const auto at = std::lower_bound(binding_.begin(), binding_.end(), k) - binding_.begin();
    binding_.insert(binding_.begin() + at, k);
    before_.insert(before_.begin() + at, price);
    bound_s_.insert(bound_s_.begin() + at, 0.0);
    return true;
  }

  // The price before binding point m searched for its passing time, the others held; run and
  // the prices are set to the best run found. False (with a note) when no run meets it.
  bool search_price(std::size_t m, LambdaRun& run) {
    const PartPoint& p = points_[binding_[m]];
    const double bound = search_target_s(m);
    LambdaRun best;
    double best_abs = kInf;
    bool best_ok = false;
    double best_before = 0.0, best_after = 0.0;
    std::vector<double> before = before_;
    auto g = [&](double x) {
      before[m] = std::exp(x);
      Inner in = solve_arrival(before);
      const Passing at = passing_at(in.run.sim.trace, p.s_m);
      if (!in.ok || !finite(at.t_s)) return kInf;
      const double err = at.t_s - bound;
      if (std::abs(err) < best_abs) {
        best_abs = std::abs(err);
        best = std::move(in.run);
        best_ok = true;
        best_before = std::exp(x);
        best_after = std::exp(in.x_after);
      }
      return err;
    };
    falling_root(g, std::log(std::max(1.0, before_[m])), 0.3, 0.0, 30.0, kOuterBudget,
                 passing_tolerance_s());
    if (!best_ok) {
      notes_.push_back(format_text("the price search for %s found no run that meets it",
                                   point_name(p.index, windows_[p.index]).c_str()));
      return false;
    }
    run = std::move(best);
    before_[m] = best_before;
    lambda_after_ = best_after;
    return true;
  }

  // With several binding points, no switch-point trim closes their last tenths (a switch
  // between two of them changes the speed at the later one, and the run after it by seconds),
  // so each is searched for a time kInside_s inside its bound, within kInside_s: it passes
  // within 2 kInside_s of its bound, inside its window. One binding point: at its bound, within
  // kPassingTolerance_s, and trimmed.
  double search_target_s(std::size_t m) const {
    if (binding_.size() == 1) return bound_s_[m];
    const PartPoint& p = points_[binding_[m]];
    return bound_s_[m] == p.latest_s ? bound_s_[m] - kInside_s : bound_s_[m] + kInside_s;
  }
  double passing_tolerance_s() const {
    return binding_.size() == 1 ? kPassingTolerance_s : kInside_s;
  }

  // Every binding point's price searched for its time: one root search for one point; for
  // several, cycles of one search per point (skipping those already within the tolerance)
  // until all are within it.
  bool meet_bindings(LambdaRun& run) {
    const std::size_t k = binding_.size();
    auto within = [&](std::size_t m) {
      const double t = passing_at(run.sim.trace, points_[binding_[m]].s_m).t_s;
      return finite(t) && std::abs(t - search_target_s(m)) <= passing_tolerance_s();
    };
    const int cycles = k > 1 ? kMaxCycles : 1;
    for (int cycle = 0; cycle < cycles; ++cycle) {
      for (std::size_t m = 0; m < k; ++m) {
        if (k > 1 && within(m)) continue;
        if (!search_price(m, run)) return false;
      }
      bool all = true;
      for (std::size_t m = 0; m < k; ++m) all = all && within(m);
      if (all) break;
    }
    return true;
  }

  // The price searches stop within a few tenths (the running time is ragged on a grid); the
  // switch-point trims close the rest to kTrimTolerance_s.
  static constexpr double kArrivalTolerance_s = 0.25;
  static constexpr double kPassingTolerance_s = 0.25;
  static constexpr double kTrimTolerance_s = 0.01;
  static constexpr int kInnerBudget = 40;
  static constexpr int kOuterBudget = 25;
  static constexpr int kMaxCycles = 6;  // of the searches for several binding points
  static constexpr double kInside_s = 0.1;

  const SectionEngine& engine_;
  StartState start_;
  EndCheck end_;
  double target_s_;
  double earliest_arrival_s_;
  std::vector<PartPoint> points_;
  const std::vector<TimingWindow>& windows_;
  const TimingJourneyOptions& options_;
  std::vector<SpeedBand> bands_;
  std::vector<std::string> notes_;
  // The binding passing points (indices into points_, in order along the part), the bound each
  // meets and the price of the stretch ending at it; lambda_after_ after the last of them.
  bool arrival_at_floor_ = false;  // the last arrival search: even its lowest price is early
  std::vector<int> binding_;
  std::vector<bool> inactive_;  // per binding point (see inactive())
  std::vector<double> bound_s_;
  std::vector<double> before_;
  double lambda_after_ = 0.0;
  double x_after_guess_ = std::log(3e5);
  int evaluations_ = 0;
};

// Where the parts start and end: indices of the points that bound them.
struct PartBounds {
  int first = 0, last = 0;
};

std::vector<PartBounds> split_into_parts(const std::vector<TimingWindow>& w) {
  std::vector<PartBounds> parts;
  int first = 0;
  const int n = static_cast<int>(w.size());
  for (int i = 1; i < n; ++i) {
    if (!(w[i].is_stop() || i == n - 1)) continue;
    parts.push_back({first, i});
    // Two points at one position: arrival at and departure from the stop.
    if (i + 1 < n && w[i + 1].position_m == w[i].position_m) ++i;
    first = i;
  }
  return parts;
}

void check_structure(const std::vector<TimingWindow>& w, double track_length_m) {
  const int n = static_cast<int>(w.size());
  if (n < 2) throw WindowInfeasibleError(0, "a journey needs at least two timing points");
  for (int i = 0; i < n; ++i) {
    const TimingWindow& p = w[i];
    if (!(p.position_m >= 0.0 && p.position_m <= track_length_m + 1e-6)) {
      throw WindowInfeasibleError(i, format_text("%s lies outside the track (0 to %.1f m)",
                                                 point_name(i, p).c_str(), track_length_m));
    }
    if (p.earliest_s > p.latest_s || p.min_speed_ms > p.max_speed_ms) {
      throw WindowInfeasibleError(i, point_name(i, p) + " has a lower bound above its upper bound");
    }
    if (i > 0) {
      const TimingWindow& q = w[i - 1];
      if (p.position_m < q.position_m) {
        throw WindowInfeasibleError(i, point_name(i, p) + " lies before the point before it");
      }
      if (p.position_m == q.position_m && !(p.is_stop() && q.is_stop())) {
        throw WindowInfeasibleError(
            i, point_name(i, p) +
                   " shares its position with the point before it, but only a stop (speed "
                   "window [0, 0]) may have two points (arrival and departure)");
      }
      if (p.position_m == q.position_m && i >= 2 && w[i - 2].position_m == p.position_m) {
        throw WindowInfeasibleError(i, point_name(i, p) + ": a stop has at most two points");
      }
    }
  }
  if (w.back().position_m <= w.front().position_m) {
    throw WindowInfeasibleError(n - 1, "the last timing point must lie after the first");
  }
  if (!finite(w.back().latest_s)) {
    throw WindowInfeasibleError(
        n - 1, point_name(n - 1, w.back()) + " needs a latest time (the arrival's)");
  }
}

// The route whose speed envelope a part that ends moving uses: the part, then a level, straight
// stretch whose limit is the end window's top speed (the line's limit at the end when that is
// lower or the window has none), long enough that the envelope does not brake to rest before
// its end. The envelope at the end point is then the lower of the window's top speed and the
// line's limit there, and the grid's last stage has every speed up to it. Nothing beyond the
// last timing point is braked for: the journey ends there.
physics::Route runoff_route(const physics::Train& train, const physics::Route& part, double top_ms,
                            double resolution_m) {
  const double length = part.length_m();
  physics::RouteSegment extra = part.segments().back();
  extra.start_m = length;
  extra.gradient_permille = 0.0;
  extra.curve_radius_m = 0.0;
  extra.curve_N_per_kN = -1.0;
  extra.tunnel_drag_N_per_kN_kmh2 = 0.0;
  if (finite(top_ms)) extra.speed_limit_ms = std::min(extra.speed_limit_ms, top_ms);
  const int direction = part.km_post_m(1.0) >= part.km_post_m(0.0) ? 1 : -1;
  for (double runoff_m = 500.0;; runoff_m *= 2.0) {
    std::vector<physics::RouteSegment> segs = part.segments();
    extra.end_m = length + runoff_m;
    segs.push_back(extra);
    physics::Route route(std::move(segs), part.km_post_m(0.0), direction, part.from_name(),
                         part.to_name());
    const physics::SpeedEnvelope envelope(train, route, resolution_m);
    if (envelope.v_at(length) >= envelope.static_limit_ms(length) - 1e-6 || runoff_m > 2e5) {
      return route;
    }
  }
}

}  // namespace

TimingJourneySolution solve_timing_journey(const physics::Train& train, const physics::Route& track,
                                           const std::vector<TimingWindow>& windows,
                                           const TimingJourneyOptions& options,
                                           const std::string& id) {
  const auto t0 = Clock::now();
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument(why);
  check_structure(windows, track.length_m());
  const double tol_t = options.time_tolerance_s;
  const double tol_v = units::kmh_to_ms(options.speed_tolerance_kmh);
  const int n = static_cast<int>(windows.size());

  TimingJourneySolution out;
  const std::vector<PartBounds> bounds = split_into_parts(windows);
  std::vector<std::unique_ptr<SectionEngine>> engines;
  std::vector<StartState> starts;
  // A last point that is not a stop (its speed window reaches above 0): the last part ends
  // moving, with that window as its end band (at rest is allowed when the window holds 0).
  EndCheck moving_end;
  moving_end.moving = !windows.back().is_stop();
  moving_end.min_ms = std::max(0.0, windows.back().min_speed_ms);
  moving_end.max_ms = windows.back().max_speed_ms;
  moving_end.tol_ms = tol_v;
  std::vector<EndCheck> ends;
  for (const PartBounds& b : bounds) {
    out.routes.push_back(
        slice_route(track, windows[b.first].position_m, windows[b.last].position_m));
    const bool moving = b.last == n - 1 && moving_end.moving;
    ends.push_back(moving ? moving_end : EndCheck{});
    if (moving) {
      const physics::Route envelope_route = runoff_route(
          train, out.routes.back(), moving_end.max_ms, options.engine.envelope_resolution_m);
      engines.push_back(std::make_unique<SectionEngine>(train, out.routes.back(), options.engine,
                                                        envelope_route));
    } else {
      engines.push_back(std::make_unique<SectionEngine>(train, out.routes.back(), options.engine));
    }
    // A run that starts moving starts at the first point's lowest allowed speed.
    const double v0 = b.first == 0 ? std::max(0.0, windows[0].min_speed_ms) : 0.0;
    starts.push_back({0.0, v0});
  }
  if (starts[0].speed_ms > engines[0]->envelope().v_at(0.0) + tol_v) {
    throw WindowInfeasibleError(
        0, format_text("%s asks to start at %.2f km/h, above what the train may run there "
                       "(%.2f km/h)",
                       point_name(0, windows[0]).c_str(), units::ms_to_kmh(starts[0].speed_ms),
                       units::ms_to_kmh(engines[0]->envelope().v_at(0.0))));
  }

  // The proof of infeasibility: the earliest time each point can be reached, from flat-out
  // runs. Leaving point i at the highest speed its window and the line allow and running flat
  // out is the fastest any run can cover the stretch to point i + 1 (no run is faster than the
  // envelope-following flat-out run from the highest speed), so earliest[i + 1] >= earliest[i]
  // + that time is a lower bound; a point whose lower bound exceeds its latest time is proved
  // infeasible. cause[i]: the point whose earliest bound the chain starts from.
  std::vector<double> earliest(n), min_leg_s(n, 0.0);
  std::vector<int> cause(n);
  double departure0 = finite(windows[0].earliest_s) ? windows[0].earliest_s : 0.0;
  earliest[0] = departure0;
  cause[0] = 0;
  for (std::size_t j = 0; j < bounds.size(); ++j) {
    const SectionEngine& engine = *engines[j];
    const double origin = windows[bounds[j].first].position_m;
    for (int i = bounds[j].first; i < bounds[j].last; ++i) {
      const TimingWindow& w = windows[i];
      const double s = w.position_m - origin;
      double v = i == bounds[j].first ? starts[j].speed_ms
                                      : std::min(engine.envelope().v_at(s), w.max_speed_ms);
      v = std::max(0.0, v);
      const physics::SimulationResult flat = engine.min_time_run({s, v});
      const Passing at_next = passing_at(flat.trace, windows[i + 1].position_m - origin);
      min_leg_s[i + 1] = finite(at_next.t_s) ? at_next.t_s : kInf;
      if (finite(at_next.v_ms) && windows[i + 1].min_speed_ms > at_next.v_ms + tol_v) {
        throw WindowInfeasibleError(
            i + 1, format_text("%s: min speed %.2f km/h cannot be met: the train reaches at "
                               "most %.2f km/h there",
                               point_name(i + 1, windows[i + 1]).c_str(),
                               units::ms_to_kmh(windows[i + 1].min_speed_ms),
                               units::ms_to_kmh(at_next.v_ms)));
      }
      double e = earliest[i] + min_leg_s[i + 1];
      cause[i + 1] = cause[i];
      if (windows[i + 1].earliest_s > e) e = windows[i + 1].earliest_s, cause[i + 1] = i + 1;
      earliest[i + 1] = e;
      if (e > windows[i + 1].latest_s + tol_t) {
        const int c = cause[i];
        std::string from =
            c == 0 ? format_text("departing at %.1f s", earliest[0])
                   : format_text("%s no earlier than %.1f s (its window)",
                                 point_name(c, windows[c]).c_str(), windows[c].earliest_s);
        throw WindowInfeasibleError(
            i + 1,
            format_text("%s: latest %.1f s cannot be met: %s, the train needs at least %.1f s "
                        "from %.1f m to %.1f m (flat out), so it arrives no earlier than %.1f s",
                        point_name(i + 1, windows[i + 1]).c_str(), windows[i + 1].latest_s,
                        from.c_str(), e - earliest[c], windows[c].position_m,
                        windows[i + 1].position_m, e));
      }
    }
    // The next part departs from the same stop (its second point, if it has one).
    if (j + 1 < bounds.size() && bounds[j + 1].first != bounds[j].last) {
      const int dep = bounds[j + 1].first;
      double e = earliest[bounds[j].last];
      cause[dep] = cause[bounds[j].last];
      if (windows[dep].earliest_s > e) e = windows[dep].earliest_s, cause[dep] = dep;
      earliest[dep] = e;
      if (e > windows[dep].latest_s + tol_t) {
        throw WindowInfeasibleError(
            dep, format_text("%s: latest departure %.1f s cannot be met: the train arrives "
                             "there no earlier than %.1f s",
                             point_name(dep, windows[dep]).c_str(), windows[dep].latest_s, e));
      }
    }
  }

  // Times of the parts: depart at the earliest allowed, arrive at the latest allowed (energy
  // falls with running time). Where an arrival window reaches past the next departure's
  // earliest time (overlapping windows, or one window at a one-point stop), the part arrives
  // at that time for now (dwell 0 unless the run is slower); the split of time between the two
  // parts is then optimised below.
  std::vector<char> overlaps(bounds.size(), 0);
  double departure = departure0;
  for (std::size_t j = 0; j < bounds.size(); ++j) {
    const TimingWindow& arr = windows[bounds[j].last];
    double arrival = arr.latest_s;
    if (j + 1 < bounds.size()) {
      const TimingWindow& dep = windows[bounds[j + 1].first];
      if (!finite(arrival) && !finite(dep.earliest_s)) {
        throw WindowInfeasibleError(
            bounds[j].last,
            point_name(bounds[j].last, arr) +
                " needs a latest arrival or its departure an earliest time (the part's running "
                "time is otherwise unbounded)");
      }
      if (finite(dep.earliest_s) && dep.earliest_s < arrival) {
        arrival = std::max(dep.earliest_s, earliest[bounds[j].last]);
        overlaps[j] = 1;
      }
    }
    TimingPart part;
    part.first_point = bounds[j].first;
    part.last_point = bounds[j].last;
    part.start_m = windows[bounds[j].first].position_m;
    part.end_m = arr.position_m;
    part.departure_s = departure;
    part.arrival_target_s = arrival;
    out.parts.push_back(part);
    if (j + 1 < bounds.size()) {
      const TimingWindow& dep = windows[bounds[j + 1].first];
      departure = finite(dep.earliest_s) ? std::max(dep.earliest_s, arrival) : arrival;
    }
  }

  // The passing points of part j, relative to a departure at departure_s.
  auto points_of = [&](std::size_t j, double departure_s) {
    const SectionEngine& engine = *engines[j];
    std::vector<PartPoint> points;
    for (int i = bounds[j].first + 1; i < bounds[j].last; ++i) {
      PartPoint p;
      p.index = i;
      p.s_m = windows[i].position_m - windows[bounds[j].first].position_m;
      p.stage = std::clamp(static_cast<int>(std::lround(p.s_m / engine.options().grid.ds_m)), 0,
                           engine.grid().stage_count() - 1);
      p.earliest_s = windows[i].earliest_s - departure_s;
      p.latest_s = windows[i].latest_s - departure_s;
      points.push_back(p);
    }
    return points;
  };
  // The energy cost of part j between two times; +inf where it misses a window or its time.
  auto part_cost_J = [&](std::size_t j, double departure_s, double arrival_s) {
    if (!(arrival_s > departure_s)) return kInf;
    PartSolver solver(*engines[j], starts[j], ends[j], arrival_s - departure_s,
                      windows[bounds[j].last].earliest_s - departure_s, points_of(j, departure_s),
                      windows, options);
    try {
      bool met = false;
      const LambdaRun run = solver.solve(&met);
      return met && ends[j].reaches_end(run.sim) ? run.cost_J : kInf;
    } catch (const TimeRequestError&) {
      return kInf;
    }
  };

  // The best split at a stop whose windows overlap. Its time x is both the arrival of the part
  // before and the departure of the part after: an arrival before the departure would only
  // take time from one of the two parts, so the stop is left at once. Each part's least
  // energy falls and is convex in its running time, so the pair's energy is unimodal in x:
  // golden section over the times both windows and the next part's flat-out run allow, stop
  // by stop from the first (a later stop sees the departure chosen before it). The earliest
  // time (the rule without this search) is evaluated too, and the search's x is taken only
  // where it is cheaper.
  constexpr double kSplitTolerance_s = 0.5;
  constexpr int kSplitSteps = 12;
  for (std::size_t j = 0; j + 1 < bounds.size(); ++j) {
    if (!overlaps[j]) continue;
    TimingPart& before = out.parts[j];
    TimingPart& after = out.parts[j + 1];
    const double lo = before.arrival_target_s;
    const double hi = std::min(
        {windows[bounds[j].last].latest_s, windows[bounds[j + 1].first].latest_s,
         after.arrival_target_s - engines[j + 1]->min_time_run(starts[j + 1]).running_time_s});
    std::string how = "not optimised (the later bound is open)";
    if (finite(hi) && hi > lo + kSplitTolerance_s) {
      auto pair_cost = [&](double x) {
        const double first = part_cost_J(j, before.departure_s, x);
        return finite(first) ? first + part_cost_J(j + 1, x, after.arrival_target_s) : kInf;
      };
      const GoldenSectionResult g = golden_section_minimum(pair_cost, lo, hi, kSplitTolerance_s,
                                                           kSplitSteps, /*ties_go_left=*/true);
      const double at_lo = pair_cost(lo);
      if (finite(g.best_f) && g.best_f < at_lo) {
        before.arrival_target_s = after.departure_s = g.best_x;
        how = format_text(
            "chosen by golden section in [%.1f, %.1f] s to %.1f s, %.1f kJ less "
            "than at its earliest time",
            lo, hi, kSplitTolerance_s, units::J_to_kJ(at_lo - g.best_f));
      } else {
        how = format_text("chosen by golden section in [%.1f, %.1f] s: its earliest time", lo, hi);
      }
    } else if (finite(hi)) {
      how = format_text("its earliest time (the windows leave %.1f s)", std::max(0.0, hi - lo));
    }
    out.summary.warnings.push_back(format_text(
        "the arrival and departure windows at %.1f m overlap: the stop is at %.1f s (dwell 0), "
        "%s",
        windows[bounds[j].last].position_m, before.arrival_target_s, how.c_str()));
  }

  // Solve each part.
  bool all_met = true;
  bool all_arrive = true;
  std::vector<std::vector<PartPoint>> part_points(bounds.size());
  std::vector<int> binding_sign(n, 0);     // per timing point
  std::vector<double> bind_slack(n, 0.0);  // how far inside its bound a binding point may pass
  for (std::size_t j = 0; j < bounds.size(); ++j) {
    TimingPart& part = out.parts[j];
    const SectionEngine& engine = *engines[j];
    const std::vector<PartPoint> points = points_of(j, part.departure_s);
    const double target = part.arrival_target_s - part.departure_s;
    const double earliest_arrival = windows[part.last_point].earliest_s - part.departure_s;
    auto solver = std::make_unique<PartSolver>(engine, starts[j], ends[j], target, earliest_arrival,
                                               points, windows, options);
    bool met = false;
    LambdaRun run;
    try {
      run = solver->solve(&met);
    } catch (const LongTimeError& e) {
      // Slower than the engine solves reliably: arrive as late as it can, if that is allowed.
      const double latest_ok = part.departure_s + e.maximum_s() - 0.5;
      if (latest_ok < windows[part.last_point].earliest_s) throw;
      part.arrival_target_s = latest_ok;
      out.summary.warnings.push_back(format_text(
          "part %zu: its latest arrival is beyond the slowest run the grid solves reliably; it "
          "arrives at %.1f s",
          j + 1, latest_ok));
      solver =
          std::make_unique<PartSolver>(engine, starts[j], ends[j], latest_ok - part.departure_s,
                                       earliest_arrival, points, windows, options);
      run = solver->solve(&met);
    }
    part.evaluations = solver->evaluations();
    part_points[j] = solver->points();
    all_arrive = all_arrive && ends[j].reaches_end(run.sim);
    all_met = all_met && met;
    for (const auto& note : solver->notes()) out.summary.warnings.push_back(note);
    // Prices of the stretches, first to last, and the sign of each binding point's multiplier
    // (+1 its latest bound binds, -1 its earliest).
    for (int k = 0; k <= static_cast<int>(points.size()); ++k) {
      part.stretch_lambda_J_per_s.push_back(solver->stretch_price(k));
      if (k < static_cast<int>(points.size())) {
        binding_sign[points[k].index] = solver->binding_sign(k);
        bind_slack[points[k].index] = solver->binding_slack_s();
      }
    }

    if (ends[j].moving && ends[j].reaches_end(run.sim) && run.sim.end_speed_ms > 0.0) {
      // The simulator reports a moving end's stop error as where full braking would bring it
      // to rest; this run's end is the end point itself, which it reaches (it does not stop).
      run.sim.end_position_m -= run.sim.stop_error_m;
      run.sim.stop_error_m = 0.0;
    }
    JourneySection sec;
    sec.run = std::move(run);
    sec.regimes = regime_spans(sec.run.sim.trace);
    sec.marginal_J_per_s = NAN;
    sec.min_time_s = engine.min_time_run(starts[j]).running_time_s;
    out.journey.sections.push_back(std::move(sec));
  }
  for (std::size_t j = 0; j + 1 < bounds.size(); ++j) {
    out.journey.sections[j].dwell_after_s =
        out.parts[j + 1].departure_s -
        (out.parts[j].departure_s + out.journey.sections[j].run.sim.running_time_s);
  }

  // The windows on the re-simulation.
  out.windows.resize(n);
  bool windows_met = true;
  for (std::size_t j = 0; j < bounds.size(); ++j) {
    const TimingPart& part = out.parts[j];
    const auto& sim = out.journey.sections[j].run.sim;
    auto record = [&](int i, double t, double v, bool departure_point, bool arrival_point, int sign,
                      double slack_s = 0.0) {
      WindowResult& r = out.windows[i];
      const TimingWindow& w = windows[i];
      r.window = w;
      r.time_s = t;
      r.speed_ms = v;
      r.met = finite(t) && t >= w.earliest_s - tol_t && t <= w.latest_s + tol_t &&
              v >= w.min_speed_ms - tol_v && v <= w.max_speed_ms + tol_v;
      r.binds.clear();
      if (finite(w.earliest_s) && std::abs(t - w.earliest_s) <= tol_t + slack_s &&
          (departure_point || sign < 0)) {
        r.binds.push_back("earliest");
      }
      if (finite(w.latest_s) && std::abs(t - w.latest_s) <= tol_t + slack_s &&
          (arrival_point || sign > 0)) {
        r.binds.push_back("latest");
      }
      if (!w.is_stop()) {
        if (finite(w.min_speed_ms) && std::abs(v - w.min_speed_ms) <= tol_v) {
          r.binds.push_back("min_speed");
        }
        if (finite(w.max_speed_ms) && std::abs(v - w.max_speed_ms) <= tol_v) {
          r.binds.push_back("max_speed");
        }
      }
      windows_met = windows_met && r.met;
    };
    record(part.first_point, part.departure_s, starts[j].speed_ms, true, false, 0.0);
    for (const PartPoint& p : part_points[j]) {
      const Passing at = passing_at(sim.trace, p.s_m);
      record(p.index, part.departure_s + at.t_s, at.v_ms, false, false, binding_sign[p.index],
             bind_slack[p.index]);
    }
    const bool arrives = ends[j].reaches_end(sim);
    record(part.last_point, arrives ? part.departure_s + sim.running_time_s : NAN,
           arrives ? sim.end_speed_ms : NAN, false, true, 0.0);
  }
  out.windows_met = windows_met && all_arrive;

  // Totals, as a journey's.
  JourneySolution& jr = out.journey;
  jr.lambda_J_per_s = NAN;
  for (const auto& s : jr.sections) {
    jr.net_J += s.run.sim.energy.net_J();
    jr.running_time_s += s.run.sim.running_time_s;
    jr.traction_work_J += s.run.sim.energy.traction_work_J;
    jr.brake_work_J += s.run.sim.energy.brake_work_J;
    jr.regen_J += s.run.sim.energy.regen_J;
  }
  jr.target_time_s = 0.0;
  for (const auto& p : out.parts) jr.target_time_s += p.arrival_target_s - p.departure_s;
  jr.converged = out.windows_met && all_met;
  jr.total_wall_s = seconds_since(t0);
  jr.warnings = out.summary.warnings;

  TimingJourneySummary& s = out.summary;
  s.id = id;
  s.parts = static_cast<int>(out.parts.size());
  s.distance_m = windows.back().position_m - windows.front().position_m;
  s.grid = options.engine.grid;
  s.objective = options.engine.objective;
  for (const auto& p : out.parts) s.evaluations += p.evaluations;
  jr.lambda_evaluations = s.evaluations;
  s.windows_met = out.windows_met;
  s.termination = !all_arrive       ? Termination::FAILURE
                  : out.windows_met ? Termination::CONVERGENCE
                                    : Termination::NO_CONVERGENCE;
  jr.summary.termination = s.termination;
  s.running_time_s = jr.running_time_s;
  s.trip_time_s = out.windows.back().time_s - out.parts.front().departure_s;
  s.traction_energy_kJ = units::J_to_kJ(jr.traction_work_J);
  s.regen_energy_kJ = units::J_to_kJ(jr.regen_J);
  s.net_energy_kJ = units::J_to_kJ(jr.net_J);
  for (const auto& w : out.windows) {
    if (!w.met) {
      s.warnings.push_back(
          format_text("the window at %.1f m is missed in the re-simulation: %.2f s, %.2f km/h",
                      w.window.position_m, w.time_s, units::ms_to_kmh(w.speed_ms)));
    }
  }
  jr.warnings = s.warnings;
  s.total_wall_s = seconds_since(t0);
  return out;
}

std::string TimingJourneySummary::BriefReport() const {
  return format_text(
      "ecorail solve --journey %s (%d parts, %.1f m) in %.3f s running time (trip %.3f s): "
      "traction %.1f kJ, regenerated %.1f kJ, windows %s; %d price evaluations, %.3f s wall, "
      "%s\n",
      id.empty() ? "-" : id.c_str(), parts, distance_m, running_time_s, trip_time_s,
      traction_energy_kJ, regen_energy_kJ, windows_met ? "met" : "MISSED", evaluations,
      total_wall_s, std::string(status_word(termination, warnings.size())).c_str());
}

std::string TimingJourneySummary::FullReport() const {
  std::string r = "Timing-point journey " + (id.empty() ? std::string("-") : id) + "\n";
  r += format_text("  %-28s %d\n", "Parts (stop to stop)", parts);
  r += format_text("  %-28s %.1f m\n", "Distance", distance_m);
  r += format_text("  %-28s ds %.3f m, dv %.3f km/h\n", "Grid", grid.ds_m, grid.dv_kmh);
  r += format_text("  %-28s %s\n", "Objective", std::string(objective_name(objective)).c_str());
  r += format_text("  %-28s %d\n", "Price evaluations", evaluations);
  r += format_text("  %-28s %.3f s\n", "Wall time", total_wall_s);
  r += format_text("  %-28s %.4f s\n", "Running time", running_time_s);
  r += format_text("  %-28s %.4f s\n", "Trip time", trip_time_s);
  r += format_text("  %-28s %.3f kJ\n", "Traction energy", traction_energy_kJ);
  r += format_text("  %-28s %.3f kJ\n", "Regenerated energy", regen_energy_kJ);
  r += format_text("  %-28s %.3f kJ\n", "Net energy", net_energy_kJ);
  r += format_text("  %-28s %s\n", "Windows met", windows_met ? "yes" : "no");
  r += format_text("  %-28s %s\n", "Termination",
                   std::string(termination_name(termination)).c_str());
  for (const auto& w : warnings) r += "  warning: " + w + "\n";
  return r;
}

}  // namespace ecorail::dp
