// A small fleet for the fleet and energy-model tests: the reference train on A6 -> A9 (three
// sections, 30 s dwells), its pattern trip with the optimal split of a given trip time, built
// once per test program; TestFleet: a problem with the model its options name, and the
// concrete model's parts the tests look into (a power balance, the overlap tables, the network
// setup).
#pragma once

#include <memory>
#include <vector>

#include "data/line_loader.hpp"
#include "data/route_builder.hpp"
#include "data/train_io.hpp"
#include "dp/section_library.hpp"
#include "energy/model_registry.hpp"
#include "energy/network_bound.hpp"
#include "energy/network_model.hpp"
#include "energy/overlap_energy_model.hpp"
#include "energy/pair_bound.hpp"
#include "energy/power_flow_model.hpp"
#include "fleet/fleet_pattern.hpp"
#include "fleet/fleet_problem.hpp"
#include "fleet/headway_optimiser.hpp"
#include "fleet/pattern_search.hpp"
#include "power/network_balance.hpp"

namespace ecorail::fleet {

using energy::EnergyModelOptions;
using energy::FleetEnergy;
using energy::FleetEvaluation;
using energy::kNetworkTimeStep_s;
using energy::make_profile;
using energy::MicroJoules;
using energy::network_substation_bound;
using energy::NetworkBound;
using energy::OverlapModel;
using energy::OverlapVariant;
using energy::PairBound;
using energy::PowerBalance;
using energy::PowerProfile;
using energy::to_joules;
using energy::used_regen_bound;
using power::evaluate_network;
using power::NetworkBalance;
using power::NetworkProfile;
using power::NetworkSetup;

class TestFleet {
 public:
  TestFleet(const physics::Trip& trip, const FleetProblem& problem,
            const EnergyModelOptions& options)
      : problem_(problem), model_(make_model(trip, problem, options)) {}
  const FleetProblem& problem() const { return problem_; }
  const EnergyModelOptions& options() const { return model_->options(); }
  const energy::FleetEnergyModel& model() const { return *model_; }
  FleetEvaluation evaluate(const std::vector<int>& departures_s) const {
    return model_->evaluate(departures_s);
  }
  const energy::PowerFlowModel& power_flow() const {
    return dynamic_cast<const energy::PowerFlowModel&>(*model_);
  }
  std::unique_ptr<PowerBalance> make_balance() const { return power_flow().make_power_balance(); }
  std::unique_ptr<PowerBalance> make_balance(std::vector<const PowerProfile*> profiles) const {
    return power_flow().make_power_balance(std::move(profiles));
  }
  const PowerProfile& profile() const { return power_flow().profile(); }
  // Used regenerated energy (J) of the power-flow balance with these headways.
  double used_J(const std::vector<int>& headways_s) const {
    auto balance = make_balance();
    balance->place_all(departures_from_headways(headways_s));
    return to_joules(balance->used());
  }
  const energy::OverlapModel& overlap() const {
    return dynamic_cast<const energy::OverlapEnergyModel&>(*model_).overlap();
  }
  NetworkSetup network_setup(int threads = 0) const {
    return dynamic_cast<const energy::NetworkModel&>(*model_).network_setup(threads);
  }
  const NetworkProfile& network_profile() const {
    return dynamic_cast<const energy::NetworkModel&>(*model_).network_profile();
  }

 private:
  FleetProblem problem_;
  std::shared_ptr<const energy::FleetEnergyModel> model_;
};

inline HeadwayOptimiserResult optimise_headways(const TestFleet& fleet,
                                                const HeadwayOptimiserOptions& options) {
  return optimise_headways(fleet.model(), fleet.problem(), options);
}

namespace testing {

inline const dp::SectionLibrary& small_library() {
  static const std::unique_ptr<dp::SectionLibrary> lib = [] {
    const auto line = data::default_line();
    const auto train = data::default_train();
    const auto stops = data::stops_between(line, "A6", "A9");
    return std::make_unique<dp::SectionLibrary>(train, data::build_routes(line, stops, train),
                                                dp::SectionLibraryOptions{});
  }();
  return *lib;
}

// Trip time 480 s: 420 s running over A6 -> A9 (flat out about 360 s) and two 30 s dwells.
inline const PatternTrip& small_pattern() {
  static const PatternTrip pattern = [] {
    dp::JourneyOptions o;
    o.measure_marginals = false;
    return optimal_split_pattern(small_library(), {30.0, 30.0}, 480.0, o);
  }();
  return pattern;
}

// A fleet of the small pattern: trains, headway range and span.
// The models' options on a 0.1 s grid (cheap enough to enumerate small fleets).
inline EnergyModelOptions tenth_of_a_second() {
  EnergyModelOptions o;
  o.time_step_s = 0.1;
  return o;
}

inline FleetProblem small_fleet(int trains, int headway_min_s, int headway_max_s, int span_s) {
  FleetProblem p;
  p.trains = trains;
  p.headway_min_s = headway_min_s;
  p.headway_max_s = headway_max_s;
  p.span_s = span_s;
  return p;
}

}  // namespace testing
}  // namespace ecorail::fleet
