// The overlap model as a FleetEnergyModel: the contest's time-overlap rule between neighbours
// (energy/overlap_model.hpp), exact on the trip's traction and braking intervals. Its used
// energy is a sum over headways (train ahead) or a sum less a double count of consecutive pairs
// (either neighbour), so the searches solve it exactly by a DP over headways and need no
// balance.
#pragma once

#include "energy/fleet_energy_model.hpp"
#include "energy/overlap_model.hpp"

namespace ecorail::energy {

class OverlapEnergyModel : public FleetEnergyModel {
 public:
  OverlapEnergyModel(const physics::Trip& trip, const FleetLimits& limits,
                     const EnergyModelOptions& options);
  std::string_view name() const override { return "overlap"; }
  const OverlapModel& overlap() const { return overlap_; }
  FleetEvaluation evaluate(const std::vector<int>& departures_s) const override;
  std::unique_ptr<FleetEnergyModel> rebuilt(const physics::Trip& trip, const FleetLimits& limits,
                                            const EnergyModelOptions& options) const override;
  std::optional<HeadwayDecomposition> headway_decomposition() const override;
  std::vector<double> two_train_values_J(int lo_s, int hi_s, int threads) const override;

 private:
  OverlapModel overlap_;
};

}  // namespace ecorail::energy
