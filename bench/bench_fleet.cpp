// Speed of the fleet timetable work on question 2.1's reference case (100 trains, span 63900 s,
// headways 120-660 s, the reference pattern: 30 s dwells, optimal split of 1726 s running):
// one full power-flow evaluation at the default 0.01 s step (laying 100 trains into an empty
// balance), one incremental move of one train (and back), a proposal moved and undone against
// one priced without moving, the exact overlap DPs (train ahead;
// either neighbour), the pair bound, and the whole power-flow headway optimisation with its
// defaults. The pattern is built once, outside the timings.
// Run: build/bench/bench_fleet --benchmark_min_time=1
#include <benchmark/benchmark.h>

#include <filesystem>
#include <map>
#include <memory>
#include <string>

#include "data/line_loader.hpp"
#include "data/route_builder.hpp"
#include "data/train_io.hpp"
#include "energy/fleet_energy_model.hpp"
#include "energy/network_bound.hpp"
#include "energy/network_model.hpp"
#include "energy/pair_bound.hpp"
#include "energy/power_flow_model.hpp"
#include "fleet/fleet_pattern.hpp"
#include "fleet/headway_optimiser.hpp"
#include "fleet/pattern_search.hpp"
#include "power/network_balance.hpp"
#include "power/network_evaluation.hpp"
#include "power/supply_loader.hpp"
#include "reference_pattern.hpp"

namespace {

using namespace ecorail;

const fleet::PatternTrip& pattern() {
  return bench::reference_pattern();
}

// The reference fleet's model of that name (and overlap variant), built once.
const energy::FleetEnergyModel& models(const std::string& model, energy::OverlapVariant variant) {
  static std::map<std::string, std::unique_ptr<energy::FleetEnergyModel>> cache;
  auto& slot = cache[model + std::string(energy::overlap_variant_name(variant))];
  if (!slot) {
    energy::EnergyModelOptions o;
    o.model = model;
    o.overlap = variant;
    slot = fleet::make_model(pattern().trip, fleet::FleetProblem{}, o);
  }
  return *slot;
}

const energy::PowerFlowModel& power_flow() {
  return dynamic_cast<const energy::PowerFlowModel&>(
      models("power-flow", energy::OverlapVariant::Ahead));
}

std::vector<int> uniform() {
  return fleet::departures_from_headways(fleet::uniform_headways({}));
}

void BM_FullEvaluation(benchmark::State& state) {
  auto balance = power_flow().make_power_balance();
  const auto t = uniform();
  for (auto _ : state) {
    balance->place_all(t);  // removes the previous placement, lays all 100 trains again
    benchmark::DoNotOptimize(balance->used());
  }
}
BENCHMARK(BM_FullEvaluation)->Unit(benchmark::kMillisecond);

void BM_IncrementalMove(benchmark::State& state) {
  auto balance = power_flow().make_power_balance();
  const auto t = uniform();
  balance->place_all(t);
  int k = 1;
  for (auto _ : state) {
    benchmark::DoNotOptimize(balance->move(k, t[k] + 1));
    benchmark::DoNotOptimize(balance->move(k, t[k]));
    k = k % 98 + 1;
  }
  state.SetItemsProcessed(2 * state.iterations());  // moves
}
BENCHMARK(BM_IncrementalMove)->Unit(benchmark::kMicrosecond);

// What the annealing and the polish pay per proposal: a move of one train by `shift` seconds
// and its undo (4 passes over the train's bins), against its price without moving
// (used_change_if_moved: one read-only pass over the shifted profile's regions). Argument 0:
// the annealing's 1 s grid, 1: the model's 0.01 s grid; second argument the shift.
// The uniform timetable laid on the grid of argument 0 (the model lives as long as the balance).
struct ProposalSetup {
  std::unique_ptr<energy::FleetEnergyModel> model;
  std::unique_ptr<energy::PowerBalance> balance;
  std::vector<int> t = uniform();
  explicit ProposalSetup(const benchmark::State& state)
      : model(power_flow().on_grid(state.range(0) == 0 ? 1.0 : 0.01)),
        balance(dynamic_cast<const energy::PowerFlowModel&>(*model).make_power_balance()) {
    balance->place_all(t);
  }
};

void BM_ProposalMoveAndUndo(benchmark::State& state) {
  ProposalSetup setup(state);
  auto& balance = setup.balance;
  const auto& t = setup.t;
  const int shift = static_cast<int>(state.range(1));
  int k = 1;
  for (auto _ : state) {
    benchmark::DoNotOptimize(balance->move(k, t[k] + shift));
    benchmark::DoNotOptimize(balance->move(k, t[k]));
    k = k % 98 + 1;
  }
  state.SetItemsProcessed(state.iterations());  // proposals
}
BENCHMARK(BM_ProposalMoveAndUndo)->Args({0, 7})->Args({1, 7})->Unit(benchmark::kMicrosecond);

void BM_ProposalPriced(benchmark::State& state) {
  ProposalSetup setup(state);
  const auto& balance = setup.balance;
  const auto& t = setup.t;
  const int shift = static_cast<int>(state.range(1));
  int k = 1;
  for (auto _ : state) {
    benchmark::DoNotOptimize(balance->used_change_if_moved(k, t[k] + shift));
    k = k % 98 + 1;
  }
  state.SetItemsProcessed(state.iterations());  // proposals
}
BENCHMARK(BM_ProposalPriced)->Args({0, 7})->Args({1, 7})->Unit(benchmark::kMicrosecond);

void BM_OverlapExactDp(benchmark::State& state) {
  const auto variant =
      state.range(0) == 0 ? energy::OverlapVariant::Ahead : energy::OverlapVariant::Either;
  const auto& m = models("overlap", variant);
  for (auto _ : state) benchmark::DoNotOptimize(fleet::optimise_headways(m, {}, {}));
}
BENCHMARK(BM_OverlapExactDp)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->Iterations(1);

void BM_PairBound(benchmark::State& state) {
  for (auto _ : state)
    benchmark::DoNotOptimize(
        energy::used_regen_bound(power_flow().profile(), power_flow().limits()));
}
BENCHMARK(BM_PairBound)->Unit(benchmark::kMillisecond)->Iterations(1);

void BM_PowerFlowOptimisation(benchmark::State& state) {
  for (auto _ : state) {
    const auto r = fleet::optimise_headways(power_flow(), {}, {});
    state.counters["used_regen_kJ"] = r.summary.used_regen_J / 1e3;
    state.counters["gap_pct"] = 100.0 * r.summary.gap_fraction;
  }
}
BENCHMARK(BM_PowerFlowOptimisation)->Unit(benchmark::kSecond)->Iterations(1);

}  // namespace

