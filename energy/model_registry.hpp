// The fleet energy models by name: the one place that lists them. `make_energy_model` builds the
// model EnergyModelOptions::model names; the CLI's `--model` values and its help come from here,
// and so does what each model reads of EnergyModelOptions (ModelInputs), by which the CLI and
// the Python module refuse an option the chosen model does not read and pick its default step.
// Adding a model: its own files (a FleetEnergyModel, energy/fleet_energy_model.hpp), one line in
// the table of model_registry.cpp, and its tests; a model used only by a program or a test is
// added at run time by register_energy_model.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "energy/fleet_energy_model.hpp"

namespace ecorail::energy {

using ModelFactory = std::function<std::unique_ptr<FleetEnergyModel>(
    const physics::Trip& trip, const FleetLimits& limits, const EnergyModelOptions& options)>;

// What a model reads of EnergyModelOptions besides its step, and what it offers the pattern
// search: a model that does not read an option is never given one.
struct ModelInputs {
  bool overlap_variant = false;       // EnergyModelOptions::overlap
  bool section_boundaries = false;    // EnergyModelOptions::section_boundaries_m, at least one
  bool power_supply = false;          // EnergyModelOptions::power_supply, required
  bool per_train_trips = false;       // prices one train's own trip (per-train patterns)
  double default_time_step_s = 0.01;  // EnergyModelOptions::time_step_s when none is asked for
};

struct RegisteredModel {
  RegisteredModel(std::string name, std::string summary, ModelFactory make, ModelInputs inputs = {})
      : name(std::move(name)), summary(std::move(summary)), make(std::move(make)), inputs(inputs) {}
  std::string name;     // EnergyModelOptions::model, the CLI's --model value
  std::string summary;  // one line for the help
  ModelFactory make;
  ModelInputs inputs;
};

// Every registered model, in the order of registration (the built-in ones first).
std::vector<RegisteredModel> energy_models();
// "power-flow, overlap, sections or network" (and any registered after them).
std::string energy_model_names();
bool is_energy_model(const std::string& name);
// What the model `name` reads; std::invalid_argument for a name that is not registered.
ModelInputs model_inputs(const std::string& name);
// The models that read an input (or offer it), "sections" or "power-flow or sections", each
// name between `quote`s: for the message that refuses the input to another model.
std::string models_with(bool ModelInputs::*input, const std::string& quote = "");
// Adds a model; std::invalid_argument when the name is taken or empty.
void register_energy_model(RegisteredModel model);
// The model options.model names, for this trip and fleet; std::invalid_argument for an unknown
// name or invalid options.
std::unique_ptr<FleetEnergyModel> make_energy_model(const physics::Trip& trip,
                                                    const FleetLimits& limits,
                                                    const EnergyModelOptions& options);

}  // namespace ecorail::energy
