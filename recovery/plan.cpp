#include "recovery/plan.hpp"

#include <cmath>
#include <stdexcept>

#include "fleet/fleet_pattern.hpp"
#include "fleet/fleet_problem.hpp"

namespace ecorail::recovery {

int Plan::station_index(const std::string& name) const {
  for (std::size_t j = 0; j < stations.size(); ++j)
    if (stations[j] == name) return static_cast<int>(j);
  return -1;
}

std::string Plan::problem() const {
  if (stations.size() < 2) return "a plan needs at least two stations";
  if (trains.empty()) return "a plan needs at least one train";
  for (std::size_t k = 0; k < trains.size(); ++k) {
    const TrainStops& t = trains[k];
    const std::string who = "train " + std::to_string(k + 1);
    if (t.arrival_s.size() != stations.size() || t.departure_s.size() != stations.size())
      return who + " does not have one arrival and one departure at each of the " +
             std::to_string(stations.size()) + " stations";
    for (std::size_t j = 0; j < stations.size(); ++j) {
      if (!std::isfinite(t.arrival_s[j]) || !std::isfinite(t.departure_s[j]))
        return who + " has a time that is not a number at " + stations[j];
      if (t.departure_s[j] < t.arrival_s[j])
        return who + " departs " + stations[j] + " before it arrives there";
      if (j + 1 < stations.size() && !(t.arrival_s[j + 1] > t.departure_s[j]))
        return who + " arrives at " + stations[j + 1] + " no later than it departs " + stations[j];
    }
    if (k > 0 && !(t.departure_s[0] > trains[k - 1].departure_s[0]))
      return who + " departs " + stations[0] + " no later than the train before it";
  }
  return "";
}

Plan plan_from_pattern(const std::vector<std::string>& stations,
                       const std::vector<double>& running_times_s,
                       const std::vector<double>& dwells_s,
                       const std::vector<double>& departures_s) {
  if (stations.size() < 2 || running_times_s.size() + 1 != stations.size() ||
      dwells_s.size() + 2 != stations.size())
    throw std::invalid_argument(
        "plan_from_pattern: one running time per section and one dwell per intermediate stop");
  Plan plan;
  plan.stations = stations;
  for (double d : departures_s) {
    TrainStops t;
    double clock = d;
    for (std::size_t j = 0; j < stations.size(); ++j) {
      if (j > 0) clock += running_times_s[j - 1];
      t.arrival_s.push_back(clock);
      if (j > 0 && j + 1 < stations.size()) clock += dwells_s[j - 1];
      t.departure_s.push_back(clock);
    }
    plan.trains.push_back(std::move(t));
  }
  return plan;
}

Plan reference_plan(const dp::SectionLibrary& library, const std::vector<std::string>& stations,
                    const dp::JourneyOptions& journey, int trains, int span_s, double trip_time_s,
                    double dwell_s) {
  const std::vector<double> dwells(library.size() - 1, dwell_s);
  const fleet::PatternTrip pattern =
      fleet::optimal_split_pattern(library, dwells, trip_time_s, journey);
  fleet::FleetProblem fleet;
  fleet.trains = trains;
  fleet.span_s = span_s;
  fleet.trip_time_s = trip_time_s;
  std::vector<double> departures;
  for (int d : fleet::departures_from_headways(fleet::uniform_headways(fleet)))
    departures.push_back(d);
  return plan_from_pattern(stations, pattern.pattern.running_times_s, pattern.pattern.dwells_s,
                           departures);
}

}  // namespace ecorail::recovery
