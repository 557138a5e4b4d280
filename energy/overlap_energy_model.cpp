#include "energy/overlap_energy_model.hpp"

namespace ecorail::energy {

OverlapEnergyModel::OverlapEnergyModel(const physics::Trip& trip, const FleetLimits& limits,
                                       const EnergyModelOptions& options)
    : FleetEnergyModel(trip, limits, options), overlap_(trip) {}

FleetEvaluation OverlapEnergyModel::evaluate(const std::vector<int>& departures_s) const {
  check_departures(departures_s);
  const OverlapVariant variant = options().overlap;
  FleetEvaluation out;
  out.model = name();
  out.overlap_variant = overlap_variant_name(variant);
  out.departures_s = departures_s;
  out.total = overlap_.evaluate(departures_s, variant);
  for (std::size_t k = 0; k < departures_s.size(); ++k) {
    out.per_train.push_back({overlap_.trip_traction_J(), overlap_.trip_regen_J(),
                             overlap_.train_used_J(departures_s, k, variant)});
  }
  return out;
}

std::unique_ptr<FleetEnergyModel> OverlapEnergyModel::rebuilt(
    const physics::Trip& trip, const FleetLimits& limits, const EnergyModelOptions& options) const {
  return std::make_unique<OverlapEnergyModel>(trip, limits, options);
}

std::optional<HeadwayDecomposition> OverlapEnergyModel::headway_decomposition() const {
  const OverlapModel* ov = &overlap_;
  HeadwayDecomposition d;
  if (options().overlap == OverlapVariant::Ahead) {
    d.value_J = [ov](int h) { return ov->used_from_ahead_J(h); };
    d.what = "overlap, train ahead";
  } else {
    d.value_J = [ov](int h) { return ov->used_from_ahead_J(h) + ov->used_from_behind_J(h); };
    d.penalty_J = [ov](int a, int b) { return ov->double_count_J(a, b); };
    d.what = "overlap, either neighbour";
  }
  return d;
}

std::vector<double> OverlapEnergyModel::two_train_values_J(int lo_s, int hi_s, int) const {
  std::vector<double> out;
  for (int h = lo_s; h <= hi_s; ++h)
    out.push_back(overlap_.evaluate({0, h}, options().overlap).used_regen_J);
  return out;
}

}  // namespace ecorail::energy
