#include "timetable/pattern_search.hpp"

#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>

namespace ecorail::timetable {

namespace {

// Section solves by (section, running time in hundredths of a second), kept so that a pattern
// revisited or re-timed back costs nothing; map nodes are stable, so trips can point into them.
class SolveCache {
 public:
  explicit SolveCache(const dp::SectionLibrary& library) : library_(library) {}
  const dp::SectionTimeSolve& get(std::size_t section, double time_s) {
    const auto key = std::make_pair(section, std::llround(time_s * 100.0));
    auto it = cache_.find(key);
    if (it == cache_.end())
      it = cache_.emplace(key, library_.solve(section, static_cast<double>(key.second) / 100.0))
               .first;
    return it->second;
  }

 private:
  const dp::SectionLibrary& library_;
  std::map<std::pair<std::size_t, long long>, dp::SectionTimeSolve> cache_;
};

// The trip of a pattern from cached solves; nullopt when a section misses its time.
std::optional<physics::Trip> trip_of(SolveCache& cache, const dp::SectionLibrary& library,
                                     const FleetPattern& pattern) {
  std::vector<const physics::SimulationResult*> runs;
  for (std::size_t i = 0; i < library.size(); ++i) {
    const dp::SectionTimeSolve& s = cache.get(i, pattern.running_times_s[i]);
    if (!s.search.converged) return std::nullopt;
    runs.push_back(&s.search.run.sim);
  }
  return trip_from_runs(library, runs, pattern.dwells_s);
}

}  // namespace

bool PatternSearchOptions::IsValid(std::string* error) const {
  if (!headways.IsValid(error)) return false;
  for (double d : deltas_s) {
    if (!(d > 0.0 && d <= 60.0)) {
      if (error) *error = "deltas_s: expected steps in (0, 60] s";
      return false;
    }
  }
  if (max_moves < 0) {
    if (error) *error = "max_moves: expected >= 0";
    return false;
  }
  return true;
}

std::string PatternSearchResult::BriefReport() const {
  const FleetEnergy& a = headways_only.total;
  const FleetEnergy& b = timetable.evaluation.total;
  char buf[512];
  std::snprintf(buf, sizeof buf,
                "pattern search: %d moves accepted of %d patterns; substation %.1f -> %.1f kJ "
                "(%.1f kJ), traction %.1f -> %.1f kJ (%+.1f kJ), used regen %.1f -> %.1f kJ",
                moves_accepted, patterns_evaluated, a.substation_J() / 1e3, b.substation_J() / 1e3,
                (b.substation_J() - a.substation_J()) / 1e3, a.traction_J / 1e3, b.traction_J / 1e3,
                (b.traction_J - a.traction_J) / 1e3, a.used_regen_J / 1e3, b.used_regen_J / 1e3);
  return buf;
}

PatternSearchResult optimise_pattern(const dp::SectionLibrary& library, const FleetProblem& problem,
                                     const EnergyModelOptions& model, const PatternTrip& start,
                                     const PatternSearchOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument(why);
  PatternSearchResult out;
  // 1. Headways for the start pattern.
  const FleetModels start_models(start.trip, problem, model);
  HeadwayOptimiserResult first = optimise_headways(start_models, options.headways);
  out.headways_only = first.evaluation;
  const std::vector<int> departures = first.evaluation.departures_s;

  // 2. The pattern for those headways, by feasible trip-time-keeping moves.
  SolveCache cache(library);
  FleetPattern best = start.pattern;
  double best_substation = first.evaluation.total.substation_J();
  const std::size_t n = library.size();
  std::vector<double> min_time(n);
  for (std::size_t i = 0; i < n; ++i) min_time[i] = library.min_time_s(i) + 0.5;
  // The moves, each keeping the trip time: a dwell longer (shorter) with the section before or
  // after it shorter (longer), and time moved between two neighbouring sections.
  struct PatternMove {
    int dwell = -1;
    double dwell_sign = 0.0;
    int longer = -1, shorter = -1;
  };
  std::vector<PatternMove> moves;
  for (int j = 0; j + 1 < static_cast<int>(n); ++j) {
    for (int i : {j, j + 1}) {
      moves.push_back({j, +1.0, -1, i});
      moves.push_back({j, -1.0, i, -1});
    }
    moves.push_back({-1, 0.0, j, j + 1});
    moves.push_back({-1, 0.0, j + 1, j});
  }
  for (double delta : options.deltas_s) {
    bool improved = true;
    while (improved && out.moves_accepted < options.max_moves) {
      improved = false;
      for (const PatternMove& m : moves) {
        FleetPattern p = best;
        if (m.dwell >= 0) p.dwells_s[m.dwell] += m.dwell_sign * delta;
        if (m.longer >= 0) p.running_times_s[m.longer] += delta;
        if (m.shorter >= 0) p.running_times_s[m.shorter] -= delta;
        bool feasible = true;
        for (double d : p.dwells_s)
          feasible &= d >= problem.dwell_min_s - 1e-9 && d <= problem.dwell_max_s + 1e-9;
        for (std::size_t i = 0; i < n; ++i) feasible &= p.running_times_s[i] >= min_time[i];
        if (!feasible) continue;
        const std::optional<physics::Trip> trip = trip_of(cache, library, p);
        ++out.patterns_evaluated;
        if (!trip) continue;
        const FleetEvaluation e = FleetModels(*trip, problem, model).evaluate(departures);
        if (e.total.substation_J() < best_substation - 1.0) {  // 1 J: not a rounding wobble
          best = p;
          best_substation = e.total.substation_J();
          improved = true;
          ++out.moves_accepted;
          break;
        }
      }
    }
  }

  // 3. Headways for the pattern found (a trip copies its runs, so it outlives the cache); the
  // better of the re-optimised and the kept departures is the result.
  out.pattern.pattern = best;
  out.pattern.trip = *trip_of(cache, library, best);
  if (out.moves_accepted == 0) {
    out.timetable = std::move(first);
    return out;
  }
  const FleetModels models(out.pattern.trip, problem, model);
  out.timetable = optimise_headways(models, options.headways);
  const FleetEvaluation kept = models.evaluate(departures);
  if (kept.total.substation_J() < out.timetable.evaluation.total.substation_J()) {
    HeadwayOptimiserSummary& s = out.timetable.summary;
    out.timetable.evaluation = kept;
    out.timetable.headways_s = headways_from_departures(departures);
    s.used_regen_J = kept.total.used_regen_J;
    s.substation_J = kept.total.substation_J();
    if (std::isfinite(s.bound_used_regen_J))
      s.gap_fraction = (s.bound_used_regen_J - s.used_regen_J) / s.substation_J;
  }
  return out;
}

}  // namespace ecorail::timetable
