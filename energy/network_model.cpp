#include "energy/network_model.hpp"

#include <cmath>
#include <stdexcept>

#include "energy/network_bound.hpp"
#include "energy/power_flow_model.hpp"
#include "power/network_balance.hpp"

namespace ecorail::energy {

namespace {

class NetworkFleetBalance : public FleetBalance {
 public:
  NetworkFleetBalance(const NetworkModel& model, int threads)
      : balance_(model.network_profile(), *model.options().power_supply,
                 model.options().traction_efficiency, model.limits().trains, model.horizon_s(),
                 threads) {}
  int trains() const override { return balance_.trains(); }
  void place_all(const std::vector<int>& departures_s) override {
    balance_.place_all(departures_s);
  }
  MicroJoules move(int train, int departure_s) override {
    return balance_.move(train, departure_s);
  }
  MicroJoules substation() const override { return balance_.substation(); }
  long unsolved_bins() const override { return balance_.unsolved_bins(); }

 private:
  power::NetworkBalance balance_;
};

// An improvement smaller than this is a rounding wobble (the pattern search's own threshold).
constexpr double kScreenImprovementJ = 1.0;

// Candidate trips screened on a coarse grid (a tenth of the load flows at 1 s); only one better
// there is evaluated in full on the model's own grid.
class NetworkPricer : public TripPricer {
 public:
  NetworkPricer(const NetworkModel& model, std::vector<int> departures, double screen_step_s,
                int threads)
      : model_(model), departures_(std::move(departures)), threads_(threads) {
    screen_ = model.options();
    screen_.time_step_s = std::max(screen_.time_step_s, screen_step_s);
    best_coarse_ = coarse(model.trip());
  }
  std::optional<double> substation_J(const physics::Trip& trip) override {
    coarse_ = coarse(trip);
    if (!(coarse_ < best_coarse_ - kScreenImprovementJ)) return std::nullopt;
    ++full_evaluations_;
    const FleetEvaluation full = model_.with_trip(trip)->evaluate(departures_);
    if (full.network->unsolved_instants > 0) return std::nullopt;  // never a solution
    return full.total.substation_J();
  }
  void accept() override { best_coarse_ = coarse_; }

 private:
  double coarse(const physics::Trip& trip) const {
    const power::NetworkProfile profile(trip, screen_.ticks_per_second());
    power::NetworkBalance balance(profile, *screen_.power_supply, screen_.traction_efficiency,
                                  model_.limits().trains,
                                  model_.limits().span_s + trip.arrival_s() + 10.0, threads_);
    balance.place_all(departures_);
    return balance.unsolved_bins() > 0 ? HUGE_VAL : to_joules(balance.substation());
  }
  const NetworkModel& model_;
  std::vector<int> departures_;
  int threads_;
  EnergyModelOptions screen_;
  double best_coarse_ = 0.0, coarse_ = 0.0;
};

}  // namespace

NetworkModel::NetworkModel(const physics::Trip& trip, const FleetLimits& limits,
                           const EnergyModelOptions& options)
    : FleetEnergyModel(trip, limits, options) {
  if (!options.power_supply)
    throw std::invalid_argument("power_supply: the network model needs a power supply");
  // The profile's four numbers per bin of the trip and the balance's account per bin of the day.
  check_memory(trip_bins() * 4.0 * 8.0 + horizon_bins() * (4.0 * 8.0 + 1.0),
               "the network balance of " + std::to_string(limits.trains) + " trains");
  profile_ = std::make_unique<power::NetworkProfile>(trip, options.ticks_per_second());
}

power::NetworkSetup NetworkModel::network_setup(int threads) const {
  return {profile_.get(), options().power_supply.get(), options().traction_efficiency, horizon_s(),
          threads};
}

FleetEvaluation NetworkModel::evaluate(const std::vector<int>& departures_s) const {
  check_departures(departures_s);
  FleetEvaluation out;
  out.model = name();
  out.departures_s = departures_s;
  out.time_step_s = options().time_step_s;
  auto net = std::make_shared<power::NetworkEvaluation>(
      power::evaluate_network(network_setup(), departures_s));
  const power::NetworkProfile& np = *profile_;
  out.total = {net->traction_wheel_J, net->regen_J, net->traction_wheel_J - net->substation_J};
  for (std::size_t k = 0; k < departures_s.size(); ++k)
    out.per_train.push_back({np.traction_total_J(), np.regen_total_J(),
                             np.regen_total_J() - net->train_curtailed_regen_J[k]});
  out.network = std::move(net);
  return out;
}

std::unique_ptr<FleetEnergyModel> NetworkModel::rebuilt(const physics::Trip& trip,
                                                        const FleetLimits& limits,
                                                        const EnergyModelOptions& options) const {
  return std::make_unique<NetworkModel>(trip, limits, options);
}

std::unique_ptr<FleetBalance> NetworkModel::make_balance(int threads) const {
  return std::make_unique<NetworkFleetBalance>(*this, threads);
}

std::vector<double> NetworkModel::two_train_values_J(int lo_s, int hi_s, int threads) const {
  power::NetworkBalance two(*profile_, *options().power_supply, options().traction_efficiency, 2,
                            hi_s + trip().arrival_s() + 10.0, threads);
  std::vector<double> out;
  for (int h = lo_s; h <= hi_s; ++h) {
    two.place_all({0, h});
    out.push_back(-to_joules(two.substation()));
  }
  return out;
}

FleetLowerBound NetworkModel::lower_bound(const std::function<bool()>& stop) const {
  const NetworkBound nb = network_substation_bound(*profile_, *options().power_supply,
                                                   options().traction_efficiency, limits(), stop);
  FleetLowerBound b;
  b.name = "network bound";
  if (!nb.cut_short.empty()) b.name += ", " + nb.cut_short;
  b.substation_J = nb.substation_J;
  return b;
}

std::optional<double> NetworkModel::substation_without_reuse_J(
    const std::vector<int>& departures_s) const {
  return power::evaluate_network(network_setup(), departures_s, false).substation_J;
}

std::unique_ptr<FleetEnergyModel> NetworkModel::start_proxy() const {
  EnergyModelOptions o;
  o.model = "power-flow";
  o.time_step_s = options().time_step_s;
  return std::make_unique<PowerFlowModel>(trip(), limits(), o);
}

SearchPlan NetworkModel::search_plan() const {
  SearchPlan plan;
  plan.draw_salt = 0x6e6574776f726bULL;
  plan.draw_offset = 64;
  plan.temperature_samples = 16;
  plan.samples_within_move_window = true;
  plan.time_check_every = 16;
  // A polish sweep of a long day on the model's grid costs minutes.
  plan.anneal_share_of_time_limit = 0.6;
  plan.run_without_restarts = true;
  plan.two_train_values_on_search_grid = true;
  plan.price_starts = false;
  plan.polish_every_run = false;
  plan.polish = {{-1.0, -1, 5, false}, {0.0, 2, 3, true}};
  plan.method_note = " on the network model";
  return plan;
}

std::unique_ptr<TripPricer> NetworkModel::make_trip_pricer(const std::vector<int>& departures_s,
                                                           double screen_step_s,
                                                           int threads) const {
  return std::make_unique<NetworkPricer>(*this, departures_s, screen_step_s, threads);
}

}  // namespace ecorail::energy
