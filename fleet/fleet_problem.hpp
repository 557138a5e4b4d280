// The fleet timetable problem of question 2.1 (and 2.2's peak classes). N identical trains leave
// the first station at whole-second clock times t_1 = 0 < ... < t_N = span; every headway
// h_k = t_{k+1} - t_k lies in [headway_min, headway_max]; every train runs the whole line with
// one pattern (dwells and section running times, trip time fixed). The objective is the
// substation energy of all trains: their traction energy less the regenerated braking energy
// that other trains use at the same moment, by one of the energy models of energy/
// (energy/model_registry.hpp).
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "energy/model_options.hpp"

namespace ecorail::fleet {

// A peak window of the timetable clock (question 2.2): the open interval (from_s, to_s).
struct PeakWindow {
  int from_s = 0, to_s = 0;
};

// Departure constraints of the fleet (question 2.1's reference values by default).
struct FleetProblem {
  int trains = 100;
  int headway_min_s = 120;
  int headway_max_s = 660;
  int span_s = 63900;           // t_N - t_1
  double trip_time_s = 2086.0;  // running times plus dwells, first departure to last arrival
  double dwell_min_s = 30.0;
  double dwell_max_s = 45.0;
  // Clock-dependent headway classes (question 2.2, fleet/windowed_classes.hpp): a headway
  // whose open interval (t_k, t_k+1) overlaps a peak window lies in the peak range instead of
  // [headway_min_s, headway_max_s] (then the off-peak range). Empty: one class, as in 2.1.
  std::vector<PeakWindow> peak_windows;
  int peak_headway_min_s = 120, peak_headway_max_s = 150;
  bool windowed() const { return !peak_windows.empty(); }
  // Whether a train may depart at to_s after one at from_s (the headway's class by the clock).
  bool headway_allowed(int from_s, int to_s) const;
  // The shortest and longest headway of any class.
  int any_headway_min_s() const;
  int any_headway_max_s() const;
  // Checks every field and that some timetable exists; one sentence naming the field.
  bool IsValid(std::string* error) const;
};

// The fleet the energy models price: the problem's trains and span, its headway classes relaxed
// to the one range covering both (so a model's lower bound holds on every timetable of it).
energy::FleetLimits limits_of(const FleetProblem& problem);

// Departures from headways (t_1 = 0) and back.
std::vector<int> departures_from_headways(const std::vector<int>& headways_s);
std::vector<int> headways_from_departures(const std::vector<int>& departures_s);
// Why the departures break the problem's rules ("" when they keep them): count, first at 0,
// last at span, every headway within its bounds.
std::string departures_problem(const FleetProblem& problem, const std::vector<int>& departures_s);
// As even as whole seconds allow: the first (span mod (N-1)) headways one second longer.
std::vector<int> uniform_headways(const FleetProblem& problem);

}  // namespace ecorail::fleet
