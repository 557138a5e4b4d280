// Journeys: one train over several consecutive sections with dwells between them and one total
// running time (dwells excluded, as the published problem counts it). With the optimal split,
// a single time price lambda applies to every section, so at the optimum each section's
// marginal energy per second is the same; lambda is searched on the total time of runs
// re-simulated at the search step (0.5 m by default; the best price's runs are then made fine)
// to within half a second, and the rest is closed by trimming one section (first-order neutral,
// as in the single-section search; a search the coarse runs cannot converge runs again on fine
// runs). The proportional split gives each section a share of the time in
// proportion to its length and solves each on its own, for comparison with published methods.
// Every solve returns a JourneySummary (termination, BriefReport, FullReport) like a section's;
// options are checked (IsValid) before any work.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "dp/regimes.hpp"
#include "dp/section_engine.hpp"
#include "dp/section_library.hpp"
#include "dp/termination.hpp"
#include "dp/time_target.hpp"
#include "physics/trip.hpp"

namespace ecorail::dp {

enum class Split { Optimal, Proportional };

// Names to and from text, in one place: "optimal", "proportional".
inline std::string_view split_name(Split s) {
  return s == Split::Proportional ? "proportional" : "optimal";
}
inline std::optional<Split> split_from_name(std::string_view name) {
  if (name == "optimal") return Split::Optimal;
  if (name == "proportional") return Split::Proportional;
  return std::nullopt;
}

struct JourneyOptions {
  EngineOptions engine;
  TimeSearchOptions search;
  Split split = Split::Optimal;
  // Measure each section's marginal energy per second by re-solving it at +-0.5 s.
  bool measure_marginals = true;
  double marginal_step_s = 0.5;
  // On a library that already holds every section's frontier, start the price search where the
  // frontiers say the price lies (fewer evaluations; the result is still searched on
  // re-simulated runs).
  bool use_frontiers = true;
  // Where the train is in the first section (a restart mid-run): the journey is then the rest
  // of the run, and total_time_s the running time that remains.
  StartState start;
  // A minimum length or duration of the control phases (dp/regimes.hpp): each section's run is
  // merged and trimmed back to its own running time, so the total is kept. None by default.
  MinRegimeOptions min_regime;
  // Checks every field; on failure writes one sentence naming the field into *error.
  bool IsValid(std::string* error) const;
};

struct JourneySection {
  LambdaRun run;
  std::vector<RegimeSpan> regimes;
  double dwell_after_s = 0.0;     // at the section's arrival stop (0 for the last)
  double marginal_J_per_s = 0.0;  // -(dE/dT) measured by re-solving; NaN if not measured
  double min_time_s = 0.0;
};

// The report of a journey, under the same names and units as a section's (SectionSolveSummary:
// kJ, s, km/h, m), with a Termination: CONVERGENCE when every section comes to rest at its stop
// and the total running time is met, NO_CONVERGENCE when the stops are met but not the time,
// FAILURE when a section misses its stop.
struct JourneySummary {
  std::string from, to;  // first and last stop
  int sections = 0;
  Split split = Split::Optimal;
  double distance_m = 0.0;
  double target_time_s = 0.0;
  double min_time_s = 0.0;  // sum of the sections' flat-out runs
  GridSpec grid;
  int threads = 1;
  Objective objective = Objective::Traction;
  double lambda_J_per_s = 0.0;  // NaN for the proportional split
  int lambda_evaluations = 0;
  Termination termination = Termination::FAILURE;
  bool converged() const { return termination == Termination::CONVERGENCE; }
  double build_wall_s = 0.0;
  double search_wall_s = 0.0;
  double total_wall_s = 0.0;
  double running_time_s = 0.0;  // dwells excluded
  double dwell_time_s = 0.0;
  double traction_energy_kJ = 0.0;
  double braking_energy_kJ = 0.0;
  double regen_energy_kJ = 0.0;
  double net_energy_kJ = 0.0;
  double stop_error_m = 0.0;  // the largest of the sections', by size
  double max_overspeed_kmh = 0.0;
  // The library built each section's table per sweep (SectionLibraryOptions::memory_budget_bytes)
  // because all of them together (tables_estimate_bytes) would not fit.
  bool streamed_tables = false;
  double tables_estimate_bytes = 0.0;
  std::vector<std::string> warnings;

  std::string BriefReport() const;
  std::string FullReport() const;
  bool IsSolutionUsable() const { return is_usable(termination); }
};

struct JourneySolution {
  std::vector<JourneySection> sections;
  double lambda_J_per_s = 0.0;  // common price (optimal split); NaN for proportional
  double target_time_s = 0.0;
  double running_time_s = 0.0;  // sum of section times
  double traction_work_J = 0.0;
  double brake_work_J = 0.0;
  double regen_J = 0.0;
  double net_J = 0.0;
  int lambda_evaluations = 0;
  // With a minimum regime: phases merged over all sections and the energy (by the objective)
  // before and after, against the unmerged optimum.
  int merged_regimes = 0;
  double unmerged_cost_J = 0.0, merged_cost_J = 0.0;
  double build_wall_s = 0.0;
  double search_wall_s = 0.0;
  double total_wall_s = 0.0;
  std::vector<std::string> warnings;
  JourneySummary summary;
  // The one verdict is summary.termination; this reads it.
  bool converged() const { return summary.termination == Termination::CONVERGENCE; }
};

// Solves a journey over `routes` (consecutive sections) with `dwells_s[i]` after section i.
// Builds a section library for the routes and solves on it.
JourneySolution solve_journey(const physics::Train& train,
                              const std::vector<physics::Route>& routes,
                              const std::vector<double>& dwells_s, double total_time_s,
                              const JourneyOptions& options);

// A stop's dwell left free within [min_s, max_s].
struct DwellRange {
  double min_s = 0.0;
  double max_s = 0.0;
};

// Free dwells: the trip time (running times plus dwells) is fixed and each dwell may lie in its
// range; the optimum decides running times and dwells together. With no other coupling a
// second of dwell is a second less of running, and energy falls with running time, so every
// dwell goes to its minimum: the journey is solved with the minimum dwells and the running time
// that leaves. (Timetable couplings, such as regenerated energy shared between trains, are what
// make longer dwells worth having; they live in fleet/.)
JourneySolution solve_journey_free_dwells(const SectionLibrary& library, std::size_t first,
                                          std::size_t last, const std::vector<DwellRange>& dwells,
                                          double trip_time_s, const JourneyOptions& options);

// The same over sections [first, last) of a library: engines already built are reused, so a
// second journey on the same library builds nothing.
JourneySolution solve_journey(const SectionLibrary& library, std::size_t first, std::size_t last,
                              const std::vector<double>& dwells_s, double total_time_s,
                              const JourneyOptions& options);

// The journey laid out as one train's trip on a clock, departing at departure_s: the sections'
// re-simulated runs end to end with their dwells (routes: the journey's, one per section).
physics::Trip journey_trip(const JourneySolution& solution,
                           const std::vector<physics::Route>& routes, double departure_s,
                           double regen_efficiency);

}  // namespace ecorail::dp
