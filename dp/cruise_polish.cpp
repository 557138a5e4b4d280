#include "dp/cruise_polish.hpp"

#include "dp/golden_section.hpp"
#include "dp/lambda_bracket.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>
#include <vector>

#include "dp/time_target.hpp"

namespace ecorail::dp {

bool CruisePolishOptions::IsValid(std::string* error) const {
  auto fail = [&](const char* what) {
    if (error != nullptr) *error = what;
    return false;
  };
  if (!(std::isfinite(min_cruise_m) && min_cruise_m >= 0.0)) {
    return fail("cruise polish min_cruise_m must be finite and >= 0");
  }
  if (!(std::isfinite(short_phase_m) && short_phase_m >= 0.0)) {
    return fail("cruise polish short_phase_m must be finite and >= 0");
  }
  if (!(std::isfinite(search_half_width_m) && search_half_width_m > 0.0)) {
    return fail("cruise polish search_half_width_m must be finite and > 0");
  }
  if (!(std::isfinite(search_tolerance_m) && search_tolerance_m > 0.0)) {
    return fail("cruise polish search_tolerance_m must be finite and > 0");
  }
  if (!(std::isfinite(search_step_m) && search_step_m > 0.0 && search_step_m <= 10.0)) {
    return fail("cruise polish search_step_m must be in (0, 10] m");
  }
  if (!(std::isfinite(price_search_step_m) && price_search_step_m > 0.0 &&
        price_search_step_m <= 50.0)) {
    return fail("cruise polish price_search_step_m must be in (0, 50] m");
  }
  if (!(std::isfinite(price_first_step_m) && price_first_step_m > 0.0)) {
    return fail("cruise polish price_first_step_m must be finite and > 0");
  }
  if (price_max_simulations < 1) return fail("cruise polish price_max_simulations must be >= 1");
  if (max_simulations < 1) return fail("cruise polish max_simulations must be >= 1");
  if (first_scan_points < 0) return fail("cruise polish first_scan_points must be >= 0");
  if (!(std::isfinite(price_time_tolerance_s) && price_time_tolerance_s > 0.0)) {
    return fail("cruise polish price_time_tolerance_s must be finite and > 0");
  }
  return true;
}

namespace {

using physics::Control;
using physics::ControlProgram;

constexpr double kInf = std::numeric_limits<double>::infinity();
// The hold-speed solve: at most this many re-simulations per coasting point.
constexpr int kMaxTimeSolves = 30;
// The price search: its first step in log lambda, and at most this many prices.
constexpr double kPriceBracketStep = 0.05;
constexpr int kMaxPrices = 12;
// The narrowest bracket of a hold start worth another re-simulation.
constexpr double kMinBracket_m = 1e-9;

// A run of short phases starts at a limit's rise when it starts this close to it (two steps of
// the default 5 m grid, whose switch points fall on its stages).
constexpr double kRiseSlack_m = 10.0;
// A hold this long is polished on its own, short as it is.
constexpr double kShortestCruise_m = 20.0;

// The polished shape: one traction phase ending at the hold (index hold), the cruise, and the
// phase that leaves it (index exit).
struct CruiseShape {
  ControlProgram program;
  std::size_t hold = 0, exit = 0;
  int dropped = 0;
  // The cruise starts with the grid's staircase down to a lower limit, made a hold and a coast.
  bool steps_down = false;
};

// The speed of a run at s_m (linear between trace points).
double speed_at(const physics::SimulationResult& sim, double s_m) {
  const auto& tr = sim.trace;
  if (tr.empty()) return 0.0;
  std::size_t lo = 0, hi = tr.size() - 1;
  if (s_m <= tr[lo].s_m) return tr[lo].v_ms;
  if (s_m >= tr[hi].s_m) return tr[hi].v_ms;
  while (hi - lo > 1) {
    const std::size_t mid = (lo + hi) / 2;
    (tr[mid].s_m <= s_m ? lo : hi) = mid;
  }
  const double w = (s_m - tr[lo].s_m) / std::max(1e-12, tr[hi].s_m - tr[lo].s_m);
  return tr[lo].v_ms + w * (tr[hi].v_ms - tr[lo].v_ms);
}

// Where the route's limit steps down (below the limit before it) and up, in track order.
struct LimitSteps {
  std::vector<double> drops_m, rises_m;
  // The limit just before each rise (parallel to rises_m).
  std::vector<double> below_rise_ms;
  double length_m = 0.0;
  // Where the limit rises again after s_m (the route's end when it does not).
  double rise_after_m(double s_m) const {
    for (double r : rises_m) {
      if (r > s_m) return r;
    }
    return length_m;
  }
};

LimitSteps limit_steps(const physics::Route& route) {
  LimitSteps steps;
  steps.length_m = route.length_m();
  const auto& segs = route.segments();
  for (std::size_t i = 1; i < segs.size(); ++i) {
    if (segs[i].speed_limit_ms < segs[i - 1].speed_limit_ms - 1e-9)
      steps.drops_m.push_back(segs[i].start_m);
    if (segs[i].speed_limit_ms > segs[i - 1].speed_limit_ms + 1e-9) {
      steps.rises_m.push_back(segs[i].start_m);
      steps.below_rise_ms.push_back(segs[i - 1].speed_limit_ms);
    }
  }
  return steps;
}

// Drops the short phases inside the cruise (first hold to last hold). nullopt when the program
// has no cruise to polish. sim: the program's run; steps: where the route's limit steps down
// and up.
std::optional<CruiseShape> cruise_shape(const ControlProgram& program,
                                        const physics::SimulationResult& sim, double length_m,
                                        const LimitSteps& steps,
                                        const CruisePolishOptions& options) {
  const std::vector<double>& drops_m = steps.drops_m;
  const std::size_t n = program.size();
  std::size_t first = n, last = n;
  for (std::size_t k = 0; k < n; ++k) {
    if (program[k].control != Control::Hold) continue;
    if (first == n) first = k;
    last = k;
  }
  auto end_of = [&](std::size_t k) { return k + 1 < n ? program[k + 1].from_m : length_m; };
  auto is_short_phase = [&](std::size_t k) {
    return end_of(k) - program[k].from_m < options.short_phase_m;
  };
  // The cruise's first long hold: the short holds and traction blips before it (the grid's
  // staircase up to the cruise speed) are traction.
  while (first < n && (program[first].control != Control::Hold || is_short_phase(first))) {
    ++first;
  }
  // No long hold: the grid may step down to a lower limit and ride it at full traction (capped
  // by the limit) instead of holding it. That ride is the cruise, when a staircase leads into
  // it (checked below: such a cruise is polished only when it steps down).
  bool rides_limit = false;
  if (first == n) {
    for (std::size_t k = 2; k < n; ++k) {
      if (program[k].control != Control::MaxTraction || is_short_phase(k) ||
          !is_short_phase(k - 1)) {
        continue;
      }
      for (double d : drops_m) {
        if (d >= program[k].from_m - options.short_phase_m &&
            d <= program[k].from_m + options.short_phase_m) {
          rides_limit = true;
        }
      }
      if (rides_limit) {
        first = k;
        if (last == n || last < first) last = first;
        break;
      }
    }
  }
  // No long hold nor a ride of a lower limit: the grid may break its cruise into short holds
  // between short coasts and blips of traction (A6 -> A7 at 140 s: holds of 1 to 125 m from
  // 87 m to 370 m, 0.018 % above one hold polished; A8 -> A9 at 120 s: 2 to 28 m from 196 m to
  // 368 m), or hold briefly where the optimum holds not at all (A1 -> A2 at 89 s: 72 m, 0.041 %
  // above traction and coast). A run of short phases that starts with a hold and spans at least
  // short_phase_m, or holds somewhere for at least kShortestCruise_m, is that cruise.
  if (first == n) {
    for (std::size_t k = 1; k < n; ++k) {
      if (program[k].control != Control::Hold) continue;
      std::size_t j = k;
      double longest_hold_m = 0.0;
      for (; j < n && is_short_phase(j); ++j) {
        if (program[j].control == Control::Hold) {
          longest_hold_m = std::max(longest_hold_m, end_of(j) - program[j].from_m);
        }
      }
      if (j < n && (program[j].from_m - program[k].from_m >= options.short_phase_m ||
                    longest_hold_m >= kShortestCruise_m)) {
        first = k;
        break;
      }
      k = j;
    }
  }
  if (first == n || first == 0 || first > last) return std::nullopt;
  if (last + 1 >= n) return std::nullopt;  // a cruise into the stop: nothing leaves it
  // Whether a lower limit begins within [from_m, to_m + short_phase_m].
  auto drop_near = [&](double from_m, double to_m) {
    for (double d : drops_m) {
      if (d > from_m && d <= to_m + options.short_phase_m) return true;
    }
    return false;
  };
  // On a metro section the grid reaches its cruise speed, then steps down in short coasts and
  // holds (a blip of traction or braking among them) to a lower limit and rides it. That
  // staircase, from the end of the last long traction phase, is a hold of free speed and a
  // coast, which the search and the ties place: the cruise then starts there.
  std::size_t start = first;
  {
    std::size_t s = first;
    while (s > 1 && is_short_phase(s - 1)) --s;
    double coast_m = 0.0, traction_m = 0.0;
    for (std::size_t k = s; k < first; ++k) {
      const double m = end_of(k) - program[k].from_m;
      if (program[k].control == Control::Coast) coast_m += m;
      if (program[k].control == Control::MaxTraction) traction_m += m;
    }
    if (s < first && program[s - 1].control == Control::MaxTraction && coast_m > traction_m &&
        drop_near(program[s].from_m, program[first].from_m)) {
      start = s;
    }
  }
  const double cruise_m = program[last + 1].from_m - program[start].from_m;
  // A step down to a lower limit is polished whatever the cruise's length: there the grid's
  // staircase costs the most (0.26 % on A5 -> A6 at 150 s).
  if (start == first && (rides_limit || cruise_m < options.min_cruise_m)) return std::nullopt;
  CruiseShape shape;
  for (std::size_t k = 0; k < start; ++k) {
    const bool short_phase = k > 0 && is_short_phase(k);
    if (short_phase) {
      ++shape.dropped;
      continue;
    }
    if (!shape.program.empty() && shape.program.back().control == program[k].control) continue;
    shape.program.push_back(program[k]);
  }
  if (shape.program.back().control != Control::MaxTraction) return std::nullopt;
  shape.program.push_back({program[start].from_m, Control::Hold});
  shape.hold = shape.program.size() - 1;
  shape.steps_down = start < first;
  auto is_short = [&](std::size_t k) { return k <= last && is_short_phase(k); };
  for (std::size_t k = start; k < n; ++k) {
    if (k == start && start == first) continue;  // the hold pushed above
    if (!is_short(k)) {
      if (shape.program.back().control != program[k].control) shape.program.push_back(program[k]);
      continue;
    }
    // A run of short phases (a staircase: short coasts and holds descending into a lower
    // limit, or blips of traction inside a cruise) becomes one phase of the control it spends
    // the most distance in; a run of one is dropped and the phase before it goes on.
    std::size_t j = k;
    while (j < n && is_short(j)) ++j;
    // A run that starts where the limit rises begins with the acceleration to the higher
    // limit: its phases up to the last traction are that traction, and the rest (the grid's
    // staircase to the hold and coast after it) is merged on its own. Merged whole, its coasts
    // would outweigh the traction and the run would coast from the rise. Only traction that
    // ends above the lower limit is that acceleration: a blip that ends below it (A2 -> A3 at
    // 120 s: 5 m from 53.8 to 54.9 km/h, 5 m before the rise from 55 km/h) is part of the
    // cruise, and taken as an acceleration it made the cruise a coast (0.011 % above the
    // independent search).
    std::size_t last_traction = n;
    for (std::size_t i = k; i < j; ++i) {
      if (program[i].control == Control::MaxTraction) last_traction = i;
    }
    bool at_rise = false;
    if (last_traction < n) {
      const double traction_end_ms = speed_at(sim, end_of(last_traction));
      for (std::size_t r = 0; r < steps.rises_m.size(); ++r) {
        at_rise = at_rise || (std::abs(program[k].from_m - steps.rises_m[r]) <= kRiseSlack_m &&
                              traction_end_ms > steps.below_rise_ms[r]);
      }
    }
    if (at_rise && last_traction + 1 < j) {
      if (shape.program.back().control != Control::MaxTraction) {
        shape.program.push_back({program[k].from_m, Control::MaxTraction});
      }
      shape.dropped += static_cast<int>(last_traction - k);
      k = last_traction + 1;
    }
    double length_by_control[physics::kControlCount] = {};
    for (std::size_t i = k; i < j; ++i) {
      length_by_control[static_cast<int>(program[i].control)] += end_of(i) - program[i].from_m;
    }
    shape.dropped += static_cast<int>(j - k);
    // The staircase from the cruise's start down to a lower limit is one coast, to be tied.
    if (k == start && start < first) {
      shape.program.push_back({program[k].from_m, Control::Coast});
      --shape.dropped;
    } else if (j - k >= 2) {
      int dominant = 0;
      for (int c = 1; c < physics::kControlCount; ++c) {
        if (length_by_control[c] > length_by_control[dominant]) dominant = c;
      }
      const Control control = static_cast<Control>(dominant);
      if (shape.program.back().control != control) {
        shape.program.push_back({program[k].from_m, control});
        --shape.dropped;
      }
    }
    k = j - 1;
  }
  shape.exit = shape.program.size();
  for (std::size_t k = shape.program.size(); k-- > shape.hold;) {
    if (shape.program[k].control == Control::Hold) {
      shape.exit = k + 1;
      break;
    }
  }
  if (shape.exit >= shape.program.size()) return std::nullopt;
  return shape;
}

struct Candidate {
  ControlProgram program;
  physics::SimulationResult sim;
  double cost_J = kInf;
};

class Polisher {
 public:
  Polisher(const SectionEngine& engine, const StartState& start, double target_s,
           double tolerance_s, const PolishEnd& end, CruisePolishReport& report)
      : engine_(engine),
        start_(start),
        target_s_(target_s),
        tolerance_s_(tolerance_s),
        end_(end),
        report_(report) {}

