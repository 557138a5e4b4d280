// JSON reports of runs: the keys are a contract with users and reviewers (see docs/outputs.md);
// new keys may be added, none renamed. All figures come from the re-simulated run.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <ostream>
#include <vector>

#include "dp/regimes.hpp"
#include "dp/section_solve.hpp"
#include "physics/simulator.hpp"
#include "physics/train.hpp"

namespace ecorail::output {

nlohmann::json regimes_json(const std::vector<dp::RegimeSpan>& spans);
// Energies, time, stop error, overspeed and regimes of a re-simulated run; the regime spans are
// taken from the trace unless the caller already has them.
// Energy of the train's constant auxiliary power over on_line_s (running time and dwells): the
// same for every way of driving in that time, so reported beside the optimum, not in it.
double auxiliary_energy_kJ(const physics::Train& train, double on_line_s);

nlohmann::json run_json(const physics::SimulationResult& sim);
nlohmann::json run_json(const physics::SimulationResult& sim,
                        const std::vector<dp::RegimeSpan>& spans);
// The full report of a single-section solve.
nlohmann::json section_solution_json(const dp::SectionSolution& solution);
// Writes a JSON document (indented, newline-terminated) atomically.
void write_json(const std::filesystem::path& path, const nlohmann::json& document);
// The same text on a stream (for data::OutputBatch).
void write_json(std::ostream& out, const nlohmann::json& document);

}  // namespace ecorail::output
