#include "energy/fleet_energy_model.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "dp/resource_estimate.hpp"

namespace ecorail::energy {

void FleetBalance::substation_at(int train, int placed_at_s, const std::vector<int>& departures_s,
                                 std::vector<MicroJoules>& substation_J) {
  substation_J.resize(departures_s.size());
  if (departures_s.empty()) return;
  for (std::size_t i = 0; i < departures_s.size(); ++i) {
    move(train, departures_s[i]);
    substation_J[i] = substation();
  }
  move(train, placed_at_s);
}

MicroJoules FleetBalance::change_if_moved(int train, int placed_at_s, int departure_s) {
  const MicroJoules change = move(train, departure_s);
  move(train, placed_at_s);
  return change;
}

MicroJoules FleetBalance::substation_change_if(int, const physics::Trip&) const {
  throw std::logic_error("this model's balance lays one trip under every train");
}

void FleetBalance::set_trip(int, const physics::Trip&) {
  throw std::logic_error("this model's balance lays one trip under every train");
}

FleetEvaluation FleetBalance::evaluation() const {
  throw std::logic_error("this model's balance gives no account of its own");
}

FleetEnergyModel::FleetEnergyModel(const physics::Trip& trip, const FleetLimits& limits,
                                   const EnergyModelOptions& options)
    : trip_(trip), limits_(limits), options_(options) {
  std::string why;
  if (!options_.IsValid(&why)) throw std::invalid_argument(why);
  if (limits_.trains < 1) throw std::invalid_argument("trains: expected at least 1");
}

std::unique_ptr<FleetEnergyModel> FleetEnergyModel::with_trip(const physics::Trip& trip) const {
  return rebuilt(trip, limits_, options_);
}

std::unique_ptr<FleetEnergyModel> FleetEnergyModel::on_grid(double step_s) const {
  EnergyModelOptions o = options_;
  o.time_step_s = std::max(options_.time_step_s, step_s);
  return rebuilt(trip_, limits_, o);
}

std::unique_ptr<FleetBalance> FleetEnergyModel::make_balance(int) const {
  return nullptr;
}

std::optional<HeadwayDecomposition> FleetEnergyModel::headway_decomposition() const {
  return std::nullopt;
}

std::vector<double> FleetEnergyModel::two_train_values_J(int lo_s, int hi_s, int) const {
  // Two trains alone: the model's own account of a two-train fleet.
  FleetLimits two = limits_;
  two.trains = 2;
  std::vector<double> out;
  for (int h = lo_s; h <= hi_s; ++h) {
    two.span_s = two.headway_min_s = two.headway_max_s = h;
    out.push_back(-rebuilt(trip_, two, options_)->evaluate({0, h}).total.substation_J());
  }
  return out;
}

FleetLowerBound FleetEnergyModel::lower_bound(const std::function<bool()>&) const {
  return {};
}

double FleetEnergyModel::gap_fraction(const FleetEvaluation& result,
                                      const FleetLowerBound& bound) const {
  const double substation = result.total.substation_J();
  if (bound.used_regen_J == bound.used_regen_J)
    return (bound.used_regen_J - result.total.used_regen_J) / substation;
  const double curtailed = result.network ? result.network->curtailed_traction_J : 0.0;
  return (substation + curtailed - bound.substation_J) / substation;
}

double FleetEnergyModel::pair_sum_J(const std::vector<int>&) const {
  return 0.0;
}

std::optional<double> FleetEnergyModel::substation_without_reuse_J(const std::vector<int>&) const {
  return std::nullopt;
}

SearchPlan FleetEnergyModel::search_plan() const {
  SearchPlan plan;
  plan.polish = {{0.1, -1, 50, false}, {0.0, 3, 50, false}};
  return plan;
}

namespace {

// Every candidate evaluated afresh for the whole fleet.
class FreshPricer : public TripPricer {
 public:
  FreshPricer(const FleetEnergyModel& model, std::vector<int> departures)
      : model_(model), departures_(std::move(departures)) {}
  std::optional<double> substation_J(const physics::Trip& trip) override {
    ++full_evaluations_;
    return model_.with_trip(trip)->evaluate(departures_).total.substation_J();
  }
  void accept() override {}

 private:
  const FleetEnergyModel& model_;
  std::vector<int> departures_;
};

}  // namespace

std::unique_ptr<TripPricer> FleetEnergyModel::make_trip_pricer(const std::vector<int>& departures_s,
                                                               double, int) const {
  return std::make_unique<FreshPricer>(*this, departures_s);
}

void FleetEnergyModel::check_departures(const std::vector<int>& departures_s) const {
  const std::string why = limits_.departures_problem(departures_s);
  if (!why.empty()) throw std::invalid_argument(why);
}

double FleetEnergyModel::horizon_bins() const {
  return std::ceil(horizon_s() * options_.ticks_per_second());
}

double FleetEnergyModel::trip_bins() const {
  return std::ceil((trip_.arrival_s() + 1.0) * options_.ticks_per_second());
}

void FleetEnergyModel::check_memory(double bytes, const std::string& what) const {
  // A quarter: the searches hold a balance per thread beside the trip's own bins.
  const double limit = 0.25 * dp::memory_limit_bytes();
  if (bytes <= limit) return;
  char buf[512];
  std::snprintf(buf, sizeof buf,
                "%s on a %g s grid needs about %.1f GB, more than a quarter of the %.1f GB "
                "this process can have: a coarser time step",
                what.c_str(), options_.time_step_s, bytes / 1e9, 4.0 * limit / 1e9);
  throw dp::ResourceLimitError(buf);
}

std::vector<int> FleetEnergyModel::refined_headways_s(const std::vector<int>&, int, double) const {
  return {};
}

ExactPartOptimum FleetEnergyModel::exact_part_optimum(const std::vector<int>&, int, double) const {
  ExactPartOptimum out;
  out.why_not = "the " + std::string(name()) + " model has no exact search on part of its domain";
  return out;
}

}  // namespace ecorail::energy
