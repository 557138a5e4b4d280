// The network model as a FleetEnergyModel: the fleet on the DC traction power network
// (substations, conductor resistance, rectifier diodes, voltage limits), every bin of the day
// one instant of the load flow (power/load_flow.hpp) with the trains on the line at that bin
// (power/network_evaluation.hpp for the account, power/network_balance.hpp for moves). A move
// re-solves the load flows of the bins the moved train touches, which costs far more than the
// power-flow model's sums: its search plan screens on the annealing's coarse grid, checks the
// clock often, keeps 40 % of a time limit for the polish and polishes only the best run. Its
// lower bound is energy/network_bound.hpp.
#pragma once

#include <memory>
#include <vector>

#include "energy/fleet_energy_model.hpp"
#include "power/network_evaluation.hpp"
#include "power/network_profile.hpp"

namespace ecorail::energy {

class NetworkModel : public FleetEnergyModel {
 public:
  // options.power_supply must be set (std::invalid_argument if not).
  NetworkModel(const physics::Trip& trip, const FleetLimits& limits,
               const EnergyModelOptions& options);
  std::string_view name() const override { return "network"; }
  const power::NetworkProfile& network_profile() const { return *profile_; }
  // What the load flows need besides the departures.
  power::NetworkSetup network_setup(int threads = 0) const;

  FleetEvaluation evaluate(const std::vector<int>& departures_s) const override;
  std::unique_ptr<FleetEnergyModel> rebuilt(const physics::Trip& trip, const FleetLimits& limits,
                                            const EnergyModelOptions& options) const override;
  std::unique_ptr<FleetBalance> make_balance(int threads = 0) const override;
  std::vector<double> two_train_values_J(int lo_s, int hi_s, int threads) const override;
  FleetLowerBound lower_bound(const std::function<bool()>& stop = {}) const override;
  std::optional<double> substation_without_reuse_J(
      const std::vector<int>& departures_s) const override;
  SearchPlan search_plan() const override;
  // The power-flow model of the same trip on the same grid: a load flow costs about a thousand
  // times its balance, too much for the periodic-regime analysis, and on question 2.2's day its
  // optimum's timetable beats the network search's own (docs/power_network.md).
  std::unique_ptr<FleetEnergyModel> start_proxy() const override;
  std::unique_ptr<TripPricer> make_trip_pricer(const std::vector<int>& departures_s,
                                               double screen_step_s, int threads) const override;

 private:
  std::unique_ptr<power::NetworkProfile> profile_;
};

}  // namespace ecorail::energy
