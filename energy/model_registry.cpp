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
      {"power-flow", "one supply section, min(regenerated, traction) power per time bin",
       factory<PowerFlowModel>()},
      {"overlap", "the contest's time-overlap rule between neighbours (exact intervals)",
       factory<OverlapEnergyModel>()},
      {"sections", "the power-flow balance in each supply section (--sections-at)",
       factory<PowerFlowModel>()},
      {"network", "the DC traction network, a load flow at every time bin (--power-supply)",
       factory<NetworkModel>()},
  };
  return models;
}

}  // namespace

std::vector<RegisteredModel> energy_models() {
  const std::lock_guard<std::mutex> lock(registry_mutex());
  return registry();
}

std::string energy_model_names() {
  const std::vector<RegisteredModel> models = energy_models();
  std::string out;
  for (std::size_t i = 0; i < models.size(); ++i) {
    if (i > 0) out += i + 1 == models.size() ? " or " : ", ";
    out += models[i].name;
  }
  return out;
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