  // Whether a run ends as asked.
  bool ends(const physics::SimulationResult& sim) const {
    return end_.moving ? end_.reaches(sim) : run_arrives(sim);
  }

  // The run of program at step_m, resumed from `earlier` (a run at that step, or empty). For a
  // run that ends at a pinned speed, the final brake's onset is solved first (the end speed
  // rises as braking starts later): only the tail after the onset is integrated again.
  physics::SimulationResult simulate(ControlProgram& program, double step_m,
                                     const physics::SimulationResult& earlier) {
    physics::SimulationResult sim = engine_.resimulate(program, start_, step_m, earlier);
    ++report_.simulations;
    if (!end_.moving || !std::isfinite(end_.pinned_speed_ms) ||
        program.back().control != Control::MaxBrake || program.size() < 2) {
      return sim;
    }
    const double target = end_.pinned_speed_ms;
    auto miss = [&](const physics::SimulationResult& r) {
      return end_.reaches(r) || r.end_speed_ms > target ? target - r.end_speed_ms : target;
    };
    if (std::abs(miss(sim)) <= 0.5 * end_.speed_tolerance_ms) return sim;
    const std::size_t k = program.size() - 1;
    const double lo = program[k - 1].from_m + 1e-6, hi = engine_.route().length_m() - 1e-6;
    if (!(lo < hi)) return sim;
    physics::SimulationResult trial;
    bool met = false;
    auto f = [&](double x) {
      program[k].from_m = x;
      trial = engine_.resimulate(program, start_, step_m, sim);
      ++report_.simulations;
      const double m = miss(trial);
      met = std::abs(m) <= 0.5 * end_.speed_tolerance_ms;
      return m;
    };
    const double f_lo = f(lo);
    if (met) return trial;
    const double f_hi = f(hi);
    if (met) return trial;
    if (!(f_lo >= 0.0 && f_hi <= 0.0)) return sim;
    LambdaBracket root(f, lo, f_lo, hi, f_hi, kMaxTimeSolves);
    root.narrow([&] { return met; }, kMinBracket_m);
    return trial;
  }

