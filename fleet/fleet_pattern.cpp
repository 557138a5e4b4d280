#include "fleet/fleet_pattern.hpp"

#include <numeric>
#include <stdexcept>

namespace ecorail::fleet {

double FleetPattern::trip_time_s() const {
  return std::accumulate(dwells_s.begin(), dwells_s.end(), 0.0) +
         std::accumulate(running_times_s.begin(), running_times_s.end(), 0.0);
}

physics::Trip trip_from_runs(const dp::SectionLibrary& library,
                             const std::vector<const physics::SimulationResult*>& runs,
                             const std::vector<double>& dwells_s) {
  const std::size_t n = library.size();
  if (runs.size() != n || dwells_s.size() + 1 != n)
    throw std::invalid_argument("a pattern trip needs one run per section and one dwell per stop");
  std::vector<physics::TripSection> sections;
  for (std::size_t i = 0; i < n; ++i)
    sections.push_back({&library.route(i), runs[i], i + 1 < n ? dwells_s[i] : 0.0});
  return physics::Trip(sections, 0.0, library.train().regen_efficiency);
}

PatternTrip optimal_split_pattern(const dp::SectionLibrary& library,
                                  const std::vector<double>& dwells_s, double trip_time_s,
                                  const dp::JourneyOptions& options) {
  const std::size_t n = library.size();
  if (dwells_s.size() + 1 != n)
    throw std::invalid_argument("a pattern needs one dwell per intermediate stop");
  const double running = trip_time_s - std::accumulate(dwells_s.begin(), dwells_s.end(), 0.0);
  const dp::JourneySolution sol = dp::solve_journey(library, 0, n, dwells_s, running, options);
  if (!sol.converged())
    throw std::runtime_error("the pattern's journey misses a stop or its running time");
  PatternTrip out;
  out.pattern.dwells_s = dwells_s;
  std::vector<const physics::SimulationResult*> runs;
  for (const dp::JourneySection& section : sol.sections) {
    out.pattern.running_times_s.push_back(section.run.sim.running_time_s);
    runs.push_back(&section.run.sim);
  }
  out.trip = trip_from_runs(library, runs, dwells_s);
  return out;
}

PatternTrip pattern_trip(const dp::SectionLibrary& library, const FleetPattern& pattern) {
  const std::size_t n = library.size();
  if (pattern.dwells_s.size() + 1 != n || pattern.running_times_s.size() != n)
    throw std::invalid_argument("a pattern needs one dwell per stop and one time per section");
  std::vector<dp::SectionTimeSolve> solves;
  solves.reserve(n);
  PatternTrip out;
  out.pattern.dwells_s = pattern.dwells_s;
  std::vector<const physics::SimulationResult*> runs;
  for (std::size_t i = 0; i < n; ++i) {
    solves.push_back(library.solve(i, pattern.running_times_s[i]));
    if (!solves.back().search.converged)
      throw std::runtime_error("section " + std::to_string(i + 1) + " misses its running time");
    out.pattern.running_times_s.push_back(solves.back().search.run.sim.running_time_s);
    runs.push_back(&solves.back().search.run.sim);
  }
  out.trip = trip_from_runs(library, runs, pattern.dwells_s);
  return out;
}

}  // namespace ecorail::fleet
