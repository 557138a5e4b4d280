#include "energy/model_registry.hpp"

#include <mutex>
#include <stdexcept>

#include "energy/network_model.hpp"
#include "energy/overlap_energy_model.hpp"
#include "energy/power_flow_model.hpp"

namespace ecorail::energy {

namespace {

template <class Model>
ModelFactory factory() {
  return [](const physics::Trip& trip, const FleetLimits& limits,
            const EnergyModelOptions& options) -> std::unique_ptr<FleetEnergyModel> {
    return std::make_unique<Model>(trip, limits, options);
  };
}

std::mutex& registry_mutex() {
  static std::mutex m;
  return m;
}

std::vector<RegisteredModel>& registry() {
  static std::vector<RegisteredModel> models = {
      {"power-flow",
       "one supply section, min(regenerated, traction) power per time bin",
       factory<PowerFlowModel>(),
       {.per_train_trips = true}},
      {"overlap",
       "the contest's time-overlap rule between neighbours (exact intervals)",
       factory<OverlapEnergyModel>(),
       {.overlap_variant = true}},
      {"sections",
       "the power-flow balance in each supply section (--sections-at)",
       factory<PowerFlowModel>(),
       {.section_boundaries = true, .per_train_trips = true}},
      {"network",
       "the DC traction network, a load flow at every time bin (--power-supply)",
       factory<NetworkModel>(),
       {.power_supply = true, .default_time_step_s = kNetworkTimeStep_s}},
  };
  return models;
}

// "a", "a or b", "a, b or c", each between quotes.
std::string listed(const std::vector<std::string>& names, const std::string& quote) {
  std::string out;
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (i > 0) out += i + 1 == names.size() ? " or " : ", ";
    out += quote + names[i] + quote;
  }
  return out;
}

}  // namespace

std::vector<RegisteredModel> energy_models() {
  const std::lock_guard<std::mutex> lock(registry_mutex());
  return registry();
}

std::string energy_model_names() {
  std::vector<std::string> names;
  for (const RegisteredModel& m : energy_models()) names.push_back(m.name);
  return listed(names, "");
}

ModelInputs model_inputs(const std::string& name) {
  for (const RegisteredModel& m : energy_models())
    if (m.name == name) return m.inputs;
  throw std::invalid_argument("model: expected " + energy_model_names() + "; got '" + name + "'");
}

std::string models_with(bool ModelInputs::*input, const std::string& quote) {
  std::vector<std::string> names;
  for (const RegisteredModel& m : energy_models())
    if (m.inputs.*input) names.push_back(m.name);
  return listed(names, quote);
}

bool is_energy_model(const std::string& name) {
  for (const RegisteredModel& m : energy_models())
    if (m.name == name) return true;
  return false;
}

void register_energy_model(RegisteredModel model) {
  if (model.name.empty() || !model.make)
    throw std::invalid_argument("a model needs a name and a factory");
  const std::lock_guard<std::mutex> lock(registry_mutex());
  for (const RegisteredModel& m : registry())
    if (m.name == model.name)
      throw std::invalid_argument("energy model '" + model.name + "' is registered already");
  registry().push_back(std::move(model));
}

std::unique_ptr<FleetEnergyModel> make_energy_model(const physics::Trip& trip,
                                                    const FleetLimits& limits,
                                                    const EnergyModelOptions& options) {
  for (const RegisteredModel& m : energy_models())
    if (m.name == options.model) return m.make(trip, limits, options);
  throw std::invalid_argument("model: expected " + energy_model_names() + "; got '" +
                              options.model + "'");
}

}  // namespace ecorail::energy