  // The run of program (hold speed free, everything else fixed) that meets the time at step_m:
  // the end of the traction phase before the hold is solved by a safeguarded secant on the
  // re-simulated time (which falls as the hold starts later, at a higher speed).
  Candidate meet_time(ControlProgram program, std::size_t hold, double step_m) {
    const double lo_limit = program[hold - 1].from_m + 1e-6;
    const double hi_limit =
        (hold + 1 < program.size() ? program[hold + 1].from_m : engine_.route().length_m()) - 1e-6;
    // Consecutive runs differ from the hold's start on (the earlier of the two starts), so
    // each resumes, bit for bit, from the run before it. The run is kept there alone: the
    // candidate returned is always the last one run, and takes its run from recent_ then (a
    // copy per run, a million trace points at the fine step, cost the GPOPS-II case of
    // docs/ttobench.md 88 MiB of its peak memory and about 6 % of its wall time).
    auto f_at = [&](double x, Candidate* out) {
      program[hold].from_m = x;
      recent_ = simulate(program, step_m, recent_);
      out->program = program;
      out->cost_J = engine_.energy_cost_J(recent_);
      // A run that does not arrive counts as too slow: the hold must start later.
      return ends(recent_) ? recent_.running_time_s - target_s_ : kInf;
    };
    auto last_run = [&](Candidate c) {
      c.sim = recent_;
      return c;
    };
    Candidate best;
    double x0 = std::min(std::max(program[hold].from_m, lo_limit), hi_limit);
    double f0 = f_at(x0, &best);
    if (std::abs(f0) <= tolerance_s_) return last_run(std::move(best));
    // Bracket by doubling steps from x0 (f falls with x).
    double lo = lo_limit, hi = hi_limit, f_lo = kInf, f_hi = -kInf;
    double step = 8.0;
    Candidate trial;
    if (f0 > 0.0) {
      lo = x0, f_lo = f0;
      for (double x = x0 + step;; step *= 2.0, x = x0 + step) {
        x = std::min(x, hi_limit);
        const double f = f_at(x, &trial);
        if (std::abs(f) <= tolerance_s_) return last_run(std::move(trial));
        if (f < 0.0) {
          hi = x, f_hi = f;
          break;
        }
        lo = x, f_lo = f;
        if (x >= hi_limit) return {};
      }
    } else {
      hi = x0, f_hi = f0;
      for (double x = x0 - step;; step *= 2.0, x = x0 - step) {
        x = std::max(x, lo_limit);
        const double f = f_at(x, &trial);
        if (std::abs(f) <= tolerance_s_) return last_run(std::move(trial));
        if (f > 0.0) {
          lo = x, f_lo = f;
          break;
        }
        hi = x, f_hi = f;
        if (x <= lo_limit) return {};
      }
    }
    // Narrow [lo, hi] with the engine's one root search (LambdaBracket: Illinois regula falsi,
    // bisection while an end does not arrive) until the time is met.
    bool met = false;
    LambdaBracket root(
        [&](double x) {
          const double f = f_at(x, &trial);
          met = std::abs(f) <= tolerance_s_;
          return f;
        },
        lo, f_lo, hi, f_hi, kMaxTimeSolves);
    root.narrow([&] { return met; }, kMinBracket_m);
    if (met) return last_run(std::move(trial));
    return {};
  }

