#include "dp/timing_journey.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <stdexcept>

#include "dp/golden_section.hpp"
#include "dp/regimes.hpp"
#include "dp/text_format.hpp"
#include "dp/timing_binding_pins.hpp"
#include "dp/timing_journey_feasibility.hpp"
#include "dp/timing_journey_part.hpp"
#include "dp/timing_speed_pins.hpp"
#include "physics/units.hpp"

namespace ecorail::dp {

using namespace timing;

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// The journey as the solver sees it: its parts (stop to stop), an engine over each part's
// stretch, where each part starts (at rest, or moving at the first point's lowest speed) and
// how it must end.
struct Journey {
  Journey(const std::vector<TimingWindow>& w, const TimingJourneyOptions& o)
      : windows(w),
        options(o),
        tol_t(o.time_tolerance_s),
        tol_v(units::kmh_to_ms(o.speed_tolerance_kmh)) {}
  const std::vector<TimingWindow>& windows;
  const TimingJourneyOptions& options;
  double tol_t = 0.0, tol_v = 0.0;
  std::vector<PartBounds> bounds;
  std::vector<physics::Route> envelope_routes;  // per part (see runoff_route)
  std::vector<std::unique_ptr<SectionEngine>> engines;
  std::vector<StartState> starts;
  std::vector<EndCheck> ends;

