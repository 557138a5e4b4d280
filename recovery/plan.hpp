// A timetable plan for delay recovery: the stations in the order of travel and, per train (in
// departure order), its arrival and departure clock times at every station (the first station's
// arrival equals its departure, the last's departure its arrival). It is what `ecorail timetable
// evaluate|optimise --csv` writes (docs/formats.md, "Timetable CSV") and what the 2.1 reference
// plan is: every train the same pattern (30 s dwells, the optimal split of 1726 s running
// time) shifted to the uniform departures of 100 trains over 63 900 s. Running times and dwells
// are read off the clock times; the plan is checked (times rising along each train, trains in
// departure order) before any work.
#pragma once

#include <string>
#include <vector>

#include "dp/journey.hpp"
#include "dp/section_library.hpp"

namespace ecorail::recovery {

struct TrainStops {
  std::vector<double> arrival_s;    // per station, in the order of travel
  std::vector<double> departure_s;  // per station
};

struct Plan {
  std::vector<std::string> stations;
  std::vector<TrainStops> trains;  // in departure order

  std::size_t sections() const { return stations.empty() ? 0 : stations.size() - 1; }
  // Planned running time of train k over section j (station j to j + 1).
  double running_time_s(std::size_t k, std::size_t j) const {
    return trains.at(k).arrival_s.at(j + 1) - trains.at(k).departure_s.at(j);
  }
  // Planned dwell of train k at station j (0 at the first and last).
  double dwell_s(std::size_t k, std::size_t j) const {
    return trains.at(k).departure_s.at(j) - trains.at(k).arrival_s.at(j);
  }
  // Index of a station by name, or -1.
  int station_index(const std::string& name) const;
  // "" when sound, else one sentence saying what is wrong (which train, which station).
  std::string problem() const;
};

// Every train runs the pattern (running_times_s per section, dwells_s per intermediate stop),
// departing its first station at departures_s[k].
Plan plan_from_pattern(const std::vector<std::string>& stations,
                       const std::vector<double>& running_times_s,
                       const std::vector<double>& dwells_s,
                       const std::vector<double>& departures_s);

// The 2.1 reference plan on a library of the whole line: dwells of dwell_s at every
// intermediate stop, the running time trip_time_s - dwells split optimally (one time price, as
// `ecorail solve --from A1 --to A14 --time 1726 --dwell 30`), and the uniform departures of
// `trains` trains over span_s (the first departure at 0, headways in whole seconds).
Plan reference_plan(const dp::SectionLibrary& library, const std::vector<std::string>& stations,
                    const dp::JourneyOptions& journey, int trains = 100, int span_s = 63900,
                    double trip_time_s = 2086.0, double dwell_s = 30.0);

}  // namespace ecorail::recovery
