// The power-flow and sections models as FleetEnergyModels. Power-flow: one supply section; in
// every time bin the fleet uses min(regenerated, traction) of its power (the instantaneous power
// balance, energy/power_flow_balance.hpp; not the DC network's load flow, which is the network
// model). Sections: the same balance in each supply section along the line (boundaries from
// EnergyModelOptions::section_boundaries_m). Both lay the trip's power profile
// (energy/power_flow_profile.hpp) on the options' time grid; a move re-adds one train's bins, so
// the balance is cheap and the heuristic search polishes every annealed run. Its lower bound is
// the least of the window bound (energy/window_bound.hpp: one supply section and one headway
// class), the pair bound (energy/pair_bound.hpp), and the regenerated and the traction energy.
#pragma once

#include <memory>
#include <vector>

#include "energy/fleet_energy_model.hpp"
#include "energy/power_flow_balance.hpp"
#include "energy/power_flow_profile.hpp"

namespace ecorail::energy {

// A trip's power profile on the grid (and, for the sections model, the supply sections) of the
// options.
std::unique_ptr<PowerProfile> make_profile(const physics::Trip& trip,
                                           const EnergyModelOptions& options);

class PowerFlowModel : public FleetEnergyModel {
 public:
  PowerFlowModel(const physics::Trip& trip, const FleetLimits& limits,
                 const EnergyModelOptions& options);
  std::string_view name() const override { return options().model; }
  const PowerProfile& profile() const { return *profile_; }
  // An empty power balance for every train (on this model's profile, or on one profile per
  // train kept alive by the caller).
  std::unique_ptr<PowerBalance> make_power_balance() const;
  std::unique_ptr<PowerBalance> make_power_balance(std::vector<const PowerProfile*> profiles) const;
  // The account of a balance already laid out (e.g. with per-train profiles).
  FleetEvaluation evaluation_of(const PowerBalance& balance) const;

  FleetEvaluation evaluate(const std::vector<int>& departures_s) const override;
  std::unique_ptr<FleetEnergyModel> rebuilt(const physics::Trip& trip, const FleetLimits& limits,
                                            const EnergyModelOptions& options) const override;
  std::unique_ptr<FleetBalance> make_balance(int threads = 0) const override;
  bool per_train_trips() const override { return true; }
  std::vector<double> two_train_values_J(int lo_s, int hi_s, int threads) const override;
  FleetLowerBound lower_bound(const std::function<bool()>& stop = {}) const override;
  // The window bound's maximisers in the core (energy/window_bound.hpp).
  std::vector<std::vector<int>> relaxation_maximisers_s(
      const std::function<bool()>& stop = {}) const override;
  // The window terms' exact DP near the sequence (energy/window_refine.hpp).
  std::vector<int> refined_headways_s(const std::vector<int>& headways_s, int threads,
                                      double time_limit_s) const override;
  ExactPartOptimum exact_part_optimum(const std::vector<int>& incumbent_s, int threads,
                                      double time_limit_s) const override;
  double pair_sum_J(const std::vector<int>& departures_s) const override;
  std::unique_ptr<TripPricer> make_trip_pricer(const std::vector<int>& departures_s,
                                               double screen_step_s, int threads) const override;

 private:
  std::unique_ptr<PowerProfile> profile_;
};

}  // namespace ecorail::energy