// The network model (docs/power_network.md): a day of 100 trains at 0.1 s (659 961 instants,
// each a DC load flow with the example supply data/contest/power_supply.toml) evaluated in
// full on all threads (Arg: thread count), and one incremental move of one train and back
// (each re-solves the instants of the train's old and new runs, 2 x ~20 900).
const energy::NetworkModel& network_models() {
  static const std::unique_ptr<energy::NetworkModel> m = [] {
    energy::EnergyModelOptions o;
    o.model = "network";
    o.time_step_s = energy::kNetworkTimeStep_s;
    // Run from the source tree's root (or next to this file's tree).
    std::filesystem::path file = "data/contest/power_supply.toml";
    if (!std::filesystem::exists(file))
      file = std::filesystem::path(__FILE__).parent_path().parent_path() / file;
    o.power_supply =
        std::make_shared<const power::PowerSupply>(power::load_power_supply(file.string()));
    return std::make_unique<energy::NetworkModel>(pattern().trip,
                                                  fleet::limits_of(fleet::FleetProblem{}), o);
  }();
  return *m;
}

void BM_NetworkDay(benchmark::State& state) {
  const auto setup = network_models().network_setup(static_cast<int>(state.range(0)));
  const auto t = uniform();
  for (auto _ : state) {
    const auto e = power::evaluate_network(setup, t);
    benchmark::DoNotOptimize(e.substation_J);
  }
  state.SetItemsProcessed(state.iterations() * 659961);  // instants
}
BENCHMARK(BM_NetworkDay)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_NetworkMove(benchmark::State& state) {
  const auto setup = network_models().network_setup(1);
  power::NetworkBalance balance(*setup.profile, *setup.supply, 1.0, 100, setup.horizon_s, 2);
  const auto t = uniform();
  balance.place_all(t);
  int k = 1;
  for (auto _ : state) {
    benchmark::DoNotOptimize(balance.move(k, t[k] + 1));
    benchmark::DoNotOptimize(balance.move(k, t[k]));
    k = k % 98 + 1;
  }
  state.SetItemsProcessed(2 * state.iterations());  // moves
}
BENCHMARK(BM_NetworkMove)->Unit(benchmark::kMillisecond);

// What the pattern search pays to screen one candidate pattern under the network model: the
// trip's profile on the 1 s grid and the whole day laid out on it (2 threads).
void BM_NetworkPatternScreen(benchmark::State& state) {
  const auto setup = network_models().network_setup(2);
  const auto t = uniform();
  for (auto _ : state) {
    const power::NetworkProfile coarse(pattern().trip, 1);
    power::NetworkBalance balance(coarse, *setup.supply, 1.0, 100, setup.horizon_s, 2);
    balance.place_all(t);
    benchmark::DoNotOptimize(balance.substation());
  }
}
BENCHMARK(BM_NetworkPatternScreen)->Unit(benchmark::kMillisecond)->UseRealTime();

// The network optimiser's lower bound for the reference day (network_bound.hpp).
void BM_NetworkBound(benchmark::State& state) {
  const auto& m = network_models();
  for (auto _ : state) {
    benchmark::DoNotOptimize(energy::network_substation_bound(
        m.network_profile(), *m.options().power_supply, 1.0, m.limits()));
  }
}
BENCHMARK(BM_NetworkBound)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
