// The fleet timetable problem of question 2.1 and its energy models. N identical trains leave
// the first station at whole-second clock times t_1 = 0 < ... < t_N = span; every headway
// h_k = t_{k+1} - t_k lies in [headway_min, headway_max]; every train runs the whole line with
// one pattern (dwells and section running times, trip time fixed). The objective is the
// substation energy of all trains: their traction energy less the regenerated braking energy
// that other trains use at the same moment, by one of three models: `overlap` (the contest's
// time-overlap rule between neighbours), `power-flow` (one supply section, instantaneous power
// balance: used power = min(sum of regenerated, sum of traction)), `sections` (the same balance
// in each of several supply sections along the line). Names go to and from text here, once.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace ecorail::timetable {

enum class EnergyModel { PowerFlow, Overlap, Sections };
// Which trains' traction a braking train may feed in the overlap model: the train ahead only
// (the contest's rule) or either neighbour (the union of the two traction sets).
enum class OverlapVariant { Ahead, Either };

std::string_view model_name(EnergyModel m);
std::optional<EnergyModel> model_from_name(std::string_view name);
std::string_view overlap_variant_name(OverlapVariant v);
std::optional<OverlapVariant> overlap_variant_from_name(std::string_view name);

// Departure constraints of the fleet (question 2.1's reference values by default).
struct FleetProblem {
  int trains = 100;
  int headway_min_s = 120;
  int headway_max_s = 660;
  int span_s = 63900;           // t_N - t_1
  double trip_time_s = 2086.0;  // running times plus dwells, first departure to last arrival
  double dwell_min_s = 30.0;
  double dwell_max_s = 45.0;
  // Checks every field and that some timetable exists; one sentence naming the field.
  bool IsValid(std::string* error) const;
};

struct EnergyModelOptions {
  EnergyModel model = EnergyModel::PowerFlow;
  OverlapVariant overlap = OverlapVariant::Ahead;
  // Time step of the power balance (power-flow, sections); must divide one second. The default
  // comes from the convergence study in docs/fleet.md.
  double time_step_s = 0.01;
  // Supply-section boundaries along the run (m from the first station), sections model only.
  std::vector<double> section_boundaries_m;
  bool IsValid(std::string* error) const;
  // Bins per second of the time grid.
  int ticks_per_second() const;
};

// Departures from headways (t_1 = 0) and back.
std::vector<int> departures_from_headways(const std::vector<int>& headways_s);
std::vector<int> headways_from_departures(const std::vector<int>& departures_s);
// Why the departures break the problem's rules ("" when they keep them): count, first at 0,
// last at span, every headway within its bounds.
std::string departures_problem(const FleetProblem& problem, const std::vector<int>& departures_s);
// As even as whole seconds allow: the first (span mod (N-1)) headways one second longer.
std::vector<int> uniform_headways(const FleetProblem& problem);

}  // namespace ecorail::timetable
