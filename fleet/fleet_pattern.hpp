// FleetPattern: how every train runs the line: a dwell at each intermediate stop and a running
// time per section, the trip time (running plus dwells) fixed. The default pattern of question
// 2.1 is every dwell at its minimum and the running time split optimally (one time price over
// the sections, dp::solve_journey); with no timetable coupling that is the least-traction
// pattern (dp/journey.hpp, free dwells). pattern_trip re-simulates a pattern's sections on the
// section library and lays them end to end as a trip departing at 0.
#pragma once

#include <string>
#include <vector>

#include "dp/journey.hpp"
#include "dp/section_library.hpp"
#include "physics/trip.hpp"

namespace ecorail::fleet {

struct FleetPattern {
  std::vector<double> dwells_s;         // one per intermediate stop
  std::vector<double> running_times_s;  // one per section (re-simulated)
  double trip_time_s() const;
};

struct PatternTrip {
  FleetPattern pattern;
  physics::Trip trip;  // departs at 0
};

// Dwells fixed, running time trip_time_s - sum(dwells) split optimally over all sections of the
// library. Throws dp::InfeasibleTimeError when the running time is below the flat-out runs.
PatternTrip optimal_split_pattern(const dp::SectionLibrary& library,
                                  const std::vector<double>& dwells_s, double trip_time_s,
                                  const dp::JourneyOptions& options);

// A pattern's trip from one re-simulated run per section and the dwells between them (the runs
// are copied into the trip).
physics::Trip trip_from_runs(const dp::SectionLibrary& library,
                             const std::vector<const physics::SimulationResult*>& runs,
                             const std::vector<double>& dwells_s);

// The trip of a pattern whose running times are given (each section solved for its time).
PatternTrip pattern_trip(const dp::SectionLibrary& library, const FleetPattern& pattern);

}  // namespace ecorail::fleet
