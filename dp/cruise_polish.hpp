// Cruise polish: the continuous optimum of a long cruise, after the grid found its shape. On a
// long stretch the grid's optimum cruises, but its cruise is a staircase: a hold, short coasts
// and holds a fraction of a km/h apart, short traction blips (on a 48.5 km level TTOBench run,
// seventeen phases between 38 and 40 km). Each phase is the grid's, so the pair that matters,
// the hold speed (where the traction phase before the hold ends) and where the final coast
// starts, sits where the grid put it; the running-time trim then moves the hold speed alone.
// The polish makes the cruise one hold: every phase shorter than short_phase_m between the
// first and the last hold is dropped (the hold goes on), and then the coasting point is chosen
// by a golden-section search along the running-time constraint: for each coasting point the
// hold speed is solved (secant on the re-simulated time) so the time is met, and the run with
// the least energy cost is kept. The search re-simulates at search_step_m; the best run is
// re-simulated at the engine's fine step and trimmed to the time as every result is. It is
// accepted only when it arrives, meets the time and costs less than the run it replaces, so it
// never makes a result worse. An engine built without cruise_as_hold is left as the grid has it.
#pragma once

#include <functional>
#include <limits>
#include <string>

#include "dp/section_engine.hpp"

namespace ecorail::dp {

struct CruisePolishOptions {
  bool enabled = true;
  // Polish only cruises at least this long (first hold to the final coast): short holds on a
  // metro section are not worth the re-simulations.
  double min_cruise_m = 2000.0;
  double short_phase_m = 200.0;         // phases inside the cruise shorter than this are dropped
  double search_half_width_m = 3000.0;  // coasting point searched within this of the grid's
  double search_tolerance_m = 0.5;      // golden section stops at this bracket width
  double search_step_m = 0.5;           // RK4 step of the search's re-simulations
  // The search under one time price: the RK4 step of its re-simulations (at least
  // search_step_m), the first simplex's size, its budget per price, and how close to the time
  // the price's optimum must come before the first hold's speed alone closes the rest.
  double price_search_step_m = 5.0;
  double price_first_step_m = 40.0;
  int price_max_simulations = 600;
  double price_time_tolerance_s = 0.2;
  // Checks every field; on failure writes one sentence naming the field into *error.
  bool IsValid(std::string* error) const;
};

struct CruisePolishReport {
  bool applied = false;        // the polished run replaced the grid's
  int dropped_phases = 0;      // short phases dropped inside the cruise
  int simulations = 0;         // re-simulations spent
  double cost_before_J = 0.0;  // the run it started from (fine step), by the objective
  double cost_after_J = 0.0;   // the run returned
  double coast_shift_m = 0.0;  // coasting point: polished minus the grid's
};

// How the run ends: at rest at the route's end (the default, run_arrives), or moving (a
// journey's last timing point with a speed above 0): then `reaches` says whether a run ends as
// asked, and with a finite pinned_speed_ms (a speed window of zero width) the onset of the
// final brake is solved on every run so that it ends at that speed.
struct PolishEnd {
  bool moving = false;
  std::function<bool(const physics::SimulationResult&)> reaches;
  double pinned_speed_ms = std::numeric_limits<double>::quiet_NaN();
  double speed_tolerance_ms = 0.0;
};

// run must be an arriving run of engine that meets target_s within tolerance_s. On success
// (report.applied) run is replaced by the polished run, re-simulated at the engine's fine step,
// arriving, within tolerance_s of target_s and cheaper by the objective.
CruisePolishReport polish_cruise(const SectionEngine& engine, double target_s, double tolerance_s,
                                 const CruisePolishOptions& options, LambdaRun& run,
                                 const PolishEnd& end = {});

}  // namespace ecorail::dp
