#include "dp/timing_journey.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <stdexcept>

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
                double hi_m, Error error, double tol_s) {
  int used = 0;
  // Only a last correction: a larger miss is the price search's to close, not a switch's.
  const double miss = std::abs(error(run.sim));
  if (miss <= tol_s || !(miss <= kMaxTrim_s)) return used;
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
// window changes nothing). Otherwise the most missed passing window binds at its bound: the
// price before it (lambda_before) and after it (lambda_after) are searched, the outer on
// lambda_before for the passing time, the inner on lambda_after for the arrival. The arrival
// is a window too: when even the lowest price after the point arrives before the latest
// arrival, the arrival does not bind and that run is kept. Speed windows missed by the run are
// added as speed bands at their stage, and the search is repeated with them.
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
  double lambda_before() const { return lambda_before_; }
  double lambda_after() const { return lambda_after_; }
  int binding() const { return binding_; }

  StagePrices prices(double before, double after) const {
    StagePrices p;
    const int transitions = engine_.grid().stage_count() - 1;
    p.lambda_J_per_s.assign(transitions, after);
    if (binding_ >= 0) {
      const int upto = std::clamp(points_[binding_].stage, 0, transitions);
      for (int i = 0; i < upto; ++i) p.lambda_J_per_s[i] = before;
    }
    p.bands = bands_;
    p.end_moving = end_.moving;
    p.end_min_ms = end_.min_ms;
    p.end_max_ms = end_.max_ms;
    return p;
  }

  LambdaRun evaluate(double before, double after) {
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

  // For a fixed price before the binding point (before < 0: one price everywhere), the run
  // whose arrival is the latest allowed, or the slowest-priced run if even that arrives
  // earlier (the arrival then does not bind). ok: the arrival is within its window.
  struct Inner {
    LambdaRun run;
    double x_after = 0.0;
    bool ok = false;
  };
  Inner solve_arrival(double before) {
    Inner best;
    double best_abs = kInf;
    Inner floor_run;
    double floor_x = kInf;
    auto f = [&](double x) {
      const double after = std::exp(x);
      LambdaRun run = evaluate(before < 0.0 ? after : before, after);
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
    }
    if (best.ok) x_after_guess_ = best.x_after;
    return best;
  }

  // The last hundredths of the arrival by one switch point after from_m (when the arrival
  // binds: the run is not early by more than the search's tolerance).
  void trim_arrival(LambdaRun& run, double from_m) {
    if (run.sim.running_time_s > target_s_ - kArrivalTolerance_s) {
      evaluations_ += trim_switch(
          engine_, end_, run, from_m, engine_.route().length_m(),
          [&](const physics::SimulationResult& sim) { return sim.running_time_s - target_s_; },
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
      lambda_before_ = lambda_after_ = run.lambda;
      x_after_guess_ = std::log(std::max(1.0, run.lambda));
    } else {
      // A run that ends moving: the plain search ends at rest, so the one price is searched
      // here, with the end's speed band (StagePrices::end_moving).
      Inner in = solve_arrival(-1.0);
      run = std::move(in.run);
      ok = in.ok;
      lambda_before_ = lambda_after_ = std::exp(in.x_after);
      if (ok) trim_arrival(run, 0.0);
    }
    for (int round = 0; round < 3; ++round) {
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
      if (worst >= 0 && binding_ >= 0 && worst != binding_) {
        notes_.push_back(format_text(
            "%s and %s would both bind: more than one binding passing point in a part is not "
            "supported yet",
            point_name(points_[binding_].index, windows_[points_[binding_].index]).c_str(),
            point_name(points_[worst].index, windows_[points_[worst].index]).c_str()));
        break;
      }
      if (worst < 0 && binding_ < 0) {
        // Bands alone: one price, searched with them.
        Inner in = solve_arrival(-1.0);
        run = std::move(in.run);
        ok = in.ok;
        lambda_before_ = lambda_after_ = std::exp(in.x_after);
        if (ok) trim_arrival(run, 0.0);
        continue;
      }
      if (worst >= 0) binding_ = worst;
      const PartPoint& p = points_[binding_];
      const double miss = time_miss_s(run, p);
      const double bound = miss > 0.0 ? p.latest_s : miss < 0.0 ? p.earliest_s : bound_s_;
      bound_s_ = bound;
      LambdaRun best;
      double best_abs = kInf;
      bool best_ok = false;
      double best_before = 0.0, best_after = 0.0;
      auto g = [&](double x) {
        Inner in = solve_arrival(std::exp(x));
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
      falling_root(g, std::log(std::max(1.0, lambda_before_)), 0.3, 0.0, 30.0, kOuterBudget,
                   kPassingTolerance_s);
      if (!best_ok) {
        notes_.push_back(format_text("the price search for %s found no run that meets it",
                                     point_name(p.index, windows_[p.index]).c_str()));
        ok = false;
        break;
      }
      run = std::move(best);
      ok = best_ok;
      lambda_before_ = best_before;
      lambda_after_ = best_after;
      // The last hundredths by switch points (first-order neutral at the optimum): one before
      // the point for its passing time, then one after it for the arrival (if it binds).
      const double s_k = p.s_m;
      evaluations_ += trim_switch(
          engine_, end_, run, 0.0, s_k,
          [&](const physics::SimulationResult& sim) {
            return passing_at(sim.trace, s_k).t_s - bound;
          },
          kTrimTolerance_s);
      trim_arrival(run, s_k);
    }
    if (binding_ >= 0 && ok) {
      const PartPoint& p = points_[binding_];
      const double off = std::abs(passing_at(run.sim.trace, p.s_m).t_s - bound_s_);
      if (off > options_.time_tolerance_s) {
        // Inside the window but not at the bound the unconstrained run missed: feasible, and
        // possibly not the least energy (the prices could not be set closer on this grid).
        notes_.push_back(format_text(
            "the price search for %s ended %.2f s from its %s bound: every window can hold, but "
            "the run may not be the least-energy one",
            point_name(p.index, windows_[p.index]).c_str(), off,
            bound_s_ == p.latest_s ? "latest" : "earliest"));
      }
    }
    *met = ok;
    return run;
  }

 private:
  // The price searches stop within a few tenths (the running time is ragged on a grid); the
  // switch-point trims close the rest to kTrimTolerance_s.
  static constexpr double kArrivalTolerance_s = 0.25;
  static constexpr double kPassingTolerance_s = 0.25;
  static constexpr double kTrimTolerance_s = 0.01;
  static constexpr int kInnerBudget = 40;
  static constexpr int kOuterBudget = 25;

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
  int binding_ = -1;  // index into points_ of the binding passing point
  double bound_s_ = 0.0;
  double lambda_before_ = 0.0, lambda_after_ = 0.0;
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
  // earliest time, the part arrives at that time (dwell 0 unless the run is slower) and a
  // warning says the split between the two parts was not optimised.
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
        out.summary.warnings.push_back(format_text(
            "the arrival and departure windows at %.1f m overlap: the part arrives at %.1f s; "
            "the split of time between the parts beside it is not optimised",
            arr.position_m, arrival));
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

  // Solve each part.
  bool all_met = true;
  bool all_arrive = true;
  std::vector<std::vector<PartPoint>> part_points(bounds.size());
  std::vector<int> binding_sign(bounds.size(), 0), binding_point(bounds.size(), -1);
  for (std::size_t j = 0; j < bounds.size(); ++j) {
    TimingPart& part = out.parts[j];
    const SectionEngine& engine = *engines[j];
    std::vector<PartPoint> points;
    for (int i = part.first_point + 1; i < part.last_point; ++i) {
      PartPoint p;
      p.index = i;
      p.s_m = windows[i].position_m - part.start_m;
      p.stage = std::clamp(static_cast<int>(std::lround(p.s_m / engine.options().grid.ds_m)), 0,
                           engine.grid().stage_count() - 1);
      p.earliest_s = windows[i].earliest_s - part.departure_s;
      p.latest_s = windows[i].latest_s - part.departure_s;
      points.push_back(p);
    }
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
    // Prices of the stretches, first to last: lambda_before up to the binding point.
    const int binding = solver->binding();
    for (int k = 0; k <= static_cast<int>(points.size()); ++k) {
      part.stretch_lambda_J_per_s.push_back(k <= binding ? solver->lambda_before()
                                                         : solver->lambda_after());
    }
    // The sign of the binding point's multiplier: +1 its latest bound binds, -1 its earliest.
    binding_sign[j] = binding < 0 ? 0 : solver->lambda_before() > solver->lambda_after() ? 1 : -1;
    binding_point[j] = binding < 0 ? -1 : points[binding].index;

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
    auto record = [&](int i, double t, double v, bool departure_point, bool arrival_point,
                      int sign) {
      WindowResult& r = out.windows[i];
      const TimingWindow& w = windows[i];
      r.window = w;
      r.time_s = t;
      r.speed_ms = v;
      r.met = finite(t) && t >= w.earliest_s - tol_t && t <= w.latest_s + tol_t &&
              v >= w.min_speed_ms - tol_v && v <= w.max_speed_ms + tol_v;
      r.binds.clear();
      if (finite(w.earliest_s) && std::abs(t - w.earliest_s) <= tol_t &&
          (departure_point || sign < 0)) {
        r.binds.push_back("earliest");
      }
      if (finite(w.latest_s) && std::abs(t - w.latest_s) <= tol_t && (arrival_point || sign > 0)) {
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
      record(p.index, part.departure_s + at.t_s, at.v_ms, false, false,
             p.index == binding_point[j] ? binding_sign[j] : 0);
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
