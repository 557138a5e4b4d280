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

#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "power/power_supply.hpp"

namespace ecorail::timetable {

// Network: the DC traction power network (substations, conductor resistance, rectifier diodes,
// voltage limits) solved by a load flow at every instant (power/load_flow.hpp).
enum class EnergyModel { PowerFlow, Overlap, Sections, Network };
// Which trains' traction a braking train may feed in the overlap model: the train ahead only
// (the contest's rule) or either neighbour (the union of the two traction sets).
enum class OverlapVariant { Ahead, Either };

std::string_view model_name(EnergyModel m);
std::optional<EnergyModel> model_from_name(std::string_view name);
std::string_view overlap_variant_name(OverlapVariant v);
std::optional<OverlapVariant> overlap_variant_from_name(std::string_view name);

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
  // Clock-dependent headway classes (question 2.2, timetable/windowed_classes.hpp): a headway
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

struct EnergyModelOptions {
  EnergyModel model = EnergyModel::PowerFlow;
  OverlapVariant overlap = OverlapVariant::Ahead;
  // Time step of the power balance (power-flow, sections); must divide one second. The default
  // comes from the convergence study in docs/fleet.md.
  double time_step_s = 0.01;
  // Supply-section boundaries along the run (m from the first station), sections model only.
  std::vector<double> section_boundaries_m;
  // Network model: the line's power supply and the trains' traction efficiency (wheel power /
  // electrical input; the train's own). Its default step is kNetworkTimeStep_s.
  std::shared_ptr<const power::PowerSupply> power_supply;
  double traction_efficiency = 1.0;
  bool IsValid(std::string* error) const;
  // Bins per second of the time grid.
  int ticks_per_second() const;
};

// Default step of the network model (convergence study in docs/power_network.md).
inline constexpr double kNetworkTimeStep_s = 0.1;

// Departures from headways (t_1 = 0) and back.
std::vector<int> departures_from_headways(const std::vector<int>& headways_s);
std::vector<int> headways_from_departures(const std::vector<int>& departures_s);
// Why the departures break the problem's rules ("" when they keep them): count, first at 0,
// last at span, every headway within its bounds.
std::string departures_problem(const FleetProblem& problem, const std::vector<int>& departures_s);
// As even as whole seconds allow: the first (span mod (N-1)) headways one second longer.
std::vector<int> uniform_headways(const FleetProblem& problem);

}  // namespace ecorail::timetable
