// The JSON reports of the single-train jobs (a section, a journey, a journey with timing points,
// a flat-out run, frontiers) assembled in one place, so the ecorail program's --json and the
// Python module's to_dict() are the same document: the library's builders (run_json,
// journey_json, frontier_json) plus the notes, auxiliary energy and provenance each job adds.
// Keys are the contract of docs/outputs.md.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "data/line.hpp"
#include "dp/journey.hpp"
#include "dp/regimes.hpp"
#include "dp/section_solve.hpp"
#include "dp/timing_journey.hpp"
#include "output/frontier_io.hpp"
#include "output/journey_json.hpp"
#include "physics/route.hpp"
#include "physics/simulator.hpp"
#include "physics/train.hpp"

namespace ecorail::output {

// What a report's provenance names besides the data's checksums: where line and train came
// from ("embedded" for the reference data compiled in), the run's ends, the objective's name
// and the grid.
struct RunInputs {
  std::string line = "embedded";
  std::string train = "embedded";
  std::string from, to;
  std::string objective = "traction";
  double ds_m = 5.0;
  double dv_kmh = 0.2;
};

// The "provenance" of a report (output/provenance.hpp) with extra_options (running time,
// dwells, split...) added to the options.
nlohmann::json run_provenance_json(const data::Line& line, const physics::Train& train,
                                   const RunInputs& inputs,
                                   const nlohmann::json& extra_options = nlohmann::json::object());

// The note a report carries when the line allows more than the train can run on the way from
// stops.front() to stops.back(): those limits are capped at the train's maximum speed
// (data::build_route). Empty when no limit is capped.
std::string speed_cap_note(const data::Line& line, const std::vector<std::string>& stops,
                           const physics::Train& train);

// `solve` of one section: section_solution_json plus notes, auxiliary energy and provenance.
nlohmann::json section_report_json(const dp::SectionSolution& solution, const physics::Train& train,
                                   const std::string& cap_note, const nlohmann::json& provenance);
// `solve` of a journey: journey_json plus provenance, notes, auxiliary energy over the trip
// time and, with a minimum regime, what merging cost.
nlohmann::json journey_report_json(const dp::JourneySolution& solution, const JourneyLabels& labels,
                                   const physics::Train& train, const std::string& cap_note,
                                   const dp::MinRegimeOptions& min_regime,
                                   const nlohmann::json& provenance);
// `solve --journey`: the journey keys plus windows_met, windows, trip_time_s, departure_s and
// parts (docs/ttobench.md).
nlohmann::json timing_journey_report_json(const dp::TimingJourneySolution& solution,
                                          const std::string& journey_id, double ds_m, double dv_kmh,
                                          const nlohmann::json& provenance);
// The stop labels of a timing journey's parts ("123.4 m"), as its report names them.
std::vector<std::string> timing_journey_stops(const dp::TimingJourneySolution& solution);
// `min-time`: the flat-out run with its ends, distance and minimum running time.
nlohmann::json min_time_report_json(const physics::Route& route,
                                    const physics::SimulationResult& sim,
                                    const physics::Train& train, const nlohmann::json& provenance);
// `frontier`: one section's frontier_json, or {"frontiers": [...]} with all; plus grid and
// provenance.
nlohmann::json frontier_report_json(const std::vector<LabelledFrontier>& frontiers, bool all,
                                    double ds_m, double dv_kmh, const nlohmann::json& provenance);

}  // namespace ecorail::output