 private:
  const SectionEngine& engine_;
  StartState start_;
  double target_s_, tolerance_s_;
  const PolishEnd& end_;
  CruisePolishReport& report_;
  physics::SimulationResult recent_;  // the last run (empty: none yet)
};

}  // namespace

namespace {

// A hold the train cannot keep: on a climb its traction saturates and the speed falls, and
// after the climb the hold keeps the lower speed. The optimum runs full traction through the
// climb (from a point the search places, before it or on it) and then accelerates back to a
// cruise speed of its own: the hold's saturated stretch of the grid's run (at least min_m of
// full traction under Hold) becomes a traction phase followed by a hold, both switches
// searched. The program runs the same as before until the search moves them.
void split_saturated_holds(CruiseShape& shape, const physics::SimulationResult& sim,
                           double length_m, double min_m) {
  ControlProgram& p = shape.program;
  for (std::size_t k = shape.hold; k < shape.exit && k < p.size(); ++k) {
    if (p[k].control != Control::Hold) continue;
    const double a = p[k].from_m, b = k + 1 < p.size() ? p[k + 1].from_m : length_m;
    double sat_from = -1.0, sat_to = -1.0;
    for (const physics::TracePoint& t : sim.trace) {
      if (t.s_m >= b) break;  // (the trace runs forward)
      if (t.s_m <= a) continue;
      if (t.regime == physics::Regime::FullTraction) {
        if (sat_from < 0.0) sat_from = t.s_m;
        sat_to = t.s_m;
      } else if (sat_from >= 0.0) {
        if (sat_to - sat_from >= min_m) break;
        sat_from = sat_to = -1.0;  // a blip: not a climb
      }
    }
    if (!(sat_from >= 0.0 && sat_to - sat_from >= min_m && sat_to < b - 1.0)) continue;
    p.insert(p.begin() + static_cast<std::ptrdiff_t>(k) + 1,
             {{sat_from, Control::MaxTraction}, {sat_to, Control::Hold}});
    shape.exit += 2;
    k += 2;  // the hold after the climb may saturate again further on
  }
}

// A coast into a lower limit, tied: its start is solved so that the run reaches the limit's
// speed exactly at the limit's start (Howlett and Pudney's condition for a step down of the
// limit: hold, then coast to meet the lower limit where it begins). coast is its index in the
// program, limit_m where the lower limit begins.
struct CoastTie {
  std::size_t coast = 0;
  double limit_m = 0.0;
  double limit_ms = 0.0;
  // The hold put back after the limit's rise (0 when none), and the rise: a hold that starts
  // before the rise holds the lower limit, the run riding it, so it is searched after the rise.
  std::size_t hold_after_rise = 0;
  double rise_m = 0.0;
  // A coast that runs on past the limit's start below its speed (it neither holds nor rides
  // the lower limit): only its start is solved, and the phase after it stays free.
  bool passes = false;
};

// Every coast of the cruise that runs, through coasts and holds only, into a lower limit
// becomes one coast tied to that limit's start: the phases between (the grid's staircase of
// short coasts and holds above the lower limit) are dropped, and at the limit's start the run
// holds the limit or, when the grid accelerates from it before the limit rises again, rides it
// at full traction (the same run at the limit). Returns the ties in track order.
std::vector<CoastTie> tie_coasts_to_limits(CruiseShape& shape, const physics::Route& route,
                                           const LimitSteps& steps) {
  std::vector<CoastTie> ties;
  const std::vector<double>& drops = steps.drops_m;
  ControlProgram& p = shape.program;
  const double length_m = route.length_m();
  for (std::size_t k = shape.hold + 1; k < p.size(); ++k) {
    if (p[k].control != Control::Coast) continue;
    double limit_m = -1.0;
    for (double d : drops) {
      if (d > p[k].from_m + 1.0 && d < length_m - 1.0) {
        limit_m = d;
        break;
      }
    }
    if (limit_m < 0.0) continue;
    std::size_t m = k;  // the phase in force at the limit's start
    while (m + 1 < p.size() && p[m + 1].from_m <= limit_m) ++m;
    // A coast that runs past the limit's start (the grid's hold begins a step or two after it)
    // is tied as well when the next phase begins before the limit rises again.
    if (m == k && m + 1 < p.size() && p[m + 1].from_m < steps.rise_after_m(limit_m)) ++m;
    if (m == k || m + 1 >= p.size()) continue;
    bool staircase = true;
    for (std::size_t j = k + 1; j < m; ++j) {
      staircase = staircase && (p[j].control == Control::Coast || p[j].control == Control::Hold);
    }
    if (!staircase || p[m].control == Control::Coast || p[m].control == Control::MaxBrake) continue;
    Control at_limit = p[m].control;
    std::size_t after = m + 1;
    const double rise_m = steps.rise_after_m(limit_m);
    // A hold at the limit that lasts past the limit's rise (the grid's acceleration there was
    // short, and dropped) rides the limit at full traction and holds again after the rise,
    // where the search puts it.
    bool hold_after_rise = false;
    if (at_limit == Control::Hold && after < p.size() && p[after].control == Control::MaxTraction &&
        p[after].from_m <= rise_m) {
      at_limit = Control::MaxTraction;
      ++after;
      // Straight from that acceleration into a coast (the grid's hold after the rise was
      // short, and merged): the hold is put back, and the search sets its speed (a hold that
      // starts where the coast does is the run without it).
      hold_after_rise = after < p.size() && p[after].control == Control::Coast &&
                        rise_m < length_m - 2.0 && p[after].from_m > rise_m + 2.0;
    } else if (at_limit == Control::Hold && rise_m < length_m - 2.0 &&
               (after >= p.size() || p[after].from_m > rise_m + 2.0)) {
      at_limit = Control::MaxTraction;
      hold_after_rise = true;
    } else if (at_limit == Control::MaxTraction && after < p.size() &&
               p[after].control == Control::Coast && rise_m < length_m - 2.0 &&
               p[after].from_m > rise_m + 2.0) {
      // The grid rode the limit at full traction, through its rise, into the coast (its short
      // hold after the rise dropped): the hold is put back the same way.
      hold_after_rise = true;
    }
    if (after >= p.size() && at_limit == Control::MaxTraction && !hold_after_rise) continue;
    ControlProgram q(p.begin(), p.begin() + static_cast<std::ptrdiff_t>(k) + 1);
    q.push_back({limit_m, at_limit});
    if (hold_after_rise) q.push_back({rise_m + 1.0, Control::Hold});
    q.insert(q.end(), p.begin() + static_cast<std::ptrdiff_t>(after), p.end());
    shape.dropped += std::max(0, static_cast<int>(p.size()) - static_cast<int>(q.size()));
    p = std::move(q);
    ties.push_back(
        {k, limit_m, route.speed_limit_ms(limit_m + 1e-6), hold_after_rise ? k + 2 : 0, rise_m});
  }
  shape.exit = p.size();
  for (std::size_t k = p.size(); k-- > shape.hold;) {
    if (p[k].control == Control::Hold) {
      shape.exit = k + 1;
      break;
    }
  }
  return ties;
}

// The speed a run loses to its brakes in the steps that end after from_m and by to_m: their
// braking work over the effective mass and v_ref (0 when it does not brake). It grows from 0
// as a coast into a lower limit starts later than the one that meets the limit, as the speed
// the run would reach at the limit grows beyond it, so the tie's miss is one continuous
// function across its root. The step that ends at to_m counts: a run that reaches the limit a
// little too fast is capped in that step alone.
double braked_speed_ms(const physics::SimulationResult& sim, double from_m, double to_m,
                       double effective_mass_kg, double v_ref_ms) {
  double work_J = 0.0;
  double step_start_m = from_m;
  for (const auto& p : sim.trace) {
    if (p.s_m > to_m + 1e-9) break;
    if (p.s_m > from_m &&
        (p.regime == physics::Regime::PartialBrake || p.regime == physics::Regime::FullBrake)) {
      work_J -= p.force_N * (p.s_m - step_start_m);
    }
    step_start_m = p.s_m;
  }
  return work_J > 0.0 ? work_J / (effective_mass_kg * v_ref_ms) : 0.0;
}

// The tied coasts' tolerances: a coast start is narrowed to this width, and a run that reaches
// the limit this close below its speed meets it.
constexpr double kTieWidth_m = 0.02;
constexpr double kTieSpeed_ms = 1e-4;
// A coast that runs this close below a lower limit's speed at its start touches it.
constexpr double kTouchSpeed_ms = 0.05 / 3.6;
// Coordinate search: at most this many rounds over the free switch points at one price, and a
// round that moves every point less than the search tolerance ends it.
constexpr int kMaxRounds = 12;
// Moves along the time: the probe that measures how the time moves with a point, and the reach
// of the search either way (in metres of the point that moves the time less).
constexpr double kPairProbe_m = 4.0;
constexpr double kPairReach_m = 160.0;

}  // namespace

CruisePolishReport polish_cruise(const SectionEngine& engine, double target_s, double tolerance_s,
                                 const CruisePolishOptions& options, LambdaRun& run,
                                 const PolishEnd& end) {
  CruisePolishReport report;
  report.cost_before_J = run.cost_J;
  report.cost_after_J = run.cost_J;
  if (!options.enabled || !engine.options().cruise_as_hold ||
      !(end.moving ? end.reaches && end.reaches(run.sim) : run_arrives(run.sim)) ||
      std::abs(run.sim.running_time_s - target_s) > tolerance_s) {
    return report;
  }
  const double length_m = engine.route().length_m();
  const LimitSteps steps = limit_steps(engine.route());
  std::optional<CruiseShape> shape = cruise_shape(run.program, run.sim, length_m, steps, options);
  if (!shape) return report;
  split_saturated_holds(*shape, run.sim, length_m, options.short_phase_m);
  const double c0 = shape->program[shape->exit].from_m;
  std::vector<CoastTie> ties = tie_coasts_to_limits(*shape, engine.route(), steps);
  report.dropped_phases = shape->dropped;
  Polisher polisher(engine, run.start, target_s, tolerance_s, end, report);
  const std::size_t hold = shape->hold;
  const ControlProgram& base = shape->program;
  const std::size_t n = base.size();
  // What is not searched: a tied coast's start (solved), the phase at a lower limit's start
  // (fixed there), and the last phase when the end solves it (the stop's braking curve, or the
  // end speed of a run that ends at a pinned speed).
  std::vector<char> searched(n, 0);
  std::vector<std::size_t> free;
  const bool end_solved = !end.moving || std::isfinite(end.pinned_speed_ms);
  auto mark_free = [&] {
    std::fill(searched.begin(), searched.end(), 0);
    for (std::size_t k = hold; k < n; ++k) searched[k] = 1;
    for (const CoastTie& tie : ties) {
      searched[tie.coast] = 0;
      if (!tie.passes) searched[tie.coast + 1] = 0;
    }
    if (end_solved && base.back().control == Control::MaxBrake) searched[n - 1] = 0;
    free.clear();
    for (std::size_t k = hold; k < n; ++k) {
      if (searched[k]) free.push_back(k);
    }
  };
  mark_free();
  if (free.empty()) return report;
  const double price_step_m = std::max(options.search_step_m, options.price_search_step_m);
  ControlProgram current = base;
  physics::SimulationResult recent;
  double lambda = 0.0;
  // The run of `current` (ties solved from the first switch that moved, first_changed, on):
  // its Lagrangian cost + lambda * time, +inf when it does not end as asked.
  auto lagrangian_of = [&](const physics::SimulationResult& sim) {
    return polisher.ends(sim) ? engine.energy_cost_J(sim) + lambda * sim.running_time_s : kInf;
  };
  // Past the budget every run counts as not ending as asked: the searches close at once and
  // the grid's run is kept (below).
  auto exhausted = [&] { return report.simulations >= options.max_simulations; };
  auto evaluate = [&](std::size_t first_changed) {
    if (exhausted()) return kInf;
    for (const CoastTie& tie : ties) {
      if (tie.coast < first_changed) continue;
      // The coast starts as late as it can without braking before the lower limit: f falls
      // as the coast starts later (the speed at the limit's start rises; once it would pass
      // the limit's speed the run brakes, for longer the later it coasts).
      const double lo_limit = current[tie.coast - 1].from_m + 1.0;
      const double hi_limit = tie.limit_m - 1.0;
      if (!(lo_limit < hi_limit)) return kInf;
      double best = kInf, best_x = hi_limit;
      physics::SimulationResult best_sim;
      bool met = false, root_met = false;
      auto f = [&](double x) {
        current[tie.coast].from_m = x;
        recent = polisher.simulate(current, price_step_m, recent);
        // Braking counts from the phase before the coast on: a coast that starts too late
        // lets the hold before it run into the limit's braking curve.
        const double braked = braked_speed_ms(recent, lo_limit - 1.0, tie.limit_m,
                                              engine.train().effective_mass_kg(), tie.limit_ms);
        const double miss = braked > 0.0 ? -braked : tie.limit_ms - speed_at(recent, tie.limit_m);
        met = miss >= 0.0 && miss <= kTieSpeed_ms;
        // The tie's run is the one that meets the limit (a function of the points before it,
        // not of the probes the bracketing happened to make on its way there); the cheapest
        // probe stands in only when no run meets it.
        const double cost = lagrangian_of(recent);
        if ((met && !root_met) || (met == root_met && cost < best)) {
          best = cost, best_x = x, best_sim = recent;
        }
        root_met = root_met || met;
        return miss;
      };
      const double x0 = std::min(std::max(current[tie.coast].from_m, lo_limit), hi_limit);
      const double f0 = f(x0);
      if (!met) {
        double lo = lo_limit, hi = hi_limit, f_lo = 0.0, f_hi = 0.0;
        bool bracketed = false;
        // Bracket by doubling steps from the last solution (f falls with x).
        for (double step = 8.0, xp = x0, fp = f0;; step *= 2.0) {
          const double x = fp > 0.0 ? std::min(x0 + step, hi_limit) : std::max(x0 - step, lo_limit);
          const double fx = f(x);
          if (met) break;
          if ((fp > 0.0) != (fx > 0.0)) {
            lo = std::min(x, xp), hi = std::max(x, xp);
            f_lo = x < xp ? fx : fp, f_hi = x < xp ? fp : fx;
            bracketed = true;
            break;
          }
          if (x <= lo_limit || x >= hi_limit) break;
          xp = x, fp = fx;
        }
        if (bracketed && !met) {
          LambdaBracket root(f, lo, f_lo, hi, f_hi, kMaxTimeSolves);
          root.narrow([&] { return met; }, kTieWidth_m);
        }
      }
      current[tie.coast].from_m = best_x;
      if (!std::isfinite(best)) return kInf;
      recent = std::move(best_sim);
    }
    if (ties.empty() || ties.back().coast < first_changed) {
      recent = polisher.simulate(current, price_step_m, recent);
    }
    return lagrangian_of(recent);
  };
  // The neighbours that bound a free switch point: the nearest switches before and after it
  // that are not solved from it (a tied coast moves with the points before it).
  auto is_tied = [&](std::size_t m) {
    for (const CoastTie& tie : ties) {
      if (tie.coast == m) return true;
    }
    return false;
  };
  auto bounds = [&](std::size_t i) {
    const std::size_t k = free[i];
    double lo = current[is_tied(k - 1) ? k - 2 : k - 1].from_m + 1.0;
    for (const CoastTie& tie : ties) {
      if (tie.hold_after_rise == k) lo = std::max(lo, tie.rise_m + 1.0);
      if (tie.passes && tie.coast + 1 == k) lo = std::max(lo, tie.limit_m + 1.0);
    }
    std::size_t m = k + 1;
    if (m < n && is_tied(m)) ++m;
    // A last phase that the end solves moves with every point before it: only the route's end
    // bounds them.
    const bool end_phase = m + 1 == n && !searched[m] && end.moving;
    const double hi = m < n && !end_phase ? current[m].from_m - 1.0 : length_m - 1.0;
    return std::make_pair(lo, hi);
  };
  // The free switch points' optimum under one price: rounds of golden-section searches, one
  // switch point at a time along the track. Each search spans the whole interval between its
  // neighbours in the first round, so the result does not hang on where the grid put the
  // point; later rounds search a window around it that widens while the optimum sits on its
  // edge. (With the coasts into lower limits tied, the cost has no kink left inside a window.)
  std::vector<double> moved(free.size(), kInf);
  // Rounds from value (the run of `current`); moved_m: how far each free point moved in its
  // last search (inf: never searched), which sets the window of its next.
  auto run_rounds = [&](std::vector<double>& moved_m, double value) {
    const int budget_end = report.simulations + options.price_max_simulations;
    for (int round = 0; round < kMaxRounds && report.simulations < budget_end; ++round) {
      bool still = true;
      for (std::size_t i = 0; i < free.size(); ++i) {
        const std::size_t k = free[i];
        auto [lo_b, hi_b] = bounds(i);
        if (!(lo_b < hi_b)) continue;
        const double origin_m = current[k].from_m;
        double x_start = origin_m;
        double half = std::isfinite(moved_m[i])
                          ? std::max(options.price_first_step_m, 4.0 * moved_m[i])
                          : hi_b - lo_b;
        GoldenSectionResult g;
        auto at = [&](double x) {
          current[k].from_m = x;
          return evaluate(k);
        };
        // Where the cruise starts with a step down to a lower limit, the first search of a
        // point looks at the whole interval first, on a scan of first_scan_points, and narrows
        // around the best: over a descent into the lower limit the cost has more than one
        // minimum in a point, and where the grid put the point need not be in the best one's
        // basin. (On a long cruise the scan's start moved the coordinate search along a flat
        // valley: two grids' starts then ended 0.011 % apart, so it is not done there.)
        if (!std::isfinite(moved_m[i]) && shape->steps_down && options.first_scan_points > 0) {
          // The scan's runs move the tied coasts with the point; they start again from where
          // they were, so the search after the scan starts as it would without it.
          const ControlProgram before_scan = current;
          const int scan = options.first_scan_points;
          double best_x = x_start;
          for (int q = 1; q < scan; ++q) {
            const double x = lo_b + (hi_b - lo_b) * q / scan;
            const double f = at(x);
            if (f < value) value = f, best_x = x;
          }
          current = before_scan;
          current[k].from_m = x_start = best_x;
          half = (hi_b - lo_b) / scan;
        }
        while (true) {
          const double a = std::max(lo_b, x_start - half), b = std::min(hi_b, x_start + half);
          g = golden_section_minimum(at, a, b, options.search_tolerance_m, 60, true);
          const bool on_edge = (g.best_x - a < 2.0 * options.search_tolerance_m && a > lo_b) ||
                               (b - g.best_x < 2.0 * options.search_tolerance_m && b < hi_b);
          if (!on_edge) break;
          half *= 4.0;
        }
        if (g.best_f <= value) {
          current[k].from_m = g.best_x;
          value = g.best_f;
        } else {
          current[k].from_m = x_start;
        }
        value = evaluate(k);
        moved_m[i] = std::abs(current[k].from_m - origin_m);
        still = still && moved_m[i] < options.search_tolerance_m;
      }
      if (still) break;
    }
    return value;
  };
  // Whether the switch points keep their order, a metre apart (tied coasts aside: solved).
  auto in_order = [&] {
    double last_m = -kInf;
    for (std::size_t k = 1; k < n; ++k) {
      if (is_tied(k)) continue;
      if (!(current[k].from_m > last_m + 1.0)) return false;
      last_m = current[k].from_m;
    }
    return current.back().from_m < length_m - 1.0;
  };
  // Moves along the time: each free hold's start (its speed) and the free point after it (the
  // phase that leaves the hold) searched together, by golden section along the direction that
  // keeps the running time (to first order: the times of runs with either point moved on by
  // kPairProbe_m), up to kPairReach_m either way. A hold a little faster left a little earlier
  // keeps the time, and along that valley a search of one point at a time advances less than
  // its tolerance and stops: A11 -> A12 at 153 s kept its hold 5 m of traction short of the
  // best (68.9 against 69.3 km/h) and its coast 11 m late, 0.013 % above a search of
  // "traction, hold, coast, brake" on the simulator. Returns whether a move lowered value.
  auto hold_moves = [&](double& value) {
    bool lowered = false;
    for (std::size_t i = 0; i + 1 < free.size(); ++i) {
      const std::size_t ki = free[i], kj = free[i + 1];
      if (current[ki].control != Control::Hold || exhausted()) continue;
      const double xi = current[ki].from_m, xj = current[kj].from_m;
      const double t0 = recent.running_time_s;
      auto time_moved = [&](std::size_t k) {
        const double keep = current[k].from_m;
        current[k].from_m = keep + kPairProbe_m;
        const double t = in_order() && std::isfinite(evaluate(ki)) ? recent.running_time_s : kInf;
        current[k].from_m = keep;
        return t - t0;
      };
      const double dti = time_moved(ki), dtj = time_moved(kj);
      // Per unit of the search, the point that moves the time less moves a metre.
      const double scale = std::max(std::abs(dti), std::abs(dtj));
      if (std::isfinite(dti) && std::isfinite(dtj) && dti * dtj > 0.0) {
        const double ui = dtj / scale, uj = -dti / scale;
        auto at = [&](double a) {
          current[ki].from_m = xi + a * ui;
          current[kj].from_m = xj + a * uj;
          return in_order() ? evaluate(ki) : kInf;
        };
        const GoldenSectionResult g = golden_section_minimum(at, -kPairReach_m, kPairReach_m,
                                                             options.search_tolerance_m, 40, true);
        lowered = lowered || g.best_f < value;
        current[ki].from_m = g.best_f < value ? xi + g.best_x * ui : xi;
        current[kj].from_m = g.best_f < value ? xj + g.best_x * uj : xj;
      }
      value = evaluate(ki);
    }
    return lowered;
  };
  // A coast that runs past a lower limit's start at the limit's speed (capped there, or within
  // kTouchSpeed_ms below it) and on below it: the cost has a kink along the runs that just
  // touch the limit, and a search of one point at a time stops on it where the optimum lies
  // along it (the hold a little faster and the coast a little earlier: A13 -> A14 at 164 s
  // and 173 s, whose coasts touch the 65 km/h and the 50 km/h limit, stood 0.066 % and 0.054 %
  // above a search of "traction, hold, coast, brake" on the simulator). The first such coast
  // and limit, in track order.
  auto touching_coast = [&]() -> std::optional<CoastTie> {
    for (std::size_t k = hold + 1; k < n; ++k) {
      if (current[k].control != Control::Coast || is_tied(k)) continue;
      const double end_m = k + 1 < n ? current[k + 1].from_m : length_m;
      for (double d : steps.drops_m) {
        if (!(d > current[k].from_m + 1.0 && d < end_m - 1.0)) continue;
        const double limit_ms = engine.route().speed_limit_ms(d + 1e-6);
        const double braked = braked_speed_ms(recent, current[k - 1].from_m, d,
                                              engine.train().effective_mass_kg(), limit_ms);
        if (braked > 0.0 || limit_ms - speed_at(recent, d) < kTouchSpeed_ms) {
          return CoastTie{k, d, limit_ms, 0, 0.0, true};
        }
      }
    }
    return std::nullopt;
  };
  // The optimum under one price: the rounds; where the moves along the time lower the cost,
  // the rounds again from there (a window of price_first_step_m around each point); then,
  // where the run touches a lower limit from a coast that runs on, the rounds again with that
  // coast tied to the limit (its start solved from the points before it, so they move along
  // the kink). The tie is let go again, the cheaper of the two kept.
  auto optimise_at_price = [&] {
    double value = run_rounds(moved, evaluate(hold));
    if (std::isfinite(value) && hold_moves(value)) {
      std::vector<double> near(free.size(), 0.0);
      value = run_rounds(near, value);
    }
    const std::optional<CoastTie> touch = touching_coast();
    if (!touch || !std::isfinite(value) || exhausted()) return value;
    const ControlProgram before = current;
    auto at = std::find_if(ties.begin(), ties.end(),
                           [&](const CoastTie& t) { return t.coast > touch->coast; });
    ties.insert(at, *touch);
    mark_free();
    std::vector<double> ridge_moved(free.size(), 0.0);
    const double ridge = run_rounds(ridge_moved, evaluate(hold));
    ties.erase(std::find_if(ties.begin(), ties.end(), [&](const CoastTie& t) { return t.passes; }));
    mark_free();
    if (!(ridge < value)) current = before;
    return evaluate(hold);
  };
  auto time_at_price = [&](double log_lambda) {
    lambda = std::exp(log_lambda);
    if (!std::isfinite(optimise_at_price())) return kInf;
    return recent.running_time_s - target_s;
  };
  // The price whose optimum meets the time, to within price_time_tolerance_s; the last
  // hundredths are then met by the last free hold's speed alone (meet_time), after every tie.
  const double log_lambda0 = std::log(run.lambda > 0.0 ? run.lambda : 1.0);
  const double error0_s = time_at_price(log_lambda0);
  double error_s = error0_s;
  if (!(std::abs(error0_s) <= options.price_time_tolerance_s)) {
    LambdaBracket price(
        [&](double log_lambda) {
          return error_s = log_lambda == log_lambda0 ? error0_s : time_at_price(log_lambda);
        },
        log_lambda0, kPriceBracketStep, kMaxPrices);
    price.narrow([&] { return std::abs(error_s) <= options.price_time_tolerance_s; });
  }
  if (exhausted()) return report;
  std::size_t time_hold = hold;
  for (std::size_t k = hold; k + 1 < n; ++k) {
    if (searched[k] && base[k].control == Control::Hold &&
        base[k - 1].control == Control::MaxTraction)
      time_hold = k;
  }
  const double c_best = current[shape->exit].from_m;
  // The time is met by the last free hold's start, or, where that cannot meet it, by the last
  // coast's start (the run is faster the later either starts).
  std::vector<std::size_t> time_switches = {time_hold};
  for (std::size_t k = n; k-- > hold;) {
    if (searched[k] && base[k].control == Control::Coast && k != time_hold) {
      time_switches.push_back(k);
      break;
    }
  }
  Candidate fine;
  for (std::size_t k : time_switches) {
    Candidate c = polisher.meet_time(current, k, options.search_step_m);
    if (c.program.empty()) continue;
    // The result: the time met at the engine's fine step.
    fine = polisher.meet_time(c.program, k, engine.options().resim_step_m);
    if (!fine.program.empty()) break;
  }
  if (fine.program.empty() || !polisher.ends(fine.sim) ||
      std::abs(fine.sim.running_time_s - target_s) > tolerance_s || !(fine.cost_J < run.cost_J)) {
    return report;
  }
  report.applied = true;
  report.cost_after_J = fine.cost_J;
  report.coast_shift_m = c_best - c0;
  run.program = std::move(fine.program);
  run.sim = std::move(fine.sim);
  run.cost_J = fine.cost_J;
  return report;
}

}  // namespace ecorail::dp
