// FleetModels: the energy models of a fleet whose trains all run one pattern, built once from
// the pattern's trip and evaluated for any departures. The overlap model works on the trip's
// exact traction and braking intervals; power-flow and sections lay the trip's power profile
// (power_profile.hpp) on the time grid of the chosen step. evaluate() gives the fleet's totals,
// per train (used energy attributed to the braking train) and per supply section.
#pragma once

#include <memory>
#include <vector>

#include "timetable/fleet_problem.hpp"
#include "timetable/network_evaluation.hpp"
#include "timetable/network_profile.hpp"
#include "timetable/overlap_model.hpp"
#include "timetable/power_balance.hpp"
#include "timetable/power_profile.hpp"

namespace ecorail::timetable {

struct FleetEvaluation {
  EnergyModel model = EnergyModel::PowerFlow;
  OverlapVariant overlap = OverlapVariant::Ahead;
  double time_step_s = 0.0;  // power-flow and sections; 0 for overlap (exact intervals)
  std::vector<int> departures_s;
  FleetEnergy total;
  std::vector<FleetEnergy> per_train;
  std::vector<FleetEnergy> per_section;  // sections model (one entry for power-flow)
  // Network model: the full account; total.used_regen_J is then traction at the wheel less the
  // substation energy (so total.substation_J() is the substations' energy), the regenerated
  // energy that entered the line is network->used_regen_J.
  std::shared_ptr<const NetworkEvaluation> network;
};

// A trip's power profile on the grid and supply sections of the chosen model (power-flow and
// sections models).
std::unique_ptr<PowerProfile> make_profile(const physics::Trip& trip,
                                           const EnergyModelOptions& options);

class FleetModels {
 public:
  FleetModels(const physics::Trip& trip, const FleetProblem& problem,
              const EnergyModelOptions& options);

  const FleetProblem& problem() const { return problem_; }
  const EnergyModelOptions& options() const { return options_; }
  const physics::Trip& trip() const { return trip_; }
  const OverlapModel& overlap() const { return overlap_; }
  // Power profile on the options' grid (power-flow and sections models).
  const PowerProfile& profile() const { return *profile_; }
  // Network model: the trip on the options' grid and what the load flows need.
  const NetworkProfile& network_profile() const { return *network_profile_; }
  NetworkSetup network_setup(int threads = 0) const;
  // An empty power balance for every train of the problem on the options' grid.
  std::unique_ptr<PowerBalance> make_balance() const;
  // An empty power balance whose trains run profiles of their own (one per train, on the
  // options' grid, kept alive by the caller), e.g. per-train patterns.
  std::unique_ptr<PowerBalance> make_balance(std::vector<const PowerProfile*> profiles) const;

  // Departures must keep the problem's rules (departures_problem); std::invalid_argument if not.
  FleetEvaluation evaluate(const std::vector<int>& departures_s) const;
  // The evaluation of a balance already laid out (power-flow and sections models), e.g. one
  // whose trains run patterns of their own.
  FleetEvaluation evaluation_of(const PowerBalance& balance) const;

 private:
  physics::Trip trip_;
  FleetProblem problem_;
  EnergyModelOptions options_;
  OverlapModel overlap_;
  std::unique_ptr<PowerProfile> profile_;
  std::unique_ptr<NetworkProfile> network_profile_;
};

}  // namespace ecorail::timetable
