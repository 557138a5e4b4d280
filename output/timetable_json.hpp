// The JSON reports of the `timetable` commands (keys in docs/fleet.md and docs/outputs.md): the
// energy breakdown of fleet_energy_json with the pattern, the stations and the network account,
// and for `evaluate` the substation energy without reuse, for `optimise` the bound, the gap, the
// summary and the pattern search's figures. They format what fleet::TimetableStudy computed.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>

#include "fleet/timetable_study.hpp"

namespace ecorail::output {

nlohmann::json timetable_evaluation_json(const fleet::TimetableStudy& study,
                                         const fleet::StudyEvaluation& evaluation);
nlohmann::json timetable_optimisation_json(const fleet::TimetableStudy& study,
                                           const fleet::StudyOptimisation& optimisation,
                                           std::uint64_t seed);

}  // namespace ecorail::output
