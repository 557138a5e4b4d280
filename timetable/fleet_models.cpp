#include "timetable/fleet_models.hpp"

#include <stdexcept>

namespace ecorail::timetable {

std::unique_ptr<PowerProfile> make_profile(const physics::Trip& trip,
                                           const EnergyModelOptions& options) {
  const std::vector<double> none;
  return std::make_unique<PowerProfile>(
      trip, options.ticks_per_second(),
      options.model == EnergyModel::Sections ? options.section_boundaries_m : none);
}

FleetModels::FleetModels(const physics::Trip& trip, const FleetProblem& problem,
                         const EnergyModelOptions& options)
    : trip_(trip), problem_(problem), options_(options), overlap_(trip) {
  std::string why;
  if (!problem_.IsValid(&why) || !options_.IsValid(&why)) throw std::invalid_argument(why);
  if (options_.model == EnergyModel::Network)
    network_profile_ = std::make_unique<NetworkProfile>(trip_, options_.ticks_per_second());
  else if (options_.model != EnergyModel::Overlap)
    profile_ = make_profile(trip_, options_);
}

NetworkSetup FleetModels::network_setup(int threads) const {
  if (!network_profile_) throw std::logic_error("only the network model has a network setup");
  return {network_profile_.get(), options_.power_supply.get(), options_.traction_efficiency,
          problem_.span_s + trip_.arrival_s() + 10.0, threads};
}

std::unique_ptr<PowerBalance> FleetModels::make_balance() const {
  if (!profile_)
    throw std::logic_error("only the power-flow and sections models have a power balance");
  return make_balance(std::vector<const PowerProfile*>(problem_.trains, profile_.get()));
}

std::unique_ptr<PowerBalance> FleetModels::make_balance(
    std::vector<const PowerProfile*> profiles) const {
  if (profiles.size() != static_cast<std::size_t>(problem_.trains))
    throw std::invalid_argument("one power profile per train expected");
  // Every pattern keeps the trip time, so the pattern's arrival bounds every train's.
  return std::make_unique<PowerBalance>(std::move(profiles),
                                        problem_.span_s + trip_.arrival_s() + 10.0);
}

FleetEvaluation FleetModels::evaluate(const std::vector<int>& departures_s) const {
  const std::string why = departures_problem(problem_, departures_s);
  if (!why.empty()) throw std::invalid_argument(why);
  FleetEvaluation out;
  out.model = options_.model;
  out.overlap = options_.overlap;
  out.departures_s = departures_s;
  if (options_.model == EnergyModel::Overlap) {
    out.total = overlap_.evaluate(departures_s, options_.overlap);
    for (std::size_t k = 0; k < departures_s.size(); ++k) {
      out.per_train.push_back({overlap_.trip_traction_J(), overlap_.trip_regen_J(),
                               overlap_.train_used_J(departures_s, k, options_.overlap)});
    }
    return out;
  }
  if (options_.model == EnergyModel::Network) {
    out.time_step_s = options_.time_step_s;
    auto net = std::make_shared<NetworkEvaluation>(evaluate_network(network_setup(), departures_s));
    const NetworkProfile& np = *network_profile_;
    out.total = {net->traction_wheel_J, net->regen_J, net->traction_wheel_J - net->substation_J};
    for (std::size_t k = 0; k < departures_s.size(); ++k)
      out.per_train.push_back({np.traction_total_J(), np.regen_total_J(),
                               np.regen_total_J() - net->train_curtailed_regen_J[k]});
    out.network = std::move(net);
    return out;
  }
  auto balance = make_balance();
  balance->place_all(departures_s);
  return evaluation_of(*balance);
}

FleetEvaluation FleetModels::evaluation_of(const PowerBalance& balance) const {
  FleetEvaluation out;
  out.model = options_.model;
  out.overlap = options_.overlap;
  out.time_step_s = options_.time_step_s;
  for (int k = 0; k < balance.trains(); ++k) out.departures_s.push_back(balance.departure_s(k));
  out.total = balance.energy();
  out.per_train = balance.train_energy();
  out.per_section = balance.section_energy();
  return out;
}

}  // namespace ecorail::timetable
