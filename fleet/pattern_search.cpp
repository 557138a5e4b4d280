#include "fleet/pattern_search.hpp"
#include "energy/model_registry.hpp"
#include "fleet/search_support.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>

namespace ecorail::fleet {

namespace {

// Running times are solved on a grid of 0.01 s: a pattern the search reports is exactly the
// one it solved (pattern_trip of it gives the same trip).
constexpr double kTimeGridPerSecond = 100.0;
double on_grid(double time_s) {
  return static_cast<double>(std::llround(time_s * kTimeGridPerSecond)) / kTimeGridPerSecond;
}

// The start pattern on the grid, rounding the running times' running sum so that the trip time
// moves by less than one grid step.
FleetPattern snapped(FleetPattern p) {
  double sum = 0.0, before = 0.0;
  for (double& t : p.running_times_s) {
    sum += t;
    const double rounded = on_grid(sum);
    t = on_grid(rounded - before);
    before = rounded;
  }
  return p;
}

// Section solves by (section, running time in hundredths of a second), kept so that a pattern
// revisited or re-timed back costs nothing; map nodes are stable, so trips can point into them.
// fetch() solves what is missing (one thread); find() only reads, so threads may share it.
class SolveCache {
 public:
  explicit SolveCache(const dp::SectionLibrary& library) : library_(library) {}
  // Solves every section of the pattern not yet cached; false when one misses its time.
  bool fetch(const FleetPattern& pattern) {
    bool ok = true;
    for (std::size_t i = 0; i < library_.size(); ++i) {
      const Key key = key_of(i, pattern.running_times_s[i]);
      auto it = cache_.find(key);
      if (it == cache_.end())
        it = cache_.emplace(key, library_.solve(i, on_grid(pattern.running_times_s[i]))).first;
      ok &= it->second.search.converged;
    }
    return ok;
  }
  // The trip of a fetched pattern.
  physics::Trip trip(const FleetPattern& pattern) const {
    std::vector<const physics::SimulationResult*> runs;
    for (std::size_t i = 0; i < library_.size(); ++i)
      runs.push_back(&cache_.at(key_of(i, pattern.running_times_s[i])).search.run.sim);
    return trip_from_runs(library_, runs, pattern.dwells_s);
  }

