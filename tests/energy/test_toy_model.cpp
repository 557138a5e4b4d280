// A fifth energy model added the way docs/fleet.md describes: its own class (here, in the test),
// one registration line, and its tests. The toy model says a braking train feeds the train
// ahead an amount that depends on their headway alone, exchange(h) = max(0, 900 - 10 |h - 150|)
// J, so its used energy is a sum over headways. The searches are written once against
// FleetEnergyModel: the headway optimiser solves it exactly by its DP without knowing the model,
// and the test checks that optimum against every timetable of a small fleet.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <functional>
#include <vector>

#include "energy/model_registry.hpp"
#include "fleet/headway_optimiser.hpp"
#include "fleet/pattern_search.hpp"

namespace ecorail::energy {
namespace {

double exchange_J(int h) {
  return std::max(0.0, 900.0 - 10.0 * std::abs(h - 150));
}

class ToyModel : public FleetEnergyModel {
 public:
  using FleetEnergyModel::FleetEnergyModel;
  std::string_view name() const override { return "toy"; }
  FleetEvaluation evaluate(const std::vector<int>& t) const override {
    check_departures(t);
    FleetEvaluation out;
    out.model = name();
    out.departures_s = t;
    const double n = static_cast<double>(t.size());
    out.total = {10000.0 * n, 1000.0 * n, 0.0};
    for (std::size_t k = 1; k < t.size(); ++k)
      out.total.used_regen_J += exchange_J(t[k] - t[k - 1]);
    return out;
  }
  std::unique_ptr<FleetEnergyModel> rebuilt(const physics::Trip& trip, const FleetLimits& limits,
                                            const EnergyModelOptions& options) const override {
    return std::make_unique<ToyModel>(trip, limits, options);
  }
  std::optional<HeadwayDecomposition> headway_decomposition() const override {
    return HeadwayDecomposition{exchange_J, {}, "toy, train ahead"};
  }
};

// The one registration line (a program would add its model the same way).
const bool registered = [] {
  register_energy_model(
      {"toy", "a test's model: the train ahead takes exchange(h)",
       [](const physics::Trip& trip, const FleetLimits& limits,
          const EnergyModelOptions& options) -> std::unique_ptr<FleetEnergyModel> {
         return std::make_unique<ToyModel>(trip, limits, options);
       }});
  return true;
}();

// A trip with no motion: the toy model does not look at it.
physics::Trip still_trip() {
  return physics::Trip{};
}

TEST(ToyEnergyModel, IsMadeByNameAndListed) {
  ASSERT_TRUE(registered);
  EXPECT_TRUE(is_energy_model("toy"));
  EXPECT_NE(energy_model_names().find("network or toy"), std::string::npos);
  EnergyModelOptions o;
  o.model = "toy";
  const auto model = make_energy_model(still_trip(), {3, 300, 120, 180}, o);
  EXPECT_EQ(model->name(), "toy");
  EXPECT_DOUBLE_EQ(model->evaluate({0, 150, 300}).total.used_regen_J, 1800.0);
  EXPECT_THROW(register_energy_model({"toy", "again", nullptr}), std::invalid_argument);
  o.model = "no-such-model";
  EXPECT_THROW(make_energy_model(still_trip(), {3, 300, 120, 180}, o), std::invalid_argument);
}

// What each model reads comes from the registry's table (the CLI and the Python module refuse
// an option by it): the toy model, registered without inputs, reads none of them.
TEST(ToyEnergyModel, ReadsNoOptionAndTheTableSaysWhatEachModelReads) {
  ASSERT_TRUE(registered);
  const ModelInputs toy = model_inputs("toy");
  EXPECT_FALSE(toy.overlap_variant || toy.section_boundaries || toy.power_supply ||
               toy.per_train_trips);
  EXPECT_EQ(toy.default_time_step_s, 0.01);
  EXPECT_EQ(models_with(&ModelInputs::per_train_trips), "power-flow or sections");
  EXPECT_EQ(models_with(&ModelInputs::overlap_variant), "overlap");
  EXPECT_EQ(models_with(&ModelInputs::power_supply, "'"), "'network'");
  EXPECT_EQ(models_with(&ModelInputs::section_boundaries), "sections");
  EXPECT_EQ(model_inputs("network").default_time_step_s, kNetworkTimeStep_s);
  EXPECT_THROW(model_inputs("no-such-model"), std::invalid_argument);
}

TEST(ToyEnergyModel, HeadwaySearchFindsTheBruteForceOptimum) {
  ASSERT_TRUE(registered);
  fleet::FleetProblem p;
  p.trains = 5;
  p.headway_min_s = 120;
  p.headway_max_s = 200;
  p.span_s = 650;
  EnergyModelOptions o;
  o.model = "toy";
  const auto model = fleet::make_model(still_trip(), p, o);
  const fleet::HeadwayOptimiserResult r = fleet::optimise_headways(*model, p, {});
  // Every timetable: four headways in [120, 200] summing to 650.
  double best = -1.0;
  std::vector<int> h(4);
  std::function<void(int, int)> all = [&](int k, int left) {
    if (k == 3) {
      if (left < 120 || left > 200) return;
      h[3] = left;
      best = std::max(best, model->evaluate(fleet::departures_from_headways(h)).total.used_regen_J);
      return;
    }
    for (int x = 120; x <= 200; ++x) h[k] = x, all(k + 1, left - x);
  };
  all(0, 650);
  EXPECT_DOUBLE_EQ(r.evaluation.total.used_regen_J, best);
  EXPECT_TRUE(r.summary.exact);
  EXPECT_EQ(r.summary.termination, dp::Termination::CONVERGENCE);
  EXPECT_EQ(r.summary.method, "exact DP over the headway sum (toy, train ahead)");
}

}  // namespace
}  // namespace ecorail::energy
