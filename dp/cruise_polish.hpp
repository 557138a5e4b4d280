// Cruise polish: the continuous optimum of a run with long cruises, after the grid found its
// shape. On a long stretch the grid's optimum cruises, but its cruise is a staircase: a hold,
// short coasts and holds a fraction of a km/h apart, short traction blips (on a 48.5 km level
// TTOBench run, seventeen phases between 38 and 40 km), and each hold speed and coasting point
// sits where the grid put it. The polish makes each cruise one hold: a run of phases shorter
// than short_phase_m becomes one phase of the control it spends most distance in (a single
// short phase is dropped and the phase before it goes on). On a metro section the grid steps
// down from the end of full traction to a lower limit in short coasts and holds; that
// staircase becomes a hold (of free speed) and a coast. A coast that runs, through coasts
// and holds only, into a lower limit becomes one coast tied to the limit's start: its start is
// solved so that the run reaches the limit's speed exactly where the limit begins (Howlett and
// Pudney's condition for a step down of the limit), and the run holds or rides the limit from
// there. That removes the kink the cost has where a coast meets a lower limit's braking curve
// and every switch point that moves the run only along it. Then, under one time price lambda,
// every remaining switch point from the first hold on (each hold's start, which sets its speed,
// each coast's start) is placed where the run's cost plus lambda times its running time is
// least: rounds of golden-section searches (dp/golden_section.hpp), one switch point at a time
// along the track, re-simulating at price_search_step_m; the first round searches each point
// over the whole interval between its neighbours (after a scan of it, first_scan_points,
// where the cruise starts with a step down: over a descent into a lower limit the cost has
// more than one minimum in a point), so the result does not hang on where the grid put it. lambda
// is searched (the engine's one root search) until that run meets the time within
// price_time_tolerance_s. At that optimum every hold meets the same Lagrange condition: on level
// track with a constant efficiency every free hold has the same speed. The last hundredths of a
// second are met by the last free hold's speed alone (a secant on its start, after every tied
// coast, so no tie moves), at the search step and then at the engine's fine step. The result is
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
  // Polish only cruises at least this long (first hold to the final coast); a cruise that
  // starts with the grid's staircase down to a lower limit is polished whatever its length.
  // 0 (the default): every run with a hold. On the reference line's metro sections the grid's
  // runs with holds of a few hundred metres stood up to 0.22 % above the polished ones (A11 ->
  // A12, A13 -> A14; docs/journeys.md), for about 2.7 times the CPU of a frontier.
  double min_cruise_m = 0.0;
  double short_phase_m = 200.0;         // phases inside the cruise shorter than this are dropped
  double search_half_width_m = 3000.0;  // (not used by the price search; kept for callers)
  double search_tolerance_m = 0.5;      // each golden-section search narrows to this width
  double search_step_m = 0.5;           // RK4 step of the search's re-simulations
  // The search under one time price: the RK4 step of its re-simulations (at least
  // search_step_m), the least half-width of a switch point's window after its first search
  // (the window is also four times the point's last move, and widens while the optimum sits on
  // its edge), the re-simulations it may start per price (a round under way is finished), and
  // how close to the time the price's optimum must come before the last hold's speed alone
  // closes the rest.
  double price_search_step_m = 1.0;
  // Where the cruise starts with the grid's staircase down to a lower limit, the first search
  // of each switch point scans its whole interval at this many points and narrows around the
  // best (0: golden section over the whole interval at once, as on every other cruise).
  int first_scan_points = 8;
  double price_first_step_m = 40.0;
  int price_max_simulations = 600;
  // The whole polish stops after this many re-simulations and keeps the grid's run: a polish
  // that has not found a cheaper run by then rarely does (CH_StGallen_Wil with the FLIRT at
  // its minimum time + 10 % spent 27 934 re-simulations of its 29.6 km, 85 s of CPU, and kept
  // the grid's run; the 48.5 km TTOBench pairs that the polish improves use 2 700 to 5 500).
  int max_simulations = 10000;
  double price_time_tolerance_s = 0.02;
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