 private:
  using Key = std::pair<std::size_t, long long>;
  static Key key_of(std::size_t section, double time_s) {
    return {section, std::llround(time_s * kTimeGridPerSecond)};
  }
  const dp::SectionLibrary& library_;
  std::map<Key, dp::SectionTimeSolve> cache_;
};

// A move that keeps the trip time: a dwell longer (shorter) with the section before or after it
// shorter (longer), or time moved between two neighbouring sections.
struct PatternMove {
  int dwell = -1;
  double dwell_sign = 0.0;
  int longer = -1, shorter = -1;
};

std::vector<PatternMove> pattern_moves(int sections) {
  std::vector<PatternMove> moves;
  for (int j = 0; j + 1 < sections; ++j) {
    for (int i : {j, j + 1}) {
      moves.push_back({j, +1.0, -1, i});
      moves.push_back({j, -1.0, i, -1});
    }
    moves.push_back({-1, 0.0, j, j + 1});
    moves.push_back({-1, 0.0, j + 1, j});
  }
  return moves;
}

// The pattern after a move by delta; nullopt when a dwell leaves its range or a running time
// goes below its section's flat-out run (plus half a second, so the solve has room).
std::optional<FleetPattern> moved(const FleetPattern& from, const PatternMove& m, double delta,
                                  const FleetProblem& problem,
                                  const std::vector<double>& min_time_s) {
  FleetPattern p = from;
  if (m.dwell >= 0) p.dwells_s[m.dwell] += m.dwell_sign * delta;
  if (m.longer >= 0) p.running_times_s[m.longer] = on_grid(p.running_times_s[m.longer] + delta);
  if (m.shorter >= 0) p.running_times_s[m.shorter] = on_grid(p.running_times_s[m.shorter] - delta);
  for (double d : p.dwells_s) {
    if (d < problem.dwell_min_s - 1e-9 || d > problem.dwell_max_s + 1e-9) return std::nullopt;
  }
  for (std::size_t i = 0; i < min_time_s.size(); ++i) {
    if (p.running_times_s[i] < min_time_s[i]) return std::nullopt;
  }
  return p;
}

// An improvement smaller than this is a rounding wobble, not a move worth taking.
constexpr double kImprovementJ = 1.0;

}  // namespace

bool PatternSearchOptions::IsValid(std::string* error) const {
  if (!headways.IsValid(error)) return false;
  for (double d : deltas_s) {
    if (!(d > 0.0 && d <= 60.0)) {
      if (error) *error = "deltas_s: expected steps in (0, 60] s";
      return false;
    }
  }
  if (max_moves < 0 || max_per_train_moves < 0) {
    if (error) *error = "max_moves, max_per_train_moves: expected >= 0";
    return false;
  }
  return true;
}

double used_regen_of(const FleetEvaluation& e) {
  return e.used_regen_J();
}

std::unique_ptr<energy::FleetEnergyModel> make_model(const physics::Trip& trip,
                                                     const FleetProblem& problem,
                                                     const energy::EnergyModelOptions& options) {
  return energy::make_energy_model(trip, limits_of(problem), options);
}

std::string PatternSearchResult::BriefReport() const {
  const FleetEnergy& a = headways_only.total;
  const FleetEnergy& b = common_pattern.total;
  char buf[1024];
  int n = std::snprintf(
      buf, sizeof buf,
      "pattern search: %d moves accepted of %d patterns%s; substation %.1f -> %.1f kJ "
      "(%.1f kJ), traction %.1f -> %.1f kJ (%+.1f kJ), used regen %.1f -> %.1f kJ",
      moves_accepted, patterns_evaluated,
      full_evaluations > 0
          ? (" (" + std::to_string(full_evaluations) + " evaluated in full)").c_str()
          : "",
      a.substation_J() / 1e3, b.substation_J() / 1e3, (b.substation_J() - a.substation_J()) / 1e3,
      a.traction_J / 1e3, b.traction_J / 1e3, (b.traction_J - a.traction_J) / 1e3,
      used_regen_of(headways_only) / 1e3, used_regen_of(common_pattern) / 1e3);
  if (per_train.empty() && n > 0 && n < static_cast<int>(sizeof buf)) {
    std::snprintf(buf + n, sizeof buf - n, "; %s",
                  time_limit_reached   ? "stopped at the time limit"
                  : move_limit_reached ? "stopped at the move limit"
                                       : "no move improves (a local optimum)");
  }
  if (!per_train.empty() && n > 0 && n < static_cast<int>(sizeof buf)) {
    const FleetEnergy& c = timetable.evaluation.total;
    std::snprintf(buf + n, sizeof buf - n,
                  "\nper-train patterns: %d moves accepted of %d priced; substation %.1f -> %.1f "
                  "kJ (%.1f kJ), traction %+.1f kJ; %s",
                  per_train_moves_accepted, per_train_candidates, b.substation_J() / 1e3,
                  c.substation_J() / 1e3, (c.substation_J() - b.substation_J()) / 1e3,
                  (c.traction_J - b.traction_J) / 1e3,
                  time_limit_reached   ? "stopped at the time limit"
                  : move_limit_reached ? "stopped at the move limit"
                                       : "no one-train move improves (local optimum)");
  }
  return buf;
}

std::string PatternSearchResult::FullReport() const {
  return BriefReport() + "\n" + timetable.summary.FullReport();
}

PatternSearchResult optimise_pattern(const dp::SectionLibrary& library, const FleetProblem& problem,
                                     const energy::EnergyModelOptions& model,
                                     const PatternTrip& start,
                                     const PatternSearchOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument(why);
  const std::unique_ptr<energy::FleetEnergyModel> start_model =
      make_model(start.trip, problem, model);
  if (options.per_train_patterns && !start_model->per_train_trips())
    throw std::invalid_argument(
        "per-train patterns need the power-flow or sections model (the others price a pattern "
        "for the whole fleet at once; the network balance lays one trip under every train)");
  const SearchClock::time_point start_time = SearchClock::now();
  PatternSearchResult out;
  const auto report = [&](const char* stage, int accepted, int evaluated, double substation_J) {
    if (options.progress)
      options.progress({stage, accepted, evaluated, substation_J, seconds_since(start_time)});
  };

  // The whole-run limit: each stage ends by its share of it (0: none).
  const double limit = options.headways.time_limit_s;
  const auto stage_options = [&](double share) {
    HeadwayOptimiserOptions o = options.headways;
    if (limit > 0.0) o.time_limit_s = std::max(1e-6, share * limit - seconds_since(start_time));
    return o;
  };
  const auto out_of_time = [&](double share) {
    return limit > 0.0 && seconds_since(start_time) > share * limit;
  };

  // 1. Headways for the start pattern.
  HeadwayOptimiserResult first = optimise_headways(*start_model, problem, stage_options(1.0 / 3.0));
  out.headways_only = first.evaluation;
  const std::vector<int> departures = first.evaluation.departures_s;
  const int threads =
      options.headways.threads > 0 ? options.headways.threads : omp_get_max_threads();
  // The model prices candidate patterns at these departures: the incremental models in one
  // balance, a costly one screening on the annealing's coarse grid first.
  const std::unique_ptr<energy::TripPricer> pricer =
      start_model->make_trip_pricer(departures, options.headways.anneal_step_s, threads);

  // 2. One pattern for all trains, for those headways, by feasible trip-time-keeping moves.
  SolveCache cache(library);
  FleetPattern best = snapped(start.pattern);
  double best_substation = first.evaluation.total.substation_J();
  const std::size_t n = library.size();
  std::vector<double> min_time(n);
  for (std::size_t i = 0; i < n; ++i) min_time[i] = library.min_time_s(i) + 0.5;
  const std::vector<PatternMove> moves = pattern_moves(static_cast<int>(n));
  for (double delta : options.deltas_s) {
    bool improved = true;
    while (improved && out.moves_accepted < options.max_moves && !out.time_limit_reached) {
      improved = false;
      for (const PatternMove& m : moves) {
        if ((out.time_limit_reached = out_of_time(2.0 / 3.0))) break;
        const std::optional<FleetPattern> p = moved(best, m, delta, problem, min_time);
        if (!p) continue;
        ++out.patterns_evaluated;
        if (!cache.fetch(*p)) continue;
        const std::optional<double> substation = pricer->substation_J(cache.trip(*p));
        if (substation && *substation < best_substation - kImprovementJ) {
          best = *p;
          best_substation = *substation;
          pricer->accept();
          improved = true;
          ++out.moves_accepted;
          report("pattern", out.moves_accepted, out.patterns_evaluated, best_substation);
          break;
        }
      }
    }
  }
  out.full_evaluations = pricer->full_evaluations();
  out.move_limit_reached = !out.time_limit_reached && out.moves_accepted >= options.max_moves;

  // 3. Headways for the pattern found (a trip copies its runs, so it outlives the cache); the
  // better of the re-optimised and the kept departures is the result.
  if (out.moves_accepted == 0) {
    best = start.pattern;  // unchanged, as solved for the start
    out.pattern = start;
    out.timetable = std::move(first);
  } else {
    cache.fetch(best);
    out.pattern.pattern = best;
    out.pattern.trip = cache.trip(best);
    const std::unique_ptr<energy::FleetEnergyModel> models =
        start_model->with_trip(out.pattern.trip);
    // The kept departures are priced first: the limit then covers the search alone.
    const FleetEvaluation kept = models->evaluate(departures);
    out.timetable = optimise_headways(*models, problem,
                                      stage_options(options.per_train_patterns ? 5.0 / 6.0 : 1.0));
    if (kept.total.substation_J() < out.timetable.evaluation.total.substation_J()) {
      HeadwayOptimiserSummary& s = out.timetable.summary;
      out.timetable.evaluation = kept;
      out.timetable.headways_s = headways_from_departures(departures);
      s.used_regen_J = kept.used_regen_J();
      s.substation_J = kept.total.substation_J();
      if (std::isfinite(s.bound_used_regen_J))
        s.gap_fraction = (s.bound_used_regen_J - kept.total.used_regen_J) / s.substation_J;
      if (kept.network) {
        s.curtailed_traction_J = kept.network->curtailed_traction_J;
        s.gap_fraction =
            (s.substation_J + s.curtailed_traction_J - s.bound_substation_J) / s.substation_J;
      }
      settle_termination(s, options.headways.gap_fraction,
                         kept.network && kept.network->unsolved_instants > 0);
    }
  }
  out.common_pattern = out.timetable.evaluation;
  if (!options.per_train_patterns) {
    out.wall_s = seconds_since(start_time);
    return out;
  }

  // 4. Per-train patterns at the final departures: each train in turn, every move of its own
  // pattern priced against the rest of the fleet in parallel, the best improving one taken.
  const auto per_train_out_of_time = [&] { return out_of_time(1.0); };
  out.time_limit_reached = false;
  out.move_limit_reached = false;
  const std::unique_ptr<energy::FleetEnergyModel> final_model =
      start_model->with_trip(out.pattern.trip);
  const std::unique_ptr<energy::FleetBalance> balance = final_model->make_balance(threads);
  balance->place_all(out.timetable.evaluation.departures_s);
  out.per_train.assign(problem.trains, best);
  out.per_train_trips.assign(problem.trains, out.pattern.trip);
  for (double delta : options.deltas_s) {
    bool improved = true;
    while (improved && !out.move_limit_reached && !out.time_limit_reached) {
      improved = false;
      for (int k = 0; k < problem.trains; ++k) {
        if ((out.time_limit_reached = per_train_out_of_time())) break;
        if ((out.move_limit_reached = out.per_train_moves_accepted >= options.max_per_train_moves))
          break;
        std::vector<FleetPattern> candidates;
        const FleetPattern current = snapped(out.per_train[k]);
        for (const PatternMove& m : moves) {
          // Each new candidate may be a section re-solve: the limit is checked between them.
          if ((out.time_limit_reached = per_train_out_of_time())) break;
          const std::optional<FleetPattern> p = moved(current, m, delta, problem, min_time);
          if (p && cache.fetch(*p)) candidates.push_back(*p);
        }
        if (out.time_limit_reached) break;
        const int count = static_cast<int>(candidates.size());
        out.per_train_candidates += count;
        std::vector<energy::MicroJoules> change(count, 0);
        // Pricing reads the balance and the cache only; each candidate's change is an exact
        // integer, so the choice below is the same for any thread count.
#pragma omp parallel for schedule(dynamic) num_threads(threads)
        for (int i = 0; i < count; ++i)
          change[i] = balance->substation_change_if(k, cache.trip(candidates[i]));
        int chosen = -1;
        for (int i = 0; i < count; ++i) {
          if (chosen < 0 || change[i] < change[chosen]) chosen = i;
        }
        if (chosen < 0 || energy::to_joules(change[chosen]) > -kImprovementJ) continue;
        out.per_train_trips[k] = cache.trip(candidates[chosen]);
        balance->set_trip(k, out.per_train_trips[k]);
        out.per_train[k] = candidates[chosen];
        ++out.per_train_moves_accepted;
        improved = true;
        report("per-train", out.per_train_moves_accepted, out.per_train_candidates,
               energy::to_joules(balance->substation()));
      }
    }
  }
  out.timetable.evaluation = balance->evaluation();
  HeadwayOptimiserSummary& s = out.timetable.summary;
  s.used_regen_J = out.timetable.evaluation.total.used_regen_J;
  s.substation_J = out.timetable.evaluation.total.substation_J();
  // The pair bound was built for one pattern: it bounds nothing once trains differ.
  s.bound_used_regen_J = std::nan("");
  s.gap_fraction = std::nan("");
  s.method += "; per-train patterns (no bound)";
  s.time_limit_reached = out.time_limit_reached;
  settle_termination(s, options.headways.gap_fraction, false);
  s.message = out.time_limit_reached   ? "the per-train stage stopped at the time limit"
              : out.move_limit_reached ? "the per-train stage stopped at its move limit"
                                       : "the per-train stage ended at a local optimum of "
                                         "one-train moves";
  s.message += "; no bound proves a gap for per-train patterns";
  out.wall_s = seconds_since(start_time);
  return out;
}

}  // namespace ecorail::fleet
