// The registry's table of what each model reads (energy::ModelInputs, by which the program and
// the Python module refuse an option the chosen model does not read) agrees with the models the
// registry builds: each built-in model, given exactly the options its row says it reads, is
// built, carries its name, and offers per-train trips exactly when its row says so.
#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "energy/model_registry.hpp"
#include "fleet_fixture.hpp"
#include "power/supply_loader.hpp"

namespace ecorail::fleet {
namespace {

TEST(ModelInputs, TheTableAgreesWithTheModelsItBuilds) {
  const physics::Trip& trip = testing::small_pattern().trip;
  const FleetProblem problem = testing::small_fleet(3, 150, 250, 400);
  const auto supply = std::make_shared<const power::PowerSupply>(power::load_power_supply(
      std::string(ECORAIL_SOURCE_DIR) + "/data/contest/power_supply.toml"));
  int built = 0;
  for (const energy::RegisteredModel& m : energy::energy_models()) {
    energy::EnergyModelOptions o;
    o.model = m.name;
    o.time_step_s = m.inputs.default_time_step_s;
    if (m.inputs.section_boundaries) o.section_boundaries_m = {1000.0};
    if (m.inputs.power_supply) o.power_supply = supply;
    std::string why;
    ASSERT_TRUE(o.IsValid(&why)) << m.name << ": " << why;
    const std::unique_ptr<energy::FleetEnergyModel> model = make_model(trip, problem, o);
    EXPECT_EQ(model->name(), m.name);
    EXPECT_EQ(model->per_train_trips(), m.inputs.per_train_trips) << m.name;
    ++built;
  }
  EXPECT_EQ(built, 4);  // power-flow, overlap, sections, network
}

}  // namespace
}  // namespace ecorail::fleet
