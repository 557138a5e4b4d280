// The fleet energy models by name: the one place that lists them. `make_energy_model` builds the
// model EnergyModelOptions::model names; the CLI's `--model` values and its help come from here.
// Adding a model: its own files (a FleetEnergyModel, energy/fleet_energy_model.hpp), one line in
// the table of model_registry.cpp, and its tests; a model used only by a program or a test is
// added at run time by register_energy_model.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "energy/fleet_energy_model.hpp"

namespace ecorail::energy {

using ModelFactory = std::function<std::unique_ptr<FleetEnergyModel>(
    const physics::Trip& trip, const FleetLimits& limits, const EnergyModelOptions& options)>;

struct RegisteredModel {
  std::string name;     // EnergyModelOptions::model, the CLI's --model value
  std::string summary;  // one line for the help
  ModelFactory make;
};

// Every registered model, in the order of registration (the built-in ones first).
std::vector<RegisteredModel> energy_models();
// "power-flow, overlap, sections or network" (and any registered after them).
std::string energy_model_names();
bool is_energy_model(const std::string& name);
// Adds a model; std::invalid_argument when the name is taken or empty.
void register_energy_model(RegisteredModel model);
// The model options.model names, for this trip and fleet; std::invalid_argument for an unknown
// name or invalid options.
std::unique_ptr<FleetEnergyModel> make_energy_model(const physics::Trip& trip,
                                                    const FleetLimits& limits,
                                                    const EnergyModelOptions& options);

}  // namespace ecorail::energy