  // The passing points of part j, relative to a departure at departure_s.
  std::vector<PartPoint> points_of(std::size_t j, double departure_s) const {
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
  }
  // Part j's search between two times.
  PartOutcome solve(std::size_t j, double departure_s, double arrival_s, bool arrival_free = false,
                    bool by_labels = false) const {
    return solve_part(*engines[j], starts[j], ends[j], arrival_s - departure_s,
                      windows[bounds[j].last].earliest_s - departure_s, points_of(j, departure_s),
                      windows, options, arrival_free, by_labels);
  }
  // The energy cost of part j between two times; +inf where it misses a window or its time.
  double part_cost_J(std::size_t j, double departure_s, double arrival_s) const {
    if (!(arrival_s > departure_s)) return kInf;
    try {
      const PartOutcome o = solve(j, departure_s, arrival_s);
      return o.met && ends[j].reaches_end(o.run.sim) ? o.run.cost_J : kInf;
    } catch (const TimeRequestError&) {
      return kInf;
    }
  }
};

// Step 1: the parts, their stretches (out.routes), how each starts and ends, and its flat-out
// model for step 2. A last point that is not a stop (its speed window reaches above 0) makes
// the last part end moving, with that window as its end band (at rest is allowed when the
// window holds 0); its envelope runs on past the end (runoff_route).
std::vector<std::unique_ptr<FlatOutModel>> build_parts(const physics::Train& train,
                                                       const physics::Route& track, Journey& jy,
                                                       TimingJourneySolution& out) {
  const std::vector<TimingWindow>& windows = jy.windows;
  const int n = static_cast<int>(windows.size());
  jy.bounds = split_into_parts(windows);
  EndCheck moving_end;
  moving_end.moving = !windows.back().is_stop();
  moving_end.min_ms = std::max(0.0, windows.back().min_speed_ms);
  moving_end.max_ms = windows.back().max_speed_ms;
  moving_end.tol_ms = jy.tol_v;
  const EngineOptions& engine_options = jy.options.engine;
  std::vector<std::unique_ptr<FlatOutModel>> flat_out;
  for (const PartBounds& b : jy.bounds) {
    out.routes.push_back(
        slice_route(track, windows[b.first].position_m, windows[b.last].position_m));
    // A part that ends at a point pinning the state (before the last) ends moving at its speed.
    EndCheck pinned_end;
    const bool pinned = b.last < n - 1 && pins_the_state(windows[b.last]);
    if (pinned) {
      pinned_end.moving = true;
      pinned_end.min_ms = pinned_end.max_ms = windows[b.last].min_speed_ms;
      pinned_end.tol_ms = jy.tol_v;
    }
    const bool moving = (b.last == n - 1 && moving_end.moving) || pinned;
    const EndCheck& end = pinned ? pinned_end : moving_end;
    jy.ends.push_back(moving ? end : EndCheck{});
    jy.envelope_routes.push_back(moving ? runoff_route(train, out.routes.back(), end.max_ms,
                                                       engine_options.envelope_resolution_m)
                                        : out.routes.back());
    flat_out.push_back(std::make_unique<FlatOutModel>(train, out.routes.back(),
                                                      jy.envelope_routes.back(), engine_options));
    // A run that starts moving (the first point, or a point pinning the state) starts at the
    // point's lowest allowed speed.
    const bool moving_start = b.first == 0 || pins_the_state(windows[b.first]);
    const double v0 = moving_start ? std::max(0.0, windows[b.first].min_speed_ms) : 0.0;
    jy.starts.push_back({0.0, v0});
  }
  const double top = flat_out[0]->envelope().v_at(0.0);
  if (jy.starts[0].speed_ms > top + jy.tol_v) {
    throw WindowInfeasibleError(
        0, format_text("%s asks to start at %.2f km/h, above what the train may run there "
                       "(%.2f km/h)",
                       point_name(0, windows[0]).c_str(), units::ms_to_kmh(jy.starts[0].speed_ms),
                       units::ms_to_kmh(top)));
  }
  return flat_out;
}

// Step 2b: an engine over each part (the grids and transition tables), once the windows are
// proved feasible.
void build_engines(const physics::Train& train, Journey& jy, const TimingJourneySolution& out) {
  for (std::size_t j = 0; j < jy.bounds.size(); ++j) {
    jy.engines.push_back(std::make_unique<SectionEngine>(train, out.routes[j], jy.options.engine,
                                                         jy.envelope_routes[j]));
  }
}

// Step 3: times of the parts. Each departs at its earliest allowed time and arrives at its
// latest allowed (energy falls with running time). Where an arrival window reaches past the
// next departure's earliest time (overlapping windows, or one window at a one-point stop), the
// part arrives at that time for now (dwell 0 unless the run is slower), and the stop is marked
// for step 4. Returns the marks.
std::vector<char> plan_part_times(const Journey& jy, const std::vector<double>& earliest,
                                  double departure0, TimingJourneySolution& out) {
  const std::vector<TimingWindow>& windows = jy.windows;
  const std::vector<PartBounds>& bounds = jy.bounds;
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
  return overlaps;
}

// Step 4: the best split at a stop whose windows overlap. Its time x is both the arrival of
// the part before and the departure of the part after: an arrival before the departure would
// only take time from one of the two parts, so the stop is left at once. Each part's least
// energy falls and is convex in its running time, so the pair's energy is unimodal in x:
// golden section over the times both windows and the next part's flat-out run allow, stop by
// stop from the first (a later stop sees the departure chosen before it). The earliest time
// (the rule without this search) is evaluated too, and the search's x is taken only where it
// is cheaper.
void split_overlapping_stops(const Journey& jy, const std::vector<char>& overlaps,
                             TimingJourneySolution& out) {
  const std::vector<TimingWindow>& windows = jy.windows;
  const std::vector<PartBounds>& bounds = jy.bounds;
  constexpr double kSplitTolerance_s = 0.5;
  constexpr int kSplitSteps = 12;
  for (std::size_t j = 0; j + 1 < bounds.size(); ++j) {
    if (!overlaps[j]) continue;
    TimingPart& before = out.parts[j];
    TimingPart& after = out.parts[j + 1];
    const double lo = before.arrival_target_s;
    const double hi =
        std::min({windows[bounds[j].last].latest_s, windows[bounds[j + 1].first].latest_s,
                  after.arrival_target_s -
                      jy.engines[j + 1]->min_time_run(jy.starts[j + 1]).running_time_s});
    std::string how = "not optimised (the later bound is open)";
    if (finite(hi) && hi > lo + kSplitTolerance_s) {
      auto pair_cost = [&](double x) {
        const double first = jy.part_cost_J(j, before.departure_s, x);
        return finite(first) ? first + jy.part_cost_J(j + 1, x, after.arrival_target_s) : kInf;
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
}

// Earlier latest arrivals tried where a part's run misses a window (solve_parts).
constexpr int kEarlierArrivals = 3;

// Part j searched again with its latest arrival kEarlierArrivals times a tenth of its time
// earlier, down to its earliest arrival; the first outcome whose windows hold replaces o (the
// part's arrival target then says where it was searched), and the evaluations of every try add
// up.
PartOutcome earlier_arrivals(const Journey& jy, std::size_t j, TimingPart& part, PartOutcome o,
                             std::vector<std::string>& warnings) {
  const double latest = part.arrival_target_s, span_s = latest - part.departure_s;
  const double earliest = jy.windows[part.last_point].earliest_s;
  int evaluations = o.evaluations;
  for (int k = 1; k <= kEarlierArrivals && !o.holds; ++k) {
    const double t = latest - 0.1 * k * span_s;
    if (t < earliest) break;
    PartOutcome earlier;
    try {
      // Every arrival from the earliest to t is inside the window.
      earlier = jy.solve(j, part.departure_s, t, /*arrival_free=*/true);
    } catch (const TimeRequestError&) {
      break;
    }
    evaluations += earlier.evaluations;
    if (earlier.holds) {
      o = std::move(earlier);
      part.arrival_target_s = t;
      warnings.push_back(format_text(
          "part %zu: its windows are met with the latest arrival searched at %.1f s instead of "
          "%.1f s (feasible, possibly not the least energy)",
          j + 1, t, latest));
    }
  }
  o.evaluations = evaluations;
  return o;
}

// Step 5: each part solved; its run becomes a section of out.journey. binding_sign and
// bind_slack (per timing point) say which bound binds and by how much a binding point may pass
// inside it. Returns whether every part's search met its windows; *all_arrive whether every
// run reaches its end.
bool solve_parts(const Journey& jy, TimingJourneySolution& out,
                 std::vector<std::vector<PartPoint>>& part_points, std::vector<int>& binding_sign,
                 std::vector<double>& bind_slack, bool* all_arrive) {
  const std::vector<TimingWindow>& windows = jy.windows;
  bool all_met = true;
  *all_arrive = true;
  for (std::size_t j = 0; j < jy.bounds.size(); ++j) {
    TimingPart& part = out.parts[j];
    const SectionEngine& engine = *jy.engines[j];
    PartOutcome o;
    try {
      o = jy.solve(j, part.departure_s, part.arrival_target_s);
    } catch (const LongTimeError& e) {
      // Slower than the engine solves reliably: arrive as late as it can, if that is allowed.
      const double latest_ok = part.departure_s + e.maximum_s() - 0.5;
      if (latest_ok < windows[part.last_point].earliest_s) throw;
      part.arrival_target_s = latest_ok;
      out.summary.warnings.push_back(format_text(
          "part %zu: its latest arrival is beyond the slowest run the grid solves reliably; no "
          "arrival later than %.1f s is searched",
          j + 1, latest_ok));
      o = jy.solve(j, part.departure_s, latest_ok, /*arrival_free=*/true);
    }
    // Where the price search misses a window, the label search (dp/timing_label_search.hpp),
    // whose state carries what the windows need, is kept when every window of the part holds on
    // its run; where a part is run by it, its run is re-solved between the states it pins where
    // it binds a time (dp/timing_binding_pins.hpp, after every part is solved).
    if (!o.holds && jy.options.label_search_last_resort) {
      PartOutcome labelled = jy.solve(j, part.departure_s, part.arrival_target_s,
                                      /*arrival_free=*/false, /*by_labels=*/true);
      labelled.evaluations += o.evaluations;
      if (labelled.holds) {
        o = std::move(labelled);
        part.by_label_search = true;
      } else {
        o.evaluations = labelled.evaluations;
        for (const auto& note : labelled.notes) o.notes.push_back(note);
      }
    }
    // Else an earlier latest arrival, which binds, can meet every window (an earliest bound
    // that holds the run back just before a latest one that needs it fast: on a 3 km part
    // missed with the arrival searched at 500.8 s, met at 450.7 s). So earlier arrivals are
    // tried, a tenth of the part's time apart, and the first run that meets the part's windows
    // is kept: feasible, and reported as such (the latest arrival is tried first, as energy
    // falls with running time). They come after the label search: each is a search of the part
    // with a free arrival (on hb2, tests/cli/held_back_twice.sh, three of them took 107 s of
    // the journey's 318 s and met nothing; with the label search first, its part is run in 40 s
    // instead of 136 s).
    if (!o.holds) o = earlier_arrivals(jy, j, part, std::move(o), out.summary.warnings);
    part.evaluations = o.evaluations;
    part_points[j] = o.points;
    *all_arrive = *all_arrive && jy.ends[j].reaches_end(o.run.sim);
    all_met = all_met && o.met;
    for (const auto& note : o.notes) out.summary.warnings.push_back(note);
    part.stretch_lambda_J_per_s = o.stretch_lambda_J_per_s;
    for (std::size_t k = 0; k < o.points.size(); ++k) {
      binding_sign[o.points[k].index] = o.binding_sign[k];
      bind_slack[o.points[k].index] = o.binding_slack_s;
    }
    LambdaRun run = std::move(o.run);
    if (jy.ends[j].moving && jy.ends[j].reaches_end(run.sim) && run.sim.end_speed_ms > 0.0) {
      // The simulator reports a moving end's stop error as where full braking would bring it
      // to rest; this run's end is the end point itself, which it reaches (it does not stop).
      run.sim.end_position_m -= run.sim.stop_error_m;
      run.sim.stop_error_m = 0.0;
    }
    JourneySection sec;
    sec.run = std::move(run);
    sec.regimes = regime_spans(sec.run.sim.trace);
    sec.marginal_J_per_s = NAN;
    sec.min_time_s = engine.min_time_run(jy.starts[j]).running_time_s;
    out.journey.sections.push_back(std::move(sec));
  }
  for (std::size_t j = 0; j + 1 < jy.bounds.size(); ++j) {
    out.journey.sections[j].dwell_after_s =
        out.parts[j + 1].departure_s -
        (out.parts[j].departure_s + out.journey.sections[j].run.sim.running_time_s);
  }
  return all_met;
}

// Step 6: every window on the re-simulation (out.windows); whether all hold.
bool record_windows(const Journey& jy, const std::vector<std::vector<PartPoint>>& part_points,
                    const std::vector<int>& binding_sign, const std::vector<double>& bind_slack,
                    TimingJourneySolution& out) {
  const std::vector<TimingWindow>& windows = jy.windows;
  const std::vector<PartBounds>& bounds = jy.bounds;
  const std::vector<StartState>& starts = jy.starts;
  const double tol_t = jy.tol_t, tol_v = jy.tol_v;
  out.windows.resize(windows.size());
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
      // A window of zero width is met exactly (kZeroWidthTime_s, kZeroWidthSpeed_ms).
      const double tt = w.earliest_s == w.latest_s ? std::min(tol_t, kZeroWidthTime_s) : tol_t;
      const double tv =
          w.min_speed_ms == w.max_speed_ms ? std::min(tol_v, kZeroWidthSpeed_ms) : tol_v;
      r.met = finite(t) && t >= w.earliest_s - tt && t <= w.latest_s + tt &&
              v >= w.min_speed_ms - tv && v <= w.max_speed_ms + tv;
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
    // (A point pinning the state ends the part before and starts this one: it is checked on
    // the arrival of the part before, which this departure would overwrite with its bounds.)
    if (!(j > 0 && out.parts[j - 1].last_point == part.first_point &&
          pins_the_state(windows[part.first_point]))) {
      record(part.first_point, part.departure_s, starts[j].speed_ms, true, false, 0.0);
    }
    for (const PartPoint& p : part_points[j]) {
      const Passing at = passing_at(sim.trace, p.s_m);
      record(p.index, part.departure_s + at.t_s, at.v_ms, false, false, binding_sign[p.index],
             bind_slack[p.index]);
    }
    const bool arrives = jy.ends[j].reaches_end(sim);
    record(part.last_point, arrives ? part.departure_s + sim.running_time_s : NAN,
           arrives ? sim.end_speed_ms : NAN, false, true, 0.0);
  }

  return windows_met;
}

// Step 7: totals and the summary, as a journey's.
void fill_totals(const Journey& jy, bool all_met, bool all_arrive, const std::string& id,
                 Clock::time_point t0, TimingJourneySolution& out) {
  const std::vector<TimingWindow>& windows = jy.windows;
  const TimingJourneyOptions& options = jy.options;
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
  // The journey's verdict adds the parts' own searches: a window met by re-simulation after a
  // part's search stopped short is not a converged journey.
  jr.summary.termination = s.termination == Termination::CONVERGENCE && !all_met
                               ? Termination::NO_CONVERGENCE
                               : s.termination;
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
}

}  // namespace

namespace {

double first_departure_s(const std::vector<TimingWindow>& windows) {
  return finite(windows[0].earliest_s) ? windows[0].earliest_s : 0.0;
}

// Steps 1-2: the parts and their flat-out models, then the earliest time each point can be
// reached from the departure at departure0_s (WindowInfeasibleError for a window no run meets).
std::vector<double> plan_parts(const physics::Train& train, const physics::Route& track,
                               Journey& jy, double departure0_s, TimingJourneySolution& out) {
  const std::vector<std::unique_ptr<FlatOutModel>> flat_out = build_parts(train, track, jy, out);
  return earliest_times(jy.windows, jy.bounds, flat_out, jy.starts, departure0_s, jy.tol_t,
                        jy.tol_v);
}

// The journey as its windows ask (steps 1-7).
TimingJourneySolution solve_windows(const physics::Train& train, const physics::Route& track,
                                    const std::vector<TimingWindow>& windows,
                                    const TimingJourneyOptions& options, const std::string& id) {
  const auto t0 = Clock::now();
  check_structure(windows, track.length_m());
  Journey jy(windows, options);
  TimingJourneySolution out;
  const double departure0 = first_departure_s(windows);
  const std::vector<double> earliest = plan_parts(train, track, jy, departure0, out);  // 1-2
  build_engines(train, jy, out);
  const std::vector<char> overlaps = plan_part_times(jy, earliest, departure0, out);  // step 3
  split_overlapping_stops(jy, overlaps, out);                                         // step 4
  const std::size_t n = windows.size();
  std::vector<std::vector<PartPoint>> part_points(jy.bounds.size());
  std::vector<int> binding_sign(n, 0);
  std::vector<double> bind_slack(n, 0.0);
  bool all_arrive = true;
  const bool all_met =
      solve_parts(jy, out, part_points, binding_sign, bind_slack, &all_arrive);  // step 5
  out.windows_met =
      record_windows(jy, part_points, binding_sign, bind_slack, out) && all_arrive;  // step 6
  fill_totals(jy, all_met, all_arrive, id, t0, out);                                 // step 7
  return out;
}

// Whether the journey is refused before any search (steps 1-2: its layout, and flat-out runs
// that cannot meet a window); cheap, no grid is built.
bool refused_before_search(const physics::Train& train, const physics::Route& track,
                           const std::vector<TimingWindow>& windows,
                           const TimingJourneyOptions& options) {
  try {
    check_structure(windows, track.length_m());
    Journey jy(windows, options);
    TimingJourneySolution out;
    plan_parts(train, track, jy, first_departure_s(windows), out);
  } catch (const TimeRequestError&) {  // a window no run meets (WindowInfeasibleError)
    return true;
  }
  return false;
}

}  // namespace

TimingJourneySolution solve_timing_journey(const physics::Train& train, const physics::Route& track,
                                           const std::vector<TimingWindow>& windows,
                                           const TimingJourneyOptions& options,
                                           const std::string& id) {
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument(why);
  const auto solve = [&](const std::vector<TimingWindow>& w) {
    return solve_windows(train, track, w, options, id);
  };
  // The times of points asking for one speed are searched on a grid no finer than 10 m x
  // 0.5 km/h (dp/timing_speed_pins.hpp); the journey they give is solved on the asked grid.
  TimingJourneyOptions trial = options;
  trial.engine.grid.ds_m = std::max(options.engine.grid.ds_m, 10.0);
  trial.engine.grid.dv_kmh = std::max(options.engine.grid.dv_kmh, 0.5);
  trial.engine.grid.substep_m = std::max(options.engine.grid.substep_m, 5.0);
  trial.descend_on_switches = false;
  trial.label_search_last_resort = false;
  const auto solve_trial = [&](const std::vector<TimingWindow>& w) {
    return solve_windows(train, track, w, trial, id);
  };
  const auto refused = [&](const std::vector<TimingWindow>& w) {
    return refused_before_search(train, track, w, trial);
  };
  TimingJourneySolution pinned =
      with_speeds_pinned(windows, solve(windows), solve, solve_trial, refused);
  // The label search's parts re-solved between pinned states (dp/timing_binding_pins.hpp): its
  // trials on the asked grid, without the label search (a trial it would rescue is a heuristic's).
  TimingJourneyOptions unlabelled = options;
  unlabelled.label_search_last_resort = false;
  const auto solve_unlabelled = [&](const std::vector<TimingWindow>& w) {
    return solve_windows(train, track, w, unlabelled, id);
  };
  return with_label_runs_pinned(windows, std::move(pinned), solve, solve_unlabelled,
                                options.engine.threads);
}

}  // namespace ecorail::dp
