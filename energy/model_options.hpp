// What a fleet energy model is built from besides the trip: which model (by its registered
// name, energy/model_registry.hpp), its options, and the shape of the fleet it prices (trains,
// span and the headway range a bound may assume). The models' names are the CLI's `--model`
// values: `power-flow` (one supply section; in each time bin the fleet uses
// min(regenerated, traction) of its power), `sections` (the same balance per supply section),
// `overlap` (the contest's time-overlap rule between neighbours) and `network` (the DC traction
// network solved by a load flow at every bin, power/load_flow.hpp).
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "power/power_supply.hpp"

namespace ecorail::energy {

// Which trains' traction a braking train may feed in the overlap model: the train ahead only
// (the contest's rule) or either neighbour (the union of the two traction sets).
enum class OverlapVariant { Ahead, Either };
std::string_view overlap_variant_name(OverlapVariant v);
std::optional<OverlapVariant> overlap_variant_from_name(std::string_view name);

struct EnergyModelOptions {
  // A registered model's name (energy/model_registry.hpp).
  std::string model = "power-flow";
  OverlapVariant overlap = OverlapVariant::Ahead;  // overlap model
  // Time step of the time-binned models (power-flow, sections, network); must divide one
  // second. The default comes from the convergence study in docs/fleet.md; the network model's
  // own default is kNetworkTimeStep_s.
  double time_step_s = 0.01;
  // Supply-section boundaries along the run (m from the first station), sections model only.
  std::vector<double> section_boundaries_m;
  // Network model: the line's power supply and the trains' traction efficiency (wheel power /
  // electrical input; the train's own).
  std::shared_ptr<const power::PowerSupply> power_supply;
  double traction_efficiency = 1.0;
  // Checks the fields every model reads; the model checks its own (a registered name, the
  // supply of the network model) when it is built.
  bool IsValid(std::string* error) const;
  // Bins per second of the time grid.
  int ticks_per_second() const;
};

// Default step of the network model (convergence study in docs/power_network.md).
inline constexpr double kNetworkTimeStep_s = 0.1;

// The fleet a model prices: `trains` trains departing at whole seconds from t_1 = 0 to
// t_N = span_s, every headway within [headway_min_s, headway_max_s]. A problem with peak
// classes gives the one range covering both classes: a lower bound is valid on that relaxation,
// so on every timetable of the problem.
struct FleetLimits {
  int trains = 100;
  int span_s = 63900;
  int headway_min_s = 120;
  int headway_max_s = 660;
  // Headway classes the range relaxes: 1, or 2 when it covers a peak and an off-peak range
  // (a bound that gains nothing on the relaxation may then leave itself out).
  int headway_classes = 1;
  // Why the departures break the limits ("" when they keep them).
  std::string departures_problem(const std::vector<int>& departures_s) const;
};

}  // namespace ecorail::energy
